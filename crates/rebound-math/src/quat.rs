//! Quaternions as the course writes them (course items 16–18), and orientation integration.
//!
//! Conventions: Hamilton quaternions. glam stores `(x, y, z, w)`; the course writes `(w, i, j, k)` with
//! `i = x`, `j = y`, `k = z`. [`to_wijk`] and [`from_wijk`] convert between the two orders.
//!
//! Not part of a step stage itself; [`integrate_rotation`] is what the position-integration stage calls.
//!
//! # The course's rotation matrix is a transpose
//!
//! The course converts a quaternion to
//!
//! ```text
//!     | 1 − 2(j² + k²)   2(ij + kw)       2(ik − jw)     |
//! R = | 2(ij − kw)       1 − 2(i² + k²)   2(jk + iw)     |
//!     | 2(ik + jw)       2(jk − iw)       1 − 2(i² + j²) |
//! ```
//!
//! which is the **transpose** of the column-vector matrix glam builds ([`Mat3::from_quat`], used by
//! [`to_mat3`]). The course's matrix rotates *row* vectors (`v' = v·R`); applied to a column vector it
//! performs the inverse rotation. [`course_to_mat3`] builds it exactly as printed so the relation is tested,
//! not assumed.

use crate::validity::{check_direction, check_finite, check_unit_vec3};
use crate::{Mat3, MathError, Quat, Vec3};

/// Converts a glam quaternion to the course's component order `[w, i, j, k]`.
#[inline]
#[must_use]
pub fn to_wijk(q: Quat) -> [f32; 4] {
    [q.w, q.x, q.y, q.z]
}

/// Builds a glam quaternion from the course's component order `[w, i, j, k]`.
#[inline]
#[must_use]
pub fn from_wijk([w, i, j, k]: [f32; 4]) -> Quat {
    Quat::from_xyzw(i, j, k, w)
}

/// The rotation by `angle` radians about the unit `axis`, by the course's formula (course item 16):
///
/// ```text
/// q = (cos θ/2, x·sin θ/2, y·sin θ/2, z·sin θ/2)      (w, i, j, k)
/// ```
///
/// The rotation is counter-clockwise about `axis` (right-hand rule). Equal to glam's
/// [`Quat::from_axis_angle`], which panics (with `glam-assert`) or silently returns a non-unit quaternion on
/// a bad axis; this function refuses it instead.
///
/// # Errors
/// The axis must be finite, non-zero and unit length within [`crate::UNIT_LENGTH_TOLERANCE`]
/// ([`MathError::NonFiniteVector`], [`MathError::ZeroLength`], [`MathError::NonUnitVector`], field `axis`);
/// the angle must be finite ([`MathError::NonFinite`], field `angle`). Use [`from_axis_angle_normalized`] to
/// accept any non-zero axis.
///
/// ```
/// use rebound_math::{quat::from_unit_axis_angle, Vec3};
/// let q = from_unit_axis_angle(Vec3::Z, std::f32::consts::FRAC_PI_2)?;
/// assert!((q * Vec3::X).abs_diff_eq(Vec3::Y, 1e-6));
/// assert!(from_unit_axis_angle(Vec3::ZERO, 1.0).is_err());
/// # Ok::<(), rebound_math::MathError>(())
/// ```
#[inline]
pub fn from_unit_axis_angle(axis: Vec3, angle: f32) -> Result<Quat, MathError> {
    check_unit_vec3("axis", axis)?;
    check_finite("angle", angle)?;
    // Normalise anyway so that the result is unit to the last bit the tolerance allowed.
    let axis = axis.normalize();
    let (sin, cos) = crate::real::sin_cos(0.5 * angle);
    Ok(from_wijk([cos, axis.x * sin, axis.y * sin, axis.z * sin]))
}

/// Like [`from_unit_axis_angle`], but normalises any finite non-zero `axis` first.
///
/// # Errors
/// [`MathError::NonFiniteVector`] or [`MathError::ZeroLength`] (field `axis`), [`MathError::NonFinite`]
/// (field `angle`).
#[inline]
pub fn from_axis_angle_normalized(axis: Vec3, angle: f32) -> Result<Quat, MathError> {
    let (unit, _) = check_direction("axis", axis)?;
    from_unit_axis_angle(unit, angle)
}

