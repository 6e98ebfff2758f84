//! The step's one dispatch between a plain loop and the thread pool. Each parallel stage of the step calls
//! one of these helpers; the serial build (without the `parallel` feature) compiles every call to the plain
//! loop it replaces, and so does the parallel build when the current rayon pool has one thread.
//!
//! Results never depend on the number of threads: every helper hands each item to its closure alone and
//! keeps the items' results in index order, so nothing is summed or combined in an order the scheduler
//! chooses. A stage whose items are not independent (the coloured contact batches, where an item writes the
//! bodies it reads) splits its items into groups that are, and calls a helper once per group.

#[cfg(feature = "parallel")]
pub use rayon;

#[cfg(feature = "parallel")]
use rayon::prelude::*;

/// Items per task below which splitting further costs more than it saves (a solver body integrates in
/// tens of nanoseconds; a rayon task costs about a microsecond). Where items are split does not change
/// any result.
pub const MIN_ITEMS_PER_TASK: usize = 64;

/// Whether the helpers spread work over threads here: the parallel build inside a pool of more than one
/// thread (the pool installed around the call, else rayon's global pool). Always `false` in the serial
/// build.
#[inline]
#[must_use]
pub fn is_parallel() -> bool {
    #[cfg(feature = "parallel")]
    {
        rayon::current_num_threads() > 1
    }
    #[cfg(not(feature = "parallel"))]
    {
        false
    }
}

/// Calls `f(index, item)` for every item of `items`, each once, on as many threads as the pool has.
#[inline]
pub fn for_each_mut<T, F>(items: &mut [T], min_len: usize, f: F)
where
    T: Send,
    F: Fn(usize, &mut T) + Sync + Send,
{
    #[cfg(feature = "parallel")]
    if is_parallel() && items.len() > min_len {
        items
            .par_iter_mut()
            .with_min_len(min_len.max(1))
            .enumerate()
            .for_each(|(i, item)| f(i, item));
        return;
    }
    let _ = min_len;
    for (i, item) in items.iter_mut().enumerate() {
        f(i, item);
    }
}

/// Calls `f(item, with)` for every pair of `items` and `with` (zipped: the shorter sets the length), each
/// once, on as many threads as the pool has.
#[inline]
pub fn for_each_zip_mut<T, U, F>(items: &mut [T], with: &[U], min_len: usize, f: F)
where
    T: Send,
    U: Sync,
    F: Fn(&mut T, &U) + Sync + Send,
{
    #[cfg(feature = "parallel")]
    if is_parallel() && items.len() > min_len {
        items
            .par_iter_mut()
            .zip(with)
            .with_min_len(min_len.max(1))
            .for_each(|(item, w)| f(item, w));
        return;
    }
    let _ = min_len;
    for (item, w) in items.iter_mut().zip(with) {
        f(item, w);
    }
}

/// Calls `f(item, with)` for every pair of `items` and `with`, both changed in place (zipped: the shorter
/// sets the length), each once, on as many threads as the pool has.
#[inline]
pub fn for_each_zip_both_mut<T, U, F>(items: &mut [T], with: &mut [U], min_len: usize, f: F)
where
    T: Send,
    U: Send,
    F: Fn(&mut T, &mut U) + Sync + Send,
{
    for_each_indexed_zip_both_mut(items, with, min_len, |_, item, w| f(item, w));
}

/// Calls `f(index, item, with)` for every pair of `items` and `with`, both changed in place (zipped: the
/// shorter sets the length), each once, on as many threads as the pool has: one section where two stages
/// over the same items would open two.
#[inline]
pub fn for_each_indexed_zip_both_mut<T, U, F>(items: &mut [T], with: &mut [U], min_len: usize, f: F)
where
    T: Send,
    U: Send,
    F: Fn(usize, &mut T, &mut U) + Sync + Send,
{
    #[cfg(feature = "parallel")]
    if is_parallel() && items.len() > min_len {
        items
            .par_iter_mut()
            .zip(with)
            .with_min_len(min_len.max(1))
            .enumerate()
            .for_each(|(i, (item, w))| f(i, item, w));
        return;
    }
    let _ = min_len;
    for (i, (item, w)) in items.iter_mut().zip(with).enumerate() {
        f(i, item, w);
    }
}

