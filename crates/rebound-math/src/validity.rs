//! Validity checks for values entering the engine (Box2D's `b2IsValid*`), in two flavours:
//! `is_valid_*` answers yes or no; `check_*` returns a [`MathError`] that names the field and the value.
//!
//! Not part of any step stage: inputs are checked once, where they enter (insertion, setters). Inside the
//! step the data is trusted.

use crate::{MathError, Quat, Vec3};

/// How far the length of a unit vector or quaternion may stray from 1 and still count as unit.
///
/// Matches glam's `is_normalized`, which accepts `|len² − 1| ≤ 2e-4`, i.e. `|len − 1| ≲ 1e-4`.
pub const UNIT_LENGTH_TOLERANCE: f32 = 1e-4;

/// Returns `true` when `v` is finite and its length is within [`UNIT_LENGTH_TOLERANCE`] of 1.
#[inline]
#[must_use]
pub fn is_unit_vec3(v: Vec3) -> bool {
    v.is_finite() && (v.length() - 1.0).abs() <= UNIT_LENGTH_TOLERANCE
}

/// Returns `true` when `q` is finite and its length is within [`UNIT_LENGTH_TOLERANCE`] of 1, i.e. a valid
/// rotation.
#[inline]
#[must_use]
pub fn is_valid_rotation(q: Quat) -> bool {
    q.is_finite() && (q.length() - 1.0).abs() <= UNIT_LENGTH_TOLERANCE
}

/// Checks that `value` is finite.
///
/// # Errors
/// [`MathError::NonFinite`] naming `field` when `value` is NaN or ±∞.
#[inline]
pub fn check_finite(field: &'static str, value: f32) -> Result<f32, MathError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(MathError::NonFinite { field, value })
    }
}

/// Checks that `value` is finite and strictly positive (a mass, a radius, a half-extent).
///
/// # Errors
/// [`MathError::NonFinite`] or [`MathError::NotPositive`], naming `field`.
#[inline]
pub fn check_positive(field: &'static str, value: f32) -> Result<f32, MathError> {
    check_finite(field, value)?;
    if value > 0.0 {
        Ok(value)
    } else {
        Err(MathError::NotPositive { field, value })
    }
}

/// Checks that `value` is finite and not negative (a damping coefficient, a length that may be zero).
///
/// # Errors
/// [`MathError::NonFinite`] or [`MathError::Negative`], naming `field`.
#[inline]
pub fn check_non_negative(field: &'static str, value: f32) -> Result<f32, MathError> {
    check_finite(field, value)?;
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(MathError::Negative { field, value })
    }
}

/// Checks that every component of `value` is finite.
///
/// # Errors
/// [`MathError::NonFiniteVector`] naming `field`.
#[inline]
pub fn check_finite_vec3(field: &'static str, value: Vec3) -> Result<Vec3, MathError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(MathError::NonFiniteVector { field, value })
    }
}

/// Checks that `value` is finite, non-zero and unit length (within [`UNIT_LENGTH_TOLERANCE`]).
///
/// The value is returned unchanged: a caller that wants exact unit length normalises it.
///
/// # Errors
/// [`MathError::NonFiniteVector`], [`MathError::ZeroLength`] or [`MathError::NonUnitVector`], naming `field`.
#[inline]
pub fn check_unit_vec3(field: &'static str, value: Vec3) -> Result<Vec3, MathError> {
    let length = check_direction(field, value)?.1;
    if (length - 1.0).abs() <= UNIT_LENGTH_TOLERANCE {
        Ok(value)
    } else {
        Err(MathError::NonUnitVector {
            field,
            value,
            length,
            tolerance: UNIT_LENGTH_TOLERANCE,
        })
    }
}

/// Checks that `value` is finite and has a length that can be normalised, and returns the unit direction and
/// the original length.
///
/// # Errors
/// [`MathError::NonFiniteVector`] or [`MathError::ZeroLength`], naming `field`.
#[inline]
pub fn check_direction(field: &'static str, value: Vec3) -> Result<(Vec3, f32), MathError> {
    check_finite_vec3(field, value)?;
    let length = value.length();
    // `length` can overflow to ∞ for huge finite components, and a tiny length gives a non-finite reciprocal.
    match value.try_normalize() {
        Some(unit) if length.is_finite() => Ok((unit, length)),
        _ if length == 0.0 => Err(MathError::ZeroLength { field, value }),
        _ => Err(MathError::NonFiniteVector { field, value }),
    }
}

