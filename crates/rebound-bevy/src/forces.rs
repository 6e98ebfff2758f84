//! External forces and impulses on bodies: [`ExternalForce`] (held, applied at every step) and
//! [`ExternalImpulse`] (applied once at the next step, then zeroed). Read by the prepare systems.

use bevy_ecs::component::Component;
use rebound::prelude::Vec3;

/// A force (N) through the centre of mass and a torque (N·m, world space) applied at every step while the
/// component holds them (a thruster, wind). Only dynamic bodies respond. Default: none.
#[derive(Component, Debug, Clone, Copy, PartialEq, Default)]
pub struct ExternalForce {
    /// Force through the centre of mass (N, world space).
    pub force: Vec3,
    /// Torque (N·m, world space).
    pub torque: Vec3,
}

impl ExternalForce {
    /// A force (N) without torque.
    #[must_use]
    pub const fn new(force: Vec3) -> Self {
        Self {
            force,
            torque: Vec3::ZERO,
        }
    }
}

/// A linear impulse (N·s) through the centre of mass and an angular impulse (N·m·s, world space) given to
/// the body at the next step (`Δv = J/m`, `Δω = I⁻¹·L`); the step then sets both to zero, so setting them
/// again gives another kick. Only dynamic bodies respond. Default: none.
#[derive(Component, Debug, Clone, Copy, PartialEq, Default)]
pub struct ExternalImpulse {
    /// Linear impulse (N·s, world space).
    pub impulse: Vec3,
    /// Angular impulse (N·m·s, world space).
    pub angular_impulse: Vec3,
}

impl ExternalImpulse {
    /// A linear impulse (N·s) without an angular part.
    #[must_use]
    pub const fn new(impulse: Vec3) -> Self {
        Self {
            impulse,
            angular_impulse: Vec3::ZERO,
        }
    }
}
