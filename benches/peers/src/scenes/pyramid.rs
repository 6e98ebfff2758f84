//! `pyramid`: a one-box-deep pyramid of 820 unit cubes, base 40, on the ground.
//!
//! Row `r` in `0..40` holds `40 − r` cubes of half-extent 0.5 (density 1) at `x = (j − (40 − r − 1)/2)·1.0`,
//! `y = 0.5 + r`, `z = 0`: the boxes touch exactly, with no gap and no overlap; the top box is at y = 39.5.

use rapier3d::prelude::*;

use super::{Scene, SceneOptions, add_ground};
use crate::metrics::Quality;
use crate::world::{GRAVITY, World};

/// Boxes in the bottom row (and number of rows).
const BASE: usize = 40;
/// Box half-extent.
const HALF: f32 = 0.5;
/// `|top_dy|` and drift below this count as standing.
const STANDING_TOLERANCE: f32 = 0.25;

/// The `pyramid` scene.
pub struct Pyramid {
    world: World,
    /// Every box with its initial centre; the last one is the top box.
    boxes: Vec<(RigidBodyHandle, Vector)>,
    /// The largest |Δz| of any box over the steps so far (m).
    max_z_run: f32,
}

impl Pyramid {
    /// Builds the scene.
    pub fn new(options: SceneOptions) -> Self {
        let mut world = World::new(GRAVITY);
        add_ground(&mut world);
        let mut boxes = Vec::with_capacity(BASE * (BASE + 1) / 2);
        for r in 0..BASE {
            let count = BASE - r;
            for j in 0..count {
                let x = (j as f32 - (count - 1) as f32 / 2.0) * 1.0;
                let y = 0.5 + r as f32 * 1.0;
                let p = Vector::new(x, y, 0.0);
                let handle = world.add_body(
                    options.dynamic(p),
                    Some(
                        ColliderBuilder::cuboid(HALF, HALF, HALF)
                            .density(1.0)
                            .build(),
                    ),
                );
                boxes.push((handle, p));
            }
        }
        Self {
            world,
            boxes,
            max_z_run: 0.0,
        }
    }
}

impl Pyramid {
    /// The largest |Δz| of any box now (m).
    fn max_z(&self) -> f32 {
        self.boxes
            .iter()
            .map(|&(handle, p0)| (self.world.pos(handle).z - p0.z).abs())
            .fold(0.0, f32::max)
    }
}

impl Scene for Pyramid {
    fn world(&self) -> &World {
        &self.world
    }

    fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    fn observe(&mut self, _step: usize, _total: usize) {
        self.max_z_run = self.max_z_run.max(self.max_z());
    }

    /// `top_y`, `top_y0`, `top_dy` (the top box's height change), `max_horiz_drift` (largest xz displacement of
    /// any box), `max_z_drift` (largest |Δz|), `max_z_drift_run` (the same maximised over every step: the
    /// one-box-deep wall sways out of its plane slowly, so one step's value is a phase of that sway) and
    /// `standing` (`|top_dy|` < 0.25 and drift < 0.25).
    fn quality(&self) -> Quality {
        let mut max_horiz = 0.0f32;
        for &(handle, p0) in &self.boxes {
            let d = self.world.pos(handle) - p0;
            max_horiz = max_horiz.max(d.x.hypot(d.z));
        }
        let max_z = self.max_z();
        let &(top, top0) = self.boxes.last().expect("the pyramid has boxes");
        let top_y = self.world.pos(top).y;
        let top_dy = top_y - top0.y;
        let standing = top_dy.abs() < STANDING_TOLERANCE && max_horiz < STANDING_TOLERANCE;
        let mut q = Quality::new();
        q.num("top_y", top_y)
            .num("top_y0", top0.y)
            .num("top_dy", top_dy)
            .num("max_horiz_drift", max_horiz)
            .num("max_z_drift", max_z)
            .num("max_z_drift_run", self.max_z_run)
            .flag("standing", standing);
        q
    }
}

#[cfg(test)]
mod tests {
    use super::Pyramid;
    use crate::scenes::{Scene, SceneOptions};

    #[test]
    fn rows_touch_and_the_top_is_at_39_5() {
        let scene = Pyramid::new(SceneOptions::default());
        assert_eq!(scene.world().dynamic_body_count(), 820);
        let (_, top) = *scene.boxes.last().expect("boxes");
        assert_eq!((top.x, top.y, top.z), (0.0, 39.5, 0.0));
        // Bottom row: x from −19.5 to 19.5.
        assert_eq!(scene.boxes[0].1.x, -19.5);
        assert_eq!(scene.boxes[39].1.x, 19.5);
    }
}
