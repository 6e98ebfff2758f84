//! A pass of the wide path over the batches (stages *warm start*, *solve* and *relax*): one after another,
//! or a colour group's batches split among the threads of a team (`rebound_math::team`).
//!
//! The batches of one colour of one chunk share no moving body (`super::coloring`), so within such a group
//! no batch reads a velocity another one writes. On several threads each batch reads its bodies, computes
//! its lanes' new velocities and writes them into its own dynamic bodies at once (`Batch::scatter_moving`):
//! no other batch of the group reads or writes those, so the bits are those of solving the group's batches
//! one after the other, whichever thread solves which. Fixed and kinematic bodies, which several batches of
//! a group may share, are only read: a lane adds `0·λ` to their velocities (their inverse masses and
//! inertias are 0), and those velocities hold no −0 component (`SolverBody::from_body` turns a kinematic
//! body's −0 into +0, the one value `0·λ` could change), so the plain loop, which writes them back, leaves
//! them as they were too.
//!
//! In the serial build, and in a pool of one thread, a pass is the plain loop over the batches.

use super::batch::{Batch, Batches, PatchX4, PointX4, Rows, TwistX4};
use crate::contact::bias::Bias;
use crate::{SolverBody, StepContext};
use rebound_math::Disjoint;
use std::ops::Range;

/// Batches per chunk of a team: a group of fewer than twice this is solved whole by one thread.
pub(crate) const BATCHES_PER_CHUNK: usize = 16;

/// Stage *warm start* of the batches, one after another.
pub(crate) fn warm_start_batches(batches: &Batches, bodies: &mut [SolverBody]) {
    for (batch, patch) in batches.batches.iter().zip(&batches.patches) {
        batch.warm_start(patch, &batches.slots, &batches.twists, bodies);
    }
}

/// Stages *solve* (`Bias::On`) and *relax* (`Bias::Off`) of the batches, one after another.
pub(crate) fn solve_batches(
    batches: &mut Batches,
    bodies: &mut [SolverBody],
    ctx: &StepContext,
    bias: Bias,
) {
    let Batches {
        batches,
        patches,
        slots,
        twists,
        ..
    } = batches;
    for (batch, patch) in batches.iter().zip(patches.iter_mut()) {
        batch.solve(patch, slots, twists, bodies, ctx, bias);
    }
}

/// The batches' rows, shared by the chunks of a team: each chunk takes the rows of its own batches.
pub(crate) struct SharedRows<'a> {
    pub(crate) batches: &'a [Batch],
    pub(crate) patches: Disjoint<'a, PatchX4>,
    pub(crate) slots: Disjoint<'a, PointX4>,
    pub(crate) twists: Disjoint<'a, TwistX4>,
}

impl SharedRows<'_> {
    /// Batch `index`'s rows.
    ///
    /// # Safety
    /// No other reference to the batch's rows lives (a batch's rows are its own: `Batches::push`).
    #[inline(always)]
    #[expect(
        unsafe_code,
        reason = "a batch's rows out of the arrays all chunks share"
    )]
    unsafe fn rows(&self, index: usize, batch: &Batch) -> Option<Rows<'_>> {
        let first = batch.first_slot as usize;
        // SAFETY: the batch's own rows (the caller's contract).
        unsafe {
            Some(Rows {
                points: self
                    .slots
                    .slice_mut(first..first + usize::from(batch.slots)),
                patch: self.patches.get_mut(index)?,
                twist: if batch.twist {
                    self.twists.get_mut(batch.first_twist as usize)
                } else {
                    None
                },
            })
        }
    }

    /// Stage *warm start* of the batches `range` of one colour group, each written into its own bodies.
    ///
    /// # Safety
    /// The batches are of one colour group, and the only other code running on `bodies` and the rows is
    /// this function or [`SharedRows::solve`] on other batches of the same group.
    #[expect(
        unsafe_code,
        reason = "the batches of a colour group write their own bodies at once"
    )]
    pub(crate) unsafe fn warm_start(&self, range: Range<usize>, bodies: &Disjoint<'_, SolverBody>) {
        for (offset, batch) in self.batches[range.clone()].iter().enumerate() {
            // SAFETY: a batch's rows are its own, and within the group its dynamic bodies too; fixed and
            // kinematic bodies are only read (see the module docs).
            unsafe {
                let Some(rows) = self.rows(range.start + offset, batch) else {
                    continue;
                };
                let lanes = batch.shared_states(bodies);
                let twist = rows.twist.as_deref();
                let velocities = batch.warm_start_lanes(rows.points, rows.patch, twist, lanes);
                batch.scatter_moving(bodies, &velocities);
            }
        }
    }

    /// Stages *solve* and *relax* of the batches `range` of one colour group, each written into its own
    /// bodies.
    ///
    /// # Safety
    /// As [`SharedRows::warm_start`].
    #[expect(
        unsafe_code,
        reason = "the batches of a colour group write their own bodies at once"
    )]
    pub(crate) unsafe fn solve(
        &self,
        range: Range<usize>,
        bodies: &Disjoint<'_, SolverBody>,
        ctx: &StepContext,
        bias: Bias,
    ) {
        for (offset, batch) in self.batches[range.clone()].iter().enumerate() {
            // SAFETY: as in `warm_start`.
            unsafe {
                let Some(rows) = self.rows(range.start + offset, batch) else {
                    continue;
                };
                let lanes = batch.shared_states(bodies);
                let velocities = batch.solve_lanes(rows, lanes, ctx, bias);
                batch.scatter_moving(bodies, &velocities);
            }
        }
    }
}
