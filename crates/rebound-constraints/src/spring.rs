//! The spring between two anchors (course items 1–3), in two models: the oscillator step, stable for any
//! stiffness and step and free of numerical damping, and the course's explicit Hooke force. Stages:
//! *prepare* and *apply forces* (both models, every substep after integrate velocities); the solve and
//! relax passes leave springs alone.
//!
//! # The equation
//!
//! With `d = p_b − p_a` the separation of the anchors, `n = d/|d|` and the rest length `L`:
//!
//! ```text
//! C = |d| − L                                        (m)
//! Ċ = n·(v_b + ω_b × r_b − v_a − ω_a × r_a)          J = [ −nᵀ  −(r_a × n)ᵀ  nᵀ  (r_b × n)ᵀ ]
//! m_eff = 1 / (1/m_a + 1/m_b + (r_a × n)·I_a⁻¹·(r_a × n) + (r_b × n)·I_b⁻¹·(r_b × n))
//! f = −k·C − c·Ċ     the force along n on B (and −f on A), N; positive pushes the anchors apart
//! ```
//!
//! # `SpringModel::Force`: the course's explicit force
//!
//! Each substep, right after the velocities are integrated, the force of the current state is added as a
//! velocity change `Δv = f·h·n/m` (with its torque `r × f·n`) on **both** bodies (course items 1 and 2). The
//! velocity update uses the position from before the move and the position update the new velocity, so this is
//! symplectic Euler, whose map for the 1-D oscillator `ẍ = −ω²x` (ω² = k/m_eff) has the eigenvalues of
//! `λ² − (2 − h²ω²)·λ + 1 = 0`:
//!
//! ```text
//! h·ω < 2:  |λ| = 1 — bounded; the quantity ω²x² + v² − h·ω²·x·v is conserved exactly
//! h·ω > 2:  |λ| = (h²ω² − 2 + h·ω·√(h²ω² − 4)) / 2 > 1 — grows every substep
//! ```
//!
//! This answers the course's question ("problems with large time steps and large spring coefficients?"): the
//! explicit spring explodes as soon as `h > 2/ω = 2·√(m_eff/k)` (for k = 1e4 N/m on 1 kg: h > 20 ms). At
//! `h·ω = 2.1` the amplitude grows ×1.88 per substep (tested).
//!
//! # `SpringModel::Soft`: the oscillator step
//!
//! The same spring-damper, as one velocity change per substep in the same stage, from the row's effective
//! mass: `λ = m_eff·((α − 1)·Ċ + β·C)` with the [`crate::OscillatorStep`] `(α, β)`, so that with the
//! position update the substep is `v' = α·v + β·x`, `x' = x + h·v'`. `β = −α·h·ω²` makes the static stretch
//! under a load exact; `α = e^{−2ζωh}` (the map's determinant) while `h·ω ≤ 1` gives no numerical damping
//! at all — an undamped spring keeps its mean energy, a damped one decays at its physical rate — and
//! `α ≤ 1/(h·ω)²` beyond keeps it stable at any stiffness (k = 1e9 N/m on 1 kg at dt = 1/30 is tested).
//! `docs/physics.md`, "Springs without numerical damping", derives it. Optional force caps clamp the
//! impulse to `[min_force·h, max_force·h]`, which makes a bungee (`max_force = 0`: pulls, never pushes).

use crate::error::ConstraintError;
use crate::error::{check_not_nan, check_ordered};
use crate::pair::BodyPair;
use crate::part::{AxisPart, CentreAxis};
use crate::soft_spring::{OscillatorStep, SoftSpring};
use rebound_dynamics::SolverBody;
use rebound_math::Vec3;
use rebound_math::validity::check_non_negative;

rebound_math::checked_serde! { "SpringModel", SpringModel::validated;
/// How a [`Spring`] acts.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum SpringModel {
    /// The oscillator step: stable for any stiffness and step, without numerical damping. The engine's
    /// choice.
    Soft(SoftSpring),
    /// The course's explicit Hooke force `f = −k·(|d| − L) − c·Ċ`, added as a velocity change every substep.
    /// Diverges once `h·√(k/m_eff) > 2`; here to teach and to compare.
    Force {
        /// Stiffness k (N/m), ≥ 0.
        stiffness: f32,
        /// Damping c along the line (N·s/m), ≥ 0.
        damping: f32,
    },
}
}

