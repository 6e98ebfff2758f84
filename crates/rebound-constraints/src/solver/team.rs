//! [`JointTeam`]: the joint solver lent to a team of threads for the substeps' passes
//! (`rebound_math::team`): *apply forces* split among the team when the joints are pairwise apart
//! (`pool.rs`: each chunk's joints write their own two bodies at once, no write-back), every other joint
//! pass by one thread while the others wait at the team's barrier.
#![allow(
    unsafe_code,
    reason = "the solver's joints and bodies shared by the chunks of a team (rebound_math::Disjoint)"
)]

use super::dispatch::PreparedJoint;
use super::joint_solver::JointSolver;
use super::pool::JOINTS_PER_TASK;
use crate::pair::BodyPair;
use rebound_dynamics::{SolverBody, StepContext};
use rebound_math::Disjoint;
use std::marker::PhantomData;
use std::ptr::NonNull;

/// A prepared [`JointSolver`] lent to a team of threads for the substeps' passes (see the module docs):
/// [`JointSolver::team`].
pub struct JointTeam<'a> {
    /// The joints, each chunk of *apply forces* taking its own.
    joints: Disjoint<'a, PreparedJoint>,
    /// Whether *apply forces* may split the joints (`pool.rs`).
    apart: bool,
    coordinate_springs: bool,
    /// Whether the solver has nothing to solve (no joint, path or tether).
    idle: bool,
    /// Whether *warm start*, *solve* and *relax* have nothing to do: every joint acts in *apply forces*
    /// alone (a spring), and there is no path or tether.
    forces_only: bool,
    /// The solver, for the passes one thread runs alone.
    solver: NonNull<JointSolver>,
    borrow: PhantomData<&'a mut JointSolver>,
}

// SAFETY: a `JointTeam` is the solver's exclusive borrow, shared among the team; its methods' contracts keep
// the threads on disjoint parts (`JointSolver` is `Send + Sync`).
unsafe impl Send for JointTeam<'_> {}
// SAFETY: see above.
unsafe impl Sync for JointTeam<'_> {}

impl JointSolver {
    /// The solver lent to a team of threads for the substeps' passes.
    pub fn team(&mut self) -> JointTeam<'_> {
        let (apart, coordinate_springs) = (self.pool.is_active(), self.coordinate_springs);
        let no_rows =
            self.tethers.is_empty() && self.links.is_empty() && self.topology.paths.is_empty();
        let idle = no_rows && self.joints.is_empty();
        let forces_only = no_rows && self.joints.iter().all(|j| j.kind.acts_in_no_pass());
        let solver = NonNull::from(&mut *self);
        // SAFETY: `solver` is `self`, borrowed for `'a`; the passes run through `solver` by one thread alone
        // never run while a chunk holds joints (the team's barrier between phases).
        let this = unsafe { &mut *solver.as_ptr() };
        JointTeam {
            joints: Disjoint::new(&mut this.joints),
            apart,
            coordinate_springs,
            idle,
            forces_only,
            solver,
            borrow: PhantomData,
        }
    }
}

