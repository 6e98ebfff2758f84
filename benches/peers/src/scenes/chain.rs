//! `chain`: 500 balls on rope joints, released horizontally; and the supplementary `chain_spherical`.
//!
//! No ground. A fixed body without a collider sits at the origin; balls `i = 0..500` of radius 0.1 (density 1)
//! start at `((i + 1)·0.25, 0, 0)`. Rope joints of max distance 0.25, anchored at the body centres, join the
//! fixed body to ball 0 and ball `i − 1` to ball `i`. Contacts between jointed bodies are left at rapier's
//! default (enabled) and all balls collide with each other.
//!
//! `chain_spherical` (not in the default list) uses spherical joints instead, anchored at ball `i − 1`'s centre
//! (the fixed body's origin for ball 0) and at (−0.25, 0, 0) on ball `i`: rigid 0.25 m links.

use rapier3d::prelude::*;

use super::{Scene, SceneOptions};
use crate::metrics::Quality;
use crate::world::{GRAVITY, World};

/// Number of balls (and of links).
const BALLS: usize = 500;
/// Ball radius.
const RADIUS: f32 = 0.1;
/// Link length: rope max distance, or the spherical joints' anchor offset.
const LINK: f32 = 0.25;

/// Which joint links the balls.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Link {
    /// `RopeJoint` of max distance 0.25 between the body centres (the `chain` scene).
    Rope,
    /// `SphericalJoint` with a 0.25 m offset: a rigid link (the `chain_spherical` scene).
    Spherical,
}

/// The `chain` and `chain_spherical` scenes.
pub struct Chain {
    world: World,
    /// The fixed body followed by the balls in order: link `i` joins `bodies[i]` and `bodies[i + 1]`.
    bodies: Vec<RigidBodyHandle>,
    /// `max_link_stretch` maximised over every step so far.
    max_stretch_run: f32,
}

impl Chain {
    /// Builds the scene with the given link type.
    pub fn new(options: SceneOptions, link: Link) -> Self {
        let mut world = World::new(GRAVITY);
        let mut bodies = Vec::with_capacity(BALLS + 1);
        bodies.push(world.add_body(RigidBodyBuilder::fixed(), None));
        for i in 0..BALLS {
            let x = (i + 1) as f32 * LINK;
            let ball = world.add_body(
                options.dynamic(Vector::new(x, 0.0, 0.0)),
                Some(ColliderBuilder::ball(RADIUS).density(1.0).build()),
            );
            let previous = bodies[i];
            match link {
                Link::Rope => world.add_joint(previous, ball, RopeJointBuilder::new(LINK)),
                Link::Spherical => world.add_joint(
                    previous,
                    ball,
                    SphericalJointBuilder::new()
                        .local_anchor1(Vector::ZERO)
                        .local_anchor2(Vector::new(-LINK, 0.0, 0.0)),
                ),
            }
            bodies.push(ball);
        }
        Self {
            world,
            bodies,
            max_stretch_run: f32::NEG_INFINITY,
        }
    }

    /// Centre-to-centre length of every link.
    fn link_lengths(&self) -> impl Iterator<Item = f32> + '_ {
        self.bodies
            .windows(2)
            .map(|pair| self.world.pos(pair[0]).distance(self.world.pos(pair[1])))
    }

    /// Largest `length / 0.25 − 1` over the links (negative if every link is slack).
    fn max_stretch(&self) -> f32 {
        self.link_lengths()
            .map(|len| len / LINK - 1.0)
            .fold(f32::NEG_INFINITY, f32::max)
    }
}

impl Scene for Chain {
    fn world(&self) -> &World {
        &self.world
    }

    fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    fn observe(&mut self, _step: usize, _total: usize) {
        self.max_stretch_run = self.max_stretch_run.max(self.max_stretch());
    }

    /// `max_link_stretch_end` (max over links of `distance / 0.25 − 1` at the last step),
    /// `max_link_stretch_run` (the same maximised over every step), `chain_length_ratio` (sum of link lengths
    /// / 125) and `tip` (the last ball's position).
    fn quality(&self) -> Quality {
        let total_length: f32 = self.link_lengths().sum();
        let tip = self
            .world
            .pos(*self.bodies.last().expect("the chain has balls"));
        let mut q = Quality::new();
        q.num("max_link_stretch_end", self.max_stretch())
            .num("max_link_stretch_run", self.max_stretch_run)
            .num("chain_length_ratio", total_length / (BALLS as f32 * LINK))
            .vec3("tip", tip);
        q
    }
}

#[cfg(test)]
mod tests {
    use super::{Chain, Link};
    use crate::scenes::{Scene, SceneOptions};

    #[test]
    fn links_start_at_full_length() {
        for link in [Link::Rope, Link::Spherical] {
            let scene = Chain::new(SceneOptions::default(), link);
            assert_eq!(scene.world().dynamic_body_count(), 500);
            assert_eq!(scene.world().joint_count(), 500);
            assert!(scene.max_stretch().abs() < 1e-5);
            let total: f32 = scene.link_lengths().sum();
            assert!((total - 125.0).abs() < 1e-3);
        }
    }
}