/// Checks that `value` is a rotation: finite and unit length (within [`UNIT_LENGTH_TOLERANCE`]).
///
/// # Errors
/// [`MathError::NonFiniteQuat`] or [`MathError::NonUnitQuat`], naming `field`.
#[inline]
pub fn check_rotation(field: &'static str, value: Quat) -> Result<Quat, MathError> {
    if !value.is_finite() {
        return Err(MathError::NonFiniteQuat { field, value });
    }
    let length = value.length();
    if (length - 1.0).abs() <= UNIT_LENGTH_TOLERANCE {
        Ok(value)
    } else {
        Err(MathError::NonUnitQuat {
            field,
            value,
            length,
            tolerance: UNIT_LENGTH_TOLERANCE,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn finite_and_sign_checks_name_the_field_and_value() {
        assert_eq!(check_finite("mass", 2.0), Ok(2.0));
        let err = check_finite("mass", f32::NAN).unwrap_err();
        assert!(err.to_string().contains("`mass`"), "{err}");
        assert!(err.to_string().contains("NaN"), "{err}");
        assert_eq!(
            check_positive("radius", 0.0),
            Err(MathError::NotPositive {
                field: "radius",
                value: 0.0
            })
        );
        assert_eq!(
            check_positive("radius", -1.0),
            Err(MathError::NotPositive {
                field: "radius",
                value: -1.0
            })
        );
        assert!(matches!(
            check_positive("radius", f32::INFINITY),
            Err(MathError::NonFinite { .. })
        ));
        assert_eq!(check_non_negative("damping", 0.0), Ok(0.0));
        assert!(matches!(
            check_non_negative("damping", -0.1),
            Err(MathError::Negative {
                field: "damping",
                ..
            })
        ));
    }

    #[test]
    fn direction_checks_reject_zero_nan_and_non_unit() {
        assert_eq!(check_unit_vec3("axis", Vec3::Y), Ok(Vec3::Y));
        assert!(matches!(
            check_unit_vec3("axis", Vec3::ZERO),
            Err(MathError::ZeroLength { field: "axis", .. })
        ));
        assert!(matches!(
            check_unit_vec3("axis", Vec3::new(f32::NAN, 0.0, 0.0)),
            Err(MathError::NonFiniteVector { field: "axis", .. })
        ));
        let err = check_unit_vec3("axis", Vec3::new(0.0, 2.0, 0.0)).unwrap_err();
        assert!(
            matches!(err, MathError::NonUnitVector { length, .. } if (length - 2.0).abs() < 1e-6)
        );
        assert!(err.to_string().contains("with length 2"), "{err}");
        // Overflowing length: finite components whose length is not representable.
        assert!(check_direction("axis", Vec3::splat(f32::MAX)).is_err());
        // A tiny but non-zero vector normalises.
        let (unit, _) = check_direction("axis", Vec3::new(1e-15, 0.0, 0.0)).unwrap();
        assert!(is_unit_vec3(unit));
    }

    #[test]
    fn rotation_check_accepts_unit_and_rejects_the_rest() {
        assert!(check_rotation("rotation", Quat::IDENTITY).is_ok());
        assert!(is_valid_rotation(Quat::from_rotation_y(1.0)));
        assert!(matches!(
            check_rotation("rotation", Quat::from_xyzw(0.0, 0.0, 0.0, 2.0)),
            Err(MathError::NonUnitQuat { .. })
        ));
        assert!(matches!(
            check_rotation("rotation", Quat::from_xyzw(0.0, f32::NAN, 0.0, 1.0)),
            Err(MathError::NonFiniteQuat { .. })
        ));
        assert!(!is_valid_rotation(Quat::from_xyzw(0.0, 0.0, 0.0, 0.0)));
    }
}
