//! A forward walk through a sorted list: how the step matches this step's sorted lists against last step's
//! (manifolds by order key in *collide*, touching pairs in *events*) in one pass each.

/// One step of a forward walk through a list sorted by `key_of`, for keys asked in increasing order: skips the
/// items below `key` and returns the one equal to it, if any (O(n + m) for two sorted lists, and sequential
/// reads, where a binary search per key misses the cache at every probe).
pub(crate) fn walk_to<'a, T: 'a, K: Ord>(
    walk: &mut core::iter::Peekable<impl Iterator<Item = &'a T>>,
    key: &K,
    key_of: impl Fn(&T) -> K,
) -> Option<&'a T> {
    while walk.next_if(|item| key_of(item) < *key).is_some() {}
    walk.next_if(|item| key_of(item) == *key)
}
