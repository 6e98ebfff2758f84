//! The sort of the broad phase's candidate pairs (collide stage): an LSD radix sort on the two collider
//! slots of each pair, linear in the number of pairs where a comparison sort of the tens of thousands of
//! pairs of a large pile is not; and the same over the thread pool for the pool's pair search, whose
//! pairs come in parts ([`sort_parts`]).

use crate::ColliderHandle;
#[cfg(feature = "parallel")]
use rebound_math::par;

#[cfg(feature = "parallel")]
/// A candidate pair, lower handle first.
type Pair = (ColliderHandle, ColliderHandle);

/// Bits per digit of the pair sort, at most: 2,048 buckets, so a pile of 16,384 colliders (28-bit keys) sorts
/// in three passes.
const RADIX_BITS: u32 = 11;

/// Sorts `pairs` by (first slot, second slot): an LSD radix sort on the two slot indices packed into one key
/// (`first << b | second`, `b` bits per slot), one counting pass per 11-bit digit. The pairs of a 4,096-ball
/// pile (tens of thousands per step) are too many for a comparison sort; this is linear. Stable, so
/// equal keys keep their order; `scratch` is reused.
pub(crate) fn radix_sort_pairs(
    pairs: &mut Vec<(ColliderHandle, ColliderHandle)>,
    scratch: &mut Vec<(ColliderHandle, ColliderHandle)>,
) {
    let largest = pairs
        .iter()
        .map(|(h1, h2)| h1.0.index.max(h2.0.index))
        .max()
        .unwrap_or(0);
    let slot_bits = u32::BITS - largest.leading_zeros();
    let key = |&(h1, h2): &(ColliderHandle, ColliderHandle)| {
        (u64::from(h1.0.index) << slot_bits) | u64::from(h2.0.index)
    };
    let key_bits = 2 * slot_bits;
    // As many passes as digits of `RADIX_BITS` take, the bits shared evenly between them: a small world's
    // 16-bit keys sort in two passes over 256 buckets, not over 2,048 (whose clearing and prefix sums cost
    // more than a few hundred pairs).
    let passes = key_bits.div_ceil(RADIX_BITS).max(1);
    let digit_bits = key_bits.div_ceil(passes);
    let buckets = 1usize << digit_bits;
    let mask = (buckets - 1) as u64;
    // Every pass writes all of `scratch` before it becomes `pairs`: one resize suffices.
    scratch.clear();
    scratch.resize(
        pairs.len(),
        (ColliderHandle::invalid(), ColliderHandle::invalid()),
    );
    let mut shift = 0;
    let mut count = [0u32; 1 << RADIX_BITS];
    let count = &mut count[..buckets];
    while shift < key_bits {
        count.fill(0);
        for pair in pairs.iter() {
            count[((key(pair) >> shift) & mask) as usize] += 1;
        }
        let mut start = 0;
        for c in count.iter_mut() {
            let n = *c;
            *c = start;
            start += n;
        }
        for pair in pairs.iter() {
            let digit = ((key(pair) >> shift) & mask) as usize;
            scratch[count[digit] as usize] = *pair;
            count[digit] += 1;
        }
        core::mem::swap(pairs, scratch);
        shift += digit_bits;
    }
}

#[cfg(feature = "parallel")]
/// Pairs per range of first slots in [`sort_parts`], about: a range is one task's sort.
const PAIRS_PER_RANGE: usize = 2_048;

#[cfg(feature = "parallel")]
/// The most ranges [`sort_parts`] cuts the first slots into.
const MAX_RANGES: usize = 64;

#[cfg(feature = "parallel")]
/// Bits per digit of the sort of one range, at most: 256 buckets, few against a range's pairs.
const RANGE_RADIX_BITS: u32 = 8;

#[cfg(feature = "parallel")]
/// The scratch of [`sort_parts`], kept from step to step (nothing allocated once it has grown).
#[derive(Debug, Clone, Default)]
pub(crate) struct PartSort {
    /// Every part's pairs grouped by range of first slots, part after part.
    grouped: Vec<Pair>,
    /// Where each part begins in `grouped`.
    part_starts: Vec<usize>,
    /// Per part, where each range's pairs begin within its share of `grouped` (the last: its length).
    range_offsets: Vec<[usize; MAX_RANGES + 1]>,
    /// Where each range's pairs begin in the sorted list.
    range_starts: Vec<usize>,
    /// The buffer the sort of each range swaps its pairs through.
    scratch: Vec<Pair>,
}