/// `out` becomes `[f(0, &items[0]), f(1, &items[1]), …]`, in index order whichever thread computed each
/// (`out`'s allocation is reused).
#[inline]
pub fn map_collect_in_order<T, U, F>(items: &[T], out: &mut Vec<U>, min_len: usize, f: F)
where
    T: Sync,
    U: Send,
    F: Fn(usize, &T) -> U + Sync + Send,
{
    #[cfg(feature = "parallel")]
    if is_parallel() && items.len() > min_len {
        items
            .par_iter()
            .with_min_len(min_len.max(1))
            .enumerate()
            .map(|(i, item)| f(i, item))
            .collect_into_vec(out);
        return;
    }
    let _ = min_len;
    out.clear();
    out.extend(items.iter().enumerate().map(|(i, item)| f(i, item)));
}

/// Appends `part(0)`, `part(1)`, … `part(starts.len() − 1)` to `out`, in that order, copied over the pool:
/// part `r` starts `starts[r]` items into what is appended (`starts` ascending from 0), and `total` items
/// are appended in all. Each item is copied alone to its place, so the list is the same for any number of
/// threads; only `out`'s own storage grows (and only while it is short).
#[inline]
pub fn extend_concatenated<'a, T, P>(out: &mut Vec<T>, starts: &[usize], total: usize, part: P)
where
    T: Copy + Send + Sync + 'a,
    P: Fn(usize) -> &'a [T] + Sync + Send,
{
    #[cfg(feature = "parallel")]
    if is_parallel() && total > MIN_ITEMS_PER_TASK {
        out.par_extend(
            (0..total)
                .into_par_iter()
                .with_min_len(MIN_ITEMS_PER_TASK)
                .map(|at| {
                    let r = starts
                        .partition_point(|&start| start <= at)
                        .saturating_sub(1);
                    let start = starts.get(r).copied().unwrap_or(0);
                    part(r)[at - start]
                }),
        );
        return;
    }
    let _ = total;
    for r in 0..starts.len() {
        out.extend_from_slice(part(r));
    }
}

/// Appends to `out`, in the order `0..count`, what `fill(r, part)` appends to each part `r`: over the pool,
/// each part into its own buffer of `parts` (kept from call to call, so that nothing is allocated once they
/// have grown), then the buffers copied to `out` in order; on one thread, each part straight into `out`.
/// The list is the same for any number of threads. For parts whose lengths are not known before they are
/// filled (a filter, a traversal), where rayon's `par_extend` would collect into a new list per task.
#[inline]
pub fn extend_in_parts<U, F>(out: &mut Vec<U>, parts: &mut Vec<Vec<U>>, count: usize, fill: F)
where
    U: Copy + Send,
    F: Fn(usize, &mut Vec<U>) + Sync + Send,
{
    #[cfg(feature = "parallel")]
    if is_parallel() && count > 1 {
        if parts.len() < count {
            parts.resize_with(count, Vec::new);
        }
        let used = &mut parts[..count];
        used.par_iter_mut()
            .with_min_len(1)
            .enumerate()
            .for_each(|(r, part)| {
                part.clear();
                fill(r, part);
            });
        let mut widest = 0;
        for part in used.iter() {
            out.extend_from_slice(part);
            widest = widest.max(part.len());
        }
        // Every buffer made to hold twice what the fullest held: which part meets the most items moves from
        // call to call (a traversal's parts follow the tree), and a buffer grown only by its own part
        // would keep growing, one part after another, long after the total has stopped.
        for part in used.iter_mut() {
            if part.capacity() < widest {
                part.reserve(2 * widest - part.len());
            }
        }
        return;
    }
    let _ = parts;
    for r in 0..count {
        fill(r, out);
    }
}

/// Sorts `items` by `key`, not keeping the order of equal keys, on as many threads as the pool has (in
/// place: nothing is allocated). Items of equal keys may end up in another order than on one thread, so a
/// caller whose items of one key differ must combine them in a way that does not depend on their order.
#[inline]
pub fn sort_unstable_by_key<T, K, F>(items: &mut [T], key: F)
where
    T: Send,
    K: Ord,
    F: Fn(&T) -> K + Sync,
{
    #[cfg(feature = "parallel")]
    if is_parallel() && items.len() > MIN_ITEMS_PER_TASK {
        items.par_sort_unstable_by_key(key);
        return;
    }
    items.sort_unstable_by_key(key);
}