impl SpringModel {
    /// A soft spring of natural frequency `frequency_hz` (Hz) and `damping_ratio`.
    ///
    /// # Errors
    /// See [`SoftSpring::frequency`].
    pub fn soft_frequency(frequency_hz: f32, damping_ratio: f32) -> Result<Self, ConstraintError> {
        Ok(Self::Soft(SoftSpring::frequency(
            frequency_hz,
            damping_ratio,
        )?))
    }

    /// A soft spring of `stiffness` (N/m) and `damping` (N·s/m).
    ///
    /// # Errors
    /// See [`SoftSpring::stiffness`].
    pub fn soft_stiffness(stiffness: f32, damping: f32) -> Result<Self, ConstraintError> {
        Ok(Self::Soft(SoftSpring::stiffness(stiffness, damping)?))
    }

    /// The course's explicit force with `stiffness` (N/m) and `damping` (N·s/m).
    ///
    /// # Errors
    /// Both must be finite and ≥ 0.
    pub fn force(stiffness: f32, damping: f32) -> Result<Self, ConstraintError> {
        Self::Force { stiffness, damping }.validated()
    }

    /// Returns `self` if its parameters are valid.
    ///
    /// # Errors
    /// As the constructors.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        match self {
            Self::Soft(spring) => Ok(Self::Soft(spring.validated()?)),
            Self::Force { stiffness, damping } => {
                check_non_negative("stiffness", stiffness)?;
                check_non_negative("damping", damping)?;
                Ok(self)
            }
        }
    }
}

rebound_math::checked_serde! { "Spring", Spring::validated;
/// A spring between two anchors with a rest length.
///
/// ```text
/// C = |d| − L                                     (m)
/// J = [ −nᵀ  −(r_a × n)ᵀ  nᵀ  (r_b × n)ᵀ ],  n = d/|d|
/// m_eff = 1 / (1/m_a + 1/m_b + (r_a × n)·I_a⁻¹·(r_a × n) + (r_b × n)·I_b⁻¹·(r_b × n))
/// Soft:  λ = m_eff·((α − 1)·Ċ + β·C) per substep, (α, β) = OscillatorStep of (ω², σ, h)
/// Force: f = −k·C − c·Ċ (N) added as Δv = f·h·n/m on both bodies every substep; diverges for h·√(k/m_eff) > 2
/// caps: min_force·h ≤ λ ≤ max_force·h
/// ```
///
/// The [`crate::spring`] module derives both models and their stability.
///
/// # Examples
///
/// ```
/// use rebound_constraints::{Spring, SpringModel};
/// // 1 m rest length, 100 N/m, lightly damped, pulls only (a bungee).
/// let spring = Spring::new(1.0, SpringModel::soft_stiffness(100.0, 0.5)?)?
///     .with_force_range(f32::NEG_INFINITY, 0.0)?;
/// assert_eq!(spring.rest_length(), 1.0);
/// assert!(Spring::new(-1.0, SpringModel::force(10.0, 0.0)?).is_err());
/// # Ok::<(), rebound_constraints::ConstraintError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Spring {
    rest_length: f32,
    model: SpringModel,
    // The default caps, ±∞ (none), are written as `null` in JSON, and missing caps are none.
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::bounds::unbounded_below",
            default = "crate::bounds::unbounded_below::negative_infinity"
        )
    )]
    min_force: f32,
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::bounds::unbounded",
            default = "crate::bounds::unbounded::infinity"
        )
    )]
    max_force: f32,
}
}

impl Spring {
    /// A spring of `rest_length` L (m, ≥ 0; 0 makes `f = −k·d`, a drag-and-drop spring) acting by `model`,
    /// with no force caps.
    ///
    /// # Errors
    /// A negative or non-finite `rest_length`; an invalid `model`.
    pub fn new(rest_length: f32, model: SpringModel) -> Result<Self, ConstraintError> {
        check_non_negative("rest_length", rest_length)?;
        Ok(Self {
            rest_length,
            model: model.validated()?,
            min_force: f32::NEG_INFINITY,
            max_force: f32::INFINITY,
        })
    }

