//! Typed errors for invalid dynamics input (checked where values enter: body creation, setters, mass
//! properties). Not part of any step stage; the step trusts validated data.

use rebound_math::{Mat3, MathError, Vec3};

/// An invalid input to a body, mass-property or impulse function. Nothing is changed when one is returned.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum DynamicsError {
    /// A number or vector failed a basic check (non-finite, zero, negative, non-unit); the message names the
    /// field and the value.
    #[error(transparent)]
    Math(#[from] MathError),
    /// An inertia tensor given by hand was not symmetric positive semi-definite.
    #[error(
        "`{field}` must be a symmetric positive semi-definite inertia tensor (kg·m²), got {value}"
    )]
    InvalidInertia {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: Mat3,
    },
    /// A mass so small that its inverse overflows (below about 3e-39 kg): the solver would divide by it.
    #[error("`{field}` must be at least {min:e} kg so that its inverse is finite, got {value:e}")]
    MassTooSmall {
        /// The name of the offending field.
        field: &'static str,
        /// The value given (kg).
        value: f32,
        /// The smallest accepted mass (kg).
        min: f32,
    },
    /// Adding a force or torque to what the body has accumulated for the next step would make the sum
    /// non-finite (each increment finite, their sum overflowing `f32`).
    #[error(
        "adding {added} to the accumulated `{field}` {accumulated} would make it non-finite; nothing was added"
    )]
    AccumulatedNotFinite {
        /// `"force"` (N) or `"torque"` (N·m).
        field: &'static str,
        /// What had been accumulated before the call.
        accumulated: Vec3,
        /// What the call would have added.
        added: Vec3,
    },
    /// [`crate::MassProperties::combine`] was given no parts, or parts whose masses sum to zero.
    #[error("mass parts must have a positive total mass, got {total_mass} kg from {count} parts")]
    NoMass {
        /// The number of parts given.
        count: usize,
        /// Their total mass (kg).
        total_mass: f32,
    },
}
