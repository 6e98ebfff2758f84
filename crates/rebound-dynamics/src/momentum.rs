//! Linear and angular momentum, kinetic and gravitational potential energy of a body and of a set of bodies
//! (course item 9). Used by tests and diagnostics (recordings), not by the step.
//!
//! Fixed and kinematic bodies have infinite mass, so their momentum is not a number: they are left out of
//! every sum here (they contribute zero), as a conservation check needs.

use crate::RigidBody;
use rebound_math::Vec3;

impl RigidBody {
    /// Linear momentum `p = m·v` (kg·m/s); zero for fixed and kinematic bodies.
    #[inline]
    #[must_use]
    pub fn linear_momentum(&self) -> Vec3 {
        if self.is_dynamic() {
            self.linear_velocity() * self.mass_properties().mass()
        } else {
            Vec3::ZERO
        }
    }

    /// Spin angular momentum about the centre of mass, `I_w·ω` (kg·m²/s); zero for fixed and kinematic
    /// bodies.
    #[inline]
    #[must_use]
    pub fn spin_angular_momentum(&self) -> Vec3 {
        if self.is_dynamic() {
            self.inertia_world() * self.angular_velocity()
        } else {
            Vec3::ZERO
        }
    }

    /// Angular momentum about the world point `about` (kg·m²/s): spin `I_w·ω` plus orbit `(c − about) × m·v`;
    /// zero for fixed and kinematic bodies.
    #[inline]
    #[must_use]
    pub fn angular_momentum(&self, about: Vec3) -> Vec3 {
        self.angular_momentum_with_spin(self.spin_angular_momentum(), about)
    }

    /// [`RigidBody::angular_momentum`] given the spin [`RigidBody::spin_angular_momentum`].
    #[inline]
    fn angular_momentum_with_spin(&self, spin: Vec3, about: Vec3) -> Vec3 {
        if !self.is_dynamic() {
            return Vec3::ZERO;
        }
        orbit_plus_spin(spin, self.center_of_mass(), self.linear_momentum(), about)
    }

    /// Kinetic energy `½·m·|v|² + ½·ωᵀ·I_w·ω` (J); zero for fixed and kinematic bodies.
    #[inline]
    #[must_use]
    pub fn kinetic_energy(&self) -> f32 {
        self.kinetic_energy_with_spin(self.spin_angular_momentum())
    }

    /// [`RigidBody::kinetic_energy`] given the spin `I_w·ω`: `½·m·|v|² + ½·ω·(I_w·ω)`.
    #[inline]
    fn kinetic_energy_with_spin(&self, spin: Vec3) -> f32 {
        if !self.is_dynamic() {
            return 0.0;
        }
        0.5 * self.mass_properties().mass() * self.linear_velocity().length_squared()
            + 0.5 * self.angular_velocity().dot(spin)
    }

    /// Gravitational potential energy `U = −m·s·(g·c)` (J) in the uniform field `gravity` (m/s²), `s` the
    /// body's gravity scale and `c` its centre of mass in world space: zero at the height of the world
    /// origin, so for `g = (0, −g, 0)` it is `m·s·g·c_y`. Zero for fixed and kinematic bodies. With the
    /// kinetic energy it is conserved by a body in free flight (`dU/dt = −m·s·g·v = −dK/dt`).
    #[inline]
    #[must_use]
    pub fn gravitational_potential_energy(&self, gravity: Vec3) -> f32 {
        if !self.is_dynamic() {
            return 0.0;
        }
        self.gravitational_potential_energy_at(gravity, self.center_of_mass())
    }

    /// `−m·s·(g·c)` for a dynamic body whose centre of mass is `c`.
    #[inline]
    fn gravitational_potential_energy_at(&self, gravity: Vec3, c: Vec3) -> f32 {
        -self.mass_properties().mass() * self.gravity_scale() * gravity.dot(c)
    }
}

/// Angular momentum about `about` of a body with spin `spin`, centre of mass `c` and linear momentum `p`:
/// `spin + (c − about) × p`.
#[inline]
fn orbit_plus_spin(spin: Vec3, c: Vec3, p: Vec3, about: Vec3) -> Vec3 {
    spin + (c - about).cross(p)
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

/// The energy and momentum of a set of bodies, summed in one pass by [`totals`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Totals {
    /// Total kinetic energy (J).
    pub kinetic_energy: f32,
    /// Total gravitational potential energy (J).
    pub gravitational_potential_energy: f32,
    /// Total linear momentum (kg·m/s).
    pub linear_momentum: Vec3,
    /// Total angular momentum about the point given to [`totals`] (kg·m²/s).
    pub angular_momentum: Vec3,
}

/// Kinetic and potential energy (in the field `gravity`) and linear and angular momentum (about `about`) of
/// `bodies`, in one pass: the same numbers as [`total_kinetic_energy`],
/// [`total_gravitational_potential_energy`], [`total_linear_momentum`] and [`total_angular_momentum`], for
/// the cost of one world-space inertia and one centre of mass per body instead of two of each.
pub fn totals<'a>(
    bodies: impl IntoIterator<Item = &'a RigidBody>,
    gravity: Vec3,
    about: Vec3,
) -> Totals {
    let mut sum = Totals::default();
    for body in bodies {
        if !body.is_dynamic() {
            continue;
        }
        let spin = body.spin_angular_momentum();
        let c = body.center_of_mass();
        let p = body.linear_momentum();
        sum.kinetic_energy += body.kinetic_energy_with_spin(spin);
        sum.gravitational_potential_energy += body.gravitational_potential_energy_at(gravity, c);
        sum.linear_momentum += p;
        sum.angular_momentum += orbit_plus_spin(spin, c, p, about);
    }
    sum
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

    #[test]
    fn one_pass_totals_are_the_separate_sums_bit_for_bit() {
        let spinning = RigidBody::new(
            &BodyDesc::dynamic()
                .with_position(Vec3::new(1.0, 2.0, 3.0))
                .with_rotation(rebound_math::Quat::from_rotation_z(0.3))
                .with_linear_velocity(Vec3::new(0.5, -1.0, 2.0))
                .with_angular_velocity(Vec3::new(3.0, 1.0, -2.0))
                .with_mass_properties(
                    MassProperties::new(2.0, Vec3::X * 0.1, Vec3::new(1.0, 2.0, 3.0)).unwrap(),
                ),
        )
        .unwrap();
        let fixed = RigidBody::new(&BodyDesc::fixed().with_angular_velocity(Vec3::ONE)).unwrap();
        let bodies = [&spinning, &fixed, &spinning];
        let (g, about) = (Vec3::new(0.0, -9.81, 0.0), Vec3::new(-1.0, 0.5, 0.0));
        let t = totals(bodies, g, about);
        assert_eq!(
            t.kinetic_energy.to_bits(),
            total_kinetic_energy(bodies).to_bits()
        );
        assert_eq!(
            t.gravitational_potential_energy.to_bits(),
            total_gravitational_potential_energy(bodies, g).to_bits()
        );
        assert_eq!(t.linear_momentum, total_linear_momentum(bodies));
        assert_eq!(t.angular_momentum, total_angular_momentum(bodies, about));
        // L = spin + orbit for one body, against the closed form.
        let expected = spinning.inertia_world() * spinning.angular_velocity()
            + (spinning.center_of_mass() - about).cross(spinning.linear_velocity() * 2.0);
        assert!((spinning.angular_momentum(about) - expected).length() < 1e-6);
    }
}
