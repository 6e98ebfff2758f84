//! `chain`: 500 balls on ropes, released horizontally (docs/scenes.md); and the supplementary
//! `chain_spherical`.
//!
//! No ground. A fixed body without a collider sits at the origin; balls `i = 0..500` of radius 0.1 (density 1)
//! start at `((i + 1)·0.25, 0, 0)`. Ropes of max length 0.25, anchored at the body centres, join the fixed
//! body to ball 0 and ball `i − 1` to ball `i`. Jointed pairs keep colliding (Rebound's default, as rapier's)
//! and all balls collide with each other.
//!
//! `chain_spherical` (not in the default list) uses ball joints instead, anchored at ball `i − 1`'s centre
//! (the fixed body's origin for ball 0) and at (−0.25, 0, 0) on ball `i`: rigid 0.25 m links.

use rebound::RigidBody;
use rebound::prelude::*;

use super::{Scene, SceneOptions, Value, joint_error};

/// Number of balls (and of links).
pub const BALLS: usize = 500;
/// Ball radius (m).
pub const RADIUS: f32 = 0.1;
/// Link length (m): the ropes' max length, or the ball joints' anchor offset.
pub const LINK: f32 = 0.25;

/// Which joint links the balls.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Link {
    /// A [`Rope`] of max length 0.25 between the body centres (the `chain` scene).
    Rope,
    /// A [`BallJoint`] with a 0.25 m offset: a rigid link (the `chain_spherical` scene).
    Spherical,
}

/// The `chain` and `chain_spherical` scenes.
#[derive(Debug)]
pub struct Chain {
    world: PhysicsWorld,
    /// The fixed body followed by the balls in order: link `i` joins `bodies[i]` and `bodies[i + 1]`.
    bodies: Vec<BodyHandle>,
    /// `max_link_stretch` maximised over every step so far.
    max_stretch_run: f32,
}

impl Chain {
    /// Builds the scene with the given link type.
    ///
    /// # Errors
    /// Whatever Rebound refuses while building (a bug).
    pub fn new(options: SceneOptions, link: Link) -> Result<Self, Error> {
        let mut world = PhysicsWorld::new(options.settings(Vec3::new(0.0, -9.81, 0.0)))?;
        let mut bodies = Vec::with_capacity(BALLS + 1);
        bodies.push(world.insert_body(BodyDesc::fixed())?);
        for i in 0..BALLS {
            let x = (i + 1) as f32 * LINK;
            let ball = world.insert_body(options.dynamic(Vec3::new(x, 0.0, 0.0)))?;
            world.insert_collider(ColliderDesc::ball(RADIUS).with_density(1.0), ball)?;
            let joint = match link {
                Link::Rope => Joint::new(Rope::new(LINK).map_err(joint_error)?),
                Link::Spherical => Joint::new(BallJoint::new())
                    .with_local_anchors(Vec3::ZERO, Vec3::new(-LINK, 0.0, 0.0))
                    .map_err(joint_error)?,
            };
            world.insert_joint(joint, bodies[i], ball)?;
            bodies.push(ball);
        }
        Ok(Self {
            world,
            bodies,
            max_stretch_run: f32::NEG_INFINITY,
        })
    }

    /// Centre-to-centre length of every link (m).
    pub fn link_lengths(&self) -> impl Iterator<Item = f32> + '_ {
        self.bodies.windows(2).map(|pair| {
            let p = |h| self.world.body(h).map_or(Vec3::NAN, RigidBody::position);
            p(pair[0]).distance(p(pair[1]))
        })
    }

    /// Largest `length / 0.25 − 1` over the links (negative if every link is slack).
    #[must_use]
    pub fn max_stretch(&self) -> f32 {
        self.link_lengths()
            .map(|len| len / LINK - 1.0)
            .fold(f32::NEG_INFINITY, f32::max)
    }
}

impl Scene for Chain {
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
        self.max_stretch_run = self.max_stretch_run.max(self.max_stretch());
    }

    /// `max_link_stretch_end` (max over links of `distance / 0.25 − 1` at the last step),
    /// `max_link_stretch_run` (the same maximised over every step), `chain_length_ratio` (sum of link lengths
    /// / 125) and `tip` (the last ball's position).
    fn quality(&self) -> Vec<(&'static str, Value)> {
        let total_length: f32 = self.link_lengths().sum();
        let tip = self
            .bodies
            .last()
            .and_then(|&h| self.world.body(h))
            .map_or(Vec3::NAN, RigidBody::position);
        vec![
            ("max_link_stretch_end", Value::f32(self.max_stretch())),
            ("max_link_stretch_run", Value::f32(self.max_stretch_run)),
            (
                "chain_length_ratio",
                Value::f32(total_length / (BALLS as f32 * LINK)),
            ),
            ("tip", Value::vec3(tip)),
        ]
    }
}