/// Runs `a` and `b`, on two threads if the pool has them, and returns both results.
#[inline]
pub fn join<A, B, RA, RB>(a: A, b: B) -> (RA, RB)
where
    A: FnOnce() -> RA + Send,
    B: FnOnce() -> RB + Send,
    RA: Send,
    RB: Send,
{
    #[cfg(feature = "parallel")]
    if is_parallel() {
        return rayon::join(a, b);
    }
    (a(), b())
}

/// Runs `f` with the pool's other threads kept awake until it returns: each spins, running whatever the pool
/// has pending (`rayon::yield_now`), instead of going to sleep between `f`'s parallel sections. A rayon
/// worker that finds nothing to do sleeps after a few dozen rounds of yielding its core (tens of µs), and
/// waking it takes about as long again — against a small scene's whole step of 200–400 µs with several
/// sections, each of which would otherwise start with one thread while the other wakes up. Only who runs
/// which task changes, never what a task computes: the results are the same bits.
///
/// One thread is kept awake, when the pool and the machine have another: the spinner is the second half of
/// a `rayon::join` (on the stack: nothing is allocated), pushed before any of `f`'s tasks, so the first
/// thread to steal from the caller takes it before any of them, and never a thread already inside `f`'s
/// work. (Spinners forked from one another could be taken up by a thread waiting inside `f` for a task of
/// its own, which would then spin until `f` ended, and `f` would never end.) The spinner returns at once if
/// it finds itself on `f`'s own thread (taken back while `f` waits). It runs whatever the pool has pending,
/// other callers' tasks too; `with_pool_awake` returns once the task it is running when `f` ends has ended.
/// In the serial build, and in a pool of one thread, this is `f()`.
#[inline]
pub fn with_pool_awake<R, F>(f: F) -> R
where
    F: FnOnce() -> R + Send,
    R: Send,
{
    #[cfg(feature = "parallel")]
    if is_parallel() {
        return awake::run(f);
    }
    f()
}

#[cfg(feature = "parallel")]
mod awake {
    use std::sync::OnceLock;
    use std::sync::atomic::{AtomicBool, Ordering};

    /// Failed looks for pending work between two yields of the core while a spinner waits.
    const LOOKS_BEFORE_YIELD: u32 = 64;

    /// Whether a thread may spin beside the caller: the pool has another and the machine another core.
    fn spinner_wanted() -> bool {
        static CORES: OnceLock<usize> = OnceLock::new();
        let cores =
            *CORES.get_or_init(|| std::thread::available_parallelism().map_or(1, usize::from));
        rayon::current_num_threads().min(cores) > 1
    }

    pub(super) fn run<R, F>(f: F) -> R
    where
        F: FnOnce() -> R + Send,
        R: Send,
    {
        if !spinner_wanted() {
            return f();
        }
        let done = AtomicBool::new(false);
        let owner = rayon::current_thread_index();
        let (result, ()) = rayon::join(
            || {
                // Set also when `f` unwinds, so that the spinner does not wait for ever.
                let _done = SetOnDrop(&done);
                f()
            },
            || spin(&done, owner),
        );
        result
    }

    /// Runs the pool's pending work until `done`, yielding the core now and then when there is none.
    fn spin(done: &AtomicBool, owner: Option<usize>) {
        if owner.is_some() && rayon::current_thread_index() == owner {
            return;
        }
        let mut looks = 0_u32;
        while !done.load(Ordering::Acquire) {
            if rayon::yield_now() == Some(rayon::Yield::Executed) {
                looks = 0;
            } else if looks < LOOKS_BEFORE_YIELD {
                looks += 1;
                std::hint::spin_loop();
            } else {
                looks = 0;
                std::thread::yield_now();
            }
        }
    }

