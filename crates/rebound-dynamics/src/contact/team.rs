//! [`ContactTeam`]: the contact solver's passes as the chunks of a team of threads run them
//! (`rebound_math::team`): each colour group of the wide path split among the team, each thread's share of
//! batches written straight into the bodies (`wide::groups`), the scalar path and the read-back by one
//! thread while the others wait at the team's barrier. The same bits as [`ContactSolver::warm_start`] and
//! [`ContactSolver::solve`], group by group.
#![allow(
    unsafe_code,
    reason = "the solver's arrays shared by the chunks of a team (rebound_math::Disjoint)"
)]

use super::bias::Bias;
use super::solver::ContactSolver;
use super::wide::{BATCHES_PER_CHUNK, SharedRows};
use crate::{SolverBody, StepContext};
use rebound_math::Disjoint;
use std::marker::PhantomData;
use std::ops::Range;
use std::ptr::NonNull;

/// A prepared [`ContactSolver`] lent to a team for its passes: [`ContactSolver::team`].
pub struct ContactTeam<'a> {
    /// The wide path's rows, each chunk taking its batches'.
    rows: SharedRows<'a>,
    /// The end of each colour group in the batches.
    group_ends: &'a [usize],
    /// Whether the scalar path has manifolds.
    scalar: bool,
    /// The solver, for what one thread does alone (the scalar path, the read-back).
    solver: NonNull<ContactSolver>,
    borrow: PhantomData<&'a mut ContactSolver>,
}

// SAFETY: a `ContactTeam` is the solver's exclusive borrow, shared among the team; its methods' contracts keep
// the threads on disjoint parts (`ContactSolver` is `Send + Sync`).
unsafe impl Send for ContactTeam<'_> {}
// SAFETY: see above.
unsafe impl Sync for ContactTeam<'_> {}

impl ContactSolver {
    /// The solver lent to a team of threads for the substeps' passes, or `None` if it was not prepared in a
    /// pool of more than one thread (its batches then lack what the team needs: which lanes' bodies are
    /// dynamic).
    pub fn team(&mut self) -> Option<ContactTeam<'_>> {
        if !self.batches.moving && !self.batches.batches.is_empty() {
            return None;
        }
        let solver = NonNull::from(&mut *self);
        // SAFETY: `solver` is `self`, borrowed for `'a`; the rows and group ends below are fields the
        // one-thread methods reached through `solver` (scalar path, read-back) never write.
        let this = unsafe { &mut *solver.as_ptr() };
        let batches = &mut this.batches;
        Some(ContactTeam {
            rows: SharedRows {
                batches: &batches.batches,
                patches: Disjoint::new(&mut batches.patches),
                slots: Disjoint::new(&mut batches.slots),
                twists: Disjoint::new(&mut batches.twists),
            },
            group_ends: &this.coloring.group_ends,
            scalar: !this.scalar.is_empty(),
            solver,
            borrow: PhantomData,
        })
    }
}

impl ContactTeam<'_> {
    /// Whether some manifolds are left to the scalar path (else its passes may be left out).
    #[must_use]
    pub fn has_scalar(&self) -> bool {
        self.scalar
    }

    /// The number of colour groups of the wide path.
    #[must_use]
    pub fn group_count(&self) -> usize {
        self.group_ends.len()
    }

    /// Group `group`'s batches (a range of batch indices; empty past the last group).
    #[must_use]
    pub fn group(&self, group: usize) -> Range<usize> {
        let start = group
            .checked_sub(1)
            .and_then(|g| self.group_ends.get(g))
            .copied()
            .unwrap_or(0);
        let end = self.group_ends.get(group).copied().unwrap_or(start);
        start..end.max(start)
    }

    /// Into how many chunks, of at most `threads`, group `group` is best split: 1 below two chunks'
    /// worth of batches.
    #[must_use]
    pub fn chunks_of(&self, group: usize, threads: usize) -> usize {
        (self.group(group).len() / BATCHES_PER_CHUNK).clamp(1, threads.max(1))
    }

    /// Stage *warm start* of chunk `chunk` of `chunks` of group `group`'s batches.
    ///
    /// # Safety
    /// While it runs, `bodies` and this team are used by nothing but the other chunks of the same group in
    /// the same pass (the colouring keeps their bodies apart).
    pub unsafe fn warm_start_chunk(
        &self,
        group: usize,
        (chunk, chunks): (usize, usize),
        bodies: &Disjoint<'_, SolverBody>,
    ) {
        let range = split(self.group(group), chunk, chunks);
        // SAFETY: the caller's contract: only other batches of the group run at once.
        unsafe { self.rows.warm_start(range, bodies) };
    }

    /// Stages *solve* and *relax* of chunk `chunk` of `chunks` of group `group`'s batches.
    ///
    /// # Safety
    /// As [`ContactTeam::warm_start_chunk`].
    pub unsafe fn solve_chunk(
        &self,
        group: usize,
        (chunk, chunks): (usize, usize),
        bodies: &Disjoint<'_, SolverBody>,
        ctx: &StepContext,
        bias: Bias,
    ) {
        let range = split(self.group(group), chunk, chunks);
        // SAFETY: as above.
        unsafe { self.rows.solve(range, bodies, ctx, bias) };
    }

    /// Stage *warm start* of the manifolds the scalar path solves (after every group).
    ///
    /// # Safety
    /// Nothing else runs on this team while it does (one thread, the others at the barrier).
    pub unsafe fn warm_start_scalar(&self, bodies: &mut [SolverBody]) {
        // SAFETY: the caller's contract; the scalar path touches none of the rows lent to the chunks.
        unsafe { self.solver.as_ref() }.warm_start_scalar(bodies);
    }

    /// Stages *solve* and *relax* of the manifolds the scalar path solves (after every group).
    ///
    /// # Safety
    /// As [`ContactTeam::warm_start_scalar`].
    pub unsafe fn solve_scalar(&self, bodies: &mut [SolverBody], ctx: &StepContext, bias: Bias) {
        // SAFETY: as above.
        unsafe { &mut *self.solver.as_ptr() }.solve_scalar(bodies, ctx, bias);
    }

    /// [`ContactSolver::for_each_normal_impulse`].
    ///
    /// # Safety
    /// As [`ContactTeam::warm_start_scalar`].
    pub unsafe fn for_each_normal_impulse(&self, f: impl FnMut(usize, usize, f32, f32)) {
        // SAFETY: as above; only read.
        unsafe { self.solver.as_ref() }.for_each_normal_impulse(f);
    }
}

/// Chunk `chunk` of `chunks` of `range`: the chunks in order, their lengths differing by one at most.
fn split(range: Range<usize>, chunk: usize, chunks: usize) -> Range<usize> {
    let (len, chunks) = (range.len(), chunks.max(1));
    let at = |k: usize| range.start + len * k / chunks;
    at(chunk.min(chunks))..at((chunk + 1).min(chunks))
}
