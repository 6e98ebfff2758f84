//! The sort of the broad phase's candidate pairs (collide stage): an LSD radix sort on the two collider
//! slots of each pair, linear in the number of pairs where a comparison sort of the tens of thousands of
//! pairs of a large pile is not.

use crate::ColliderHandle;

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
}
