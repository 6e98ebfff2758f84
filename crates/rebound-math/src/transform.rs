//! `Transform`: translation, rotation and non-uniform scale — the model matrix of course item 19.
//!
//! Not part of a step stage: transforms place shapes and render meshes. The engine's bodies use the
//! rigid [`crate::Pose`].
//!
//! # Model, inverse and normal matrices
//!
//! A point `p` in model space maps to world space as `p' = T·R·S·p`, in homogeneous coordinates the 4×4
//! model matrix `M = T·R·S` (the `w = 1` coordinate carries the translation; directions have `w = 0`).
//! The inverse `M⁻¹ = S⁻¹·Rᵀ·T⁻¹` maps world space back to model space.
//!
//! Normals are not directions of the surface but perpendiculars to it: a tangent `t` maps to `L·t` (with
//! `L = R·S` the linear part of M), and the normal must stay perpendicular, `(N·n)·(L·t) = 0` for every
//! `n·t = 0`. That forces `N = L⁻ᵀ = R·S⁻¹` — the inverse-transpose. Under non-uniform scale `L` itself
//! would tilt normals off the surface (a test shows it).

use crate::validity::{check_finite_vec3, check_rotation};
use crate::{Mat3, Mat4, MathError, Quat, Vec3, rotate, rotate_inverse};

/// How far from uniform a scale may be (relative) and still compose or invert as a transform.
const UNIFORM_SCALE_TOLERANCE: f32 = 1e-6;

/// Translation (m), rotation (unit quaternion) and per-axis scale (dimensionless), applied scale first:
/// `p' = translation + rotation·(scale ⊙ p)`.
///
/// Build one with [`Transform::try_new`] to have it checked; the fields are public for reading and for
/// struct-update syntax, and [`Transform::is_valid`] checks one built by hand.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Transform {
    /// Translation (m). Default: zero.
    pub translation: Vec3,
    /// Rotation, a unit quaternion. Default: identity.
    pub rotation: Quat,
    /// Scale along the model's own axes (dimensionless), no component zero. Default: (1, 1, 1).
    pub scale: Vec3,
}

impl Default for Transform {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Transform {
    /// The transform that changes nothing.
    pub const IDENTITY: Self = Self {
        translation: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        scale: Vec3::ONE,
    };

    /// A checked transform.
    ///
    /// # Errors
    /// Non-finite `translation` or `scale` ([`MathError::NonFiniteVector`]), a zero scale component
    /// ([`MathError::ZeroScale`]), or a non-finite or non-unit `rotation` ([`MathError::NonFiniteQuat`],
    /// [`MathError::NonUnitQuat`]); each names the field.
    pub fn try_new(translation: Vec3, rotation: Quat, scale: Vec3) -> Result<Self, MathError> {
        check_finite_vec3("translation", translation)?;
        check_rotation("rotation", rotation)?;
        check_finite_vec3("scale", scale)?;
        if scale.cmpeq(Vec3::ZERO).any() {
            return Err(MathError::ZeroScale {
                field: "scale",
                value: scale,
            });
        }
        Ok(Self {
            translation,
            rotation: rotation.normalize(),
            scale,
        })
    }

    /// A pure translation (m).
    #[inline]
    #[must_use]
    pub const fn from_translation(translation: Vec3) -> Self {
        Self {
            translation,
            ..Self::IDENTITY
        }
    }

    /// Returns `self` with `rotation` (a unit quaternion; not checked — see [`Transform::try_new`]).
    #[inline]
    #[must_use]
    pub const fn with_rotation(self, rotation: Quat) -> Self {
        Self { rotation, ..self }
    }

    /// Returns `self` with `scale` (no zero component; not checked — see [`Transform::try_new`]).
    #[inline]
    #[must_use]
    pub const fn with_scale(self, scale: Vec3) -> Self {
        Self { scale, ..self }
    }

    /// Whether every field is finite, the rotation unit and no scale component zero.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        Self::try_new(self.translation, self.rotation, self.scale).is_ok()
    }

    /// The homogeneous model matrix `M = T·R·S` (model space → world space).
    #[inline]
    #[must_use]
    pub fn model_matrix(&self) -> Mat4 {
        Mat4::from_scale_rotation_translation(self.scale, self.rotation, self.translation)
    }

