//! Euler angles in every order glam names (course item 15), with gimbal-lock detection.
//!
//! Not part of a step stage: Euler angles are for input and display. The engine stores quaternions.
//!
//! # Conventions
//!
//! An [`EulerRot`] names three axes `e₁ e₂ e₃` and whether they are *intrinsic* (each rotation about the
//! axes of the already rotated frame) or *extrinsic* (`…Ex`: each about the fixed world axes). With angles
//! `(a, b, c)` in radians, as glam defines them (and as the tests check against glam):
//!
//! ```text
//! intrinsic  e₁e₂e₃:   R = R_e₁(a) · R_e₂(b) · R_e₃(c)
//! extrinsic  e₁e₂e₃Ex: R = R_e₃(c) · R_e₂(b) · R_e₁(a)      (a is applied first)
//! ```
//!
//! So the intrinsic order `ZXY` equals the extrinsic order `YXZEx` with the angles reversed. The course's
//! example "zxy: rotate about z, then x, then y" about the fixed axes is [`EulerRot::ZXYEx`].
//!
//! Angles are not unique: `(a, b, c)` and `(a + π, π − b, c + π)` (Tait–Bryan) name the same rotation, as do
//! all angles that differ by whole turns. [`EulerAngles::from_quat`] returns the representative glam
//! returns: middle angle in `[−π/2, π/2]` for Tait–Bryan orders, in `[0, π]` or `[−π, 0]` for proper Euler
//! orders, outer angles in `(−π, π]`.
//!
//! # Gimbal lock
//!
//! When the middle angle puts the first and third axes on one line (`b = ±90°` for Tait–Bryan orders such as
//! `XYZ`; `b = 0°` or `180°` for proper Euler orders such as `ZXZ`), only `a ± c` is determined: one degree
//! of freedom is lost. [`EulerAngles::is_gimbal_locked`] reports it within an angular tolerance; at the
//! singularity [`EulerAngles::from_quat`] makes a documented, deterministic choice: **`c = 0`, and `a`
//! carries the whole rotation about the shared axis**.

pub use glam::EulerRot;

use crate::validity::check_finite;
use crate::{Mat3, MathError, Quat, Vec3};

/// Default angular tolerance (radians, ≈ 0.057°) for gimbal-lock detection in [`EulerAngles::from_quat`].
///
/// Within this distance of the singular middle angle, the outer angles are ill-conditioned in `f32`
/// (their error grows like `ε / tolerance`), so the deterministic choice `c = 0` is taken instead.
pub const GIMBAL_LOCK_TOLERANCE: f32 = 1e-3;

/// Whether an order's axes are fixed (world) or move with the body.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EulerFrame {
    /// Each rotation is about an axis of the already rotated frame: `R = R_e₁(a)·R_e₂(b)·R_e₃(c)`.
    Intrinsic,
    /// Each rotation is about a fixed world axis, `a` first: `R = R_e₃(c)·R_e₂(b)·R_e₁(a)`.
    Extrinsic,
}

/// The family of an Euler order, which decides where its gimbal lock is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum EulerFamily {
    /// Three different axes (`XYZ`, `ZXY`, …): locked at a middle angle of ±90°.
    TaitBryan,
    /// First axis repeated (`ZXZ`, `YXY`, …): locked at a middle angle of 0° or 180°.
    ProperEuler,
}

/// The three axes of an [`EulerRot`] as unit world vectors, its frame and its family.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerAxes {
    /// `e₁, e₂, e₃`: the axes of the angles `a`, `b`, `c`.
    pub axes: [Vec3; 3],
    /// Intrinsic or extrinsic.
    pub frame: EulerFrame,
    /// Tait–Bryan or proper Euler.
    pub family: EulerFamily,
}

