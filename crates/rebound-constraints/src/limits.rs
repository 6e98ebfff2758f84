//! Lower and upper limits on a joint coordinate (a hinge angle, a slide distance, a suspension travel),
//! enforced as one-sided speculative rows (see [`crate::part`]).

use crate::error::ConstraintError;
use crate::error::check_ordered;
use rebound_math::validity::check_finite;

rebound_math::checked_serde! { "Limits", Limits::validated;
/// A closed interval `[lower, upper]` for a joint coordinate (m or rad).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Limits {
    lower: f32,
    upper: f32,
}
}

impl Limits {
    /// The interval `[lower, upper]` (m or rad). `lower == upper` locks the coordinate.
    ///
    /// # Errors
    /// Non-finite bounds (fields `lower`, `upper`); `lower > upper` ([`ConstraintError::InvertedRange`]).
    pub fn new(lower: f32, upper: f32) -> Result<Self, ConstraintError> {
        check_finite("lower", lower)?;
        check_finite("upper", upper)?;
        check_ordered("lower", lower, "upper", upper)?;
        Ok(Self { lower, upper })
    }

    /// Returns `self` if it passes the checks of [`Limits::new`] (for values that bypassed it: deserialised).
    ///
    /// # Errors
    /// As [`Limits::new`].
    pub fn validated(self) -> Result<Self, ConstraintError> {
        Self::new(self.lower, self.upper)
    }

    /// The lower bound (m or rad).
    #[must_use]
    pub fn lower(&self) -> f32 {
        self.lower
    }

    /// The upper bound (m or rad).
    #[must_use]
    pub fn upper(&self) -> f32 {
        self.upper
    }
}