impl JointTeam<'_> {
    /// Whether the solver has nothing to solve: its passes may be left out.
    #[must_use]
    pub fn is_idle(&self) -> bool {
        self.idle
    }

    /// Whether *warm start*, *solve* and *relax* leave every body as it is (every joint a spring, no path or
    /// tether): those passes may be left out, and only *apply forces* runs.
    #[must_use]
    pub fn is_forces_only(&self) -> bool {
        self.forces_only
    }

    /// Into how many chunks, of at most `threads`, *apply forces* is split: 1 unless the joints are pairwise
    /// apart and at least two chunks' worth.
    #[must_use]
    pub fn force_chunks(&self, threads: usize) -> usize {
        if self.apart {
            (self.joints.len() / JOINTS_PER_TASK).clamp(1, threads.max(1))
        } else {
            1
        }
    }

    /// Whether chunk `k` of `chunks` of *apply forces* touches only the bodies of range `k` of `chunks`
    /// equal ranges of `body_count` bodies (as the team splits integration), for every `k`: then each chunk
    /// may integrate its bodies and apply its joints' forces back to back. True for a field of springs whose
    /// bodies are numbered pair by pair.
    ///
    /// # Safety
    /// No chunk of this team runs while it looks (it reads every joint's bodies).
    #[must_use]
    pub unsafe fn forces_within_body_ranges(&self, chunks: usize, body_count: usize) -> bool {
        if !self.apart || chunks <= 1 {
            return false;
        }
        let len = self.joints.len();
        // SAFETY: nothing writes the joints meanwhile (the caller's contract).
        let joints = unsafe { self.joints.slice_mut(0..len) };
        (0..chunks).all(|k| {
            let bodies = body_count * k / chunks..body_count * (k + 1) / chunks;
            joints[len * k / chunks..len * (k + 1) / chunks]
                .iter()
                .all(|j| bodies.contains(&j.pair.index_a) && bodies.contains(&j.pair.index_b))
        })
    }

    /// Stage *apply forces* of chunk `chunk` of `chunks` of the joints ([`JointTeam::force_chunks`]); with one
    /// chunk, [`JointSolver::apply_forces`].
    ///
    /// # Safety
    /// With one chunk, nothing else runs on `bodies` or this team while it does. With more, only the other
    /// chunks of the same *apply forces* do (the joints share no body: `JointPool::plan`).
    pub unsafe fn apply_forces_chunk(
        &self,
        (chunk, chunks): (usize, usize),
        bodies: &Disjoint<'_, SolverBody>,
        ctx: &StepContext,
    ) {
        if chunks <= 1 || !self.apart {
            // SAFETY: one thread alone (the caller's contract).
            unsafe { self.solver_mut().apply_forces(bodies.all_mut(), ctx) };
            return;
        }
        let len = self.joints.len();
        let range = len * chunk / chunks..len * (chunk + 1) / chunks;
        let (h, coordinate_springs) = (ctx.h, self.coordinate_springs);
        // SAFETY: the chunks' joint ranges are disjoint, and so are their joints' bodies.
        let joints = unsafe { self.joints.slice_mut(range) };
        for j in joints {
            let (ia, ib) = (j.pair.index_a, j.pair.index_b);
            // SAFETY: the joint's own two bodies, two different ones (apart from every other joint's).
            let (a, b) = unsafe { (bodies.get_mut(ia), bodies.get_mut(ib)) };
            let read = |body: &Option<&mut SolverBody>| body.as_deref().copied();
            // The joint's stages on copies of its two bodies, as `JointSolver::joints_on_pool`.
            let mut pair_bodies = [
                read(&a).unwrap_or(SolverBody::STATIC),
                read(&b).unwrap_or(SolverBody::STATIC),
            ];
            let local = BodyPair {
                index_a: 0,
                index_b: 1,
                ..j.pair
            };
            j.kind
                .apply_forces(&local, &mut j.state, &mut pair_bodies, h);
            if coordinate_springs {
                j.kind
                    .apply_coordinate_spring(&local, &mut j.state, &mut pair_bodies, h);
            }
            if let Some(a) = a {
                *a = pair_bodies[0];
            }
            if let Some(b) = b {
                *b = pair_bodies[1];
            }
        }
    }

    /// The solver, for a pass one thread runs alone ([`JointSolver::warm_start`],
    /// [`JointSolver::solve_substep`]).
    ///
    /// # Safety
    /// Nothing else runs on this team while the reference lives (one thread, the others at the barrier).
    #[must_use]
    #[expect(
        clippy::mut_from_ref,
        reason = "one thread alone (the caller's contract)"
    )]
    pub unsafe fn solver_mut(&self) -> &mut JointSolver {
        // SAFETY: the caller's contract.
        unsafe { &mut *self.solver.as_ptr() }
    }
}
