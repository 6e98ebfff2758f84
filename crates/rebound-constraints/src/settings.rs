//! Settings of the joint solver that the dynamics layer's `StepContext` does not carry: the stiffness of the
//! position correction of hard joint parts, the iteration counts and the long-range tethers. Read at *prepare*
//! (softness, tethers) and in *solve* / *relax* (iterations).

use crate::error::ConstraintError;
use rebound_dynamics::{Softness, StepContext};
use rebound_math::validity::{check_non_negative, check_positive};

/// How the joint solver corrects the position error of hard joint parts (rope and rod lengths, ball, hinge,
/// fixed, prismatic and wheel locks, limits) and how many passes it makes. Springs use their own stiffness.
///
/// Hard parts are corrected in the bias pass as a soft constraint of natural frequency
/// `min(frequency_hz, max_frequency_ratio / h)` and damping ratio `damping_ratio`, then relaxed (bias off) —
/// Box2D v3's joint softness, whose defaults these are (`b2MakeSoft(2·contact_hz, joint_damping_ratio, h)` with
/// 30 Hz contacts). With 4 substeps at 60 Hz (h = 1/240 s) that is `bias_rate·h` = 0.28 and `mass_scale` = 0.90:
/// 28 % of the error removed per substep, heavily damped.
///
/// A soft correction holds a load `F` with an error `F/(m_eff·ω²)`, so a long chain carrying a heavy end mass
/// would stretch by its weight over the stiffness of a single link; the long-range tethers (on by default,
/// [`crate::path::tether`]) carry such loads straight to the fixed anchor instead.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(remote = "Self")
)]
// Missing fields take their defaults, so a scene file names only what differs.
#[cfg_attr(feature = "serde", serde(default))]
pub struct JointSettings {
    /// Stiffness of the position correction of hard joint parts, as a natural frequency (Hz), > 0.
    /// Default: 60 Hz.
    pub frequency_hz: f32,
    /// Damping ratio of that correction (dimensionless; 1 = critical), ≥ 0. Default: 2.
    pub damping_ratio: f32,
    /// Cap on `frequency_hz` as a fraction of the substep rate `1/h` (dimensionless), > 0: a stiffer correction
    /// than about half the substep rate overshoots. Default: 0.5.
    pub max_frequency_ratio: f32,
    /// Gauss–Seidel passes over all joints per bias (solve) call, at most [`MAX_JOINT_ITERATIONS`] (64).
    /// Default: 1.
    pub solve_iterations: u32,
    /// Gauss–Seidel passes over all joints per relax call, at most [`MAX_JOINT_ITERATIONS`] (64). Default: 1.
    pub relax_iterations: u32,
    /// Whether bodies hanging from fixed bodies through chains of ropes, rods, ball, hinge or fixed joints get
    /// long-range tethers ([`crate::path::tether`]; not those whose whole chain is one path solved directly, see
    /// `direct_chains`). Default: true.
    pub tethers: bool,
    /// Whether paths of rope, rod, ball and hinge joints (chains, ropes of links, bridges) are solved as one
    /// system each pass instead of joint by joint ([`crate::path`] explains why: stretch that does not
    /// grow with the load). Default: true.
    #[cfg_attr(feature = "serde", serde(default = "default_true"))]
    pub direct_chains: bool,
}

/// Serde's default for settings added after the first snapshot format.
#[cfg(feature = "serde")]
fn default_true() -> bool {
    true
}

/// The most Gauss–Seidel passes per solve or relax call ([`JointSettings::solve_iterations`],
/// [`JointSettings::relax_iterations`]): 64. With the default 4 substeps that is 512 passes over every joint
/// per step, far past where more passes stop paying (stiff chains are solved directly, [`crate::path`]); the
/// bound keeps one step's work finite whatever a settings file says.
pub const MAX_JOINT_ITERATIONS: u32 = 64;

rebound_math::checked_serde!(remote_self JointSettings, JointSettings::validated);

impl Default for JointSettings {
    fn default() -> Self {
        Self {
            frequency_hz: 60.0,
            damping_ratio: 2.0,
            max_frequency_ratio: 0.5,
            solve_iterations: 1,
            relax_iterations: 1,
            tethers: true,
            direct_chains: true,
        }
    }
}

impl JointSettings {
    /// Returns `self` if every field is valid.
    ///
    /// # Errors
    /// `frequency_hz` and `max_frequency_ratio` must be finite and > 0; `damping_ratio` finite and ≥ 0; the
    /// iteration counts at most [`MAX_JOINT_ITERATIONS`] ([`ConstraintError::OutOfRange`]).
    pub fn validated(self) -> Result<Self, ConstraintError> {
        check_positive("frequency_hz", self.frequency_hz)?;
        check_non_negative("damping_ratio", self.damping_ratio)?;
        check_positive("max_frequency_ratio", self.max_frequency_ratio)?;
        for (field, count) in [
            ("solve_iterations", self.solve_iterations),
            ("relax_iterations", self.relax_iterations),
        ] {
            if count > MAX_JOINT_ITERATIONS {
                return Err(ConstraintError::OutOfRange {
                    field,
                    value: count as f32,
                    min: 0.0,
                    max: MAX_JOINT_ITERATIONS as f32,
                });
            }
        }
        Ok(self)
    }

    /// The softness of hard joint parts in the bias pass for the substep of `ctx`.
    #[must_use]
    pub fn joint_softness(&self, ctx: &StepContext) -> Softness {
        let hz = self.frequency_hz.min(self.max_frequency_ratio * ctx.inv_h);
        Softness::new(hz, self.damping_ratio, ctx.h)
    }
}
