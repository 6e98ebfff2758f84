//! Rotations in the plane: the course's 2D rotation matrix (course item 14).
//!
//! ```text
//! R(θ) = | cos θ  −sin θ |
//!        | sin θ   cos θ |
//! ```
//!
//! It rotates column vectors counter-clockwise by θ radians: `R(90°)·(1, 0) = (0, 1)`.

use crate::{Mat2, Vec2};

/// The 2D rotation matrix `R(θ)` for `angle` θ in radians (counter-clockwise, column vectors).
///
/// Written from the course's formula; equal to glam's [`Mat2::from_angle`].
///
/// ```
/// use rebound_math::{rotation2d::rotation_2d, Vec2};
/// let v = rotation_2d(std::f32::consts::FRAC_PI_2) * Vec2::X;
/// assert!(v.abs_diff_eq(Vec2::Y, 1e-7));
/// ```
#[inline]
#[must_use]
pub fn rotation_2d(angle: f32) -> Mat2 {
    let (sin, cos) = crate::real::sin_cos(angle);
    // Columns: the images of (1, 0) and (0, 1).
    Mat2::from_cols(Vec2::new(cos, sin), Vec2::new(-sin, cos))
}

/// Rotates `v` counter-clockwise by `angle` radians: `R(θ)·v`.
#[inline]
#[must_use]
pub fn rotate_2d(v: Vec2, angle: f32) -> Vec2 {
    rotation_2d(angle) * v
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f32::consts::{FRAC_PI_2, PI};
    use proptest::prelude::*;

    #[test]
    fn course_example_rotates_x_by_90_degrees_onto_y() {
        // The course: R(90°)·(1, 0) = (0, 1), with R(90°) = [[0, −1], [1, 0]].
        let r = rotation_2d(FRAC_PI_2);
        assert!(r.abs_diff_eq(Mat2::from_cols(Vec2::Y, -Vec2::X), 1e-7));
        assert!(rotate_2d(Vec2::X, FRAC_PI_2).abs_diff_eq(Vec2::Y, 1e-7));
        assert!(rotate_2d(Vec2::X, PI).abs_diff_eq(-Vec2::X, 1e-7));
    }

    proptest! {
        #[test]
        fn matches_glam_and_preserves_length(angle in -10.0f32..10.0, x in -100.0f32..100.0, y in -100.0f32..100.0) {
            let v = Vec2::new(x, y);
            prop_assert!(rotation_2d(angle).abs_diff_eq(Mat2::from_angle(angle), 1e-6));
            let w = rotate_2d(v, angle);
            prop_assert!((w.length() - v.length()).abs() <= 1e-4 * (1.0 + v.length()));
            // Rotating back gives the input: R(−θ)·R(θ) = I.
            prop_assert!(rotate_2d(w, -angle).abs_diff_eq(v, 1e-4 * (1.0 + v.length())));
        }
    }
}