    /// Sets the flag when dropped.
    struct SetOnDrop<'a>(&'a AtomicBool);

    impl Drop for SetOnDrop<'_> {
        fn drop(&mut self) {
            self.0.store(true, Ordering::Release);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_collect_keeps_index_order() {
        let items: Vec<u32> = (0..1000).collect();
        let mut out = Vec::new();
        map_collect_in_order(&items, &mut out, 8, |i, &x| (i as u32) * 2 + x);
        assert_eq!(out.len(), 1000);
        assert!(out.iter().enumerate().all(|(i, &y)| y == 3 * i as u32));
    }

    #[test]
    fn for_each_visits_every_item_once() {
        let mut items = vec![0_u32; 1000];
        for_each_mut(&mut items, 8, |i, x| *x += i as u32 + 1);
        assert!(items.iter().enumerate().all(|(i, &x)| x == i as u32 + 1));
        let with: Vec<u32> = (0..1000).collect();
        for_each_zip_mut(&mut items, &with, 8, |x, &w| *x -= w);
        assert!(items.iter().all(|&x| x == 1));
        let mut with = with;
        for_each_zip_both_mut(&mut items, &mut with, 8, |x, w| {
            *w += *x;
            *x = 0;
        });
        assert!(items.iter().all(|&x| x == 0));
        assert!(with.iter().enumerate().all(|(i, &w)| w == i as u32 + 1));
        for_each_indexed_zip_both_mut(&mut items, &mut with, 8, |i, x, w| {
            *x = *w - i as u32;
        });
        assert!(items.iter().all(|&x| x == 1));
    }

    #[test]
    fn extend_concatenated_keeps_part_order() {
        let parts: [&[u32]; 4] = [&[0, 1, 2], &[], &[3], &(4..200).collect::<Vec<_>>()];
        let starts = [0, 3, 3, 4];
        let mut out = vec![u32::MAX];
        extend_concatenated(&mut out, &starts, 200, |r| parts[r]);
        assert_eq!(out.len(), 201);
        assert!(out[1..].iter().enumerate().all(|(i, &x)| x == i as u32));
    }

    #[test]
    fn extend_in_parts_keeps_part_order() {
        let mut parts = Vec::new();
        let mut out = vec![u32::MAX];
        // Part r holds the multiples of 7 in [100·r, 100·(r + 1)).
        extend_in_parts(&mut out, &mut parts, 10, |r, part| {
            part.extend((100 * r as u32..100 * (r as u32 + 1)).filter(|x| x % 7 == 0));
        });
        let expected: Vec<u32> = (0..1000).filter(|x| x % 7 == 0).collect();
        assert_eq!(out[0], u32::MAX);
        assert_eq!(out[1..], expected[..]);
    }

    #[test]
    fn with_pool_awake_returns_what_f_returns() {
        let mut items = vec![1_u32; 1000];
        let sum = with_pool_awake(|| {
            for_each_mut(&mut items, 8, |i, x| *x += i as u32);
            items.iter().sum::<u32>()
        });
        assert_eq!(sum, 1000 + (0..1000).sum::<u32>());
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn with_pool_awake_on_pools_of_any_size() {
        for threads in [1, 2, 3, 8] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap_or_else(|e| panic!("no pool: {e}"));
            let sums = pool.install(|| {
                with_pool_awake(|| {
                    (0..50)
                        .map(|round| {
                            let mut out = Vec::new();
                            let items: Vec<u64> = (0..4096).collect();
                            map_collect_in_order(&items, &mut out, 64, |i, &x| {
                                x * round + i as u64
                            });
                            out.iter().sum::<u64>()
                        })
                        .sum::<u64>()
                })
            });
            let one: u64 = (0..4096_u64).sum();
            assert_eq!(sums, (0..50).map(|r| one * r + one).sum::<u64>());
        }
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn with_pool_awake_ends_its_spinner_when_f_panics() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap_or_else(|e| panic!("no pool: {e}"));
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            pool.install(|| with_pool_awake(|| panic!("f fails")));
        }));
        assert!(result.is_err());
        assert_eq!(pool.install(|| with_pool_awake(|| 7)), 7);
    }

    #[test]
    fn join_returns_both() {
        assert_eq!(join(|| 2 + 2, || "four"), (4, "four"));
    }
}
