//! Mass properties: mass, centre of mass and inertia tensor of a body, from density for the primitive solids,
//! combined from parts, or set by hand. Read in the *prepare* and *integrate* stages.
//!
//! Units: kg, m, kg·m². The inertia tensor is about the centre of mass, in the body frame.
//!
//! An "infinite" mass is never stored as a huge number (course item 11): fixed and kinematic bodies keep
//! their mass properties for reference, but the solver sees inverse mass 0 and inverse inertia 0.

use crate::DynamicsError;
use rebound_math::glam::Vec3A;
use rebound_math::validity::{check_finite_vec3, check_positive};
use rebound_math::{Mat3, Pose, Vec3, inertia};

/// Checks a mass: finite, > 0, and large enough that its inverse is finite (below about 3e-39 kg the inverse
/// overflows to ∞, which the solver would turn into NaN).
fn check_mass(mass: f32) -> Result<f32, DynamicsError> {
    check_positive("mass", mass)?;
    if mass.recip().is_finite() {
        Ok(mass)
    } else {
        Err(DynamicsError::MassTooSmall {
            field: "mass",
            value: mass,
            min: f32::MAX.recip(),
        })
    }
}

/// Checks an inertia tensor about the centre of mass (kg·m²): finite, symmetric (to 1e-5 relative),
/// positive semi-definite, and with finite inverse moments (a moment below about 3e-39 kg·m² has an inverse
/// that overflows; a zero moment locks its axis and is accepted).
fn check_inertia(field: &'static str, inertia: Mat3) -> Result<Mat3, DynamicsError> {
    let invalid = DynamicsError::InvalidInertia {
        field,
        value: inertia,
    };
    if !inertia.is_finite() {
        return Err(invalid);
    }
    let scale = inertia
        .abs()
        .to_cols_array()
        .into_iter()
        .fold(0.0f32, f32::max);
    if !inertia.abs_diff_eq(inertia.transpose(), 1e-5 * scale) {
        return Err(invalid);
    }
    // Sylvester's criterion for semi-definiteness, on all principal minors (with a tolerance).
    let tol = -1e-5 * scale;
    let m = inertia;
    let minors_1 = [m.x_axis.x, m.y_axis.y, m.z_axis.z];
    let minors_2 = [
        m.x_axis.x * m.y_axis.y - m.y_axis.x * m.x_axis.y,
        m.x_axis.x * m.z_axis.z - m.z_axis.x * m.x_axis.z,
        m.y_axis.y * m.z_axis.z - m.z_axis.y * m.y_axis.z,
    ];
    let overflows = |v: f32| v > 0.0 && !v.recip().is_finite();
    if minors_1.iter().any(|v| *v < tol)
        || minors_1.into_iter().any(overflows)
        || minors_2.iter().any(|v| *v < tol * scale)
        || m.determinant() < tol * scale * scale
    {
        return Err(invalid);
    }
    Ok(inertia)
}

rebound_math::checked_serde! { "MassProperties", MassProperties::validated;
/// Mass, centre of mass and inertia of a body. Always valid: built only through checked constructors, and
/// checked by [`MassProperties::validated`] when deserialised.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct MassProperties {
    mass: f32,
    local_center_of_mass: Vec3,
    local_inertia: Mat3,
}
}

impl Default for MassProperties {
    /// 1 kg with the inertia of a solid ball of radius 0.5 m (2/5·1·0.5² = 0.1 kg·m² on every axis), centred
    /// at the body origin — the body of a bare `BodyDesc::dynamic()` before any shape adds mass.
    fn default() -> Self {
        Self::from_parts_unchecked(1.0, Vec3::ZERO, Mat3::from_diagonal(Vec3::splat(0.1)))
    }
}

