//! `pyramid`: a one-box-deep pyramid of 820 unit cubes, base 40, on the ground (docs/scenes.md).
//!
//! Row `r` in `0..40` holds `40 − r` cubes of half-extent 0.5 (density 1) at `x = (j − (40 − r − 1)/2)·1.0`,
//! `y = 0.5 + r`, `z = 0`: the boxes touch exactly, with no gap and no overlap; the top box is at y = 39.5.
//! The scaling series builds the same pyramid with other bases (20, 80).

use rebound::RigidBody;
use rebound::prelude::*;

use super::{Scene, SceneOptions, Value, add_ground};

/// Boxes in the bottom row (and number of rows) of the peer scene.
pub const BASE: usize = 40;
/// Box half-extent (m).
pub const HALF: f32 = 0.5;
/// `|top_dy|` and drift below this (m) count as standing.
pub const STANDING_TOLERANCE: f32 = 0.25;

/// The `pyramid` scene.
#[derive(Debug)]
pub struct Pyramid {
    world: PhysicsWorld,
    /// Every box with its initial centre, row by row from the bottom; the last one is the top box.
    boxes: Vec<(BodyHandle, Vec3)>,
    /// The largest |Δz| of any box over the steps so far (m).
    max_z_run: f32,
}

impl Pyramid {
    /// Builds a pyramid of base `base` ([`BASE`] for the peer scene): `base·(base + 1)/2` boxes.
    ///
    /// # Errors
    /// Whatever Rebound refuses while building (a bug).
    pub fn new(options: SceneOptions, base: usize) -> Result<Self, Error> {
        let mut world = PhysicsWorld::new(options.settings(Vec3::new(0.0, -9.81, 0.0)))?;
        add_ground(&mut world)?;
        let mut boxes = Vec::with_capacity(base * (base + 1) / 2);
        for r in 0..base {
            let count = base - r;
            for j in 0..count {
                let x = (j as f32 - (count - 1) as f32 / 2.0) * 1.0;
                let y = 0.5 + r as f32 * 1.0;
                let p = Vec3::new(x, y, 0.0);
                let body = world.insert_body(options.dynamic(p))?;
                world.insert_collider(
                    ColliderDesc::cuboid(Vec3::splat(HALF)).with_density(1.0),
                    body,
                )?;
                boxes.push((body, p));
            }
        }
        Ok(Self {
            world,
            boxes,
            max_z_run: 0.0,
        })
    }

    /// Every box with its initial centre, row by row from the bottom row; the last one is the top box.
    #[must_use]
    pub fn boxes(&self) -> &[(BodyHandle, Vec3)] {
        &self.boxes
    }

    /// A box's current centre (NaN for a stale handle, which the scene never holds).
    fn position(&self, handle: BodyHandle) -> Vec3 {
        self.world
            .body(handle)
            .map_or(Vec3::NAN, RigidBody::position)
    }

    /// The largest |Δz| of any box now (m).
    fn max_z(&self) -> f32 {
        self.boxes
            .iter()
            .map(|&(handle, p0)| (self.position(handle).z - p0.z).abs())
            .fold(0.0, f32::max)
    }
}

impl Scene for Pyramid {
    fn world(&self) -> &PhysicsWorld {
        &self.world
    }

    fn world_mut(&mut self) -> &mut PhysicsWorld {
        &mut self.world
    }

    fn step(&mut self) -> StepReport {
        self.world.step(super::DT)
    }

    fn observe(&mut self, _step: usize) {
        self.max_z_run = self.max_z_run.max(self.max_z());
    }

    /// `top_y`, `top_y0`, `top_dy` (the top box's height change), `max_horiz_drift` (largest xz displacement of
    /// any box), `max_z_drift` (largest |Δz|), `max_z_drift_run` (the same maximised over every step: the
    /// one-box-deep wall sways out of its plane slowly, so one step's value is a phase of that sway) and
    /// `standing` (`|top_dy|` < 0.25 and drift < 0.25).
    fn quality(&self) -> Vec<(&'static str, Value)> {
        let mut max_horiz = 0.0f32;
        for &(handle, p0) in &self.boxes {
            let d = self.position(handle) - p0;
            max_horiz = max_horiz.max(d.x.hypot(d.z));
        }
        let max_z = self.max_z();
        let (top, top0) = self
            .boxes
            .last()
            .copied()
            .unwrap_or((BodyHandle::invalid(), Vec3::NAN));
        let top_y = self.position(top).y;
        let top_dy = top_y - top0.y;
        let standing = top_dy.abs() < STANDING_TOLERANCE && max_horiz < STANDING_TOLERANCE;
        vec![
            ("top_y", Value::f32(top_y)),
            ("top_y0", Value::f32(top0.y)),
            ("top_dy", Value::f32(top_dy)),
            ("max_horiz_drift", Value::f32(max_horiz)),
            ("max_z_drift", Value::f32(max_z)),
            ("max_z_drift_run", Value::f32(self.max_z_run)),
            ("standing", Value::Bool(standing)),
        ]
    }
}
