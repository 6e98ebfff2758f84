//! Typed errors for invalid constraint input, checked where values enter (constructors and setters). Not part
//! of any step stage: the solver trusts validated data.

use rebound_math::MathError;

/// An invalid constraint parameter. Nothing is changed when one is returned.
#[derive(Debug, Clone, Copy, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ConstraintError {
    /// A number or vector failed a basic check (non-finite, negative, zero length, non-unit); the message names
    /// the field and the value.
    #[error(transparent)]
    Math(#[from] MathError),
    /// A value that may be infinite (a force cap, a break force) was NaN.
    #[error("`{field}` must not be NaN")]
    NotANumber {
        /// The name of the offending field or argument.
        field: &'static str,
    },
    /// A bound that may be infinite only away from the interval it bounds was infinite towards it (a lower
    /// force cap of +∞, an upper one of −∞): no value would pass.
    #[error("`{field}` may be infinite only as no bound at all, got {value}")]
    InfiniteTowardsTheRange {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: f32,
    },
    /// A lower bound exceeded its upper bound.
    #[error("`{lower_field}` ({lower}) must not exceed `{upper_field}` ({upper})")]
    InvertedRange {
        /// The name of the lower bound.
        lower_field: &'static str,
        /// The lower bound that was given.
        lower: f32,
        /// The name of the upper bound.
        upper_field: &'static str,
        /// The upper bound that was given.
        upper: f32,
    },
    /// A value lay outside the interval it must lie in.
    #[error("`{field}` must lie in [{min}, {max}], got {value}")]
    OutOfRange {
        /// The name of the offending field or argument.
        field: &'static str,
        /// The value that was given.
        value: f32,
        /// The smallest accepted value.
        min: f32,
        /// The largest accepted value.
        max: f32,
    },
    /// Two directions that must span a plane were parallel (or one of them was zero).
    #[error("`{field}` must not be parallel to the primary axis")]
    ParallelAxes {
        /// The name of the offending field or argument.
        field: &'static str,
    },
    /// A setter was called on a joint kind that has no such feature (a motor on a rope, limits on a ball joint).
    #[error("a {kind} joint has no {feature}")]
    Unsupported {
        /// The joint kind, e.g. `"rope"`.
        kind: &'static str,
        /// The feature asked for, e.g. `"motor"`.
        feature: &'static str,
    },
}

/// Rejects NaN but accepts ±∞ (used for caps where ∞ means "none").
pub(crate) fn check_not_nan(field: &'static str, value: f32) -> Result<f32, ConstraintError> {
    if value.is_nan() {
        Err(ConstraintError::NotANumber { field })
    } else {
        Ok(value)
    }
}

/// Accepts `value ≥ 0`, including +∞; rejects NaN and negatives.
pub(crate) fn check_non_negative_or_infinite(
    field: &'static str,
    value: f32,
) -> Result<f32, ConstraintError> {
    check_not_nan(field, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(MathError::Negative { field, value }.into())
    }
}

/// Accepts `value > 0`, including +∞; rejects NaN, zero and negatives.
pub(crate) fn check_positive_or_infinite(
    field: &'static str,
    value: f32,
) -> Result<f32, ConstraintError> {
    check_not_nan(field, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(MathError::NotPositive { field, value }.into())
    }
}

/// Checks `lower ≤ upper` (after each passed its own check).
pub(crate) fn check_ordered(
    lower_field: &'static str,
    lower: f32,
    upper_field: &'static str,
    upper: f32,
) -> Result<(), ConstraintError> {
    if lower <= upper {
        Ok(())
    } else {
        Err(ConstraintError::InvertedRange {
            lower_field,
            lower,
            upper_field,
            upper,
        })
    }
}

/// Checks `min ≤ value ≤ max` for a finite `value`.
pub(crate) fn check_in_range(
    field: &'static str,
    value: f32,
    min: f32,
    max: f32,
) -> Result<f32, ConstraintError> {
    rebound_math::validity::check_finite(field, value)?;
    if (min..=max).contains(&value) {
        Ok(value)
    } else {
        Err(ConstraintError::OutOfRange {
            field,
            value,
            min,
            max,
        })
    }
}
