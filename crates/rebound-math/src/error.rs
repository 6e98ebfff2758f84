//! Typed errors for invalid math input (not part of any step stage: inputs are checked where they enter).
//!
//! Every variant names the offending field and carries the value, so a message reads like
//! ``axis` must be unit length (|v| = 1 ± 1e-4), got [0.0, 2.0, 0.0] with length 2``.

use glam::{Quat, Vec3};

/// An invalid input to a `rebound-math` constructor or checker.
///
/// Functions that return this error change nothing: they either build a new value or fail.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum MathError {
    /// A scalar was NaN or infinite.
    #[error("`{field}` must be finite, got {value}")]
    NonFinite {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: f32,
    },
    /// A scalar that must be strictly positive was zero or negative.
    #[error("`{field}` must be > 0, got {value}")]
    NotPositive {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: f32,
    },
    /// A scalar that must not be negative was negative.
    #[error("`{field}` must be >= 0, got {value}")]
    Negative {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: f32,
    },
    /// A vector had a NaN or infinite component.
    #[error("`{field}` must be finite, got {value}")]
    NonFiniteVector {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: Vec3,
    },
    /// A direction (an axis, a normal) had zero length, so it names no direction.
    #[error("`{field}` must not be zero-length, got {value}")]
    ZeroLength {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: Vec3,
    },
    /// A direction that must be unit length was not (see [`crate::UNIT_LENGTH_TOLERANCE`]).
    #[error(
        "`{field}` must be unit length (|v| = 1 ± {tolerance}), got {value} with length {length}"
    )]
    NonUnitVector {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: Vec3,
        /// Its length.
        length: f32,
        /// The accepted deviation of the length from 1.
        tolerance: f32,
    },
    /// A quaternion had a NaN or infinite component.
    #[error("`{field}` must be finite, got {value}")]
    NonFiniteQuat {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: Quat,
    },
    /// A rotation quaternion was not unit length (see [`crate::UNIT_LENGTH_TOLERANCE`]).
    #[error(
        "`{field}` must be a unit quaternion (|q| = 1 ± {tolerance}), got {value} with length {length}"
    )]
    NonUnitQuat {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: Quat,
        /// Its length.
        length: f32,
        /// The accepted deviation of the length from 1.
        tolerance: f32,
    },
    /// A scale vector had a zero component, which would collapse space and make the model matrix singular.
    #[error("`{field}` must have no zero component, got {value}")]
    ZeroScale {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: Vec3,
    },
    /// Two transforms whose product has shear cannot be written as translation · rotation · scale.
    ///
    /// This happens when the parent has a non-uniform scale and the child is rotated (or the transform to be
    /// inverted has a non-uniform scale and a rotation). Use the 4×4 model matrices instead.
    #[error(
        "the result has shear and is not a translation-rotation-scale transform: `{field}` has non-uniform scale {scale} and a rotation is applied after it"
    )]
    ShearingScale {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The non-uniform scale.
        scale: Vec3,
    },
}
