//! The broad phase's pair search over the thread pool (the `parallel` feature, on a pool of more than one
//! thread): the colliders' boxes and leaf tests, then the traversal of the tree against itself with the
//! pair filter (`self_overlaps.rs`). Each gives what the one-thread code of `broad_phase.rs` gives, in the same order.

use super::self_overlaps::SelfOverlaps;
use crate::pair_sort::{PartSort, sort_parts};
use crate::{Collider, ColliderHandle, ColliderSet};
use parry3d::partitioning::Bvh;

/// The pool's pair search ([`BroadPhase::find_pairs`] on a pool of more than one thread, while the last
/// search found fewer than `1 / POOL_SEARCH_BELOW` of the cap): it holds every overlapping leaf pair at
/// once, where the one-thread search trims its list at twice the cap as it goes.
pub(super) const POOL_SEARCH_BELOW: usize = 4;

/// The pair search over the thread pool: the tree traversed against itself with the pair filter `keep`
/// (its verdict on two leaves) over the pool ([`SelfOverlaps`]), each unit's pairs into its own list, then
/// sorted into `pairs` over the pool ([`sort_parts`]; `slot_count` bounds the collider slots). Returns how
/// many pairs the cap `max_pairs` left out: the `max_pairs` lowest are kept, as the one-thread search keeps
/// them, so both give the same pairs.
pub(super) fn search_on_pool(
    bvh: &Bvh,
    traversal: &mut SelfOverlaps<(ColliderHandle, ColliderHandle)>,
    keep: impl Fn(u32, u32) -> Option<(ColliderHandle, ColliderHandle)> + Sync + Send,
    slot_count: usize,
    sort: &mut PartSort,
    pairs: &mut Vec<(ColliderHandle, ColliderHandle)>,
    max_pairs: usize,
) -> usize {
    // Each pair of leaves is found once, and a leaf is one collider slot: the pairs are distinct, as
    // `sort_parts` needs.
    let parts = traversal.find_parts(bvh, keep);
    sort_parts(parts, slot_count, pairs, sort);
    let capped = pairs.len().saturating_sub(max_pairs);
    pairs.truncate(max_pairs);
    capped
}

/// For every collider, in collider order: `apply(broad_phase, handle, collider, compute(broad_phase, handle,
/// collider))`, every `compute` (which only reads) over the pool first, then every `apply` (which changes
/// the tree) one after the other: the calls the one-thread loops make, on the same values. `computed` is
/// scratch (per collider slot, its computed value), kept from step to step.
pub(super) fn on_pool<'c, S: Sync, T: Send>(
    broad_phase: &mut S,
    colliders: &'c ColliderSet,
    computed: &mut Vec<Option<T>>,
    compute: impl Fn(&S, ColliderHandle, &'c Collider) -> T + Sync + Send,
    mut apply: impl FnMut(&mut S, ColliderHandle, &'c Collider, T),
) {
    let shared = &*broad_phase;
    colliders
        .arena
        .map_in_slot_order(computed, |index, collider| {
            compute(shared, ColliderHandle(index), collider)
        });
    for (handle, collider) in colliders.iter() {
        if let Some(value) = computed
            .get_mut(handle.0.index as usize)
            .and_then(Option::take)
        {
            apply(broad_phase, handle, collider, value);
        }
    }
}
