//! A pass of the wide path over the batches, colour group by colour group (stages *warm start*, *solve* and
//! *relax*). The batches of one colour of one chunk share no moving body, so within such a group no batch
//! reads a velocity another one writes: on several threads each batch reads the bodies as the group found
//! them, computes its lanes' new velocities (`Batch::solve_lanes`), and the group writes them back in batch
//! order once all are done. A dynamic body is written by one batch of the group only, so the result is the
//! bit pattern of solving the batches one after the other, for any number of threads. Fixed and kinematic
//! bodies, which several batches of a group may share, get back the velocity they held: a lane adds `0·λ`
//! to it (their inverse masses are 0), and that velocity holds no −0 component (`SolverBody::from_body`
//! turns a kinematic body's −0 into +0, the one value `0·λ` could change), so which lane's write is kept
//! does not matter.
//!
//! In the serial build, and in a pool of one thread, a pass is the plain loop over the batches.

use super::batch::{Batch, Batches, LaneVelocities, PatchX4, PointX4, Rows, TwistX4};
use crate::contact::bias::Bias;
use crate::{SolverBody, StepContext};
use rebound_math::par;

/// Batches per task: below this a group's batches are solved on one thread.
const BATCHES_PER_TASK: usize = 16;

/// Stage *warm start* of the batches.
pub(crate) fn warm_start_batches(
    batches: &mut Batches,
    group_ends: &[usize],
    bodies: &mut [SolverBody],
    scratch: &mut Vec<LaneVelocities>,
) {
    if !par::is_parallel() {
        for (batch, patch) in batches.batches.iter().zip(&batches.patches) {
            batch.warm_start(patch, &batches.slots, &batches.twists, bodies);
        }
        return;
    }
    by_groups(
        batches,
        group_ends,
        bodies,
        scratch,
        &|batch, rows, bodies| {
            batch.warm_start_lanes(rows.points, rows.patch, rows.twist.as_deref(), bodies)
        },
    );
}

/// Stages *solve* (`Bias::On`) and *relax* (`Bias::Off`) of the batches.
pub(crate) fn solve_batches(
    batches: &mut Batches,
    group_ends: &[usize],
    bodies: &mut [SolverBody],
    scratch: &mut Vec<LaneVelocities>,
    ctx: &StepContext,
    bias: Bias,
) {
    if !par::is_parallel() {
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
        return;
    }
    by_groups(
        batches,
        group_ends,
        bodies,
        scratch,
        &|batch, rows, bodies| batch.solve_lanes(rows, bodies, ctx, bias),
    );
}

/// What a pass does to one batch: its rows in, its lanes' velocities out, the bodies only read.
type Lanes<'f> = dyn Fn(&Batch, Rows<'_>, &[SolverBody]) -> LaneVelocities + Sync + 'f;

/// A run of consecutive batches with their rows: `patches[i]` is `batches[i]`'s, and `slots` and `twists`
/// begin at the first batch's.
struct Run<'a> {
    batches: &'a [Batch],
    patches: &'a mut [PatchX4],
    slots: &'a mut [PointX4],
    twists: &'a mut [TwistX4],
}

impl Run<'_> {
    /// Batch `i`'s rows.
    fn rows(&mut self, i: usize) -> Rows<'_> {
        let (first, batch) = (&self.batches[0], &self.batches[i]);
        let slot = (batch.first_slot - first.first_slot) as usize;
        let twist = (batch.first_twist - first.first_twist) as usize;
        Rows {
            points: &mut self.slots[slot..][..usize::from(batch.slots)],
            patch: &mut self.patches[i],
            twist: if batch.twist {
                self.twists.get_mut(twist)
            } else {
                None
            },
        }
    }
}

/// One pass, group after group: each group's batches over the pool, then their velocities written back in
/// batch order.
fn by_groups(
    batches: &mut Batches,
    group_ends: &[usize],
    bodies: &mut [SolverBody],
    scratch: &mut Vec<LaneVelocities>,
    lanes: &Lanes<'_>,
) {
    let mut start = 0;
    for &end in group_ends {
        let group = &batches.batches[start..end];
        let (Some(first), Some(last)) = (group.first(), group.last()) else {
            start = end;
            continue;
        };
        // A group's slots and twist rows are contiguous: `Batches::push` pushes them batch after batch.
        let slot_end = (last.first_slot - first.first_slot) as usize + usize::from(last.slots);
        let twist_end = (last.first_twist - first.first_twist) as usize + usize::from(last.twist);
        let mut run = Run {
            batches: group,
            patches: &mut batches.patches[start..end],
            slots: &mut batches.slots[first.first_slot as usize..][..slot_end],
            twists: &mut batches.twists[first.first_twist as usize..][..twist_end],
        };
        start = end;
        if group.len() < 2 * BATCHES_PER_TASK {
            for (i, batch) in group.iter().enumerate() {
                let velocities = lanes(batch, run.rows(i), bodies);
                batch.scatter(bodies, &velocities);
            }
            continue;
        }
        scratch.clear();
        scratch.resize(group.len(), LaneVelocities::default());
        split(run, bodies, scratch, lanes);
        for (batch, velocities) in group.iter().zip(scratch.iter()) {
            batch.scatter(bodies, velocities);
        }
    }
}

/// The batches of `run` halved until a half is [`BATCHES_PER_TASK`] long, the halves on two threads;
/// `out[i]` is batch `i`'s result.
fn split(mut run: Run<'_>, bodies: &[SolverBody], out: &mut [LaneVelocities], lanes: &Lanes<'_>) {
    let Some(first) = run.batches.first() else {
        return;
    };
    if run.batches.len() <= BATCHES_PER_TASK {
        for (i, o) in out.iter_mut().enumerate().take(run.batches.len()) {
            *o = lanes(&run.batches[i], run.rows(i), bodies);
        }
        return;
    }
    let mid = run.batches.len() / 2;
    let (left, right) = run.batches.split_at(mid);
    let (patches_left, patches_right) = run.patches.split_at_mut(mid);
    let (slots_left, slots_right) = run
        .slots
        .split_at_mut((right[0].first_slot - first.first_slot) as usize);
    let (twists_left, twists_right) = run
        .twists
        .split_at_mut((right[0].first_twist - first.first_twist) as usize);
    let (out_left, out_right) = out.split_at_mut(mid);
    let left = Run {
        batches: left,
        patches: patches_left,
        slots: slots_left,
        twists: twists_left,
    };
    let right = Run {
        batches: right,
        patches: patches_right,
        slots: slots_right,
        twists: twists_right,
    };
    par::join(
        || split(left, bodies, out_left, lanes),
        || split(right, bodies, out_right, lanes),
    );
}