impl EulerAxes {
    /// Describes `order`.
    #[must_use]
    pub const fn of(order: EulerRot) -> Self {
        use EulerFrame::{Extrinsic, Intrinsic};
        use EulerRot::*;
        const X: Vec3 = Vec3::X;
        const Y: Vec3 = Vec3::Y;
        const Z: Vec3 = Vec3::Z;
        let (axes, frame) = match order {
            ZYX => ([Z, Y, X], Intrinsic),
            ZXY => ([Z, X, Y], Intrinsic),
            YXZ => ([Y, X, Z], Intrinsic),
            YZX => ([Y, Z, X], Intrinsic),
            XYZ => ([X, Y, Z], Intrinsic),
            XZY => ([X, Z, Y], Intrinsic),
            ZYZ => ([Z, Y, Z], Intrinsic),
            ZXZ => ([Z, X, Z], Intrinsic),
            YXY => ([Y, X, Y], Intrinsic),
            YZY => ([Y, Z, Y], Intrinsic),
            XYX => ([X, Y, X], Intrinsic),
            XZX => ([X, Z, X], Intrinsic),
            ZYXEx => ([Z, Y, X], Extrinsic),
            ZXYEx => ([Z, X, Y], Extrinsic),
            YXZEx => ([Y, X, Z], Extrinsic),
            YZXEx => ([Y, Z, X], Extrinsic),
            XYZEx => ([X, Y, Z], Extrinsic),
            XZYEx => ([X, Z, Y], Extrinsic),
            ZYZEx => ([Z, Y, Z], Extrinsic),
            ZXZEx => ([Z, X, Z], Extrinsic),
            YXYEx => ([Y, X, Y], Extrinsic),
            YZYEx => ([Y, Z, Y], Extrinsic),
            XYXEx => ([X, Y, X], Extrinsic),
            XZXEx => ([X, Z, X], Extrinsic),
        };
        let family = if matches!(
            order,
            ZYZ | ZXZ | YXY | YZY | XYX | XZX | ZYZEx | ZXZEx | YXYEx | YZYEx | XYXEx | XZXEx
        ) {
            EulerFamily::ProperEuler
        } else {
            EulerFamily::TaitBryan
        };
        Self {
            axes,
            frame,
            family,
        }
    }
}

/// Every [`EulerRot`] glam defines: 6 Tait–Bryan and 6 proper Euler orders, each intrinsic and extrinsic.
pub const ALL_ORDERS: [EulerRot; 24] = {
    use EulerRot::*;
    [
        ZYX, ZXY, YXZ, YZX, XYZ, XZY, ZYZ, ZXZ, YXY, YZY, XYX, XZX, ZYXEx, ZXYEx, YXZEx, YZXEx,
        XYZEx, XZYEx, ZYZEx, ZXZEx, YXYEx, YZYEx, XYXEx, XZXEx,
    ]
};

/// Three angles (radians) and the order that gives them meaning.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EulerAngles {
    /// The order and frame of the three rotations.
    pub order: EulerRot,
    /// Angle about the first axis `e₁` (radians).
    pub a: f32,
    /// Angle about the middle axis `e₂` (radians); its value decides gimbal lock.
    pub b: f32,
    /// Angle about the third axis `e₃` (radians).
    pub c: f32,
}

impl EulerAngles {
    /// Angles `(a, b, c)` in radians for `order`.
    #[inline]
    #[must_use]
    pub const fn new(order: EulerRot, a: f32, b: f32, c: f32) -> Self {
        Self { order, a, b, c }
    }

    /// Like [`EulerAngles::new`] but rejects non-finite angles.
    ///
    /// # Errors
    /// [`MathError::NonFinite`] naming `a`, `b` or `c`.
    pub fn try_new(order: EulerRot, a: f32, b: f32, c: f32) -> Result<Self, MathError> {
        Ok(Self::new(
            order,
            check_finite("a", a)?,
            check_finite("b", b)?,
            check_finite("c", c)?,
        ))
    }

    /// The rotation as a unit quaternion (glam's [`Quat::from_euler`]).
    #[inline]
    #[must_use]
    pub fn to_quat(self) -> Quat {
        Quat::from_euler(self.order, self.a, self.b, self.c)
    }