    /// Caps the spring force to `[min_force, max_force]` (N; positive pushes the anchors apart, negative pulls
    /// them together; ±∞ = no cap). A bungee that only pulls: `(−∞, 0)`. Default: `(−∞, +∞)`.
    ///
    /// # Errors
    /// NaN bounds; `min_force > max_force`.
    pub fn with_force_range(
        mut self,
        min_force: f32,
        max_force: f32,
    ) -> Result<Self, ConstraintError> {
        self.set_force_range(min_force, max_force)?;
        Ok(self)
    }

    /// Returns `self` if it passes the checks of [`Spring::new`] and [`Spring::set_force_range`] (for values
    /// that bypassed them: deserialised).
    ///
    /// # Errors
    /// The first invalid field.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        Self::new(self.rest_length, self.model)?.with_force_range(self.min_force, self.max_force)
    }

    /// The rest length L (m).
    #[must_use]
    pub fn rest_length(&self) -> f32 {
        self.rest_length
    }

    /// The model and its parameters.
    #[must_use]
    pub fn model(&self) -> SpringModel {
        self.model
    }

    /// The force caps `(min_force, max_force)` (N).
    #[must_use]
    pub fn force_range(&self) -> (f32, f32) {
        (self.min_force, self.max_force)
    }

    /// Changes the rest length (m); nothing changes on error.
    ///
    /// # Errors
    /// A negative or non-finite `rest_length`.
    pub fn set_rest_length(&mut self, rest_length: f32) -> Result<(), ConstraintError> {
        self.rest_length = check_non_negative("rest_length", rest_length)?;
        Ok(())
    }

    /// Changes the model or its parameters; nothing changes on error.
    ///
    /// # Errors
    /// An invalid `model`.
    pub fn set_model(&mut self, model: SpringModel) -> Result<(), ConstraintError> {
        self.model = model.validated()?;
        Ok(())
    }

    /// Changes the force caps (N); nothing changes on error.
    ///
    /// # Errors
    /// NaN bounds; `min_force = +∞` or `max_force = −∞`
    /// ([`ConstraintError::InfiniteTowardsTheRange`]); `min_force > max_force`.
    pub fn set_force_range(
        &mut self,
        min_force: f32,
        max_force: f32,
    ) -> Result<(), ConstraintError> {
        check_not_nan("min_force", min_force)?;
        check_not_nan("max_force", max_force)?;
        if min_force.is_infinite() && min_force > 0.0 {
            return Err(ConstraintError::InfiniteTowardsTheRange {
                field: "min_force",
                value: min_force,
            });
        }
        if max_force.is_infinite() && max_force < 0.0 {
            return Err(ConstraintError::InfiniteTowardsTheRange {
                field: "max_force",
                value: max_force,
            });
        }
        check_ordered("min_force", min_force, "max_force", max_force)?;
        self.min_force = min_force;
        self.max_force = max_force;
        Ok(())
    }

    /// Stage *prepare* for substeps of `h` (s): the soft model's oscillator step for the effective mass at
    /// the start of the step — the one `last` (the spring prepared in the same slot the step before) made, if
    /// it was made for the same spring, effective mass and substep to the bit.
    pub(crate) fn prepare(
        &self,
        pair: &BodyPair,
        (a, b): (&SolverBody, &SolverBody),
        h: f32,
        last: Option<&PreparedSpring>,
    ) -> PreparedSpring {
        let between_centres = pair.is_between_centres();
        let dist = pair.distance_known(a, b, Vec3::X, between_centres);
        let step = match self.model {
            SpringModel::Soft(spring) => {
                let effective_mass = AxisPart::along(pair, &dist).effective_mass();
                let kept = last.and_then(|last| match (last.spring.model, last.step) {
                    (SpringModel::Soft(made_for), Some(made))
                        if made_for.same_bits(&spring) && made.holds_for(effective_mass, h) =>
                    {
                        Some(made.step)
                    }
                    _ => None,
                });
                Some(PreparedStep {
                    effective_mass,
                    h,
                    step: kept.unwrap_or_else(|| spring.oscillator_step(effective_mass, h)),
                })
            }
            SpringModel::Force { .. } => None,
        };
        PreparedSpring {
            spring: *self,
            fallback_axis: dist.axis,
            between_centres,
            step,
        }
    }
}

