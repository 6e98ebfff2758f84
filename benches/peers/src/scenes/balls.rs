//! `balls`: 4,096 balls falling into a pile on the ground.
//!
//! 16 × 16 × 16 balls of radius 0.5 (density 1) on a 1.1 m grid, `x = (i − 7.5)·1.1 + jx`,
//! `y = 0.6 + j·1.1`, `z = (k − 7.5)·1.1 + jz`, loops in the order i, j, k, with the jitters `jx` then `jz`
//! drawn from `U(−0.04, 0.04)` of the generator seeded `0xBA11_5EED_0000_0001` (two draws per ball). Without
//! the jitter the lattice would just stack into 16-ball columns.

use rapier3d::prelude::*;

use super::{Scene, SceneOptions, add_ground};
use crate::metrics::{Quality, active_contact_pairs, max_speed};
use crate::rng::XorShift64Star;
use crate::world::{GRAVITY, World};

/// Balls per side of the cube.
const N: usize = 16;
/// Ball radius.
const RADIUS: f32 = 0.5;
/// Grid spacing.
const SPACING: f32 = 1.1;
/// Half-width of the horizontal jitter.
const JITTER: f32 = 0.04;
/// Generator seed.
const SEED: u64 = 0xBA11_5EED_0000_0001;

/// The `balls` scene.
pub struct Balls {
    world: World,
    balls: Vec<RigidBodyHandle>,
}

impl Balls {
    /// Builds the scene.
    pub fn new(options: SceneOptions) -> Self {
        let mut world = World::new(GRAVITY);
        add_ground(&mut world);
        let mut rng = XorShift64Star::new(SEED);
        let mut balls = Vec::with_capacity(N * N * N);
        for i in 0..N {
            for j in 0..N {
                for k in 0..N {
                    let jx = rng.uniform(-JITTER, JITTER);
                    let jz = rng.uniform(-JITTER, JITTER);
                    let x = (i as f32 - 7.5) * SPACING + jx;
                    let y = 0.6 + j as f32 * SPACING;
                    let z = (k as f32 - 7.5) * SPACING + jz;
                    let handle = world.add_body(
                        options.dynamic(Vector::new(x, y, z)),
                        Some(ColliderBuilder::ball(RADIUS).density(1.0).build()),
                    );
                    balls.push(handle);
                }
            }
        }
        Self { world, balls }
    }
}

impl Scene for Balls {
    fn world(&self) -> &World {
        &self.world
    }

    fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    fn observe(&mut self, _step: usize, _total: usize) {}

    /// `min_center_y` (0.5 = resting on the ground; lower = penetration), `max_center_y`, `max_speed`,
    /// `below_ground` (balls with y < 0) and `contact_pairs` (pairs with an active contact), at the last step.
    fn quality(&self) -> Quality {
        let ys: Vec<f32> = self.balls.iter().map(|&h| self.world.pos(h).y).collect();
        let min_y = ys.iter().copied().fold(f32::INFINITY, f32::min);
        let max_y = ys.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        let mut q = Quality::new();
        q.num("min_center_y", min_y)
            .num("max_center_y", max_y)
            .num("max_speed", max_speed(&self.world))
            .count("below_ground", ys.iter().filter(|&&y| y < 0.0).count())
            .count("contact_pairs", active_contact_pairs(&self.world));
        q
    }
}

#[cfg(test)]
mod tests {
    use super::Balls;
    use crate::rng::XorShift64Star;
    use crate::scenes::{Scene, SceneOptions};

    #[test]
    fn lattice_with_the_seeded_jitter() {
        let scene = Balls::new(SceneOptions::default());
        assert_eq!(scene.world().dynamic_body_count(), 4096);
        let mut rng = XorShift64Star::new(super::SEED);
        let (jx, jz) = (rng.uniform(-0.04, 0.04), rng.uniform(-0.04, 0.04));
        let p = scene.world().pos(scene.balls[0]);
        assert_eq!((p.x, p.y, p.z), (-7.5 * 1.1 + jx, 0.6, -7.5 * 1.1 + jz));
    }
}