    /// The rotation as a column-vector matrix (glam's [`Mat3::from_euler`]).
    #[inline]
    #[must_use]
    pub fn to_mat3(self) -> Mat3 {
        Mat3::from_euler(self.order, self.a, self.b, self.c)
    }

    /// The angles of the rotation `q` in `order`, with [`GIMBAL_LOCK_TOLERANCE`].
    ///
    /// `q` need not be exactly unit: it is normalised first.
    ///
    /// # Errors
    /// `q` must be finite and non-zero ([`MathError::NonFiniteQuat`] or [`MathError::NonUnitQuat`], field `q`).
    pub fn from_quat(order: EulerRot, q: Quat) -> Result<Self, MathError> {
        Self::from_quat_with_tolerance(order, q, GIMBAL_LOCK_TOLERANCE)
    }

    /// The angles of the rotation `q` in `order`; within `tolerance` radians of gimbal lock, `c = 0` and `a`
    /// carries the rotation about the shared axis (see the module docs).
    ///
    /// A negative or non-finite `tolerance` is treated as 0 (the plain glam decomposition everywhere but the
    /// exact singularity).
    ///
    /// # Errors
    /// `q` must be finite and non-zero ([`MathError::NonFiniteQuat`] or [`MathError::NonUnitQuat`], field `q`).
    pub fn from_quat_with_tolerance(
        order: EulerRot,
        q: Quat,
        tolerance: f32,
    ) -> Result<Self, MathError> {
        if !q.is_finite() {
            return Err(MathError::NonFiniteQuat {
                field: "q",
                value: q,
            });
        }
        let length = q.length();
        if !(length > 0.0 && length.is_finite()) {
            return Err(MathError::NonUnitQuat {
                field: "q",
                value: q,
                length,
                tolerance: crate::UNIT_LENGTH_TOLERANCE,
            });
        }
        Ok(Self::from_rotation_matrix(
            order,
            Mat3::from_quat(q / length),
            tolerance,
        ))
    }

    /// The angles of a pure rotation matrix `m` (orthonormal, determinant +1) in `order`.
    ///
    /// A matrix with scale or shear gives ill-defined angles (as in glam); no error is raised because the check
    /// would cost more than the conversion. Use [`EulerAngles::from_quat`] when in doubt.
    #[must_use]
    pub fn from_rotation_matrix(order: EulerRot, m: Mat3, tolerance: f32) -> Self {
        let (a, b, c) = m.to_euler(order);
        let angles = Self::new(order, a, b, c);
        if !angles.is_gimbal_locked(tolerance) {
            return angles;
        }
        // Locked: only a ± c is known. Choose c = 0 and solve for a from the remaining single-axis rotation.
        let EulerAxes { axes, frame, .. } = EulerAxes::of(order);
        let middle_inverse = Mat3::from_axis_angle(axes[1], -b);
        let about_first = match frame {
            // R = R₁(a)·R₂(b)  ⇒  R₁(a) = R·R₂(−b)
            EulerFrame::Intrinsic => m * middle_inverse,
            // R = R₂(b)·R₁(a)  ⇒  R₁(a) = R₂(−b)·R
            EulerFrame::Extrinsic => middle_inverse * m,
        };
        Self::new(order, angle_about_axis(about_first, axes[0]), b, 0.0)
    }

    /// Whether the middle angle is within `tolerance` radians of the order's singularity: ±90° for Tait–Bryan
    /// orders, 0° or 180° for proper Euler orders. A non-finite or negative `tolerance` counts as 0.
    #[must_use]
    pub fn is_gimbal_locked(&self, tolerance: f32) -> bool {
        let tolerance = if tolerance.is_finite() {
            tolerance.max(0.0)
        } else {
            0.0
        };
        let b = self.b.abs();
        let distance = match EulerAxes::of(self.order).family {
            EulerFamily::TaitBryan => (core::f32::consts::FRAC_PI_2 - b).abs(),
            EulerFamily::ProperEuler => b.min((core::f32::consts::PI - b).abs()),
        };
        distance <= tolerance
    }
}

