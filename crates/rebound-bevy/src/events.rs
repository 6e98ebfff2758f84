//! [`PhysicsEvent`]: the facade's events (contacts, contact forces, sensors, sleep, broken joints) with entities in place of
//! handles, sent as Bevy messages by the writeback systems after each step, in the facade's deterministic
//! order.

use bevy_ecs::entity::Entity;
use bevy_ecs::message::Message;
use rebound::prelude::Vec3;

/// Something that happened during a physics step, naming entities. Read with
/// `MessageReader<PhysicsEvent>`. One type for every kind keeps the facade's order across kinds.
#[derive(Message, Debug, Clone, Copy, PartialEq)]
pub enum PhysicsEvent {
    /// The bodies of two entities started touching.
    ContactBegan {
        /// The body entity of the pair's body A.
        entity_a: Entity,
        /// The body entity of body B.
        entity_b: Entity,
        /// How fast they approached along the normal when they met (m/s, ≥ 0).
        approach_speed: f32,
    },
    /// The bodies of two entities stopped touching (or one was despawned).
    ContactEnded {
        /// The body entity of body A.
        entity_a: Entity,
        /// The body entity of body B.
        entity_b: Entity,
    },
    /// A contact pushed with at least the force event threshold of one of its colliders this step
    /// (`rebound::ColliderDesc::force_event_threshold`): for impact sounds and damage.
    ContactForce {
        /// The body entity of the pair's body A.
        entity_a: Entity,
        /// The body entity of body B.
        entity_b: Entity,
        /// The entities of the pair's colliders (on A, on B), if the step named them.
        colliders: Option<(Entity, Entity)>,
        /// The manifold's unit normal, world axes, from A to B: B was pushed along it, A against it.
        normal: Vec3,
        /// The normal impulse of the step, summed over its points and substeps (N·s).
        total_impulse: f32,
        /// The mean normal force of the step, `total_impulse / dt` (N).
        total_force: f32,
        /// The point that applied the largest impulse, world space at the end of the step (m).
        max_impulse_point: Vec3,
        /// That point's impulse over the step (N·s).
        max_impulse: f32,
    },
    /// A collider started overlapping a sensor.
    SensorEntered {
        /// The entity of the sensor's collider.
        sensor: Entity,
        /// The entity of the collider that entered.
        collider: Entity,
    },
    /// A collider stopped overlapping a sensor.
    SensorExited {
        /// The entity of the sensor's collider.
        sensor: Entity,
        /// The entity of the collider that left.
        collider: Entity,
    },
    /// A body fell asleep.
    BodyFellAsleep {
        /// The body entity.
        entity: Entity,
    },
    /// A sleeping body woke up.
    BodyWoke {
        /// The body entity.
        entity: Entity,
    },
    /// A body left the engine's bounds (`rebound::StepLimits`) and was taken out of the steps.
    BodyQuarantined {
        /// The body entity.
        entity: Entity,
    },
    /// A joint exceeded its break force or torque and is now disabled.
    JointBroken {
        /// The entity holding the [`crate::PhysicsJoint`].
        joint: Entity,
    },
}
