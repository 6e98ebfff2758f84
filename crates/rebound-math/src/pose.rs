//! `Pose`: a rigid transform (position and rotation, no scale) — how bodies are placed.
//!
//! Used by every step stage that reads or writes body placement (integrate positions, anchors in prepare).

use crate::validity::{check_finite_vec3, check_rotation};
use crate::{MathError, Quat, Transform, Vec3, rotate, rotate_inverse};

/// A rigid transform: `p' = rotation·p + position`. Also called an isometry.
///
/// The pose of a body is the placement of its body frame: `position` is the frame's origin in world space (m)
/// and `rotation` (a unit quaternion) its orientation.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Pose {
    /// Position (m). Default: origin.
    pub position: Vec3,
    /// Orientation, a unit quaternion. Default: identity.
    pub rotation: Quat,
}

impl Default for Pose {
    fn default() -> Self {
        Self::IDENTITY
    }
}

impl Pose {
    /// The pose at the origin with no rotation.
    pub const IDENTITY: Self = Self {
        position: Vec3::ZERO,
        rotation: Quat::IDENTITY,
    };

    /// A pose from a position (m) and a unit rotation (not checked; see [`Pose::try_new`]).
    #[inline]
    #[must_use]
    pub const fn new(position: Vec3, rotation: Quat) -> Self {
        Self { position, rotation }
    }

    /// A checked pose: finite position, finite unit rotation (normalised to the last bit).
    ///
    /// # Errors
    /// [`MathError::NonFiniteVector`] (field `position`), [`MathError::NonFiniteQuat`] or
    /// [`MathError::NonUnitQuat`] (field `rotation`).
    pub fn try_new(position: Vec3, rotation: Quat) -> Result<Self, MathError> {
        check_finite_vec3("position", position)?;
        check_rotation("rotation", rotation)?;
        Ok(Self::new(position, rotation.normalize()))
    }

    /// A pure translation (m).
    #[inline]
    #[must_use]
    pub const fn from_position(position: Vec3) -> Self {
        Self::new(position, Quat::IDENTITY)
    }

    /// Maps a point from this frame to the parent (world) frame.
    #[inline]
    #[must_use]
    pub fn transform_point(&self, point: Vec3) -> Vec3 {
        rotate(self.rotation, point) + self.position
    }

    /// Rotates a direction from this frame to the parent frame.
    #[inline]
    #[must_use]
    pub fn transform_vector(&self, vector: Vec3) -> Vec3 {
        rotate(self.rotation, vector)
    }

    /// Maps a point from the parent frame into this frame.
    #[inline]
    #[must_use]
    pub fn inverse_transform_point(&self, point: Vec3) -> Vec3 {
        rotate_inverse(self.rotation, point - self.position)
    }

    /// Rotates a direction from the parent frame into this frame.
    #[inline]
    #[must_use]
    pub fn inverse_transform_vector(&self, vector: Vec3) -> Vec3 {
        rotate_inverse(self.rotation, vector)
    }

    /// The inverse pose: `inverse().transform_point(transform_point(p)) = p`.
    #[inline]
    #[must_use]
    pub fn inverse(&self) -> Self {
        Self::new(
            -rotate_inverse(self.rotation, self.position),
            self.rotation.conjugate(),
        )
    }

    /// `self ∘ other`: `other` first, then `self`.
    #[inline]
    #[must_use]
    pub fn mul_pose(&self, other: &Self) -> Self {
        Self::new(
            self.transform_point(other.position),
            self.rotation * other.rotation,
        )
    }

    /// The pose as a [`Transform`] with unit scale.
    #[inline]
    #[must_use]
    pub const fn to_transform(self) -> Transform {
        Transform {
            translation: self.position,
            rotation: self.rotation,
            scale: Vec3::ONE,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn pose() -> impl Strategy<Value = Pose> {
        (
            (-50.0f32..50.0, -50.0f32..50.0, -50.0f32..50.0),
            (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
        )
            .prop_filter("non-degenerate", |(_, (x, y, z, w))| {
                x * x + y * y + z * z + w * w > 1e-2
            })
            .prop_map(|((px, py, pz), (x, y, z, w))| {
                Pose::new(
                    Vec3::new(px, py, pz),
                    Quat::from_xyzw(x, y, z, w).normalize(),
                )
            })
    }

    #[test]
    fn bad_poses_are_errors() {
        assert!(Pose::try_new(Vec3::new(f32::NAN, 0.0, 0.0), Quat::IDENTITY).is_err());
        assert!(Pose::try_new(Vec3::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 0.5)).is_err());
        assert!(Pose::try_new(Vec3::ONE, Quat::IDENTITY).is_ok());
    }

    proptest! {
        #[test]
        fn inverse_round_trips(a in pose(), p in (-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0)) {
            let p = Vec3::new(p.0, p.1, p.2);
            let tol = 1e-4 * (1.0 + a.position.length() + p.length());
            prop_assert!(a.inverse().transform_point(a.transform_point(p)).abs_diff_eq(p, tol));
            prop_assert!(a.inverse_transform_point(a.transform_point(p)).abs_diff_eq(p, tol));
            prop_assert!(a.inverse_transform_vector(a.transform_vector(p)).abs_diff_eq(p, 1e-4 * (1.0 + p.length())));
        }

        #[test]
        fn composition_applies_the_right_operand_first(a in pose(), b in pose()) {
            let p = Vec3::new(0.3, -1.2, 2.0);
            let tol = 1e-3 * (1.0 + a.position.length() + b.position.length());
            prop_assert!(a.mul_pose(&b).transform_point(p).abs_diff_eq(a.transform_point(b.transform_point(p)), tol));
            prop_assert!(a.to_transform().transform_point(p).abs_diff_eq(a.transform_point(p), tol));
        }
    }
}
