//! `WorldSettings`: everything that configures a world's step, with units and defaults. Read at stage 1 of
//! the step (the step context) and by the sleep stage.

use crate::WorldError;
use crate::limits::StepLimits;
use rebound_constraints::JointSettings;
use rebound_dynamics::SolverSettings;
use rebound_math::Vec3;
use rebound_math::validity::{check_finite, check_finite_vec3, check_non_negative, check_positive};

/// How a world steps. Public fields with [`Default`]; [`crate::World::new`] and
/// [`crate::World::set_settings`] check them.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(remote = "Self")
)]
// Missing fields take their defaults, so a scene file names only what differs.
#[cfg_attr(feature = "serde", serde(default))]
pub struct WorldSettings {
    /// Gravity (m/s²). Default: (0, −9.81, 0).
    pub gravity: Vec3,
    /// Soft substeps per step (each `dt / substep_count` long), from 1 to [`MAX_SUBSTEPS`] (64). Default: 4.
    pub substep_count: u32,
    /// Contact stiffness as a natural frequency (Hz), capped at a quarter of the substep rate. Default: 30 Hz.
    pub contact_frequency_hz: f32,
    /// Contact damping ratio (dimensionless). Default: 5.
    pub contact_damping_ratio: f32,
    /// The fastest contacts push overlapping bodies apart (m/s). Default: 3 m/s.
    pub max_push_out_speed: f32,
    /// Restitution is applied only to contacts approaching faster than this (m/s). Default: 1 m/s.
    pub restitution_threshold: f32,
    /// Whether last step's impulses seed the solver. Default: true.
    pub warm_starting: bool,
    /// Distance (m) within which the collision backend reports contacts before they touch (speculative
    /// contacts), added to what the bodies travel in a step. Default: 0.02 m.
    pub speculative_margin: f32,
    /// Whether bodies fall asleep when they come to rest. Default: true.
    pub sleep_enabled: bool,
    /// Below this speed (m/s) a body counts as resting. Default: 0.05 m/s.
    pub linear_sleep_threshold: f32,
    /// Below this angular speed (rad/s) a body counts as resting. Default: 0.05 rad/s.
    pub angular_sleep_threshold: f32,
    /// How long (s) every body of an island must rest before the island sleeps. Default: 0.5 s.
    pub time_to_sleep: f32,
    /// The step length [`crate::World::advance`] uses (s), at least [`MIN_STEP_DT`] (1 µs). Default: 1/60 s.
    pub fixed_dt: f32,
    /// The most steps one [`crate::World::advance`] call runs (the rest of the time is dropped, so a slow
    /// frame cannot snowball), from 1 to [`MAX_STEPS_PER_ADVANCE`] (1,000). Default: 8.
    pub max_steps_per_advance: u32,
    /// The overlap (m) a loaded resting contact may keep: with `Some(ε)` each resting manifold's soft rows
    /// hold the weight it carries at rest at an overlap of `min(ε, load / stiffness)`, so a stack holds its
    /// height whatever its load (a 40-box column stands within 1 cm, a 1 kg box holds a 1,000 kg one);
    /// `None` turns this off and leaves the overlap at `load / stiffness` (the column sinks 0.43 m).
    /// Positive and finite when set. Default: `Some(1e-4)` (0.1 mm). Turn it off with
    /// `WorldSettings { resting_overlap: None, ..WorldSettings::default() }` (`docs/physics.md`, "Contacts
    /// under load").
    pub resting_overlap: Option<f32>,
    /// Joint solver settings: the softness of hard joint parts, iteration counts, long-range tethers for
    /// hanging chains. Default: [`JointSettings::default`] (60 Hz, ζ = 2, one solve and one relax pass,
    /// tethers on).
    pub joints: JointSettings,
    /// The physical bounds beyond which a body is quarantined and the caps on a step's work. Default:
    /// [`StepLimits::default`] (10⁴ m/s, 10⁴ rad/s, 10⁶ m; 2¹⁷ candidate pairs, 2¹⁹ contact points).
    pub limits: StepLimits,
}

/// The most substeps per step ([`WorldSettings::substep_count`]): 64. At 60 Hz that is a substep of 1/3,840 s,
/// past which more substeps buy no visible accuracy; the bound keeps one step's work finite whatever a
/// settings file says.
pub const MAX_SUBSTEPS: u32 = 64;

/// The most steps one [`crate::World::advance`] call may run ([`WorldSettings::max_steps_per_advance`]):
/// 1,000, about 17 s of simulated time at 60 Hz in one call.
pub const MAX_STEPS_PER_ADVANCE: u32 = 1_000;

