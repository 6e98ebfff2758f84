//! Linear and angular momentum, kinetic and gravitational potential energy of a body and of a set of bodies
//! (course item 9). Used by tests and diagnostics (recordings), not by the step.
//!
//! Fixed and kinematic bodies have infinite mass, so their momentum is not a number: they are left out of
//! every sum here (they contribute zero), as a conservation check needs.

use crate::RigidBody;
use rebound_math::Vec3;

impl RigidBody {
    /// Linear momentum `p = m·v` (kg·m/s); zero for fixed and kinematic bodies.
    #[must_use]
    pub fn linear_momentum(&self) -> Vec3 {
        if self.is_dynamic() {
            self.linear_velocity() * self.mass_properties().mass()
        } else {
            Vec3::ZERO
        }
    }

    /// Angular momentum about the world point `about` (kg·m²/s): spin `I_w·ω` plus orbit `(c − about) × m·v`;
    /// zero for fixed and kinematic bodies.
    #[must_use]
    pub fn angular_momentum(&self, about: Vec3) -> Vec3 {
        if !self.is_dynamic() {
            return Vec3::ZERO;
        }
        self.inertia_world() * self.angular_velocity()
            + (self.center_of_mass() - about).cross(self.linear_momentum())
    }

    /// Kinetic energy `½·m·|v|² + ½·ωᵀ·I_w·ω` (J); zero for fixed and kinematic bodies.
    #[must_use]
    pub fn kinetic_energy(&self) -> f32 {
        if !self.is_dynamic() {
            return 0.0;
        }
        let v = self.linear_velocity();
        let w = self.angular_velocity();
        0.5 * self.mass_properties().mass() * v.length_squared()
            + 0.5 * w.dot(self.inertia_world() * w)
    }

    /// Gravitational potential energy `U = −m·s·(g·c)` (J) in the uniform field `gravity` (m/s²), `s` the
    /// body's gravity scale and `c` its centre of mass in world space: zero at the height of the world
    /// origin, so for `g = (0, −g, 0)` it is `m·s·g·c_y`. Zero for fixed and kinematic bodies. With the
    /// kinetic energy it is conserved by a body in free flight (`dU/dt = −m·s·g·v = −dK/dt`).
    #[must_use]
    pub fn gravitational_potential_energy(&self, gravity: Vec3) -> f32 {
        if !self.is_dynamic() {
            return 0.0;
        }
        -self.mass_properties().mass() * self.gravity_scale() * gravity.dot(self.center_of_mass())
    }
}

/// Total linear momentum of `bodies` (kg·m/s).
pub fn total_linear_momentum<'a>(bodies: impl IntoIterator<Item = &'a RigidBody>) -> Vec3 {
    bodies.into_iter().map(RigidBody::linear_momentum).sum()
}

/// Total angular momentum of `bodies` about the world point `about` (kg·m²/s).
pub fn total_angular_momentum<'a>(
    bodies: impl IntoIterator<Item = &'a RigidBody>,
    about: Vec3,
) -> Vec3 {
    bodies.into_iter().map(|b| b.angular_momentum(about)).sum()
}

/// Total kinetic energy of `bodies` (J).
pub fn total_kinetic_energy<'a>(bodies: impl IntoIterator<Item = &'a RigidBody>) -> f32 {
    bodies.into_iter().map(RigidBody::kinetic_energy).sum()
}

/// Total gravitational potential energy of `bodies` in the field `gravity` (J); see
/// [`RigidBody::gravitational_potential_energy`].
pub fn total_gravitational_potential_energy<'a>(
    bodies: impl IntoIterator<Item = &'a RigidBody>,
    gravity: Vec3,
) -> f32 {
    bodies
        .into_iter()
        .map(|b| b.gravitational_potential_energy(gravity))
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BodyDesc, MassProperties};

    #[test]
    fn potential_energy_is_m_s_g_h_of_the_centre_of_mass() {
        let mass = MassProperties::new(2.0, Vec3::new(0.0, 0.5, 0.0), Vec3::ONE).unwrap();
        let body = RigidBody::new(
            &BodyDesc::dynamic()
                .with_position(Vec3::new(1.0, 3.0, -2.0))
                .with_mass_properties(mass)
                .with_gravity_scale(0.5),
        )
        .unwrap();
        // centre of mass at y = 3.5: U = 2 kg · 0.5 · 9.81 m/s² · 3.5 m.
        let expected = 2.0 * 0.5 * 9.81 * 3.5;
        let u = body.gravitational_potential_energy(Vec3::new(0.0, -9.81, 0.0));
        assert!((u - expected).abs() < 1e-5 * expected, "{u} vs {expected}");
        let fixed = RigidBody::new(&BodyDesc::fixed().with_position(Vec3::Y)).unwrap();
        assert!(fixed.gravitational_potential_energy(Vec3::NEG_Y).abs() < f32::MIN_POSITIVE);
        let total = total_gravitational_potential_energy([&body, &fixed, &body], -9.81 * Vec3::Y);
        assert!((total - 2.0 * expected).abs() < 1e-5 * expected);
    }
}
