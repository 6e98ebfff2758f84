//! Events a step produces, drained by the user after it (stage *events*, last in the step). Produced in a
//! deterministic order: contact events in body-pair order, then broken joints, then sleep changes, each
//! sorted by handle.

use crate::{BodyHandle, JointHandle};

/// Something that happened during the last step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
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
    /// Two bodies stopped touching (or one was removed).
    ContactEnded {
        /// Body A of the pair.
        body_a: BodyHandle,
        /// Body B of the pair.
        body_b: BodyHandle,
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
}
