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

use super::batch::{Batch, LaneVelocities, PatchX4, PointX4};
use crate::contact::bias::Bias;
use crate::{SolverBody, StepContext};
use rebound_math::par;

/// Batches per task: below this a group's batches are solved on one thread.
const BATCHES_PER_TASK: usize = 16;

/// Stage *warm start* of the batches.
pub(crate) fn warm_start_batches(
    batches: &[Batch],
    group_ends: &[usize],
    slots: &mut [PointX4],
    patches: &mut [PatchX4],
    bodies: &mut [SolverBody],
    scratch: &mut Vec<LaneVelocities>,
) {
    if !par::is_parallel() {
        for batch in batches {
            batch.warm_start(slots, patches, bodies);
        }
        return;
    }
    by_groups(
        batches,
        group_ends,
        slots,
        patches,
        bodies,
        scratch,
        &|batch, points, patch, bodies| batch.warm_start_lanes(points, patch.map(|p| &*p), bodies),
    );
}

/// Stages *solve* (`Bias::On`) and *relax* (`Bias::Off`) of the batches.
pub(crate) fn solve_batches(
    batches: &[Batch],
    group_ends: &[usize],
    slots: &mut [PointX4],
    patches: &mut [PatchX4],
    bodies: &mut [SolverBody],
    scratch: &mut Vec<LaneVelocities>,
    ctx: &StepContext,
    bias: Bias,
) {
    if !par::is_parallel() {
        for batch in batches {
            batch.solve(slots, patches, bodies, ctx, bias);
        }
        return;
    }
    by_groups(
        batches,
        group_ends,
        slots,
        patches,
        bodies,
        scratch,
        &|batch, points, patch, bodies| batch.solve_lanes(points, patch, bodies, ctx, bias),
    );
}

/// What a pass does to one batch: its slots and patch in, its lanes' velocities out, the bodies only read.
type Lanes<'f> = dyn Fn(&Batch, &mut [PointX4], Option<&mut PatchX4>, &[SolverBody]) -> LaneVelocities
    + Sync
    + 'f;

/// One pass, group after group: each group's batches over the pool, then their velocities written back in
/// batch order.
fn by_groups(
    batches: &[Batch],
    group_ends: &[usize],
    slots: &mut [PointX4],
    patches: &mut [PatchX4],
    bodies: &mut [SolverBody],
    scratch: &mut Vec<LaneVelocities>,
    lanes: &Lanes<'_>,
) {
    let mut start = 0;
    for &end in group_ends {
        let group = &batches[start..end];
        start = end;
        let (Some(first), Some(last)) = (group.first(), group.last()) else {
            continue;
        };
        if group.len() < 2 * BATCHES_PER_TASK {
            for batch in group {
                let points = &mut slots[batch.first_slot..][..batch.slots];
                let velocities = lanes(batch, points, patches.get_mut(batch.patch), bodies);
                batch.scatter(bodies, &velocities);
            }
            continue;
        }
        // A group's slots and patches are contiguous: `Batch::new` pushes them batch after batch.
        let group_slots = &mut slots[first.first_slot..last.first_slot + last.slots];
        let group_patches = &mut patches[first.patch..=last.patch];
        scratch.clear();
        scratch.resize(group.len(), LaneVelocities::default());
        split(group, group_slots, group_patches, bodies, scratch, lanes);
        for (batch, velocities) in group.iter().zip(scratch.iter()) {
            batch.scatter(bodies, velocities);
        }
    }
}

/// The batches `batches` (whose slots begin `slots` and whose patches begin `patches`) halved until a half
/// is [`BATCHES_PER_TASK`] long, the halves on two threads; `out[i]` is batch `i`'s result.
fn split(
    batches: &[Batch],
    slots: &mut [PointX4],
    patches: &mut [PatchX4],
    bodies: &[SolverBody],
    out: &mut [LaneVelocities],
    lanes: &Lanes<'_>,
) {
    let Some(first) = batches.first() else {
        return;
    };
    if batches.len() <= BATCHES_PER_TASK {
        let (base_slot, base_patch) = (first.first_slot, first.patch);
        for (batch, o) in batches.iter().zip(out.iter_mut()) {
            let points = &mut slots[batch.first_slot - base_slot..][..batch.slots];
            *o = lanes(
                batch,
                points,
                patches.get_mut(batch.patch - base_patch),
                bodies,
            );
        }
        return;
    }
    let mid = batches.len() / 2;
    let (left, right) = batches.split_at(mid);
    let (slots_left, slots_right) = slots.split_at_mut(right[0].first_slot - first.first_slot);
    let (patches_left, patches_right) = patches.split_at_mut(right[0].patch - first.patch);
    let (out_left, out_right) = out.split_at_mut(mid);
    par::join(
        || split(left, slots_left, patches_left, bodies, out_left, lanes),
        || split(right, slots_right, patches_right, bodies, out_right, lanes),
    );
}
