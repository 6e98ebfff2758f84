//! Spring parameters shared by every soft spring in the crate (the `Soft` model of [`crate::Spring`], hinge,
//! prismatic and wheel springs, the 6-DOF drive, the orientation motor), turned into the [`OscillatorStep`]
//! of a substep or into [`Softness`] coefficients.
//!
//! Every spring — the distance [`crate::Spring`]'s `Soft` model and the springs of hinge, prismatic and wheel
//! joints — is a spring-damper `F = −k·C − c·Ċ` on one row, taken through each substep by the
//! [`OscillatorStep`] in the *apply forces* stage: stable for any stiffness and step, without numerical
//! damping. The 6-DOF joint's position drive and the orientation motor, which are capped, are soft rows
//! ([`SoftSpring::softness`], implicit Euler: Catto, "Soft Constraints", GDC 2011). The two parameterisations
//! are related through the row's effective mass `m_eff`: `k = m_eff·ω²`, `c = 2·m_eff·ζ·ω`, `ω = 2π·f`.

use crate::error::ConstraintError;
use rebound_dynamics::Softness;
use rebound_math::validity::{check_finite, check_non_negative};

rebound_math::checked_serde! { "SoftSpring", SoftSpring::validated;
/// The stiffness of a soft (implicit) spring, in one of two parameterisations.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum SoftSpring {
    /// A natural frequency and a damping ratio: the stiffness follows the effective mass, so the spring feels
    /// the same on a pebble and a truck (Box2D, Jolt's `ESpringMode::FrequencyAndDamping`).
    Frequency {
        /// Undamped natural frequency `f` (Hz), > 0.
        frequency_hz: f32,
        /// Damping ratio ζ (dimensionless; 0 = undamped, 1 = critical), ≥ 0.
        damping_ratio: f32,
    },
    /// A physical stiffness and damping coefficient (Jolt's `ESpringMode::StiffnessAndDamping`).
    Stiffness {
        /// Stiffness k (N/m; N·m/rad for an angular spring), ≥ 0 (may be +∞: rigid, written as `null` in
        /// JSON).
        #[cfg_attr(feature = "serde", serde(with = "crate::bounds::unbounded"))]
        stiffness: f32,
        /// Damping coefficient c (N·s/m; N·m·s/rad for an angular spring), ≥ 0.
        damping: f32,
    },
}
}

impl Default for SoftSpring {
    /// 5 Hz, damping ratio 0.7: a firm, slightly under-damped spring.
    fn default() -> Self {
        Self::Frequency {
            frequency_hz: 5.0,
            damping_ratio: 0.7,
        }
    }
}

impl SoftSpring {
    /// A spring of natural frequency `frequency_hz` (Hz) and `damping_ratio` (dimensionless).
    ///
    /// # Errors
    /// `frequency_hz` must be finite and > 0 (a 0 Hz spring would have no stiffness at all; leave the spring
    /// out instead); `damping_ratio` finite and ≥ 0.
    pub fn frequency(frequency_hz: f32, damping_ratio: f32) -> Result<Self, ConstraintError> {
        Self::Frequency {
            frequency_hz,
            damping_ratio,
        }
        .validated()
    }

    /// A spring of `stiffness` k (N/m or N·m/rad) and `damping` c (N·s/m or N·m·s/rad).
    ///
    /// # Errors
    /// `stiffness` must be ≥ 0 (+∞ is accepted: rigid); `damping` finite and ≥ 0.
    pub fn stiffness(stiffness: f32, damping: f32) -> Result<Self, ConstraintError> {
        Self::Stiffness { stiffness, damping }.validated()
    }

    /// Returns `self` if its parameters are valid (the variants' fields are public, so values built by hand
    /// are checked where they enter a constraint).
    ///
    /// # Errors
    /// As [`SoftSpring::frequency`] and [`SoftSpring::stiffness`].
    pub fn validated(self) -> Result<Self, ConstraintError> {
        match self {
            Self::Frequency {
                frequency_hz,
                damping_ratio,
            } => {
                rebound_math::validity::check_positive("frequency_hz", frequency_hz)?;
                check_non_negative("damping_ratio", damping_ratio)?;
            }
            Self::Stiffness { stiffness, damping } => {
                check_non_negative_allowing_infinity("stiffness", stiffness)?;
                check_non_negative("damping", damping)?;
            }
        }
        Ok(self)
    }

