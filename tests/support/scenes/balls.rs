//! `balls`: 4,096 balls falling into a pile on the ground (docs/scenes.md).
//!
//! 16 × 16 × 16 balls of radius 0.5 (density 1) on a 1.1 m grid, `x = (i − 7.5)·1.1 + jx`,
//! `y = 0.6 + j·1.1`, `z = (k − 7.5)·1.1 + jz`, loops in the order i, j, k, with the jitters `jx` then `jz`
//! drawn from `U(−0.04, 0.04)` of the generator seeded `0xBA11_5EED_0000_0001` (two draws per ball). Without
//! the jitter the lattice would just stack into 16-ball columns.
//!
//! For the scaling series the footprint changes and the height stays: `side × 16 × side` balls with
//! `x = (i − (side − 1)/2)·1.1 + jx` (side 8: 1,024 balls; 16: the peer scene, bit for bit; 32: 16,384).

use rebound::prelude::*;

use super::metrics::{active_contact_pairs, max_speed};
use super::{Scene, SceneOptions, Value, add_ground};
use crate::XorShift64Star;

/// Balls per horizontal side of the peer scene.
pub const SIDE: usize = 16;
/// Layers of balls (the `j` loop), for every footprint.
pub const LAYERS: usize = 16;
/// Ball radius (m).
pub const RADIUS: f32 = 0.5;
/// Grid spacing (m).
pub const SPACING: f32 = 1.1;
/// Half-width of the horizontal jitter (m).
pub const JITTER: f32 = 0.04;
/// Generator seed.
pub const SEED: u64 = 0xBA11_5EED_0000_0001;

/// The `balls` scene.
#[derive(Debug)]
pub struct Balls {
    world: PhysicsWorld,
    balls: Vec<BodyHandle>,
}

impl Balls {
    /// Builds the scene with `side × 16 × side` balls ([`SIDE`] for the peer scene).
    ///
    /// # Errors
    /// Whatever Rebound refuses while building (a bug).
    pub fn new(options: SceneOptions, side: usize) -> Result<Self, Error> {
        let mut world = PhysicsWorld::new(options.settings(Vec3::new(0.0, -9.81, 0.0)))?;
        add_ground(&mut world)?;
        let mut rng = XorShift64Star::new(SEED);
        let centre = (side - 1) as f32 / 2.0;
        let mut balls = Vec::with_capacity(side * LAYERS * side);
        for i in 0..side {
            for j in 0..LAYERS {
                for k in 0..side {
                    let jx = rng.uniform(-JITTER, JITTER);
                    let jz = rng.uniform(-JITTER, JITTER);
                    let x = (i as f32 - centre) * SPACING + jx;
                    let y = 0.6 + j as f32 * SPACING;
                    let z = (k as f32 - centre) * SPACING + jz;
                    let ball = world.insert_body(options.dynamic(Vec3::new(x, y, z)))?;
                    world.insert_collider(ColliderDesc::ball(RADIUS).with_density(1.0), ball)?;
                    balls.push(ball);
                }
            }
        }
        Ok(Self { world, balls })
    }

    /// The balls, in construction order.
    #[must_use]
    pub fn balls(&self) -> &[BodyHandle] {
        &self.balls
    }

    /// The balls' heights (m).
    fn heights(&self) -> impl Iterator<Item = f32> + '_ {
        self.balls
            .iter()
            .filter_map(|&h| self.world.body(h).map(|b| b.position().y))
    }
}

impl Scene for Balls {
    fn world(&self) -> &PhysicsWorld {
        &self.world
    }

    fn world_mut(&mut self) -> &mut PhysicsWorld {
        &mut self.world
    }

    fn step(&mut self) -> StepReport {
        self.world.step(super::DT)
    }

    fn observe(&mut self, _step: usize) {}

    /// `min_center_y` (0.5 = resting on the ground; lower = penetration), `max_center_y`, `max_speed`,
    /// `below_ground` (balls with y < 0) and `contact_pairs` (pairs with a point closer than the speculative
    /// margin, rapier's active contact), at the last step.
    fn quality(&self) -> Vec<(&'static str, Value)> {
        let min_y = self.heights().fold(f32::INFINITY, f32::min);
        let max_y = self.heights().fold(f32::NEG_INFINITY, f32::max);
        vec![
            ("min_center_y", Value::f32(min_y)),
            ("max_center_y", Value::f32(max_y)),
            ("max_speed", Value::f32(max_speed(&self.world))),
            (
                "below_ground",
                Value::count(self.heights().filter(|&y| y < 0.0).count()),
            ),
            (
                "contact_pairs",
                Value::count(active_contact_pairs(&self.world)),
            ),
        ]
    }
}