#[cfg(feature = "parallel")]
/// `out` becomes every pair of `parts` (distinct pairs, slots below `slot_count`), sorted by (first slot,
/// second slot) — the list [`radix_sort_pairs`] makes of them — over the thread pool, in passes with the
/// counts between them (so that every pair is written straight into its place): each part counts its
/// pairs per range of first slots, then groups them by range into its share of one buffer; then each range
/// gathers its pairs from every part into its place in `out` and sorts them with an LSD radix sort on the
/// slots within the range. Distinct pairs have one sorted order, so the list is the same for any number of
/// threads and any parts.
pub(crate) fn sort_parts(
    parts: &[Vec<Pair>],
    slot_count: usize,
    out: &mut Vec<Pair>,
    sort: &mut PartSort,
) {
    out.clear();
    sort.part_starts.clear();
    let mut total = 0;
    for part in parts {
        sort.part_starts.push(total);
        total += part.len();
    }
    if total == 0 {
        return;
    }
    let ranges = (total / PAIRS_PER_RANGE).clamp(1, MAX_RANGES);
    let width = slot_count.div_ceil(ranges).max(1);
    let range_of = |&(h1, _): &Pair| (h1.0.index as usize / width).min(ranges - 1);
    let invalid = (ColliderHandle::invalid(), ColliderHandle::invalid());
    // Each part's count per range, as offsets within its share.
    par::map_collect_in_order(parts, &mut sort.range_offsets, 1, |_, part| {
        let mut offsets = [0; MAX_RANGES + 1];
        for pair in part {
            offsets[range_of(pair) + 1] += 1;
        }
        for r in 0..ranges {
            offsets[r + 1] += offsets[r];
        }
        offsets
    });
    // Each part grouped by range (a counting sort on the range) into its share.
    sort.grouped.resize(total.max(sort.grouped.len()), invalid);
    let offsets = &sort.range_offsets;
    par::for_each_part_mut(&mut sort.grouped, &sort.part_starts, total, |p, share| {
        let (Some(part), Some(offsets)) = (parts.get(p), offsets.get(p)) else {
            return;
        };
        let mut next = *offsets;
        for pair in part {
            let at = &mut next[range_of(pair)];
            share[*at] = *pair;
            *at += 1;
        }
    });
    // Where each range begins: the ranges' counts summed over the parts.
    sort.range_starts.clear();
    let mut at = 0;
    for r in 0..ranges {
        sort.range_starts.push(at);
        at += offsets.iter().map(|o| o[r + 1] - o[r]).sum::<usize>();
    }
    out.resize(total, invalid);
    sort.scratch.resize(total.max(sort.scratch.len()), invalid);
    let (grouped, part_starts) = (&sort.grouped, &sort.part_starts);
    let second_bits = usize::BITS - (slot_count.max(1) - 1).leading_zeros();
    let first_bits = usize::BITS - (width - 1).leading_zeros();
    par::for_each_part_zip_mut(
        out,
        &mut sort.scratch,
        &sort.range_starts,
        total,
        |r, sorted, scratch| {
            let base = r * width;
            let key = |&(h1, h2): &Pair| {
                // The key holds both slots only while each is below `slot_count`.
                debug_assert!(
                    (h1.0.index as usize) < slot_count && (h2.0.index as usize) < slot_count
                );
                (((h1.0.index as usize - base) as u64) << second_bits) | u64::from(h2.0.index)
            };
            let sources = part_starts
                .iter()
                .zip(offsets)
                .map(|(&start, o)| &grouped[start + o[r]..start + o[r + 1]]);
            sort_range(sources, sorted, scratch, key, first_bits + second_bits);
        },
    );
}

#[cfg(feature = "parallel")]
/// The pairs of `sources` (concatenated) into `sorted`, sorted by `key` (below `1 << key_bits`, distinct):
/// an LSD radix sort of at most [`RANGE_RADIX_BITS`] per digit whose first pass reads the sources and whose
/// passes go back and forth between `scratch` and `sorted` (as long as the sources), ending in `sorted`.
fn sort_range<'a>(
    sources: impl Iterator<Item = &'a [Pair]> + Clone,
    sorted: &mut [Pair],
    scratch: &mut [Pair],
    key: impl Fn(&Pair) -> u64,
    key_bits: u32,
) {
    let passes = key_bits.div_ceil(RANGE_RADIX_BITS).max(1);
    let digit_bits = key_bits.div_ceil(passes);
    let mask = (1_u64 << digit_bits) - 1;
    let mut count = [0_usize; 1 << RANGE_RADIX_BITS];
    let count = &mut count[..1 << digit_bits];
    let digit = |pair: &Pair, shift: u32| ((key(pair) >> shift) & mask) as usize;
    // The last pass writes `sorted`: so does the first when the count of passes is odd.
    let ends_in_sorted = |pass: u32| (passes - 1 - pass).is_multiple_of(2);
    let first = if ends_in_sorted(0) {
        &mut *sorted
    } else {
        &mut *scratch
    };
    scatter(
        sources.clone().flatten(),
        sources.flatten(),
        first,
        count,
        |p| digit(p, 0),
    );
    for pass in 1..passes {
        let shift = pass * digit_bits;
        let (from, to) = if ends_in_sorted(pass) {
            (&*scratch, &mut *sorted)
        } else {
            (&*sorted, &mut *scratch)
        };
        scatter(from.iter(), from.iter(), to, count, |p| digit(p, shift));
    }
}