    /// Whether the softness depends on the effective mass (stiffness form), so that it must be computed in
    /// each iteration rather than once at prepare.
    #[inline]
    #[must_use]
    pub fn depends_on_mass(&self) -> bool {
        matches!(self, Self::Stiffness { .. })
    }

    /// Whether `other` is this spring to the bit (the same form and parameters): the same
    /// [`SoftSpring::oscillator_step`] for the same effective mass and substep.
    pub(crate) fn same_bits(&self, other: &Self) -> bool {
        let bits = |spring: &Self| match *spring {
            Self::Frequency {
                frequency_hz,
                damping_ratio,
            } => (false, frequency_hz.to_bits(), damping_ratio.to_bits()),
            Self::Stiffness { stiffness, damping } => {
                (true, stiffness.to_bits(), damping.to_bits())
            }
        };
        bits(self) == bits(other)
    }

    /// The exact oscillator step ([`OscillatorStep`]) of a row of effective mass `effective_mass` (kg or
    /// kg·m²) over the substep `h` (s). In stiffness form `ω² = k/m_eff`, `σ = c/(2·m_eff)`; an infinite
    /// stiffness gives the rigid limit. A zero effective mass (both ends immovable) gives the step that
    /// changes nothing.
    #[must_use]
    pub fn oscillator_step(&self, effective_mass: f32, h: f32) -> OscillatorStep {
        match *self {
            Self::Frequency {
                frequency_hz,
                damping_ratio,
            } => {
                let omega = core::f32::consts::TAU * frequency_hz;
                OscillatorStep::new(omega * omega, damping_ratio * omega, h)
            }
            Self::Stiffness { stiffness, damping } => {
                if effective_mass <= 0.0 {
                    OscillatorStep::new(0.0, 0.0, 0.0)
                } else if stiffness.is_infinite() {
                    OscillatorStep::rigid(h)
                } else {
                    let inv_mass = 1.0 / effective_mass;
                    OscillatorStep::new(stiffness * inv_mass, 0.5 * damping * inv_mass, h)
                }
            }
        }
    }

    /// The soft-constraint coefficients for a row of effective mass `effective_mass` (kg or kg·m²) and
    /// substep `h` (s). An infinite stiffness gives the rigid limit `bias_rate = 1/h`.
    #[inline]
    #[must_use]
    pub fn softness(&self, effective_mass: f32, h: f32) -> Softness {
        match *self {
            Self::Frequency {
                frequency_hz,
                damping_ratio,
            } => Softness::new(frequency_hz, damping_ratio, h),
            Self::Stiffness { stiffness, damping } => {
                if stiffness.is_infinite() {
                    Softness {
                        bias_rate: if h > 0.0 { 1.0 / h } else { 0.0 },
                        mass_scale: 1.0,
                        impulse_scale: 0.0,
                    }
                } else {
                    Softness::from_stiffness(stiffness, damping, effective_mass, h)
                }
            }
        }
    }
}

/// One substep of a spring row's oscillator `ẍ = −ω²·x − 2σ·ẋ` (`σ = ζ·ω`), written as the velocity update
/// that the engine's position update `x' = x + h·v'` completes: `v' = α·v + β·x` (`docs/physics.md`,
/// "Springs without numerical damping").
///
/// `β = −α·h·ω²` keeps the static stretch under a constant load exact (`k·x = F` is the fixed point, as in
/// implicit Euler). `α`, the map's determinant, is the energy kept per substep: the physical
/// `e^{−2σh}` while the spring is resolved (`h·ω ≤ 1`), so an undamped spring loses nothing and a damped
/// one decays at exactly its physical rate; beyond, at most `1/(h·ω)²`, which keeps the map stable for any
/// stiffness (its eigenvalues have modulus `√α < 1`) and tends to implicit Euler's `1/(1 + h²ω²)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OscillatorStep {
    /// `α` (dimensionless, in `[0, 1]`): the factor on the row's velocity.
    pub velocity_factor: f32,
    /// `β = −α·h·ω²` (1/s): the velocity added per metre (or radian) of stretch.
    pub position_rate: f32,
}

