//! Typed errors of the world API. Every error names what was wrong; nothing changes when one is returned.

use crate::{BodyHandle, JointHandle};
use rebound_dynamics::DynamicsError;
use rebound_math::MathError;

/// An invalid call on a [`crate::World`].
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum WorldError {
    /// A number failed a basic check; the message names the field and the value.
    #[error(transparent)]
    Math(#[from] MathError),
    /// A body description or setter argument was invalid.
    #[error(transparent)]
    Dynamics(#[from] DynamicsError),
    /// A joint description was invalid.
    #[error(transparent)]
    Constraint(#[from] rebound_constraints::ConstraintError),
    /// A setting had an invalid value.
    #[error("world setting `{field}` is invalid: {value}")]
    InvalidSetting {
        /// The setting's name.
        field: &'static str,
        /// The value given (converted to f32).
        value: f32,
    },
    /// A count or rate setting lay outside its documented bounds.
    #[error("world setting `{field}` must lie in [{min}, {max}], got {value}")]
    SettingOutOfRange {
        /// The setting's name.
        field: &'static str,
        /// The value given (converted to f32).
        value: f32,
        /// The smallest accepted value.
        min: f32,
        /// The largest accepted value.
        max: f32,
    },
    /// A step length was shorter than [`crate::MIN_STEP_DT`].
    #[error("world setting `{field}` must be at least {min:e} s, got {value:e} s")]
    StepTooShort {
        /// The setting's name.
        field: &'static str,
        /// The value given (s).
        value: f32,
        /// The shortest accepted step (s).
        min: f32,
    },
    /// The body handle refers to no body in this world (removed, or from another world).
    #[error("stale or foreign body handle {0:?}")]
    StaleBody(BodyHandle),
    /// The joint handle refers to no joint in this world.
    #[error("stale or foreign joint handle {0:?}")]
    StaleJoint(JointHandle),
    /// A kinematic target was set on a body that is not kinematic (a dynamic body is moved by forces, a
    /// fixed one not at all).
    #[error("body {handle:?} is {body_type:?}: a kinematic target needs a kinematic body")]
    NotKinematic {
        /// The body.
        handle: BodyHandle,
        /// Its type.
        body_type: rebound_dynamics::BodyType,
    },
    /// A joint would connect a body to itself.
    #[error("a joint needs two different bodies, got {0:?} twice")]
    SameBody(BodyHandle),
    /// A world cannot hold more objects of this kind (2³² − 1).
    #[error("the world is full: no more {0} can be inserted")]
    Full(&'static str),
    /// A snapshot could not be restored (made by an incompatible version, or with inconsistent tables).
    #[error("snapshot cannot be restored: {0}")]
    BadSnapshot(&'static str),
    /// A snapshot held a value its constructors would have refused, or a handle that resolves to nothing in
    /// it: `item` says where (`body 3`, `manifold 0, point 1`), `source` what (naming the field and value).
    #[error("snapshot cannot be restored: {item}: {source}")]
    InvalidSnapshot {
        /// Where in the snapshot.
        item: String,
        /// The error its constructor, setter or handle lookup would have returned.
        source: Box<WorldError>,
    },
}
