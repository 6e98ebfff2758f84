//! What a step reports: counts, per-phase timings and anything abnormal (Jolt's `EPhysicsUpdateError`,
//! Box2D's profile). `World::step` never fails; it says here what it did. The stages fill in their counts as
//! they go; the body counts are taken at the end of the step (stage *report*).

use crate::body_set::BodySet;
use crate::handles::BodyHandle;
use core::time::Duration;
use rebound_dynamics::BodyParams;

/// Wall-clock time spent in each phase of the last step. Not deterministic and not part of the state.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Profile {
    /// Collision backend and contact matching.
    pub collide: Duration,
    /// Building the solver arrays and preparing contacts and joints.
    pub prepare: Duration,
    /// The substep loop: integrate, warm start, solve, relax.
    pub solve: Duration,
    /// Restitution and storing impulses.
    pub restitution: Duration,
    /// Writing back, islands, sleep and events.
    pub finalize: Duration,
    /// The whole step.
    pub total: Duration,
}

/// Why a step did nothing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StepSkipped {
    /// `dt` was zero or negative: nothing moves.
    NonPositiveDt(f32),
    /// `dt` was NaN or infinite: nothing moves.
    NonFiniteDt(f32),
    /// `dt` was positive but shorter than [`crate::MIN_STEP_DT`] (1 µs): nothing moves, rather than the
    /// solver dividing by a substep too short for `f32`.
    DtTooSmall(f32),
}

/// The outcome of [`crate::World::step`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StepReport {
    /// Set when the step did nothing, and why.
    pub skipped: Option<StepSkipped>,
    /// Bodies in the world.
    pub body_count: usize,
    /// Bodies the solver moved (awake, not fixed).
    pub awake_body_count: usize,
    /// Sleeping bodies.
    pub sleeping_body_count: usize,
    /// Contact manifolds solved.
    pub contact_count: usize,
    /// Contact points solved.
    pub contact_point_count: usize,
    /// Joints solved.
    pub joint_count: usize,
    /// Joints that broke this step.
    pub broken_joint_count: usize,
    /// Manifolds the backend reported that could not be used (a stale handle, a body against itself, a
    /// non-finite normal or separation). Should be 0; anything else is a backend bug.
    pub rejected_contact_count: usize,
    /// Calls of the facade's contact hooks that panicked or returned an edit out of range this step; each
    /// left its pair or manifold as if no hook were set (`rebound::ContactHooks`). 0 in a world without
    /// hooks.
    pub hook_failure_count: usize,
    /// Bodies quarantined this step (see [`crate::Event::BodyQuarantined`]).
    pub quarantined_body_count: usize,
    /// Candidate pairs the collision backend left out because of [`crate::StepLimits::max_candidate_pairs`].
    pub capped_pair_count: usize,
    /// Manifolds left out because of [`crate::StepLimits::max_contact_points`].
    pub capped_manifold_count: usize,
    /// Phase timings.
    pub profile: Profile,
}

/// The outcome of [`crate::World::advance`].
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct AdvanceReport {
    /// Steps run.
    pub steps: u32,
    /// Time dropped because `max_steps_per_advance` was reached (s).
    pub dropped_time: f32,
    /// How far the leftover time is into the next step, in `[0, 1)`: interpolate rendered poses between the
    /// previous and the current state by this factor.
    pub alpha: f32,
    /// The report of the last step run, if any.
    pub last_step: Option<StepReport>,
}

impl StepReport {
    /// The report of a step that did nothing.
    pub(crate) fn skipped(reason: StepSkipped, bodies: &BodySet) -> Self {
        Self {
            skipped: Some(reason),
            body_count: bodies.len(),
            ..Self::default()
        }
    }

    /// Stage *report*: the body counts at the end of a step, from the world's bodies and the solver arrays
    /// of the step (solver index → body handle, `None` for the world anchor, and the body's parameters).
    pub(crate) fn count_bodies(
        &mut self,
        bodies: &BodySet,
        solver_handles: &[Option<BodyHandle>],
        params: &[BodyParams],
    ) {
        self.body_count = bodies.len();
        self.awake_body_count = solver_handles.iter().filter(|h| h.is_some()).count();
        self.awake_body_count -= params
            .iter()
            .filter(|p| !p.is_dynamic())
            .count()
            .min(self.awake_body_count);
        self.sleeping_body_count = bodies.iter().filter(|(_, b)| b.is_sleeping()).count();
    }
}
