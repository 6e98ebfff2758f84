//! The spring between two anchors (course items 1–3), in two models: an implicit soft constraint that is
//! stable for any stiffness and step, and the course's explicit Hooke force. Stages: *prepare*, *apply
//! forces* (force model, every substep after integrate velocities), *warm start* and *solve* with bias on
//! (soft model; the relax pass leaves springs alone).
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
//! # `SpringModel::Soft`: an implicit soft constraint
//!
//! The same spring-damper as a soft constraint row (Catto, "Soft Constraints", GDC 2011) with the
//! [`Softness`] from `(k, c)` or `(f, ζ)`. For one spring the solver computes, per substep,
//!
//! ```text
//! λ = −m_eff·mass_scale·(Ċ₀ + bias_rate·C),   v' = v₀ + λ/m_eff
//!   = (v₀ − h·(k/m)·C) / (1 + h·c/m + h²·k/m)          ← implicit Euler of m·ẍ = −k·x − c·ẋ
//! ```
//!
//! which is unconditionally stable: its eigenvalues have modulus `1/√(1 + h²ω²) < 1` for ζ = 0, so the spring
//! never explodes at any k and dt (k = 1e7 N/m on 1 kg at 30 Hz is tested), at the price of numerical damping
//! that grows with h·ω. Optional force caps clamp the accumulated impulse to `[min_force·h, max_force·h]`, which
//! makes a bungee (`max_force = 0`: pulls, never pushes).

use crate::error::ConstraintError;
use crate::error::{check_not_nan, check_ordered};
use crate::pair::BodyPair;
use crate::part::{AxisPart, RowTarget};
use crate::soft_spring::SoftSpring;
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::{Bias, Softness, SolverBody, StepContext};
use rebound_math::Vec3;
use rebound_math::validity::check_non_negative;

rebound_math::checked_serde! { "SpringModel", SpringModel::validated;
/// How a [`Spring`] acts.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub enum SpringModel {
    /// An implicit soft constraint: stable for any stiffness and step. The engine's choice.
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
/// Soft:  soft row with Softness::new(f, ζ, h) or Softness::from_stiffness(k, c, m_eff, h), bias pass only
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

    pub(crate) fn prepare(
        &self,
        pair: &BodyPair,
        a: &SolverBody,
        b: &SolverBody,
        ctx: &StepContext,
    ) -> PreparedSpring {
        let softness = match self.model {
            SpringModel::Soft(spring) => spring.softness(0.0, ctx.h),
            SpringModel::Force { .. } => Softness::RIGID,
        };
        PreparedSpring {
            spring: *self,
            softness,
            fallback_axis: initial_axis(pair, a, b),
        }
    }
}

/// The direction A → B at prepare, or +x when the anchors coincide: the fallback direction of distance parts.
pub(crate) fn initial_axis(pair: &BodyPair, a: &SolverBody, b: &SolverBody) -> Vec3 {
    pair.distance(a, b, Vec3::X).axis
}

/// A spring ready for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedSpring {
    spring: Spring,
    /// The soft model's coefficients in frequency form (the stiffness form is computed per iteration).
    softness: Softness,
    fallback_axis: Vec3,
}

impl PreparedSpring {
    /// Whether this is the soft model (whose impulse is warm-started; the force model's is only recorded).
    pub(crate) fn is_soft(&self) -> bool {
        matches!(self.spring.model, SpringModel::Soft(_))
    }

    /// The force model's force along n (N) in the current state, capped.
    fn force(&self, part: &AxisPart, length: f32, a: &SolverBody, b: &SolverBody) -> Option<f32> {
        let SpringModel::Force { stiffness, damping } = self.spring.model else {
            return None;
        };
        let f = -stiffness * (length - self.spring.rest_length) - damping * part.velocity(a, b);
        Some(f.max(self.spring.min_force).min(self.spring.max_force))
    }

    /// Stage *apply forces* (force model only): `Δv = f·h·n/m` on both bodies.
    pub(crate) fn apply_forces(
        &self,
        pair: &BodyPair,
        a: &mut SolverBody,
        b: &mut SolverBody,
        h: f32,
    ) {
        if !matches!(self.spring.model, SpringModel::Force { .. }) {
            return;
        }
        let dist = pair.distance(a, b, self.fallback_axis);
        let part = AxisPart::new(pair, dist.axis, dist.anchors.r_a, dist.anchors.r_b);
        if let Some(f) = self.force(&part, dist.length, a, b) {
            part.apply(pair, a, b, f * h);
        }
    }

    pub(crate) fn warm_start(
        &self,
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        if self.is_soft() && state.axial_impulse != 0.0 {
            let dist = pair.distance(a, b, self.fallback_axis);
            let part = AxisPart::new(pair, dist.axis, dist.anchors.r_a, dist.anchors.r_b);
            part.apply(pair, a, b, state.axial_impulse);
        }
    }

    pub(crate) fn solve(
        &mut self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        if stage.bias == Bias::Off {
            return;
        }
        let dist = pair.distance(a, b, self.fallback_axis);
        self.fallback_axis = dist.axis;
        let part = AxisPart::new(pair, dist.axis, dist.anchors.r_a, dist.anchors.r_b);
        match self.spring.model {
            SpringModel::Soft(spring) => {
                let softness = if spring.depends_on_mass() {
                    spring.softness(part.effective_mass(), stage.h)
                } else {
                    self.softness
                };
                let c = dist.length - self.spring.rest_length;
                part.solve(
                    pair,
                    a,
                    b,
                    RowTarget::spring(c, softness),
                    &mut state.axial_impulse,
                    self.spring.min_force * stage.h,
                    self.spring.max_force * stage.h,
                );
            }
            SpringModel::Force { .. } => {
                // Recorded, not applied: the force of this substep as an impulse, for reporting and breaking.
                state.axial_impulse = self.force(&part, dist.length, a, b).unwrap_or(0.0) * stage.h;
            }
        }
    }
}
