//! `Scratch`: the buffers the step reuses from step to step, so that a steady-state step allocates nothing.
//! Not part of the world's state (a snapshot leaves them out), except the joint solver's kept rows, which
//! the snapshot reads through it. Grouped below by the stage that writes each buffer.

use crate::events::EventBuffers;
use crate::handles::{BodyHandle, JointHandle};
use crate::manifold::ContactManifold;
use crate::union_find::UnionFind;
use rebound_constraints::{Joint, JointBodies, JointSolver, JointState};
use rebound_dynamics::{BodyParams, Contact, ContactSolver, SolverBody};
use rebound_math::Mat3;

/// Body slot → solver index: no solver index (a sleeping body, or a fixed one no constraint needs).
pub(crate) const NO_INDEX: u32 = u32::MAX;

/// Buffers reused from step to step (no allocation in a steady-state step). Not part of the state.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    // ---- collide ----
    /// Manifolds the backend reported this step, validated and warm-started (sorted by order key).
    pub(crate) manifolds: Vec<ContactManifold>,
    /// For each manifold of this step, the approach speed before the step (m/s): the contact events' speed
    /// and the waking test.
    pub(crate) approach_speeds: Vec<f32>,
    /// Body slot → the rotation matrix of the body's orientation and the collide call that computed it
    /// (`collide_calls`): each body's matrix is computed once per collide stage, at its first manifold.
    pub(crate) rotations: Vec<(u64, Mat3)>,
    /// How many collide stages ran (so that a matrix of an earlier one is never read as current).
    pub(crate) collide_calls: u64,

    // ---- prepare ----
    /// Body slot → solver index, or [`NO_INDEX`].
    pub(crate) solver_index: Vec<u32>,
    /// Solver index → body handle (`None` for the world anchor entry).
    pub(crate) solver_handles: Vec<Option<BodyHandle>>,
    /// Solver index → the body's solver state (velocities, pose deltas) and constant parameters.
    pub(crate) states: Vec<SolverBody>,
    pub(crate) params: Vec<BodyParams>,
    /// Solver contacts and, for each, the manifold it came from.
    pub(crate) contacts: Vec<Contact>,
    pub(crate) contact_sources: Vec<usize>,
    /// Joints handed to the solver, their states and bodies, and the handles they came from.
    pub(crate) joints: Vec<Joint>,
    pub(crate) joint_states: Vec<JointState>,
    pub(crate) joint_bodies: Vec<JointBodies>,
    pub(crate) joint_handles: Vec<JointHandle>,
    pub(crate) contact_solver: ContactSolver,
    pub(crate) joint_solver: JointSolver,

    // ---- store ----
    /// Indices (into `joints`) of the joints that broke this step.
    pub(crate) broken: Vec<usize>,
    /// For each manifold of this step, whether the solver pushed with it (a contact that touched during the
    /// step, even one that bounced off and ended with no accumulated impulse).
    pub(crate) pushed: Vec<bool>,

    // ---- islands and sleep ----
    pub(crate) union_find: UnionFind,
    /// Solver index → whether the body has rested long enough to sleep.
    pub(crate) can_rest: Vec<bool>,
    /// Island root → whether every member may sleep.
    pub(crate) island_ok: Vec<bool>,
    /// Pairs of solver indices that belong to the same island.
    pub(crate) links: Vec<(u32, u32)>,
    /// (island root, body) of the bodies falling asleep.
    pub(crate) sleepers: Vec<(u32, BodyHandle)>,
    /// Bodies to wake (waking by a changed body, by touch and by joints).
    pub(crate) to_wake: Vec<BodyHandle>,

    // ---- events ----
    pub(crate) events: EventBuffers,
}