impl MassProperties {
    /// Mass properties from a `mass` (kg), a centre of mass in the body frame (m) and principal moments about
    /// it along the body axes (kg·m²). A zero moment locks rotation about that axis.
    ///
    /// # Errors
    /// `mass` must be finite and > 0 (field `mass`); the centre finite (`local_center_of_mass`); the moments
    /// finite and ≥ 0 (`principal_inertia`).
    pub fn new(
        mass: f32,
        local_center_of_mass: Vec3,
        principal_inertia: Vec3,
    ) -> Result<Self, DynamicsError> {
        check_mass(mass)?;
        check_finite_vec3("local_center_of_mass", local_center_of_mass)?;
        check_finite_vec3("principal_inertia", principal_inertia)?;
        let overflows = |v: f32| v > 0.0 && !v.recip().is_finite();
        if principal_inertia.min_element() < 0.0
            || principal_inertia.to_array().into_iter().any(overflows)
        {
            return Err(DynamicsError::InvalidInertia {
                field: "principal_inertia",
                value: Mat3::from_diagonal(principal_inertia),
            });
        }
        Ok(Self {
            mass,
            local_center_of_mass,
            local_inertia: Mat3::from_diagonal(principal_inertia),
        })
    }

    /// Mass properties with a full inertia tensor (kg·m², about the centre of mass, body frame).
    ///
    /// # Errors
    /// As [`MassProperties::new`], and [`DynamicsError::InvalidInertia`] unless the tensor is finite, symmetric
    /// (to 1e-5 relative) and positive semi-definite.
    pub fn from_inertia_tensor(
        mass: f32,
        local_center_of_mass: Vec3,
        inertia: Mat3,
    ) -> Result<Self, DynamicsError> {
        Self {
            mass,
            local_center_of_mass,
            local_inertia: inertia,
        }
        .validated()
    }

    /// Returns `self` if it passes the checks of [`MassProperties::from_inertia_tensor`] — mass finite, > 0
    /// and with a finite inverse (`mass`), finite centre (`local_center_of_mass`), a symmetric positive
    /// semi-definite tensor with finite inverse moments (`inertia`): the one check behind every constructor,
    /// [`MassProperties::transformed`], [`MassProperties::combine`] and deserialisation.
    ///
    /// # Errors
    /// The first invalid field.
    pub fn validated(self) -> Result<Self, DynamicsError> {
        check_mass(self.mass)?;
        check_finite_vec3("local_center_of_mass", self.local_center_of_mass)?;
        check_inertia("inertia", self.local_inertia)?;
        Ok(self)
    }

    /// A solid ball of `density` (kg/m³) and `radius` (m), centred at the body origin.
    ///
    /// # Errors
    /// Both must be finite and > 0 (fields `density`, `radius`).
    pub fn ball(density: f32, radius: f32) -> Result<Self, DynamicsError> {
        check_positive("density", density)?;
        check_positive("radius", radius)?;
        let mass = density * inertia::sphere_volume(radius);
        Self::new(mass, Vec3::ZERO, inertia::sphere(mass, radius)?)
    }

    /// A solid cuboid of `density` (kg/m³) and `half_extents` (m), centred at the body origin.
    ///
    /// # Errors
    /// Density and every half-extent must be finite and > 0.
    pub fn cuboid(density: f32, half_extents: Vec3) -> Result<Self, DynamicsError> {
        check_positive("density", density)?;
        let moments_per_kg = inertia::cuboid(1.0, half_extents)?;
        let mass = density * inertia::cuboid_volume(half_extents);
        Self::new(mass, Vec3::ZERO, moments_per_kg * mass)
    }

    /// A solid capsule along y (cylinder `radius`, `half_height` plus two hemispheres; m) of `density`.
    ///
    /// # Errors
    /// Density and radius finite and > 0, half-height finite and ≥ 0.
    pub fn capsule(density: f32, radius: f32, half_height: f32) -> Result<Self, DynamicsError> {
        check_positive("density", density)?;
        let moments_per_kg = inertia::capsule(1.0, radius, half_height)?;
        let mass = density * inertia::capsule_volume(radius, half_height);
        Self::new(mass, Vec3::ZERO, moments_per_kg * mass)
    }

    /// A solid cylinder along y of `density` (kg/m³), `radius` and `half_height` (m).
    ///
    /// # Errors
    /// All finite and > 0.
    pub fn cylinder(density: f32, radius: f32, half_height: f32) -> Result<Self, DynamicsError> {
        check_positive("density", density)?;
        let moments_per_kg = inertia::cylinder(1.0, radius, half_height)?;
        let mass = density * inertia::cylinder_volume(radius, half_height);
        Self::new(mass, Vec3::ZERO, moments_per_kg * mass)
    }

