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
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
// Missing fields take their defaults, so a scene file names only what differs.
#[cfg_attr(feature = "serde", serde(default))]
pub struct WorldSettings {
    /// Gravity (m/s²). Default: (0, −9.81, 0).
    pub gravity: Vec3,
    /// Soft substeps per step (each `dt / substep_count` long). Default: 4. Must be ≥ 1.
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
    /// The step length [`crate::World::advance`] uses (s). Default: 1/60 s.
    pub fixed_dt: f32,
    /// The most steps one [`crate::World::advance`] call runs (the rest of the time is dropped, so a slow
    /// frame cannot snowball). Default: 8.
    pub max_steps_per_advance: u32,
    /// Joint solver settings: the softness of hard joint parts, iteration counts, long-range tethers for
    /// hanging chains. Default: [`JointSettings::default`] (60 Hz, ζ = 2, one solve and one relax pass,
    /// tethers on).
    pub joints: JointSettings,
    /// The physical bounds beyond which a body is quarantined and the caps on a step's work. Default:
    /// [`StepLimits::default`] (10⁴ m/s, 10⁴ rad/s, 10⁶ m; 2¹⁷ candidate pairs, 2¹⁹ contact points).
    pub limits: StepLimits,
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
            joints: JointSettings::default(),
            limits: StepLimits::default(),
        }
    }
}

impl WorldSettings {
    /// Checks every field.
    ///
    /// # Errors
    /// A [`WorldError`] naming the first invalid field: non-finite values, a zero substep count, negative
    /// thresholds or damping, a non-positive fixed step.
    pub fn validate(&self) -> Result<(), WorldError> {
        check_finite_vec3("gravity", self.gravity)?;
        if self.substep_count == 0 {
            return Err(WorldError::InvalidSetting {
                field: "substep_count",
                value: 0.0,
            });
        }
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
        if self.max_steps_per_advance == 0 {
            return Err(WorldError::InvalidSetting {
                field: "max_steps_per_advance",
                value: 0.0,
            });
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
        }
    }
}
