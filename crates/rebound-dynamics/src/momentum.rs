//! Linear and angular momentum and kinetic energy of a body and of a set of bodies (course item 9). Used by
//! tests and diagnostics, not by the step.
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