    /// A solid cone along y (base at `−half_height`, apex at `+half_height`) of `density` (kg/m³); its centre of
    /// mass sits a quarter of the height above the base.
    ///
    /// # Errors
    /// All finite and > 0.
    pub fn cone(density: f32, radius: f32, half_height: f32) -> Result<Self, DynamicsError> {
        check_positive("density", density)?;
        let moments_per_kg = inertia::cone(1.0, radius, half_height)?;
        let mass = density * inertia::cone_volume(radius, half_height);
        Self::new(
            mass,
            inertia::cone_center_of_mass(half_height),
            moments_per_kg * mass,
        )
    }

    /// The same solid placed at `pose` in the body frame: its centre moves, its tensor rotates.
    ///
    /// # Errors
    /// A pose that is not finite with a unit rotation (fields `position`, `rotation`); a result the solver
    /// could not use (a centre beyond `f32`, see [`MassProperties::validated`]).
    pub fn transformed(self, pose: Pose) -> Result<Self, DynamicsError> {
        let pose = Pose::try_new(pose.position, pose.rotation)?;
        Self {
            mass: self.mass,
            local_center_of_mass: pose.transform_point(self.local_center_of_mass),
            local_inertia: inertia::rotate_inertia(pose.rotation, self.local_inertia),
        }
        .validated()
    }

    /// The mass properties of a rigid union of `parts` (each already placed in the body frame):
    ///
    /// ```text
    /// M = Σ mᵢ,   c = Σ mᵢ·cᵢ / M,   I = Σ [Iᵢ + mᵢ·(|dᵢ|²·E − dᵢ·dᵢᵀ)],  dᵢ = cᵢ − c
    /// ```
    ///
    /// # Errors
    /// [`DynamicsError::NoMass`] for an empty list or a total mass that is not finite; a result the solver
    /// could not use (a centre or tensor that overflows, see [`MassProperties::validated`]).
    pub fn combine(parts: &[Self]) -> Result<Self, DynamicsError> {
        let total_mass: f32 = parts.iter().map(|p| p.mass).sum();
        if parts.is_empty() || !(total_mass > 0.0 && total_mass.is_finite()) {
            return Err(DynamicsError::NoMass {
                count: parts.len(),
                total_mass,
            });
        }
        let center = parts
            .iter()
            .map(|p| p.local_center_of_mass * p.mass)
            .sum::<Vec3>()
            / total_mass;
        let local_inertia = parts.iter().fold(Mat3::ZERO, |acc, p| {
            acc + inertia::parallel_axis(p.local_inertia, p.mass, p.local_center_of_mass - center)
        });
        Self {
            mass: total_mass,
            local_center_of_mass: center,
            local_inertia,
        }
        .validated()
    }

    /// Builds from parts the caller guarantees valid (used for constants).
    pub(crate) const fn from_parts_unchecked(
        mass: f32,
        local_center_of_mass: Vec3,
        local_inertia: Mat3,
    ) -> Self {
        Self {
            mass,
            local_center_of_mass,
            local_inertia,
        }
    }

    /// Mass (kg).
    #[inline]
    #[must_use]
    pub const fn mass(&self) -> f32 {
        self.mass
    }

    /// Inverse mass (1/kg).
    #[inline]
    #[must_use]
    pub fn inv_mass(&self) -> f32 {
        1.0 / self.mass
    }

    /// Centre of mass in the body frame (m).
    #[inline]
    #[must_use]
    pub const fn local_center_of_mass(&self) -> Vec3 {
        self.local_center_of_mass
    }

    /// Inertia tensor about the centre of mass in the body frame (kg·m²).
    #[inline]
    #[must_use]
    pub const fn local_inertia(&self) -> Mat3 {
        self.local_inertia
    }

    /// Whether the inertia tensor is a multiple of the identity (every axis principal, equal moments: a ball,
    /// a cube): then it, and its inverse, are the same in every frame.
    #[inline]
    #[must_use]
    pub fn is_isotropic(&self) -> bool {
        let d = self.local_inertia.x_axis.x;
        self.local_inertia == Mat3::from_diagonal(Vec3::splat(d))
    }

