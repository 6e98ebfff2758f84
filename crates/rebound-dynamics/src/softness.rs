//! Soft-constraint coefficients (Catto, "Soft Constraints", GDC 2011; Box2D's `b2Softness`), shared by
//! contacts (here) and joints (`rebound-constraints`). Computed in the *prepare* stage, used in *solve*.
//!
//! A soft constraint behaves as a spring-damper (stiffness k, damping c) integrated with implicit Euler. With
//! `m` the constraint's effective mass, `ω = 2π·f = √(k/m)` and `ζ = c / (2·m·ω)`:
//!
//! ```text
//! a₁ = 2ζ + h·ω,   a₂ = h·ω·a₁,   a₃ = 1 / (1 + a₂)
//! bias_rate     = ω / a₁           (1/s)   velocity bias per metre of error:  bias = bias_rate · C
//! mass_scale    = a₂ · a₃          (–)     scales the effective mass
//! impulse_scale = a₃               (–)     leaks the accumulated impulse
//! impulse = −m·mass_scale·(J·v + bias) − impulse_scale·λ_accumulated
//! ```
//!
//! In terms of k and c directly (needed when the user gives stiffness, not frequency):
//! `h(c + hk) = m·a₂`, so `bias_rate = k / (c + h·k)`, `mass_scale = h(c + hk) / (h(c + hk) + m)` and
//! `impulse_scale = m / (h(c + hk) + m)`. `docs/physics.md` derives both.

use core::f32::consts::TAU;

/// The three coefficients of a soft constraint for one substep length `h`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Softness {
    /// Velocity bias per unit of position error (1/s).
    pub bias_rate: f32,
    /// Factor on the effective mass (dimensionless, in `[0, 1]`).
    pub mass_scale: f32,
    /// Factor on the accumulated impulse subtracted each iteration (dimensionless, in `[0, 1]`).
    pub impulse_scale: f32,
}

impl Softness {
    /// A rigid constraint: no bias, full mass, no leak. Used in the relax (bias-off) iterations.
    pub const RIGID: Self = Self {
        bias_rate: 0.0,
        mass_scale: 1.0,
        impulse_scale: 0.0,
    };

    /// Softness from a natural frequency `frequency_hz` (Hz) and `damping_ratio` (dimensionless; 1 =
    /// critical) for substep `h` (s). A frequency of 0 gives [`Softness::RIGID`].
    ///
    /// Inputs are trusted (validated where the user gave them); non-positive `h` gives `RIGID`.
    #[must_use]
    pub fn new(frequency_hz: f32, damping_ratio: f32, h: f32) -> Self {
        if frequency_hz <= 0.0 || h <= 0.0 {
            return Self::RIGID;
        }
        let omega = TAU * frequency_hz;
        let a1 = 2.0 * damping_ratio + h * omega;
        let a2 = h * omega * a1;
        let a3 = 1.0 / (1.0 + a2);
        Self {
            bias_rate: omega / a1,
            mass_scale: a2 * a3,
            impulse_scale: a3,
        }
    }

    /// Softness from a physical `stiffness` k (N/m, or N·m/rad for angular constraints) and `damping` c
    /// (N·s/m), acting through `effective_mass` m (kg, or kg·m²), for substep `h` (s).
    ///
    /// `k = c = 0` gives a constraint that applies nothing (`mass_scale = 0`, `impulse_scale = 1`); a zero
    /// effective mass (both bodies immovable) gives `mass_scale = 1`, harmless because the mass multiplies it.
    #[must_use]
    pub fn from_stiffness(stiffness: f32, damping: f32, effective_mass: f32, h: f32) -> Self {
        let hc = h * (damping + h * stiffness);
        let denominator = hc + effective_mass;
        if denominator <= 0.0 {
            return Self {
                bias_rate: 0.0,
                mass_scale: 0.0,
                impulse_scale: 1.0,
            };
        }
        let spring = damping + h * stiffness;
        Self {
            bias_rate: if spring > 0.0 {
                stiffness / spring
            } else {
                0.0
            },
            mass_scale: hc / denominator,
            impulse_scale: effective_mass / denominator,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn both_parameterisations_agree() {
        // k = m ω², c = 2 m ζ ω.
        let (m, f, zeta, h) = (2.5f32, 3.0f32, 0.4f32, 1.0 / 240.0);
        let omega = TAU * f;
        let k = m * omega * omega;
        let c = 2.0 * m * zeta * omega;
        let a = Softness::new(f, zeta, h);
        let b = Softness::from_stiffness(k, c, m, h);
        assert!((a.bias_rate - b.bias_rate).abs() < 1e-3 * a.bias_rate);
        assert!((a.mass_scale - b.mass_scale).abs() < 1e-5);
        assert!((a.impulse_scale - b.impulse_scale).abs() < 1e-5);
        assert!((a.mass_scale + a.impulse_scale - 1.0).abs() < 1e-6);
    }

    #[test]
    fn stiffer_is_more_rigid() {
        let h = 1.0 / 240.0;
        let soft = Softness::new(5.0, 1.0, h);
        let stiff = Softness::new(60.0, 1.0, h);
        assert!(stiff.mass_scale > soft.mass_scale && stiff.impulse_scale < soft.impulse_scale);
        // Infinite stiffness tends to rigid with bias 1/h (a full correction per substep).
        let rigid = Softness::from_stiffness(1e12, 0.0, 1.0, h);
        assert!((rigid.bias_rate - 1.0 / h).abs() < 1e-2 / h);
        assert!(rigid.impulse_scale < 1e-6);
        assert_eq!(Softness::new(0.0, 1.0, h), Softness::RIGID);
    }

    #[test]
    fn zero_stiffness_and_damping_applies_nothing() {
        let s = Softness::from_stiffness(0.0, 0.0, 1.0, 1.0 / 60.0);
        // impulse = −m·0·(…) − 1·λ: cancels whatever was accumulated.
        assert!(s.mass_scale.abs() < f32::EPSILON && (s.impulse_scale - 1.0).abs() < f32::EPSILON);
    }
}