    /// The inverse model matrix `M⁻¹ = S⁻¹·Rᵀ·T(−t)` (world space → model space), built in closed form
    /// rather than by a general 4×4 inversion.
    #[inline]
    #[must_use]
    pub fn inverse_model_matrix(&self) -> Mat4 {
        let linear =
            Mat3::from_diagonal(self.scale.recip()) * Mat3::from_quat(self.rotation.conjugate());
        let mut m = Mat4::from_mat3(linear);
        m.w_axis = (-(linear * self.translation)).extend(1.0);
        m
    }

    /// The normal matrix `N = (R·S)⁻ᵀ = R·S⁻¹`: the inverse-transpose of the model matrix's linear part.
    #[inline]
    #[must_use]
    pub fn normal_matrix(&self) -> Mat3 {
        Mat3::from_quat(self.rotation) * Mat3::from_diagonal(self.scale.recip())
    }

    /// Maps a model-space point to world space: `R·(S·p) + t` (the `w = 1` column of M).
    #[inline]
    #[must_use]
    pub fn transform_point(&self, point: Vec3) -> Vec3 {
        rotate(self.rotation, self.scale * point) + self.translation
    }

    /// Maps a model-space direction or displacement to world space: `R·(S·v)` (no translation, `w = 0`).
    #[inline]
    #[must_use]
    pub fn transform_vector(&self, vector: Vec3) -> Vec3 {
        rotate(self.rotation, self.scale * vector)
    }

    /// Maps a model-space surface normal to a **unit** world-space normal: `normalise(R·(S⁻¹·n))`.
    ///
    /// Returns zero for a zero normal.
    #[inline]
    #[must_use]
    pub fn transform_normal(&self, normal: Vec3) -> Vec3 {
        rotate(self.rotation, normal / self.scale).normalize_or_zero()
    }

    /// Maps a world-space point back to model space: `S⁻¹·(Rᵀ·(p − t))`.
    #[inline]
    #[must_use]
    pub fn inverse_transform_point(&self, point: Vec3) -> Vec3 {
        rotate_inverse(self.rotation, point - self.translation) / self.scale
    }

    /// Maps a world-space direction back to model space: `S⁻¹·(Rᵀ·v)`.
    #[inline]
    #[must_use]
    pub fn inverse_transform_vector(&self, vector: Vec3) -> Vec3 {
        rotate_inverse(self.rotation, vector) / self.scale
    }

    /// Maps a world-space normal back to a **unit** model-space normal: `normalise(S·(Rᵀ·n))`, the normal
    /// matrix of `M⁻¹`, which is `Mᵀ`'s linear part.
    #[inline]
    #[must_use]
    pub fn inverse_transform_normal(&self, normal: Vec3) -> Vec3 {
        (self.scale * rotate_inverse(self.rotation, normal)).normalize_or_zero()
    }

    /// The transform `self ∘ child`: first `child`, then `self` (like matrix product `M_self·M_child`).
    ///
    /// Exact whenever the result is itself translation · rotation · scale: when `self`'s scale is uniform, or
    /// when `child` is not rotated.
    ///
    /// # Errors
    /// [`MathError::ShearingScale`] when `self` has non-uniform scale and `child` a rotation: the product
    /// shears. Multiply the [`Transform::model_matrix`]es instead.
    pub fn try_mul_transform(&self, child: &Self) -> Result<Self, MathError> {
        let scale = if is_uniform(self.scale) {
            // R_p·s·R_c·S_c = (R_p·R_c)·(s·S_c)
            self.scale.x * child.scale
        } else if child.rotation == Quat::IDENTITY {
            // R_p·S_p·S_c: scales along the same axes multiply.
            self.scale * child.scale
        } else {
            return Err(MathError::ShearingScale {
                field: "self.scale",
                scale: self.scale,
            });
        };
        Ok(Self {
            translation: self.transform_point(child.translation),
            rotation: (self.rotation * child.rotation).normalize(),
            scale,
        })
    }

    /// The inverse transform, when it is one: exact for uniform scale or no rotation.
    ///
    /// # Errors
    /// [`MathError::ShearingScale`] when the scale is non-uniform and there is a rotation (`S⁻¹·Rᵀ` is then
    /// not of the form `R'·S'`). Use [`Transform::inverse_model_matrix`] or the `inverse_transform_*`
    /// methods instead.
    pub fn try_inverse(&self) -> Result<Self, MathError> {
        let inverse_rotation = self.rotation.conjugate();
        if !is_uniform(self.scale) && self.rotation != Quat::IDENTITY {
            return Err(MathError::ShearingScale {
                field: "scale",
                scale: self.scale,
            });
        }
        let scale = self.scale.recip();
        Ok(Self {
            translation: -rotate_inverse(self.rotation, self.translation) * scale,
            rotation: inverse_rotation,
            scale,
        })
    }
}