    /// Inverse inertia tensor in the body frame (1/(kg·m²)). A diagonal tensor inverts per axis with a zero
    /// moment giving a zero inverse (a locked axis); a full tensor inverts as a matrix, or gives zero where
    /// singular.
    #[inline]
    #[must_use]
    pub fn local_inv_inertia(&self) -> Mat3 {
        let m = self.local_inertia;
        let diagonal = Vec3A::new(m.x_axis.x, m.y_axis.y, m.z_axis.z);
        // Diagonal: the six off-diagonal entries zero (and the moments numbers). The three inverses side by
        // side (each lane the same division as alone), a zero moment giving zero.
        let off_diagonal = Vec3A::new(m.x_axis.y, m.x_axis.z, m.y_axis.z).abs()
            + Vec3A::new(m.y_axis.x, m.z_axis.x, m.z_axis.y).abs();
        if off_diagonal.cmpeq(Vec3A::ZERO).all() && diagonal.cmpeq(diagonal).all() {
            let inverse = Vec3A::select(
                diagonal.cmpgt(Vec3A::ZERO),
                Vec3A::ONE / diagonal,
                Vec3A::ZERO,
            );
            return Mat3::from_diagonal(inverse.into());
        }
        let det = m.determinant();
        if det > 0.0 && det.is_finite() {
            m.inverse()
        } else {
            Mat3::ZERO
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rebound_math::Quat;

    #[test]
    fn density_constructors_give_volume_times_density() {
        let ball = MassProperties::ball(1000.0, 0.5).unwrap();
        assert!((ball.mass() - 1000.0 * inertia::sphere_volume(0.5)).abs() < 1e-2);
        let cube = MassProperties::cuboid(2.0, Vec3::splat(0.5)).unwrap();
        assert!((cube.mass() - 2.0).abs() < 1e-6);
        assert!((cube.local_inertia().x_axis.x - 2.0 / 6.0).abs() < 1e-6);
        let cone = MassProperties::cone(1.0, 1.0, 1.0).unwrap();
        assert!((cone.local_center_of_mass().y + 0.5).abs() < 1e-6);
        assert!(MassProperties::capsule(1.0, 0.5, 1.0).is_ok());
        assert!(MassProperties::cylinder(1.0, 0.5, 1.0).is_ok());
    }

    /// Balls and cubes are isotropic; a box with unequal sides, or a tensor with products of inertia, is not.
    /// The world inverse inertia of an isotropic body, taken as its local tensor, is `R·I⁻¹·Rᵀ` to rounding
    /// for any rotation; an anisotropic body's is that product exactly.
    #[test]
    fn an_isotropic_tensor_is_the_same_in_every_frame() {
        let ball = MassProperties::ball(3.0, 0.4).unwrap();
        let cube = MassProperties::cuboid(2.0, Vec3::splat(0.5)).unwrap();
        let plank = MassProperties::cuboid(1.0, Vec3::new(0.25, 0.1, 1.0)).unwrap();
        assert!(ball.is_isotropic() && cube.is_isotropic());
        assert!(!plank.is_isotropic());
        let rotation = Quat::from_axis_angle(Vec3::new(1.0, 2.0, -0.5).normalize(), 1.1);
        for props in [ball, cube] {
            let body = crate::RigidBody::new(
                &crate::BodyDesc::dynamic()
                    .with_rotation(rotation)
                    .with_mass_properties(props),
            )
            .unwrap();
            let local = props.local_inv_inertia();
            assert_eq!(body.inv_inertia_world(), local);
            let r = Mat3::from_quat(rotation);
            let rotated = r * local * r.transpose();
            let scale = local.x_axis.x;
            for (got, want) in local.to_cols_array().iter().zip(rotated.to_cols_array()) {
                assert!((got - want).abs() <= 1e-6 * scale, "{got} vs {want}");
            }
        }
        let body = crate::RigidBody::new(
            &crate::BodyDesc::dynamic()
                .with_rotation(rotation)
                .with_mass_properties(plank),
        )
        .unwrap();
        let r = Mat3::from_quat(rotation);
        assert_eq!(
            body.inv_inertia_world(),
            r * plank.local_inv_inertia() * r.transpose()
        );
    }

    #[test]
    fn invalid_input_is_rejected_with_the_field_named() {
        let err = MassProperties::ball(-1.0, 1.0).unwrap_err();
        assert!(err.to_string().contains("`density`"), "{err}");
        assert!(MassProperties::cuboid(1.0, Vec3::new(1.0, 0.0, 1.0)).is_err());
        assert!(MassProperties::new(0.0, Vec3::ZERO, Vec3::ONE).is_err());
        assert!(
            MassProperties::new(1e-39, Vec3::ZERO, Vec3::ONE).is_err(),
            "1/m would overflow"
        );
        assert!(MassProperties::new(1.0, Vec3::ZERO, Vec3::new(1.0, -1.0, 1.0)).is_err());
        assert!(MassProperties::new(1.0, Vec3::splat(f32::NAN), Vec3::ONE).is_err());
        // Not symmetric, not PSD.
        let skewed = Mat3::from_cols(Vec3::new(1.0, 0.5, 0.0), Vec3::new(0.0, 1.0, 0.0), Vec3::Z);
        assert!(MassProperties::from_inertia_tensor(1.0, Vec3::ZERO, skewed).is_err());
        let indefinite = Mat3::from_diagonal(Vec3::new(1.0, -1.0, 1.0));
        assert!(MassProperties::from_inertia_tensor(1.0, Vec3::ZERO, indefinite).is_err());
        assert!(matches!(
            MassProperties::combine(&[]),
            Err(DynamicsError::NoMass { count: 0, .. })
        ));
    }

    #[test]
    fn two_balls_on_a_rod_combine_by_the_parallel_axis_theorem() {
        // Two 1 kg point-like balls at x = ±1: I_yy = I_zz = 2·(I_ball + 1·1²), I_xx = 2·I_ball.
        let ball = MassProperties::new(1.0, Vec3::ZERO, Vec3::splat(0.01)).unwrap();
        let left = ball
            .transformed(Pose::from_position(Vec3::new(-1.0, 0.0, 0.0)))
            .unwrap();
        let right = ball
            .transformed(Pose::from_position(Vec3::new(1.0, 0.0, 0.0)))
            .unwrap();
        let both = MassProperties::combine(&[left, right]).unwrap();
        assert!((both.mass() - 2.0).abs() < 1e-6);
        assert!(both.local_center_of_mass().length() < 1e-6);
        let i = both.local_inertia();
        assert!(
            (i.x_axis.x - 0.02).abs() < 1e-6
                && (i.y_axis.y - 2.02).abs() < 1e-5
                && (i.z_axis.z - 2.02).abs() < 1e-5
        );
        // Two halves of a box combine to the whole box.
        let half = MassProperties::cuboid(1.0, Vec3::new(0.5, 0.5, 0.5)).unwrap();
        let a = half
            .transformed(Pose::from_position(Vec3::new(-0.5, 0.0, 0.0)))
            .unwrap();
        let b = half
            .transformed(Pose::from_position(Vec3::new(0.5, 0.0, 0.0)))
            .unwrap();
        let whole = MassProperties::cuboid(1.0, Vec3::new(1.0, 0.5, 0.5)).unwrap();
        let combined = MassProperties::combine(&[a, b]).unwrap();
        assert!(
            combined
                .local_inertia()
                .abs_diff_eq(whole.local_inertia(), 1e-5)
        );
        // A rotated part stays valid as a full tensor and inverts as a matrix.
        let rotated = whole
            .transformed(Pose::new(Vec3::ZERO, Quat::from_rotation_z(0.4)))
            .unwrap();
        let product = rotated.local_inertia() * rotated.local_inv_inertia();
        assert!(product.abs_diff_eq(Mat3::IDENTITY, 1e-4));
        assert!(
            MassProperties::from_inertia_tensor(1.0, Vec3::ZERO, rotated.local_inertia()).is_ok()
        );
    }

    #[test]
    fn zero_moments_lock_axes() {
        let locked = MassProperties::new(2.0, Vec3::ZERO, Vec3::new(0.0, 1.0, 0.0)).unwrap();
        assert_eq!(
            locked.local_inv_inertia(),
            Mat3::from_diagonal(Vec3::new(0.0, 1.0, 0.0))
        );
        assert!((locked.inv_mass() - 0.5).abs() < f32::EPSILON);
    }
}
