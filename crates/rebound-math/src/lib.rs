#![doc = include_str!("../README.md")]
// sin, atan2, exp… only through `rebound_math::real` (the same bits on every platform under
// `enhanced-determinism`); clippy.toml lists them.
#![warn(clippy::disallowed_methods)]

pub mod disjoint;
pub mod euler;
pub mod inertia;
pub mod par;
pub mod pose;
pub mod quat;
pub mod real;
pub mod rotation2d;
pub mod team;
pub mod transform;
pub mod validity;

mod checked_serde;
mod error;

/// The glam this crate is built on, re-exported so downstream crates and users share one version — the same
/// one parry3d uses.
pub use glam;
pub use glam::{Affine3A, EulerRot, Mat2, Mat3, Mat4, Quat, Vec2, Vec3, Vec4};

pub use disjoint::Disjoint;
pub use error::MathError;
pub use euler::EulerAngles;
pub use pose::Pose;
pub use quat::{RotationIntegrator, rotate, rotate_inverse};
pub use transform::Transform;
pub use validity::UNIT_LENGTH_TOLERANCE;

/// The engine's floating-point type. Everything is `f32`, as parry3d's default build; this alias is the one
/// place to change should an `f64` build be added.
pub type Scalar = f32;

/// The cross-product matrix `[v]×`, so that `skew(v) * w == v.cross(w)`.
///
/// Used to write angular Jacobians as matrices (`r × J` as `[r]×·J`).
#[inline]
#[must_use]
pub fn skew(v: Vec3) -> Mat3 {
    Mat3::from_cols(
        Vec3::new(0.0, v.z, -v.y),
        Vec3::new(-v.z, 0.0, v.x),
        Vec3::new(v.y, -v.x, 0.0),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #[test]
        fn skew_is_the_cross_product(a in (-9.0f32..9.0, -9.0f32..9.0, -9.0f32..9.0), b in (-9.0f32..9.0, -9.0f32..9.0, -9.0f32..9.0)) {
            let (a, b) = (Vec3::new(a.0, a.1, a.2), Vec3::new(b.0, b.1, b.2));
            prop_assert!((skew(a) * b).abs_diff_eq(a.cross(b), 1e-4));
            // Antisymmetric.
            prop_assert!(skew(a).transpose().abs_diff_eq(-skew(a), 0.0));
        }
    }
}