/// The angle of a rotation matrix `m` that rotates about the unit coordinate axis `axis` only.
fn angle_about_axis(m: Mat3, axis: Vec3) -> f32 {
    // Pick u ⟂ axis (the next coordinate axis) and v = axis × u; then m·u = cos θ·u + sin θ·v.
    let u = Vec3::new(axis.z, axis.x, axis.y);
    let v = axis.cross(u);
    let image = m * u;
    crate::real::atan2(image.dot(v), image.dot(u))
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f32::consts::{FRAC_PI_2, PI};
    use proptest::prelude::*;

    fn axis_rotation(axis: Vec3, angle: f32) -> Mat3 {
        Mat3::from_axis_angle(axis, angle)
    }

    /// The composition the module docs state, built from single-axis rotations.
    fn documented_matrix(order: EulerRot, a: f32, b: f32, c: f32) -> Mat3 {
        let EulerAxes { axes, frame, .. } = EulerAxes::of(order);
        let (ra, rb, rc) = (
            axis_rotation(axes[0], a),
            axis_rotation(axes[1], b),
            axis_rotation(axes[2], c),
        );
        match frame {
            EulerFrame::Intrinsic => ra * rb * rc,
            EulerFrame::Extrinsic => rc * rb * ra,
        }
    }

    #[test]
    fn documented_convention_matches_glam_for_every_order() {
        for order in ALL_ORDERS {
            for (a, b, c) in [(0.3, -0.7, 1.1), (-2.0, 0.4, 0.25), (1.0, 1.2, -3.0)] {
                let glam = Mat3::from_euler(order, a, b, c);
                assert!(
                    documented_matrix(order, a, b, c).abs_diff_eq(glam, 1e-5),
                    "{order:?} differs from the documented convention"
                );
                assert!(
                    EulerAngles::new(order, a, b, c)
                        .to_mat3()
                        .abs_diff_eq(glam, 1e-6)
                );
            }
        }
    }

    #[test]
    fn course_zxy_example() {
        // The course: "zxy-convention: 1. rotation about z, 2. about x, 3. about y". About the fixed axes
        // that is ZXYEx, and the same rotation is the intrinsic YXZ with the angles reversed.
        let (z, x, y) = (FRAC_PI_2, FRAC_PI_2, 0.0);
        let course = EulerAngles::new(EulerRot::ZXYEx, z, x, y).to_quat();
        // Step by step with quaternions: p applied first, so the product is q_y · q_x · q_z.
        let by_hand =
            Quat::from_rotation_y(y) * Quat::from_rotation_x(x) * Quat::from_rotation_z(z);
        assert!(course.abs_diff_eq(by_hand, 1e-6) || course.abs_diff_eq(-by_hand, 1e-6));
        let intrinsic = EulerAngles::new(EulerRot::YXZ, y, x, z).to_quat();
        assert!(course.abs_diff_eq(intrinsic, 1e-6) || course.abs_diff_eq(-intrinsic, 1e-6));
        // Worked out: z by 90° takes x̂ to ŷ; x by 90° then takes ŷ to ẑ.
        assert!((course * Vec3::X).abs_diff_eq(Vec3::Z, 1e-6));
        // And the order matters: x first, then z, sends x̂ to ŷ instead.
        let swapped = EulerAngles::new(EulerRot::XZYEx, x, z, y).to_quat();
        assert!((swapped * Vec3::X).abs_diff_eq(Vec3::Y, 1e-6));
    }

    #[test]
    fn euler_angles_are_not_unique() {
        // (a + π, π − b, c + π) is the same rotation for a Tait–Bryan order.
        let (a, b, c) = (0.4, 0.3, -1.2);
        let q1 = EulerAngles::new(EulerRot::ZXY, a, b, c).to_quat();
        let q2 = EulerAngles::new(EulerRot::ZXY, a + PI, PI - b, c + PI).to_quat();
        assert!(q1.abs_diff_eq(q2, 1e-5) || q1.abs_diff_eq(-q2, 1e-5));
    }

    #[test]
    fn families_and_frames() {
        assert_eq!(EulerAxes::of(EulerRot::XYZ).family, EulerFamily::TaitBryan);
        assert_eq!(
            EulerAxes::of(EulerRot::ZXZ).family,
            EulerFamily::ProperEuler
        );
        assert_eq!(EulerAxes::of(EulerRot::ZXZEx).frame, EulerFrame::Extrinsic);
        let proper = ALL_ORDERS
            .iter()
            .filter(|o| EulerAxes::of(**o).family == EulerFamily::ProperEuler)
            .count();
        assert_eq!(proper, 12);
    }

    #[test]
    fn gimbal_lock_is_detected_for_every_order() {
        for order in ALL_ORDERS {
            let singular_b = match EulerAxes::of(order).family {
                EulerFamily::TaitBryan => FRAC_PI_2,
                EulerFamily::ProperEuler => 0.0,
            };
            let locked = EulerAngles::new(order, 0.3, singular_b, 0.5);
            assert!(locked.is_gimbal_locked(1e-3), "{order:?}");
            let near = EulerAngles::new(order, 0.3, singular_b + 0.5e-3, 0.5);
            assert!(near.is_gimbal_locked(1e-3), "{order:?}");
            let free = EulerAngles::new(order, 0.3, singular_b + 0.1, 0.5);
            assert!(!free.is_gimbal_locked(1e-3), "{order:?}");
        }
        // The other singularities: −90° for Tait–Bryan, 180° for proper Euler.
        assert!(EulerAngles::new(EulerRot::XYZ, 0.0, -FRAC_PI_2, 0.0).is_gimbal_locked(1e-4));
        assert!(EulerAngles::new(EulerRot::ZXZ, 0.0, PI, 0.0).is_gimbal_locked(1e-4));
        assert!(EulerAngles::new(EulerRot::ZXZ, 0.0, -PI, 0.0).is_gimbal_locked(1e-4));
    }

    #[test]
    #[expect(
        clippy::float_cmp,
        reason = "the choice at the singularity is exactly c = 0"
    )]
    fn at_gimbal_lock_the_choice_is_c_zero_and_the_rotation_is_kept() {
        for order in ALL_ORDERS {
            let singular_b = match EulerAxes::of(order).family {
                EulerFamily::TaitBryan => FRAC_PI_2,
                EulerFamily::ProperEuler => 0.0,
            };
            // Many (a, c) pairs with the same a ± c give one rotation; all must decode the same way.
            let q = EulerAngles::new(order, 0.7, singular_b, 0.4).to_quat();
            let decoded = EulerAngles::from_quat(order, q).unwrap();
            assert!(
                decoded.is_gimbal_locked(GIMBAL_LOCK_TOLERANCE),
                "{order:?} {decoded:?}"
            );
            assert_eq!(decoded.c, 0.0, "{order:?}");
            let back = decoded.to_quat();
            assert!(
                back.abs_diff_eq(q, 1e-5) || back.abs_diff_eq(-q, 1e-5),
                "{order:?}: {decoded:?} does not reproduce the rotation"
            );
            // Deterministic: the same rotation decodes to the same bits.
            assert_eq!(decoded, EulerAngles::from_quat(order, q).unwrap());
        }
    }

    #[test]
    #[expect(
        clippy::float_cmp,
        reason = "the choice at the singularity is exactly c = 0"
    )]
    fn rotations_near_the_lock_stay_within_the_tolerance_bound() {
        // Inside the tolerance band the choice c = 0 reproduces the rotation to about the tolerance.
        for order in [EulerRot::XYZ, EulerRot::ZXYEx, EulerRot::ZXZ] {
            let singular_b = match EulerAxes::of(order).family {
                EulerFamily::TaitBryan => FRAC_PI_2,
                EulerFamily::ProperEuler => 0.0,
            };
            let q = EulerAngles::new(order, 0.2, singular_b - 0.5e-3, -0.9).to_quat();
            let decoded = EulerAngles::from_quat(order, q).unwrap();
            assert_eq!(decoded.c, 0.0);
            assert!(crate::quat::angle_between(decoded.to_quat(), q) < 2.0 * GIMBAL_LOCK_TOLERANCE);
        }
    }

    #[test]
    fn bad_quaternions_are_errors() {
        assert!(matches!(
            EulerAngles::from_quat(EulerRot::XYZ, Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0)),
            Err(MathError::NonFiniteQuat { field: "q", .. })
        ));
        assert!(matches!(
            EulerAngles::from_quat(EulerRot::XYZ, Quat::from_xyzw(0.0, 0.0, 0.0, 0.0)),
            Err(MathError::NonUnitQuat { field: "q", .. })
        ));
        assert!(EulerAngles::try_new(EulerRot::XYZ, 0.0, f32::INFINITY, 0.0).is_err());
        // A non-unit but finite quaternion is normalised.
        let q = Quat::from_rotation_y(0.5) * 3.0;
        let decoded = EulerAngles::from_quat(EulerRot::YXZ, q).unwrap();
        assert!((decoded.a - 0.5).abs() < 1e-5 && decoded.b.abs() < 1e-5 && decoded.c.abs() < 1e-5);
    }

    /// The distance between two angles on the circle (radians, in `[0, π]`).
    fn angle_distance(x: f32, y: f32) -> f32 {
        let d = (x - y).rem_euclid(2.0 * PI);
        d.min(2.0 * PI - d)
    }

    proptest! {
        #[test]
        fn euler_quat_euler_round_trips_for_every_order(
            index in 0usize..24, a in -3.1f32..3.1, c in -3.1f32..3.1, unit in 0.0f32..1.0,
        ) {
            let order = ALL_ORDERS[index];
            let family = EulerAxes::of(order).family;
            // Stay 0.01 rad away from the singularities, where the angles are well defined.
            let b = match family {
                EulerFamily::TaitBryan => -FRAC_PI_2 + 0.01 + (PI - 0.02) * unit,
                EulerFamily::ProperEuler => 0.01 + (PI - 0.02) * unit,
            };
            let q = EulerAngles::new(order, a, b, c).to_quat();
            let decoded = EulerAngles::from_quat(order, q).unwrap();
            // Proper Euler orders have the twin (a + π, −b, c + π); glam reports the one whose middle angle
            // has the order's sign.
            let (ea, eb, ec) = if family == EulerFamily::ProperEuler && decoded.b < 0.0 {
                (a + PI, -b, c + PI)
            } else {
                (a, b, c)
            };
            prop_assert!(angle_distance(decoded.a, ea) < 2e-3, "{order:?}: a {ea} -> {}", decoded.a);
            prop_assert!((decoded.b - eb).abs() < 2e-3, "{order:?}: b {eb} -> {}", decoded.b);
            prop_assert!(angle_distance(decoded.c, ec) < 2e-3, "{order:?}: c {ec} -> {}", decoded.c);
            // Through the matrix: the same angles.
            let from_matrix = EulerAngles::from_rotation_matrix(order, Mat3::from_quat(q), GIMBAL_LOCK_TOLERANCE);
            prop_assert!(angle_distance(from_matrix.a, decoded.a) < 1e-4);
        }

        #[test]
        fn any_rotation_decodes_to_angles_that_reproduce_it(
            index in 0usize..24, x in -1.0f32..1.0, y in -1.0f32..1.0, z in -1.0f32..1.0, w in -1.0f32..1.0,
        ) {
            let q = Quat::from_xyzw(x, y, z, w);
            prop_assume!(q.length() > 0.1);
            let q = q.normalize();
            let order = ALL_ORDERS[index];
            let back = EulerAngles::from_quat(order, q).unwrap().to_quat();
            // Including near gimbal lock, where the bound is the tolerance.
            prop_assert!(crate::quat::angle_between(back, q) < 2.0 * GIMBAL_LOCK_TOLERANCE, "{order:?}");
        }
    }
}