/// The course's component formula for the quaternion product `q·p` (course item 17):
///
/// ```text
/// w = w₁w₂ − (i₁i₂ + j₁j₂ + k₁k₂)
/// i = w₁i₂ + w₂i₁ + j₁k₂ − k₁j₂
/// j = w₁j₂ + w₂j₁ + k₁i₂ − i₁k₂
/// k = w₁k₂ + w₂k₁ + i₁j₂ − j₁i₂
/// ```
///
/// The product applies `p` first, then `q`: `(q·p)·v = q·(p·v)`. It is the Hamilton product, equal to glam's
/// `q * p` (tested); the engine itself uses glam's SIMD version.
#[inline]
#[must_use]
pub fn course_mul(q: Quat, p: Quat) -> Quat {
    let [w1, i1, j1, k1] = to_wijk(q);
    let [w2, i2, j2, k2] = to_wijk(p);
    from_wijk([
        w1 * w2 - (i1 * i2 + j1 * j2 + k1 * k2),
        w1 * i2 + w2 * i1 + j1 * k2 - k1 * j2,
        w1 * j2 + w2 * j1 + k1 * i2 - i1 * k2,
        w1 * k2 + w2 * k1 + i1 * j2 - j1 * i2,
    ])
}

/// Rotates `v` by the unit quaternion `q`: `q·v·q*`, computed as `v + w·t + u × t` with `t = 2 u × v`
/// (`u` the vector part of `q`, `w` its scalar part). The same rotation as glam's `q * v` (tested to 1e-5).
///
/// **Use this, not `q * v`, on the step's paths.** glam's SIMD `Quat * Vec3` widens the vector to four lanes
/// and only reads three back, so the optimiser is free to fill the fourth lane with whatever sits next to the
/// vector in memory — a struct's padding, a neighbouring integer. Those bits are often a subnormal float, and a
/// multiply that meets one takes a microcode assist of a hundred cycles or more. In the pyramid scene the two
/// pose compositions of every contact pair spent two thirds of the collide phase in such assists (the
/// collide phase ran 1.6× faster with subnormals flushed to zero). This scalar form touches only the three
/// components, so no lane is undefined (about as many instructions as the SIMD form).
#[inline]
#[must_use]
pub fn rotate(q: Quat, v: Vec3) -> Vec3 {
    rotate_by_parts(Vec3::new(q.x, q.y, q.z), q.w, v)
}

/// Rotates `v` by the inverse of the unit quaternion `q` (`q*·v·q`) — [`rotate`] by the conjugate, without
/// building it.
#[inline]
#[must_use]
pub fn rotate_inverse(q: Quat, v: Vec3) -> Vec3 {
    rotate_by_parts(Vec3::new(-q.x, -q.y, -q.z), q.w, v)
}

/// `v` rotated by the unit quaternion with vector part `u` and scalar part `w`: `v + w·t + u × t`,
/// `t = 2 u × v` (see [`rotate`]).
#[inline]
fn rotate_by_parts(u: Vec3, w: f32, v: Vec3) -> Vec3 {
    let t = 2.0 * u.cross(v);
    v + w * t + u.cross(t)
}

/// The rotation matrix of the unit quaternion `q` in glam's column-vector convention: `v' = R·v`.
///
/// Same as [`Mat3::from_quat`]. See [`course_to_mat3`] for the course's (transposed) form.
#[inline]
#[must_use]
pub fn to_mat3(q: Quat) -> Mat3 {
    Mat3::from_quat(q)
}

