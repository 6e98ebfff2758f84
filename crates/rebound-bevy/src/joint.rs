//! The [`PhysicsJoint`] component: a facade [`Joint`] (any [`rebound::JointKind`]) between the bodies of two
//! entities, or between a body and the world. Read by the prepare systems.

use bevy_ecs::component::Component;
use bevy_ecs::entity::Entity;
use rebound::prelude::Joint;

/// A joint between two body entities. It may live on either body's entity or on an entity of its own.
///
/// * `joint` is the facade's joint: its kind (spring, rope, rod, ball, hinge, fixed, prismatic, wheel) and
///   parameters, anchors (m, in each body's frame), frames and break limits (N, N·m).
/// * `body_a: None` makes a world joint: anchor A is then a point in world space (m).
/// * Until both entities' bodies exist the joint waits; an entity that has no [`crate::Body`] at all is an
///   error ([`crate::PhysicsError::NotABody`]).
///
/// Editing the component updates the joint in place when it joins the same bodies (its accumulated impulses
/// are kept) and re-creates it otherwise. Despawning either body removes the joint; it comes back if that
/// entity gets a `Body` again (the component still names it).
///
/// ```
/// use bevy_ecs::world::World;
/// use rebound_bevy::prelude::*;
/// let mut world = World::new();
/// let (a, b) = (world.spawn(Body::fixed()).id(), world.spawn(Body::dynamic()).id());
/// let hinge = Joint::new(HingeJoint::new()).with_local_axes(Vec3::Z, Vec3::Z)?;
/// world.spawn(PhysicsJoint::new(hinge, a, b));
/// # Ok::<(), rebound_bevy::rebound::ConstraintError>(())
/// ```
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct PhysicsJoint {
    /// The joint.
    pub joint: Joint,
    /// The entity of body A, or `None` for a world joint.
    pub body_a: Option<Entity>,
    /// The entity of body B.
    pub body_b: Entity,
    /// Whether the two bodies keep colliding with each other. Default: true.
    pub contacts_enabled: bool,
}

impl PhysicsJoint {
    /// A joint between the bodies of `body_a` and `body_b`.
    #[must_use]
    pub fn new(joint: impl Into<Joint>, body_a: Entity, body_b: Entity) -> Self {
        Self {
            joint: joint.into(),
            body_a: Some(body_a),
            body_b,
            contacts_enabled: true,
        }
    }

    /// A joint between the world (anchor A is a world point, m) and the body of `body`.
    #[must_use]
    pub fn to_world(joint: impl Into<Joint>, body: Entity) -> Self {
        Self {
            joint: joint.into(),
            body_a: None,
            body_b: body,
            contacts_enabled: true,
        }
    }

    /// Sets whether the two bodies collide with each other.
    #[must_use]
    pub const fn with_contacts_enabled(mut self, enabled: bool) -> Self {
        self.contacts_enabled = enabled;
        self
    }
}