/// The shortest step (s): 1 µs. [`crate::World::step`] with a shorter `dt` moves nothing and reports
/// [`crate::StepSkipped::DtTooSmall`]; [`WorldSettings::fixed_dt`] may not be shorter. Below it, with
/// [`MAX_SUBSTEPS`] substeps, the rates `1/h` and `1/h²` the solver forms would leave the range where `f32`
/// keeps them exact enough (and at 1e-38 s, `1/h` overflows to ∞).
pub const MIN_STEP_DT: f32 = 1e-6;

rebound_math::checked_serde!(remote_self WorldSettings, |s: WorldSettings| s.validate().map(|()| s));

/// Checks `min ≤ count ≤ max` for a count setting.
fn check_count(field: &'static str, count: u32, min: u32, max: u32) -> Result<u32, WorldError> {
    if (min..=max).contains(&count) {
        Ok(count)
    } else {
        Err(WorldError::SettingOutOfRange {
            field,
            value: count as f32,
            min: min as f32,
            max: max as f32,
        })
    }
}

impl Default for WorldSettings {
    fn default() -> Self {
        let solver = SolverSettings::default();
        Self {
            gravity: solver.gravity,
            substep_count: solver.substep_count,
            contact_frequency_hz: solver.contact_frequency_hz,
            contact_damping_ratio: solver.contact_damping_ratio,
            max_push_out_speed: solver.max_push_out_speed,
            restitution_threshold: solver.restitution_threshold,
            warm_starting: solver.warm_starting,
            speculative_margin: 0.02,
            sleep_enabled: true,
            linear_sleep_threshold: 0.05,
            angular_sleep_threshold: 0.05,
            time_to_sleep: 0.5,
            fixed_dt: 1.0 / 60.0,
            max_steps_per_advance: 8,
            resting_overlap: solver.resting_overlap,
            joints: JointSettings::default(),
            limits: StepLimits::default(),
        }
    }
}

impl WorldSettings {
    /// Checks every field.
    ///
    /// # Errors
    /// A [`WorldError`] naming the first invalid field: non-finite values, a substep count outside
    /// `1..=`[`MAX_SUBSTEPS`] or a step count outside `1..=`[`MAX_STEPS_PER_ADVANCE`]
    /// ([`WorldError::SettingOutOfRange`]), negative thresholds or damping, a fixed step shorter than
    /// [`MIN_STEP_DT`] ([`WorldError::StepTooShort`]), invalid joint settings (iterations beyond
    /// [`rebound_constraints::MAX_JOINT_ITERATIONS`]).
    pub fn validate(&self) -> Result<(), WorldError> {
        check_finite_vec3("gravity", self.gravity)?;
        check_count("substep_count", self.substep_count, 1, MAX_SUBSTEPS)?;
        check_positive("contact_frequency_hz", self.contact_frequency_hz)?;
        check_non_negative("contact_damping_ratio", self.contact_damping_ratio)?;
        check_positive("max_push_out_speed", self.max_push_out_speed)?;
        check_non_negative("restitution_threshold", self.restitution_threshold)?;
        check_non_negative("speculative_margin", self.speculative_margin)?;
        check_non_negative("linear_sleep_threshold", self.linear_sleep_threshold)?;
        check_non_negative("angular_sleep_threshold", self.angular_sleep_threshold)?;
        check_finite("time_to_sleep", self.time_to_sleep)?;
        check_non_negative("time_to_sleep", self.time_to_sleep)?;
        check_positive("fixed_dt", self.fixed_dt)?;
        if self.fixed_dt < MIN_STEP_DT {
            return Err(WorldError::StepTooShort {
                field: "fixed_dt",
                value: self.fixed_dt,
                min: MIN_STEP_DT,
            });
        }
        check_count(
            "max_steps_per_advance",
            self.max_steps_per_advance,
            1,
            MAX_STEPS_PER_ADVANCE,
        )?;
        if let Some(overlap) = self.resting_overlap {
            check_positive("resting_overlap", overlap)?;
        }
        self.joints.validated()?;
        self.limits.validate()?;
        Ok(())
    }

    /// The part the dynamics solver reads.
    #[must_use]
    pub fn solver_settings(&self) -> SolverSettings {
        SolverSettings {
            gravity: self.gravity,
            substep_count: self.substep_count,
            contact_frequency_hz: self.contact_frequency_hz,
            contact_damping_ratio: self.contact_damping_ratio,
            max_push_out_speed: self.max_push_out_speed,
            restitution_threshold: self.restitution_threshold,
            warm_starting: self.warm_starting,
            resting_overlap: self.resting_overlap,
        }
    }
}