/// The course's quaternion → matrix formula exactly as printed (course item 18), for the unit quaternion `q`.
///
/// This is the **transpose** of [`to_mat3`]: it rotates row vectors (`v' = v·R`), or, applied to column
/// vectors, rotates by `q⁻¹`. Do not feed it to code that expects glam's convention.
#[inline]
#[must_use]
pub fn course_to_mat3(q: Quat) -> Mat3 {
    let [w, i, j, k] = to_wijk(q);
    let rows = [
        [
            1.0 - 2.0 * (j * j + k * k),
            2.0 * (i * j + k * w),
            2.0 * (i * k - j * w),
        ],
        [
            2.0 * (i * j - k * w),
            1.0 - 2.0 * (i * i + k * k),
            2.0 * (j * k + i * w),
        ],
        [
            2.0 * (i * k + j * w),
            2.0 * (j * k - i * w),
            1.0 - 2.0 * (i * i + j * j),
        ],
    ];
    // glam is column-major: a matrix given row by row is the transpose of the one given column by column.
    Mat3::from_cols_array_2d(&rows).transpose()
}

/// How [`integrate_rotation`] advances an orientation by an angular velocity.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub enum RotationIntegrator {
    /// First order: `q ← normalise(q + ½·h·(ω, 0)·q)`. The classic game-engine update (Box2D, rapier);
    /// it under-rotates by `O((|ω|h)³)` per step. Default.
    #[default]
    FirstOrder,
    /// The exact exponential map: `q ← exp(½·h·ω)·q`, a rotation by `|ω|·h` about `ω/|ω|`. Exact for a
    /// constant ω over the step, at the cost of a `sin`/`cos`.
    Exact,
}

/// Advances the orientation `q` by the world-space angular velocity `angular_velocity` (rad/s) over `h`
/// seconds, and returns a unit quaternion.
///
/// The kinematic equation is `dq/dt = ½·(ω, 0)·q` with ω in world space (a left multiplication).
/// [`RotationIntegrator`] picks its discretisation.
///
/// Non-finite input is not checked here (the step trusts validated data); the result is the input `q`
/// whenever the update would not be normalisable, so it never produces a zero quaternion.
#[inline]
#[must_use]
pub fn integrate_rotation(
    q: Quat,
    angular_velocity: Vec3,
    h: f32,
    method: RotationIntegrator,
) -> Quat {
    let next = match method {
        RotationIntegrator::FirstOrder => {
            let omega = Quat::from_xyzw(
                angular_velocity.x,
                angular_velocity.y,
                angular_velocity.z,
                0.0,
            );
            q + omega * q * (0.5 * h)
        }
        RotationIntegrator::Exact => Quat::from_scaled_axis(angular_velocity * h) * q,
    };
    next.try_normalize().unwrap_or(q)
}

/// The angle (radians, in `[0, π]`) of the rotation that takes `from` to `to`, accurate for small angles.
///
/// glam's [`Quat::angle_between`] uses `acos` of the dot product, whose `f32` resolution near 0 is about
/// `3e-4` rad; this uses `2·atan2(|v|, |w|)` of the relative rotation instead, accurate to a few ulps.
#[inline]
#[must_use]
pub fn angle_between(from: Quat, to: Quat) -> f32 {
    let relative = to * from.conjugate();
    2.0 * crate::real::atan2(relative.xyz().length(), relative.w.abs())
}

/// glam 0.33's `Quat` has no `try_normalize`; this adds it in the glam spirit.
trait TryNormalize: Sized {
    fn try_normalize(self) -> Option<Self>;
}

impl TryNormalize for Quat {
    #[inline]
    fn try_normalize(self) -> Option<Self> {
        let inv_length = self.length_recip();
        (inv_length.is_finite() && inv_length > 0.0).then(|| self * inv_length)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f32::consts::{FRAC_PI_2, PI};
    use proptest::prelude::*;

    const EPS: f32 = 1e-5;

    fn unit_quat() -> impl Strategy<Value = Quat> {
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0)
            .prop_filter("non-degenerate", |(x, y, z, w)| {
                x * x + y * y + z * z + w * w > 1e-2
            })
            .prop_map(|(x, y, z, w)| Quat::from_xyzw(x, y, z, w).normalize())
    }

