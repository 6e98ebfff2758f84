//! The facade's events: the world's (contacts, joints, sleep) plus sensor overlaps, produced after each step
//! in a deterministic order — the world's events first (contact events in body-pair order, then broken
//! joints, sleep changes and wakes), then sensor events: entries in (sensor, collider) order, then exits in
//! (sensor, collider) order.

use crate::ColliderHandle;
use rebound_world::{BodyHandle, ContactForce, JointHandle, QuarantineReason};
use serde::{Deserialize, Serialize};

/// Something that happened during the last step (or the steps of the last `advance`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Event {
    /// Two bodies started touching.
    ContactBegan {
        /// Body A of the pair (the lower handle).
        body_a: BodyHandle,
        /// Body B of the pair.
        body_b: BodyHandle,
        /// How fast they approached along the normal when they met (m/s, ≥ 0).
        approach_speed: f32,
    },
    /// Two bodies stopped touching (or one was removed, or their contacts were disabled).
    ContactEnded {
        /// Body A of the pair.
        body_a: BodyHandle,
        /// Body B of the pair.
        body_b: BodyHandle,
    },
    /// A contact pushed with at least the force event threshold of one of its colliders this step
    /// ([`crate::ColliderDesc::force_event_threshold`]).
    ContactForce {
        /// The pair's colliders (A, on body A, the lower handle; B), or `None` for a world event converted
        /// outside a [`crate::PhysicsWorld`] step.
        colliders: Option<(ColliderHandle, ColliderHandle)>,
        /// The forces: total normal impulse (N·s) and mean force (N) of the step, the normal, the point
        /// with the largest impulse.
        force: ContactForce,
    },
    /// A joint's impulse exceeded its break force or torque; it is now disabled.
    JointBroken {
        /// The joint.
        joint: JointHandle,
    },
    /// A body fell asleep with its island.
    BodyFellAsleep {
        /// The body.
        body: BodyHandle,
    },
    /// A sleeping body woke up.
    BodyWoke {
        /// The body.
        body: BodyHandle,
    },
    /// A body left the bounds of [`rebound_world::StepLimits`] (or its solver result was not finite) and was
    /// taken out of the steps until [`crate::PhysicsWorld::release_quarantine`].
    BodyQuarantined {
        /// The body.
        body: BodyHandle,
        /// What was out of bounds.
        reason: QuarantineReason,
    },
    /// A collider started overlapping a sensor (at the poses after the step).
    SensorEntered {
        /// The sensor collider.
        sensor: ColliderHandle,
        /// The collider that entered it.
        collider: ColliderHandle,
    },
    /// A collider stopped overlapping a sensor (it left, was removed or disabled, or the sensor was).
    SensorExited {
        /// The sensor collider.
        sensor: ColliderHandle,
        /// The collider that left it.
        collider: ColliderHandle,
    },
}

impl From<rebound_world::Event> for Event {
    fn from(event: rebound_world::Event) -> Self {
        use rebound_world::Event as W;
        match event {
            W::ContactBegan {
                body_a,
                body_b,
                approach_speed,
            } => Self::ContactBegan {
                body_a,
                body_b,
                approach_speed,
            },
            W::ContactEnded { body_a, body_b } => Self::ContactEnded { body_a, body_b },
            W::ContactForce(force) => Self::ContactForce {
                colliders: None,
                force,
            },
            W::JointBroken { joint } => Self::JointBroken { joint },
            W::BodyFellAsleep { body } => Self::BodyFellAsleep { body },
            W::BodyWoke { body } => Self::BodyWoke { body },
            W::BodyQuarantined { body, reason } => Self::BodyQuarantined { body, reason },
        }
    }
}
