//! The batches' lanes prepared over the thread pool (the `parallel` feature, on a pool of more than one
//! thread). The colouring names each batch's manifolds; each batch's slots and twist row take the places
//! the one-thread preparation gives them (a running sum of the batches' slot counts and twist rows), so
//! every batch is prepared alone, into its own places, with the same bits.

use super::batch::{Batch, BatchInfo, BatchSink, Batches, PatchX4, PointX4, TwistX4, build, shape};
use crate::contact::prepared::{PrepareInput, PreparedContact};
use rebound_math::par;

/// Batches per task below which the pool does not split further (a batch prepares in about a microsecond).
const BATCHES_PER_TASK: usize = 32;

/// The batches of `groups` (ranges of `members`, each one to four indices into `contacts`), in order, into
/// `batches` (emptied first), over the pool; `places` is scratch (each batch's first slot and twist row).
pub(crate) fn fill_on_pool(
    batches: &mut Batches,
    groups: &[(u32, u32)],
    members: &[usize],
    places: &mut Vec<(u32, u32)>,
    contacts: &[PreparedContact],
    input: &PrepareInput<'_>,
) {
    places.clear();
    let (mut slots, mut twists) = (0_u32, 0_u32);
    for &(start, end) in groups {
        places.push((slots, twists));
        let (count, twist) = shape(&members[start as usize..end as usize], contacts);
        slots += count as u32;
        twists += u32::from(twist);
    }
    // Every entry is written below: the old contents stand in until then.
    let n = groups.len();
    batches.batches.resize(n, Batch::default());
    batches.patches.resize(n, PatchX4::default());
    batches.infos.resize(n, BatchInfo::default());
    batches.slots.resize(slots as usize, PointX4::default());
    batches.twists.resize(twists as usize, TwistX4::default());
    let out = Out {
        batches: &mut batches.batches,
        patches: &mut batches.patches,
        infos: &mut batches.infos,
        slots: &mut batches.slots,
        twists: &mut batches.twists,
    };
    fill(out, groups, places, members, contacts, input);
}

/// The arrays of a run of batches: their entries, and the slots and twist rows from the run's first.
struct Out<'a> {
    batches: &'a mut [Batch],
    patches: &'a mut [PatchX4],
    infos: &'a mut [BatchInfo],
    slots: &'a mut [PointX4],
    twists: &'a mut [TwistX4],
}

impl<'a> Out<'a> {
    /// The first `batches` batches and the rest, with the slots and twist rows each starts at.
    fn split(self, batches: usize, slots: usize, twists: usize) -> (Self, Self) {
        let (b0, b1) = self.batches.split_at_mut(batches);
        let (p0, p1) = self.patches.split_at_mut(batches);
        let (i0, i1) = self.infos.split_at_mut(batches);
        let (s0, s1) = self.slots.split_at_mut(slots);
        let (t0, t1) = self.twists.split_at_mut(twists);
        let first = Out {
            batches: b0,
            patches: p0,
            infos: i0,
            slots: s0,
            twists: t0,
        };
        let rest = Out {
            batches: b1,
            patches: p1,
            infos: i1,
            slots: s1,
            twists: t1,
        };
        (first, rest)
    }
}

/// Prepares the batches of `groups` into `out`, halving the run over the pool down to [`BATCHES_PER_TASK`].
fn fill(
    mut out: Out<'_>,
    groups: &[(u32, u32)],
    places: &[(u32, u32)],
    members: &[usize],
    contacts: &[PreparedContact],
    input: &PrepareInput<'_>,
) {
    let Some(&(first_slot, first_twist)) = places.first() else {
        return;
    };
    if groups.len() > BATCHES_PER_TASK {
        let mid = groups.len() / 2;
        let (slot, twist) = places[mid];
        let (a, b) = out.split(
            mid,
            (slot - first_slot) as usize,
            (twist - first_twist) as usize,
        );
        par::join(
            || fill(a, &groups[..mid], &places[..mid], members, contacts, input),
            || fill(b, &groups[mid..], &places[mid..], members, contacts, input),
        );
        return;
    }
    for (k, (&(start, end), &(slot, twist))) in groups.iter().zip(places).enumerate() {
        let group = &members[start as usize..end as usize];
        let mut sink = Places {
            out: &mut out,
            batch: k,
            slot: (slot - first_slot) as usize,
            twist: (twist - first_twist) as usize,
        };
        // Batches prepared over the pool are solved by a team of threads: they carry their moving masks.
        build(
            group,
            contacts,
            input,
            (slot as usize, twist),
            true,
            &mut sink,
        );
    }
}

/// A batch's places in a run's arrays: its entry `batch`, its next slot and its twist row.
struct Places<'o, 'a> {
    out: &'o mut Out<'a>,
    batch: usize,
    slot: usize,
    twist: usize,
}

impl BatchSink for Places<'_, '_> {
    fn slot(&mut self, slot: PointX4) {
        self.out.slots[self.slot] = slot;
        self.slot += 1;
    }
    fn twist(&mut self, row: TwistX4) {
        self.out.twists[self.twist] = row;
    }
    fn patch(&mut self, patch: PatchX4) {
        self.out.patches[self.batch] = patch;
    }
    fn info(&mut self, info: BatchInfo) {
        self.out.infos[self.batch] = info;
    }
    fn batch(&mut self, batch: Batch) {
        self.out.batches[self.batch] = batch;
    }
}
