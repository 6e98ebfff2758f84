//! The per-step constants every stage reads (Box2D's `b2StepContext`): step and substep lengths, their
//! inverses, gravity and the contact softness. Built once at the start of a step (stage 1 of the step,
//! `docs/architecture.md`).

use crate::Softness;
use rebound_math::Vec3;

/// The solver settings a step context is built from. `rebound-world`'s `WorldSettings` embeds these.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Gravity (m/s²). Default: (0, −9.81, 0).
    pub gravity: Vec3,
    /// Substeps per step (each of length `h = dt / substep_count`). Default: 4. 0 is treated as 1.
    pub substep_count: u32,
    /// Stiffness of contacts as a natural frequency (Hz). Capped at a quarter of the substep rate so that a
    /// contact never asks more than the substep can give. Default: 30 Hz.
    pub contact_frequency_hz: f32,
    /// Damping ratio of contacts (dimensionless; 1 = critical). Default: 5 (over-damped: contacts push out
    /// without bouncing — bounce comes from restitution; rapier's default). Box2D's 10 corrects overlap half as
    /// fast (the bias rate is `ω/(2ζ + hω)`) and let the pyramid scene rock out of its plane by 0.8 cm
    /// (5 gives 0.3 cm, 20 topples it); see `docs/physics.md`, "Contact damping ratio".
    pub contact_damping_ratio: f32,
    /// The fastest a contact pushes overlapping bodies apart (m/s). Default: 3 m/s.
    pub max_push_out_speed: f32,
    /// Below this approach speed (m/s) restitution is not applied, so resting contacts do not jitter.
    /// Default: 1 m/s.
    pub restitution_threshold: f32,
    /// Whether stored impulses from the last step seed the solver. Default: true.
    pub warm_starting: bool,
    /// The overlap (m) a loaded resting contact may keep: with `Some(ε)` each resting manifold's soft rows
    /// hold the weight it carries ([`StackLoads`](crate::contact::StackLoads)) at rest at an overlap of
    /// `min(ε, load / stiffness)`; with `None` (off) the overlap at rest is `load / stiffness`. Default:
    /// `Some(1e-4)` (0.1 mm, keeps a 40-box column within 1 cm; `docs/physics.md`, "Contacts under load").
    pub resting_overlap: Option<f32>,
}

impl Default for SolverSettings {
    fn default() -> Self {
        Self {
            gravity: Vec3::new(0.0, -9.81, 0.0),
            substep_count: 4,
            contact_frequency_hz: 30.0,
            contact_damping_ratio: 5.0,
            max_push_out_speed: 3.0,
            restitution_threshold: 1.0,
            warm_starting: true,
            resting_overlap: Some(1e-4),
        }
    }
}

/// Constants of one step, computed once by [`StepContext::new`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StepContext {
    /// Step length (s).
    pub dt: f32,
    /// 1/dt (1/s).
    pub inv_dt: f32,
    /// Substep length `h = dt / substep_count` (s).
    pub h: f32,
    /// 1/h (1/s).
    pub inv_h: f32,
    /// Number of substeps.
    pub substep_count: u32,
    /// Gravity (m/s²).
    pub gravity: Vec3,
    /// Softness of contacts between two moving bodies.
    pub contact_softness: Softness,
    /// Softness of contacts against a fixed or kinematic body: twice the frequency, as Box2D, since only one
    /// body gives way.
    pub static_softness: Softness,
    /// Push-out speed cap (m/s).
    pub max_push_out_speed: f32,
    /// Restitution threshold speed (m/s).
    pub restitution_threshold: f32,
    /// Whether warm starting is on.
    pub warm_starting: bool,
    /// The overlap (m) a loaded resting contact may keep, `None` when loads are not held
    /// ([`SolverSettings::resting_overlap`]).
    pub resting_overlap: Option<f32>,
}

impl StepContext {
    /// The context of a step of `dt` seconds (`dt > 0` and finite; the world checks it).
    #[must_use]
    pub fn new(dt: f32, settings: &SolverSettings) -> Self {
        let substep_count = settings.substep_count.max(1);
        let h = dt / substep_count as f32;
        let inv_h = if h > 0.0 { 1.0 / h } else { 0.0 };
        // Box2D: contact stiffness at most a quarter of the substep rate.
        let contact_hz = settings.contact_frequency_hz.min(0.25 * inv_h);
        Self {
            dt,
            inv_dt: if dt > 0.0 { 1.0 / dt } else { 0.0 },
            h,
            inv_h,
            substep_count,
            gravity: settings.gravity,
            contact_softness: Softness::new(contact_hz, settings.contact_damping_ratio, h),
            static_softness: Softness::new(2.0 * contact_hz, settings.contact_damping_ratio, h),
            max_push_out_speed: settings.max_push_out_speed,
            restitution_threshold: settings.restitution_threshold,
            warm_starting: settings.warm_starting,
            resting_overlap: settings.resting_overlap,
        }
    }
}
