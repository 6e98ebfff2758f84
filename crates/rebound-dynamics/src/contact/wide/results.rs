//! The batches' results read back per manifold, for stage *store impulses* and the contact events: each
//! point's accumulated normal impulse, its share of the patch's friction and its largest applied normal
//! impulse. The friction shares are computed in the lanes, with [`PatchShare`]'s formulas in the same order
//! of operations, so each lane gives bit for bit what `PatchShare::at` gives for its manifold; the read-back
//! touches the batch's arrays only, not the prepared manifolds.
//!
//! [`PatchShare`]: crate::contact::patch::PatchShare

use super::batch::{Batches, TwistX4};
use super::lanes::{LANES, Mask4, Vec3x4};
use crate::contact::manifold::MAX_CONTACT_POINTS;
use rebound_math::{Vec3, Vec4, par};
use std::ops::Range;

/// Batches per task below which the read-back over the pool does not split further (a batch reads back in
/// tens of nanoseconds per point).
const BATCHES_PER_TASK: usize = 64;

impl Batches {
    /// Calls `f(source, point, normal_impulse)` for every point of every batched manifold: the index of its
    /// source contact, the point's index in it and its accumulated normal impulse (N·s).
    pub(crate) fn for_each_normal_impulse(&self, mut f: impl FnMut(usize, usize, f32)) {
        for (batch, info) in self.batches.iter().zip(&self.infos) {
            let points = &self.slots[batch.first_slot as usize..][..usize::from(batch.slots)];
            for lane in 0..usize::from(batch.lanes) {
                let source = info.sources[lane] as usize;
                let count = info.point_counts[lane] as usize;
                for (k, slot) in points[..count].iter().enumerate() {
                    f(source, k, slot.normal_impulse[lane]);
                }
            }
        }
    }

    /// Calls `f(source, point, normal_impulse, tangent_impulse, max_normal_impulse)` for every point of every
    /// batched manifold, manifold after manifold in batch order: the index of its source contact, the point's
    /// index in it, its accumulated normal impulse (N·s), its share of the patch's friction (world vector,
    /// N·s) and its largest applied normal impulse (N·s).
    pub(crate) fn for_each_point_result(&self, mut f: impl FnMut(usize, usize, f32, Vec3, f32)) {
        for index in 0..self.batches.len() {
            self.batch_results(index, &mut f);
        }
    }

    /// [`Batches::for_each_point_result`] over the thread pool: the batches split into runs, each run's
    /// manifolds on one thread, in batch order within the run. Every manifold's points are read back in one
    /// run, and each manifold is in one batch only, so `f` is never called for one source on two threads.
    pub(crate) fn for_each_point_result_on_pool(
        &self,
        f: &(impl Fn(usize, usize, f32, Vec3, f32) + Sync + Send),
    ) {
        self.results_of_run(0..self.batches.len(), f);
    }

    /// The results of the batches `run`, halving the run over the pool down to [`BATCHES_PER_TASK`].
    fn results_of_run(
        &self,
        run: Range<usize>,
        f: &(impl Fn(usize, usize, f32, Vec3, f32) + Sync + Send),
    ) {
        if run.len() > BATCHES_PER_TASK {
            let mid = run.start + run.len() / 2;
            par::join(
                || self.results_of_run(run.start..mid, f),
                || self.results_of_run(mid..run.end, f),
            );
            return;
        }
        for index in run {
            self.batch_results(index, &mut |source, k, normal, tangent, max| {
                f(source, k, normal, tangent, max);
            });
        }
    }

    /// [`Batches::for_each_point_result`] of batch `index`.
    #[inline(always)]
    fn batch_results(&self, index: usize, f: &mut impl FnMut(usize, usize, f32, Vec3, f32)) {
        let (Some(batch), Some(info), Some(patch)) = (
            self.batches.get(index),
            self.infos.get(index),
            self.patches.get(index),
        ) else {
            return;
        };
        let points = &self.slots[batch.first_slot as usize..][..usize::from(batch.slots)];
        let twist = if batch.twist {
            self.twists
                .get(batch.first_twist as usize)
                .unwrap_or(&TwistX4::EMPTY)
        } else {
            &TwistX4::EMPTY
        };
        // `PatchShare::new`: the patch's tangent impulse as a world vector; with two points or more, its
        // share per point and the twist impulse per unit of spread.
        let [t0, t1] = batch.tangents;
        let [x, y] = patch.tangent_impulse;
        let linear = t0.scale(x).add(&t1.scale(y));
        let count = Vec4::from_array(info.point_counts.map(|n| n as f32));
        let many: Mask4 = count.cmpgt(Vec4::ONE);
        let linear = Vec3x4 {
            x: Vec4::select(many, linear.x / count, linear.x),
            y: Vec4::select(many, linear.y / count, linear.y),
            z: Vec4::select(many, linear.z / count, linear.z),
        };
        let rate = Vec4::select(
            many & info.spread.cmpgt(Vec4::ZERO),
            twist.impulse / info.spread,
            Vec4::ZERO,
        );
        // `PatchShare::at`: the linear share, plus `(n × ρ)·rate` where the rate is not zero.
        let twisting = rate.cmpne(Vec4::ZERO);
        let mut shares = [[Vec3::ZERO; LANES]; MAX_CONTACT_POINTS];
        for (share, slot) in shares.iter_mut().zip(points) {
            let value = if twisting.any() {
                let rho = slot.anchor_a.sub(&info.center_a);
                let turned = linear.add(&batch.normal.cross(&rho).scale(rate));
                Vec3x4 {
                    x: Vec4::select(twisting, turned.x, linear.x),
                    y: Vec4::select(twisting, turned.y, linear.y),
                    z: Vec4::select(twisting, turned.z, linear.z),
                }
            } else {
                linear
            };
            *share = value.lanes();
        }
        for lane in 0..usize::from(batch.lanes) {
            let source = info.sources[lane] as usize;
            let count = info.point_counts[lane] as usize;
            for (k, (slot, share)) in points[..count].iter().zip(&shares).enumerate() {
                f(
                    source,
                    k,
                    slot.normal_impulse[lane],
                    share[lane],
                    slot.max_normal_impulse[lane],
                );
            }
        }
    }
}