    fn vec3(range: f32) -> impl Strategy<Value = Vec3> {
        (-range..range, -range..range, -range..range).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    #[test]
    fn course_axis_angle_matches_the_formula_and_glam() {
        let q = from_unit_axis_angle(Vec3::Z, FRAC_PI_2).unwrap();
        let half = FRAC_PI_2 / 2.0;
        assert!(
            (q.w - crate::real::cos(half)).abs() < EPS
                && (q.z - crate::real::sin(half)).abs() < EPS
        );
        assert!(q.abs_diff_eq(Quat::from_axis_angle(Vec3::Z, FRAC_PI_2), EPS));
        // 90° about z takes x to y, as the 2D example.
        assert!((q * Vec3::X).abs_diff_eq(Vec3::Y, EPS));
    }

    #[test]
    fn bad_axes_are_errors() {
        assert!(matches!(
            from_unit_axis_angle(Vec3::ZERO, 1.0),
            Err(MathError::ZeroLength { field: "axis", .. })
        ));
        assert!(matches!(
            from_unit_axis_angle(Vec3::new(f32::NAN, 0.0, 0.0), 1.0),
            Err(MathError::NonFiniteVector { field: "axis", .. })
        ));
        assert!(matches!(
            from_unit_axis_angle(Vec3::new(0.0, 3.0, 0.0), 1.0),
            Err(MathError::NonUnitVector { field: "axis", .. })
        ));
        assert!(matches!(
            from_unit_axis_angle(Vec3::Y, f32::INFINITY),
            Err(MathError::NonFinite { field: "angle", .. })
        ));
        // The normalising variant accepts a long axis but still refuses a zero one.
        let q = from_axis_angle_normalized(Vec3::new(0.0, 3.0, 0.0), PI).unwrap();
        assert!(q.abs_diff_eq(Quat::from_rotation_y(PI), EPS));
        assert!(from_axis_angle_normalized(Vec3::ZERO, 1.0).is_err());
    }

    #[test]
    fn course_matrix_is_the_transpose_of_glams() {
        let q = from_unit_axis_angle(Vec3::Z, FRAC_PI_2).unwrap();
        // glam: column vectors, x → y. The course's matrix applied to a column vector rotates the other way.
        assert!((to_mat3(q) * Vec3::X).abs_diff_eq(Vec3::Y, EPS));
        assert!((course_to_mat3(q) * Vec3::X).abs_diff_eq(-Vec3::Y, EPS));
        // As a row-vector matrix (v' = v·R = Rᵀ·v) it gives the same rotation as glam.
        assert!((course_to_mat3(q).transpose() * Vec3::X).abs_diff_eq(Vec3::Y, EPS));
    }

    proptest! {
        #[test]
        fn scalar_rotation_equals_glams(q in unit_quat(), v in vec3(10.0)) {
            let tol = EPS * (1.0 + v.length());
            prop_assert!(rotate(q, v).abs_diff_eq(q * v, tol));
            prop_assert!(rotate_inverse(q, v).abs_diff_eq(q.conjugate() * v, tol));
            prop_assert!(rotate_inverse(q, rotate(q, v)).abs_diff_eq(v, tol));
            prop_assert!((rotate(q, v).length() - v.length()).abs() <= tol);
        }

        #[test]
        fn course_product_equals_glams(q in unit_quat(), p in unit_quat()) {
            prop_assert!(course_mul(q, p).abs_diff_eq(q * p, EPS));
        }

        #[test]
        fn product_applies_p_first(q in unit_quat(), p in unit_quat(), v in vec3(10.0)) {
            let tol = EPS * (1.0 + v.length());
            prop_assert!((course_mul(q, p) * v).abs_diff_eq(q * (p * v), tol));
        }

        #[test]
        fn products_keep_unit_length(q in unit_quat(), p in unit_quat()) {
            prop_assert!((course_mul(q, p).length() - 1.0).abs() < EPS);
        }

        #[test]
        fn quat_times_inverse_is_identity(q in unit_quat()) {
            // q and −q are the same rotation; compare the rotation, and the product exactly up to sign.
            let r = q * q.inverse();
            prop_assert!(r.abs_diff_eq(Quat::IDENTITY, EPS) || r.abs_diff_eq(-Quat::IDENTITY, EPS));
            prop_assert!(course_mul(q, q.conjugate()).abs_diff_eq(Quat::IDENTITY, EPS));
        }

        #[test]
        fn course_matrix_equals_transpose_for_any_rotation(q in unit_quat(), v in vec3(10.0)) {
            prop_assert!(course_to_mat3(q).abs_diff_eq(to_mat3(q).transpose(), EPS));
            // The row-vector reading v·R equals the quaternion rotation.
            let row_times = course_to_mat3(q).transpose() * v;
            prop_assert!(row_times.abs_diff_eq(q * v, EPS * (1.0 + v.length())));
        }

        #[test]
        fn axis_angle_matches_glam(axis in vec3(1.0), angle in -10.0f32..10.0) {
            prop_assume!(axis.length() > 1e-3);
            let q = from_axis_angle_normalized(axis, angle).unwrap();
            prop_assert!(q.abs_diff_eq(Quat::from_axis_angle(axis.normalize(), angle), EPS));
            prop_assert!((q.length() - 1.0).abs() < EPS);
        }

        #[test]
        fn integration_keeps_unit_length(q in unit_quat(), omega in vec3(50.0), h in 0.0f32..0.1) {
            for method in [RotationIntegrator::FirstOrder, RotationIntegrator::Exact] {
                prop_assert!((integrate_rotation(q, omega, h, method).length() - 1.0).abs() < EPS);
            }
        }

        #[test]
        fn exact_integration_rotates_by_omega_h(q in unit_quat(), omega in vec3(20.0), h in 0.0f32..0.1) {
            let next = integrate_rotation(q, omega, h, RotationIntegrator::Exact);
            // The relative rotation next·q⁻¹ is |ω|h about ω.
            let expected = Quat::from_scaled_axis(omega * h);
            let delta = next * q.inverse();
            prop_assert!(delta.abs_diff_eq(expected, 1e-4) || delta.abs_diff_eq(-expected, 1e-4));
        }
    }

    #[test]
    fn first_order_converges_to_exact_with_second_order_local_error() {
        // Spin about z at 2 rad/s for 1 s; compare with the exact angle 2 rad for shrinking h.
        let omega = Vec3::new(0.0, 0.0, 2.0);
        let angle_error = |steps: u32| {
            let h = 1.0 / steps as f32;
            let mut q = Quat::IDENTITY;
            for _ in 0..steps {
                q = integrate_rotation(q, omega, h, RotationIntegrator::FirstOrder);
            }
            angle_between(q, Quat::from_rotation_z(2.0))
        };
        let coarse = angle_error(20);
        let fine = angle_error(40);
        // Global error O(h²): halving h divides it by ~4 (accept 3–5).
        assert!(coarse > 1e-4, "coarse error {coarse}");
        let ratio = coarse / fine;
        assert!((3.0..5.0).contains(&ratio), "ratio {ratio}");
        // Exact integration has no truncation error at all.
        let mut q = Quat::IDENTITY;
        for _ in 0..20 {
            q = integrate_rotation(q, omega, 0.05, RotationIntegrator::Exact);
        }
        assert!(angle_between(q, Quat::from_rotation_z(2.0)) < 1e-5);
    }

    #[test]
    fn angle_between_is_accurate_for_small_angles() {
        let a = Quat::from_rotation_x(0.3);
        let b = Quat::from_rotation_y(1e-5) * a;
        assert!((angle_between(a, b) - 1e-5).abs() < 1e-9);
        assert!(
            (angle_between(a, -a)).abs() < 1e-7,
            "q and −q are the same rotation"
        );
        assert!((angle_between(Quat::IDENTITY, Quat::from_rotation_z(3.0)) - 3.0).abs() < 1e-5);
    }

    #[test]
    fn integration_never_returns_a_zero_quaternion() {
        let q = Quat::IDENTITY;
        let out = integrate_rotation(
            q,
            Vec3::splat(f32::NAN),
            0.1,
            RotationIntegrator::FirstOrder,
        );
        assert_eq!(out, q);
    }
}