fn is_uniform(scale: Vec3) -> bool {
    let reference = scale.x.abs().max(f32::MIN_POSITIVE);
    (scale.y - scale.x).abs() <= UNIFORM_SCALE_TOLERANCE * reference
        && (scale.z - scale.x).abs() <= UNIFORM_SCALE_TOLERANCE * reference
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

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

    fn scale() -> impl Strategy<Value = Vec3> {
        // Magnitudes in [0.2, 5] with either sign (mirroring is allowed).
        let component = (0.2f32..5.0, any::<bool>()).prop_map(|(m, neg)| if neg { -m } else { m });
        (component.clone(), component.clone(), component).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    fn transform() -> impl Strategy<Value = Transform> {
        (vec3(100.0), unit_quat(), scale())
            .prop_map(|(t, r, s)| Transform::try_new(t, r, s).unwrap())
    }

    #[test]
    fn bad_transforms_are_errors() {
        assert!(matches!(
            Transform::try_new(Vec3::ZERO, Quat::IDENTITY, Vec3::new(1.0, 0.0, 1.0)),
            Err(MathError::ZeroScale { field: "scale", .. })
        ));
        assert!(matches!(
            Transform::try_new(Vec3::ZERO, Quat::IDENTITY, Vec3::new(1.0, f32::NAN, 1.0)),
            Err(MathError::NonFiniteVector { field: "scale", .. })
        ));
        assert!(matches!(
            Transform::try_new(Vec3::splat(f32::INFINITY), Quat::IDENTITY, Vec3::ONE),
            Err(MathError::NonFiniteVector {
                field: "translation",
                ..
            })
        ));
        assert!(matches!(
            Transform::try_new(Vec3::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 2.0), Vec3::ONE),
            Err(MathError::NonUnitQuat {
                field: "rotation",
                ..
            })
        ));
        assert!(!Transform::IDENTITY.with_scale(Vec3::ZERO).is_valid());
        assert!(Transform::default().is_valid());
    }

    #[test]
    fn model_matrix_carries_translation_in_homogeneous_coordinates() {
        let t = Transform::try_new(
            Vec3::new(1.0, 2.0, 3.0),
            Quat::from_rotation_z(core::f32::consts::FRAC_PI_2),
            Vec3::new(2.0, 1.0, 1.0),
        )
        .unwrap();
        // (1, 0, 0) scaled to (2, 0, 0), rotated to (0, 2, 0), translated to (1, 4, 3).
        let point = t.model_matrix() * Vec3::X.extend(1.0);
        assert!(point.abs_diff_eq(Vec3::new(1.0, 4.0, 3.0).extend(1.0), 1e-6));
        // A direction (w = 0) is not translated.
        let direction = t.model_matrix() * Vec3::X.extend(0.0);
        assert!(direction.abs_diff_eq(Vec3::new(0.0, 2.0, 0.0).extend(0.0), 1e-6));
    }

    #[test]
    fn under_non_uniform_scale_only_the_normal_matrix_keeps_normals_perpendicular() {
        // A plane through the origin with normal n = (1, 1, 0)/√2 and tangent t = (1, −1, 0).
        let n = Vec3::new(1.0, 1.0, 0.0).normalize();
        let tangent = Vec3::new(1.0, -1.0, 0.0);
        let t = Transform::try_new(
            Vec3::ZERO,
            Quat::from_rotation_y(0.3),
            Vec3::new(4.0, 1.0, 1.0),
        )
        .unwrap();
        let world_tangent = t.transform_vector(tangent);
        let right = t.transform_normal(n);
        assert!(
            right.dot(world_tangent).abs() < 1e-5,
            "normal matrix: {}",
            right.dot(world_tangent)
        );
        // The model matrix itself tilts the normal: it is no longer perpendicular to the surface.
        let wrong = t.transform_vector(n).normalize();
        assert!(
            wrong.dot(world_tangent).abs() > 0.5,
            "model matrix: {}",
            wrong.dot(world_tangent)
        );
        // Explicit matrices agree with the methods.
        assert!((t.normal_matrix() * n).normalize().abs_diff_eq(right, 1e-6));
        let inverse_transpose = Mat3::from_mat4(t.model_matrix()).inverse().transpose();
        assert!(t.normal_matrix().abs_diff_eq(inverse_transpose, 1e-5));
    }

    #[test]
    fn composition_with_shear_is_an_error_and_the_rest_compose() {
        let parent = Transform::try_new(
            Vec3::X,
            Quat::from_rotation_z(0.5),
            Vec3::new(2.0, 1.0, 1.0),
        )
        .unwrap();
        let rotated_child =
            Transform::from_translation(Vec3::Y).with_rotation(Quat::from_rotation_x(0.3));
        assert!(matches!(
            parent.try_mul_transform(&rotated_child),
            Err(MathError::ShearingScale { .. })
        ));
        assert!(parent.try_inverse().is_err());
        let child = Transform::from_translation(Vec3::Y).with_scale(Vec3::new(1.0, 3.0, 1.0));
        let composed = parent.try_mul_transform(&child).unwrap();
        assert!(
            composed
                .model_matrix()
                .abs_diff_eq(parent.model_matrix() * child.model_matrix(), 1e-5)
        );
    }

    proptest! {
        #[test]
        fn point_round_trips_through_inverse(t in transform(), p in vec3(100.0)) {
            let back = t.inverse_transform_point(t.transform_point(p));
            prop_assert!(back.abs_diff_eq(p, 1e-4 * (1.0 + p.length() + t.translation.length())));
            let v = t.inverse_transform_vector(t.transform_vector(p));
            prop_assert!(v.abs_diff_eq(p, 1e-4 * (1.0 + p.length())));
        }

        #[test]
        fn model_matrix_times_inverse_is_identity(t in transform()) {
            let product = t.model_matrix() * t.inverse_model_matrix();
            let tol = 1e-4 * (1.0 + t.translation.length());
            prop_assert!(product.abs_diff_eq(Mat4::IDENTITY, tol), "{product}");
            let other = t.inverse_model_matrix() * t.model_matrix();
            prop_assert!(other.abs_diff_eq(Mat4::IDENTITY, tol), "{other}");
        }

        #[test]
        fn methods_agree_with_the_matrices(t in transform(), p in vec3(10.0)) {
            let tol = 1e-4 * (1.0 + p.length() + t.translation.length()) * t.scale.abs().max_element();
            prop_assert!(t.model_matrix().transform_point3(p).abs_diff_eq(t.transform_point(p), tol));
            prop_assert!(t.inverse_model_matrix().transform_point3(p).abs_diff_eq(t.inverse_transform_point(p), 1e-3 * (1.0 + p.length() + t.translation.length()) * 5.0));
        }

        #[test]
        fn transformed_normals_stay_perpendicular_to_transformed_tangents(
            t in transform(), n in vec3(1.0), other in vec3(1.0),
        ) {
            prop_assume!(n.length() > 0.1);
            let tangent = n.cross(other);
            prop_assume!(tangent.length() > 0.1);
            let world_normal = t.transform_normal(n);
            let world_tangent = t.transform_vector(tangent).normalize();
            prop_assert!(world_normal.dot(world_tangent).abs() < 1e-4);
            // And back again.
            let model_normal = t.inverse_transform_normal(world_normal);
            prop_assert!(model_normal.dot(tangent.normalize()).abs() < 1e-4);
            prop_assert!(model_normal.abs_diff_eq(n.normalize(), 1e-4));
        }

        #[test]
        fn uniform_scale_composes_and_inverts_exactly(
            a in (vec3(10.0), unit_quat(), 0.2f32..5.0), b in transform(), p in vec3(10.0),
        ) {
            let parent = Transform::try_new(a.0, a.1, Vec3::splat(a.2)).unwrap();
            let composed = parent.try_mul_transform(&b).unwrap();
            let expected = parent.transform_point(b.transform_point(p));
            prop_assert!(composed.transform_point(p).abs_diff_eq(expected, 1e-3 * (1.0 + expected.length())));
            let inverse = parent.try_inverse().unwrap();
            let identity = parent.try_mul_transform(&inverse).unwrap();
            prop_assert!(identity.transform_point(p).abs_diff_eq(p, 1e-3 * (1.0 + p.length() + a.0.length())));
        }
    }
}
