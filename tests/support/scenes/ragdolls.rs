//! `ragdolls` (supplementary, not in the default list): ten 15-part ragdolls ([`rebound::ragdoll`]) dropped
//! onto a pile of 48 boxes, as the rapier side builds them (`benches/peers/src/scenes/ragdolls.rs`).
//!
//! The ground of docs/scenes.md; a pile of 4 × 4 × 3 cubes of side 0.5 m (density 200) centred on the origin,
//! top at y = 1.5; ten ragdolls standing in two layers of five along x (x = −1.4 + 0.7·i, feet at y = 1.6 and
//! 3.6), each tipped about x by ±0.3 rad. Contacts between jointed parts are disabled.
//!
//! Metrics: `max_joint_gap_end` and `max_joint_gap_run` (the largest distance between a joint's two anchors at
//! the last step and over the run, m), `lowest_part_y_run` (the lowest part centre over the run, m), and
//! Rebound's `max_limit_excess_run` (the largest angle past a joint's limits over the run, rad; rapier's
//! per-axis limits are not the same model, so it has no counterpart there).

use rebound::prelude::*;
use rebound::ragdoll::{Ragdoll, RagdollDesc};

use super::{Scene, SceneOptions, Value, add_ground};

/// The ragdolls in the scene.
pub const RAGDOLLS: usize = 10;

/// The `ragdolls` scene.
#[derive(Debug)]
pub struct Ragdolls {
    world: PhysicsWorld,
    ragdolls: Vec<Ragdoll>,
    max_gap_run: f32,
    max_excess_run: f32,
    lowest_run: f32,
}

impl Ragdolls {
    /// Builds the scene.
    ///
    /// # Errors
    /// Whatever Rebound refuses while building (a bug).
    pub fn new(options: SceneOptions) -> Result<Self, Error> {
        let mut world = PhysicsWorld::new(options.settings(Vec3::new(0.0, -9.81, 0.0)))?;
        add_ground(&mut world)?;
        for layer in 0..3 {
            for i in 0..4 {
                for k in 0..4 {
                    let p = Vec3::new(
                        -0.75 + 0.5 * i as f32,
                        0.25 + 0.5 * layer as f32,
                        -0.75 + 0.5 * k as f32,
                    );
                    let body = world.insert_body(options.dynamic(p))?;
                    world.insert_collider(
                        ColliderDesc::cuboid(Vec3::splat(0.25)).with_density(200.0),
                        body,
                    )?;
                }
            }
        }
        let mut ragdolls = Vec::with_capacity(RAGDOLLS);
        for r in 0..RAGDOLLS {
            let (i, layer) = (r % 5, r / 5);
            let tilt = if r % 2 == 0 { 0.3 } else { -0.3 };
            let desc = RagdollDesc {
                position: Vec3::new(-1.4 + 0.7 * i as f32, 1.6 + 2.0 * layer as f32, 0.0),
                rotation: Quat::from_rotation_x(tilt),
                ..RagdollDesc::default()
            };
            ragdolls.push(Ragdoll::build(&mut world, &desc)?);
        }
        Ok(Self {
            world,
            ragdolls,
            max_gap_run: 0.0,
            max_excess_run: 0.0,
            lowest_run: f32::INFINITY,
        })
    }

    fn max_gap(&self) -> f32 {
        self.ragdolls
            .iter()
            .map(|r| r.worst_joint_gap(&self.world))
            .fold(0.0, f32::max)
    }
}

impl Scene for Ragdolls {
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
        self.max_gap_run = self.max_gap_run.max(self.max_gap());
        for r in &self.ragdolls {
            self.max_excess_run = self.max_excess_run.max(r.worst_limit_excess(&self.world));
            for &p in &r.parts {
                if let Some(body) = self.world.body(p) {
                    self.lowest_run = self.lowest_run.min(body.position().y);
                }
            }
        }
    }

    fn quality(&self) -> Vec<(&'static str, Value)> {
        vec![
            ("max_joint_gap_end", Value::f32(self.max_gap())),
            ("max_joint_gap_run", Value::f32(self.max_gap_run)),
            ("lowest_part_y_run", Value::f32(self.lowest_run)),
            ("max_limit_excess_run", Value::f32(self.max_excess_run)),
        ]
    }
}