#[cfg(feature = "parallel")]
/// One counting pass: the pairs of `pairs` (read twice: counted, then placed) into `to` by `digit`, in
/// order within a digit (`count` is scratch, one per digit).
#[inline(always)]
fn scatter<'a>(
    counted: impl Iterator<Item = &'a Pair>,
    pairs: impl Iterator<Item = &'a Pair>,
    to: &mut [Pair],
    count: &mut [usize],
    digit: impl Fn(&Pair) -> usize,
) {
    count.fill(0);
    for pair in counted {
        count[digit(pair)] += 1;
    }
    let mut start = 0;
    for c in count.iter_mut() {
        let n = *c;
        *c = start;
        start += n;
    }
    for pair in pairs {
        let d = digit(pair);
        to[count[d]] = *pair;
        count[d] += 1;
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        /// The radix sort orders pairs as a comparison sort of the handles does, for slot indices of any size
        /// (one to three digits per slot).
        #[test]
        fn radix_sort_orders_pairs_as_handles_order(
            raw in proptest::collection::vec((0u32..1 << 20, 0u32..1 << 20, 0u32..4), 0..300),
            scale in 0u32..3,
        ) {
            let shrink = [1 << 12, 1 << 6, 1][scale as usize];
            let mut pairs: Vec<_> = raw
                .iter()
                .map(|&(a, b, g)| {
                    (
                        ColliderHandle::from_raw_parts(a / shrink, g),
                        ColliderHandle::from_raw_parts(b / shrink, g),
                    )
                })
                .collect();
            let mut expected = pairs.clone();
            expected.sort_by_key(|&(h1, h2)| (h1.0.index, h2.0.index));
            let mut scratch = Vec::new();
            radix_sort_pairs(&mut pairs, &mut scratch);
            let slots = |v: &[(ColliderHandle, ColliderHandle)]| {
                v.iter().map(|(a, b)| (a.0.index, b.0.index)).collect::<Vec<_>>()
            };
            prop_assert_eq!(slots(&pairs), slots(&expected));
            // Stable: equal slot pairs keep their order, so the generations match the stable sort too.
            prop_assert_eq!(pairs, expected);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(48))]
        /// The pool's sort of pairs found in parts gives the list the one-thread radix sort gives, for any
        /// parts, any slot count (one range to many) and pools of one to three threads.
        #[cfg(feature = "parallel")]
        #[test]
        fn sorting_parts_on_the_pool_gives_the_radix_sort(
            raw in proptest::collection::vec((0u32..1 << 14, 0u32..1 << 14), 0..24_000),
            cuts in proptest::collection::vec(0usize..12_000, 0..70),
            scale in 0u32..3,
        ) {
            let shrink = [1 << 8, 1 << 2, 1][scale as usize];
            let mut pairs: Vec<(u32, u32)> = raw
                .iter()
                .map(|&(a, b)| (a / shrink, b / shrink))
                .filter(|(a, b)| a < b)
                .collect();
            pairs.sort_unstable();
            pairs.dedup();
            // Distinct pairs in a scrambled order, cut into parts at `cuts`.
            let n = pairs.len();
            let mut order: Vec<usize> = (0..n).collect();
            order.sort_by_key(|&i| (i.wrapping_mul(2_654_435_761)) % n.max(1));
            let handles: Vec<Pair> = order
                .iter()
                .map(|&i| {
                    let (a, b) = pairs[i];
                    (ColliderHandle::from_raw_parts(a, 1), ColliderHandle::from_raw_parts(b, 1))
                })
                .collect();
            let mut ends: Vec<usize> = cuts.iter().map(|&c| c.min(n)).collect();
            ends.push(n);
            ends.sort_unstable();
            let mut parts = Vec::new();
            let mut start = 0;
            for end in ends {
                parts.push(handles[start..end].to_vec());
                start = end;
            }
            let mut expected = handles.clone();
            radix_sort_pairs(&mut expected, &mut Vec::new());
            let slot_count = (1 << 14) / shrink as usize;
            for threads in [1, 2, 3] {
                let pool = par::rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .expect("the test machine starts threads");
                let mut sorted = vec![(ColliderHandle::invalid(), ColliderHandle::invalid())];
                let mut sort = PartSort::default();
                pool.install(|| sort_parts(&parts, slot_count, &mut sorted, &mut sort));
                prop_assert_eq!(&sorted, &expected, "{} threads", threads);
            }
        }
    }
}