/// A spring ready for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedSpring {
    spring: Spring,
    fallback_axis: Vec3,
    /// [`BodyPair::is_between_centres`] of the joint's pair, which every substep asks.
    between_centres: bool,
    /// The soft model's step at prepare.
    step: Option<PreparedStep>,
}

/// The oscillator step of an effective mass and a substep, made at prepare: a spring whose effective mass
/// does not change within the step (anchored at the centres of mass, the common case) uses it in every
/// substep instead of making it again (an exponential each).
#[derive(Debug, Clone, Copy, PartialEq)]
struct PreparedStep {
    effective_mass: f32,
    h: f32,
    step: OscillatorStep,
}

impl PreparedStep {
    /// Whether the step was made for the effective mass `effective_mass` and substep `h`, to the bit.
    #[inline]
    fn holds_for(&self, effective_mass: f32, h: f32) -> bool {
        self.effective_mass.to_bits() == effective_mass.to_bits() && self.h.to_bits() == h.to_bits()
    }
}

impl PreparedSpring {
    /// The force model's force along n (N) in the current state, capped.
    fn force(&self, part: &AxisPart, length: f32, a: &SolverBody, b: &SolverBody) -> Option<f32> {
        let SpringModel::Force { stiffness, damping } = self.spring.model else {
            return None;
        };
        let f = -stiffness * (length - self.spring.rest_length) - damping * part.velocity(a, b);
        Some(f.max(self.spring.min_force).min(self.spring.max_force))
    }

    /// Stage *apply forces*: the substep's impulse along n on both bodies (N·s), returned for the joint's
    /// state. Soft model: the exact oscillator step of the row's effective mass,
    /// `λ = m_eff·((α − 1)·Ċ + β·C)`, capped to `[min_force·h, max_force·h]`; force model: `f·h`.
    pub(crate) fn apply_forces(
        &self,
        pair: &BodyPair,
        a: &mut SolverBody,
        b: &mut SolverBody,
        h: f32,
    ) -> f32 {
        let dist = pair.distance_known(a, b, self.fallback_axis, self.between_centres);
        let c = dist.length - self.spring.rest_length;
        // Anchored at both centres of mass: no lever arm, so the row has no angular side and its effective
        // mass is prepare's for the whole step.
        if self.between_centres
            && let Some(prepared) = self.step
            && prepared.h.to_bits() == h.to_bits()
        {
            let part = CentreAxis::along(&dist);
            let speed = part.velocity(a, b);
            let impulse = self.capped(prepared.step.impulse(prepared.effective_mass, speed, c), h);
            part.apply(pair, a, b, impulse);
            return impulse;
        }
        let part = AxisPart::along(pair, &dist);
        let impulse = match self.spring.model {
            SpringModel::Soft(spring) => {
                let effective_mass = part.effective_mass();
                let step = match self.step {
                    Some(prepared) if prepared.holds_for(effective_mass, h) => prepared.step,
                    _ => spring.oscillator_step(effective_mass, h),
                };
                let speed = part.velocity(a, b);
                self.capped(step.impulse(effective_mass, speed, c), h)
            }
            SpringModel::Force { .. } => self.force(&part, dist.length, a, b).unwrap_or(0.0) * h,
        };
        part.apply(pair, a, b, impulse);
        impulse
    }

    /// The soft model's impulse `impulse` (N·s) clamped to the force caps over a substep of `h` (s),
    /// `[min_force·h, max_force·h]`.
    #[inline]
    fn capped(&self, impulse: f32, h: f32) -> f32 {
        impulse
            .max(self.spring.min_force * h)
            .min(self.spring.max_force * h)
    }
}
