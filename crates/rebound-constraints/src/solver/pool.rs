//! Stage *apply forces* (the joints' springs) over the thread pool, for a step whose joints are pairwise
//! apart: no two joints share a body, fixed bodies included — a field of separate springs. Each joint then
//! reads and writes its two bodies alone, so running the joints at once gives every body the operations, in
//! the order, that the joint-by-joint loop gives it: the same bits for any number of threads.
//!
//! The stage copies each joint's two bodies out (over the pool), runs the joint on its copies (over the
//! pool), and writes the copies back in joint order. Any other step (joints sharing a body), the serial
//! build and a pool of one thread take the plain loop of `passes.rs`; the substeps' team splits the same
//! joints its own way (`team.rs`).

use super::dispatch::PreparedJoint;
use rebound_dynamics::SolverBody;
use rebound_math::par;

/// Joints per task: below twice this the plain loop runs.
pub(super) const JOINTS_PER_TASK: usize = 64;

/// The pool's plan for this step's joints and its scratch.
#[derive(Debug, Clone, Default)]
pub(super) struct JointPool {
    /// Whether the joints of the prepared step may be solved at once (see the module docs).
    apart: bool,
    /// Scratch: per joint, its two bodies while the pool runs it.
    pub(super) bodies: Vec<[SolverBody; 2]>,
    /// Scratch: per solver body, whether a joint of the step uses it.
    used: Vec<bool>,
}

impl JointPool {
    /// Decides, once *prepare* has listed the step's joints, whether *apply forces* may run them at once: a
    /// pool of more than one thread, enough joints, and no body (of `body_count`) in two joints or twice in
    /// one.
    pub(super) fn plan(&mut self, joints: &[PreparedJoint], body_count: usize) {
        self.apart = false;
        if !par::is_parallel() || joints.len() < 2 * JOINTS_PER_TASK {
            return;
        }
        self.used.clear();
        self.used.resize(body_count, false);
        for j in joints {
            for index in [j.pair.index_a, j.pair.index_b] {
                match self.used.get_mut(index) {
                    Some(used) if !*used => *used = true,
                    _ => return,
                }
            }
        }
        self.apart = true;
    }

    /// Whether this step's *apply forces* runs on the pool.
    pub(super) fn is_active(&self) -> bool {
        self.apart && par::is_parallel()
    }
}