impl OscillatorStep {
    /// The step for `ω²` `omega_squared` (1/s²), decay rate `sigma = ζ·ω = c/(2·m_eff)` (1/s) and substep
    /// `h` (s); `h ≤ 0` gives the step that changes nothing.
    #[must_use]
    pub fn new(omega_squared: f32, sigma: f32, h: f32) -> Self {
        if h <= 0.0 {
            return Self {
                velocity_factor: 1.0,
                position_rate: 0.0,
            };
        }
        let resolution = omega_squared * h * h;
        let physical = rebound_math::real::exp(-2.0 * sigma * h);
        let velocity_factor = if resolution > 1.0 {
            physical.min(1.0 / resolution)
        } else {
            physical
        };
        Self {
            velocity_factor,
            position_rate: -velocity_factor * h * omega_squared,
        }
    }

    /// The impulse (N·s or N·m·s) that takes a row of effective mass `effective_mass` (kg or kg·m²) moving
    /// at `speed` (`Ċ`, m/s or rad/s) with the stretch `stretch` (`C`, m or rad) through the step:
    /// `λ = m_eff·((α − 1)·Ċ + β·C)`, so that `Ċ' = α·Ċ + β·C`.
    #[inline]
    #[must_use]
    pub fn impulse(&self, effective_mass: f32, speed: f32, stretch: f32) -> f32 {
        effective_mass * ((self.velocity_factor - 1.0) * speed + self.position_rate * stretch)
    }

    /// The rigid limit (`ω → ∞`): the stretch is closed in one substep, `v' = −x/h`.
    #[must_use]
    pub fn rigid(h: f32) -> Self {
        Self {
            velocity_factor: 0.0,
            position_rate: if h > 0.0 { -1.0 / h } else { 0.0 },
        }
    }
}

fn check_non_negative_allowing_infinity(
    field: &'static str,
    value: f32,
) -> Result<f32, ConstraintError> {
    if value.is_infinite() && value > 0.0 {
        Ok(value)
    } else {
        Ok(check_non_negative(field, value)?)
    }
}

rebound_math::checked_serde! { "JointSpring", JointSpring::validated;
/// A soft spring on a joint coordinate (a hinge angle, a slide distance): relaxed at `target`.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct JointSpring {
    target: f32,
    spring: SoftSpring,
}
}

impl JointSpring {
    /// A spring relaxed at `target` (m for a prismatic joint, rad for a hinge) with stiffness `spring`.
    ///
    /// # Errors
    /// A non-finite `target` (field `target`); an invalid `spring` (see [`SoftSpring::validated`]).
    pub fn new(target: f32, spring: SoftSpring) -> Result<Self, ConstraintError> {
        check_finite("target", target)?;
        Ok(Self {
            target,
            spring: spring.validated()?,
        })
    }

    /// Returns `self` if it passes the checks of [`JointSpring::new`] (for values that bypassed it:
    /// deserialised).
    ///
    /// # Errors
    /// As [`JointSpring::new`].
    pub fn validated(self) -> Result<Self, ConstraintError> {
        Self::new(self.target, self.spring)
    }

    /// A spring relaxed at 0 (parameters already validated).
    pub(crate) const fn relaxed_at_zero(spring: SoftSpring) -> Self {
        Self {
            target: 0.0,
            spring,
        }
    }

    /// The coordinate at which the spring is relaxed (m or rad).
    #[must_use]
    pub fn target(&self) -> f32 {
        self.target
    }

    /// The stiffness.
    #[must_use]
    pub fn spring(&self) -> SoftSpring {
        self.spring
    }
}
