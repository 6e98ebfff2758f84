//! `Scratch`: the buffers the step reuses from step to step, so that a steady-state step allocates nothing,
//! one part per stage that owns them. Not part of the world's state (a snapshot leaves them out), except the
//! joint solver's kept rows, which the snapshot reads through it.

use crate::collide::Collision;
use crate::events::EventBuffers;
use crate::handles::BodyHandle;
use crate::islands::SleepBuffers;
use crate::limits::QuarantineReason;
use crate::prepare::Solver;
use crate::quarantine::StartCheck;

/// Buffers reused from step to step (no allocation in a steady-state step). Not part of the state.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    /// This step's manifolds (stage *collide*) and what *store* learns of each.
    pub(crate) collision: Collision,
    /// The solver arrays and the solvers (stage *prepare* builds them, the solver passes run on them).
    pub(crate) solver: Solver,
    /// The buffers of waking and sleep (stage *islands and sleep*).
    pub(crate) sleep: SleepBuffers,
    /// The buffers of stage *events*.
    pub(crate) events: EventBuffers,
    /// Bodies the solver's result put out of bounds (the quarantine's suspects).
    pub(crate) suspects: Vec<(BodyHandle, QuarantineReason)>,
    /// What the quarantine's start-of-step check knows of the bodies the last step wrote back.
    pub(crate) start_check: StartCheck,
}
