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
/// thread (the pool installed around the call, else rayon's global pool), outside [`serially`]. Always
/// `false` in the serial build.
#[inline]
#[must_use]
pub fn is_parallel() -> bool {
    #[cfg(feature = "parallel")]
    {
        rayon::current_num_threads() > 1 && !serial::is_on()
    }
    #[cfg(not(feature = "parallel"))]
    {
        false
    }
}

/// Runs `f` with every helper on this thread: inside, [`is_parallel`] is `false`. The results are the same
/// bits as on the pool (they are for any number of threads); a step too small to gain from a second thread
/// runs so, without waking one.
pub fn serially<R>(f: impl FnOnce() -> R) -> R {
    #[cfg(feature = "parallel")]
    {
        let _on = serial::Guard::new();
        f()
    }
    #[cfg(not(feature = "parallel"))]
    {
        f()
    }
}

#[cfg(feature = "parallel")]
mod serial {
    use std::cell::Cell;

    std::thread_local! {
        /// Whether this thread runs inside [`super::serially`].
        static ON: Cell<bool> = const { Cell::new(false) };
    }

    /// Whether this thread runs inside [`super::serially`].
    #[inline]
    pub(super) fn is_on() -> bool {
        ON.with(Cell::get)
    }

    /// Sets the flag while it lives, and puts the one before back when dropped (a panic inside included).
    pub(super) struct Guard {
        before: bool,
    }

    impl Guard {
        pub(super) fn new() -> Self {
            Self {
                before: ON.with(|on| on.replace(true)),
            }
        }
    }

    impl Drop for Guard {
        fn drop(&mut self) {
            ON.with(|on| on.set(self.before));
        }
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
        spin::split_mut(
            items,
            0,
            min_len,
            rayon::current_num_threads(),
            &|start, part| {
                for (k, item) in part.iter_mut().enumerate() {
                    f(start + k, item);
                }
            },
        );
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
        let len = items.len().min(with.len());
        spin::split_mut(
            &mut items[..len],
            0,
            min_len,
            rayon::current_num_threads(),
            &|start, part| {
                for (item, w) in part.iter_mut().zip(&with[start..]) {
                    f(item, w);
                }
            },
        );
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
        let len = items.len().min(with.len());
        let threads = rayon::current_num_threads();
        spin::split_both_mut(
            &mut items[..len],
            &mut with[..len],
            0,
            min_len,
            threads,
            &|start, part, with| {
                for (k, (item, w)) in part.iter_mut().zip(with).enumerate() {
                    f(start + k, item, w);
                }
            },
        );
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

/// `out` becomes `[f(0, chunk 0 of items, chunk 0 of with), f(1, …), …]`: `items` and `with` cut into
/// chunks of `chunk_len` (the last one shorter; zipped: the shorter list sets how many), each chunk handed
/// to `f` alone, with its number, on as many threads as the pool has, and the results kept in chunk order
/// (`out`'s allocation is reused). For a pass whose items need what came before them in their chunk (a
/// forward walk, a count), where [`for_each_zip_both_mut`] hands out single items.
#[inline]
pub fn map_chunks_zip_mut<T, U, R, F>(
    items: &mut [T],
    with: &mut [U],
    chunk_len: usize,
    out: &mut Vec<R>,
    f: F,
) where
    T: Send,
    U: Send,
    R: Send,
    F: Fn(usize, &mut [T], &mut [U]) -> R + Sync + Send,
{
    let chunk_len = chunk_len.max(1);
    #[cfg(feature = "parallel")]
    if is_parallel() && items.len() > chunk_len {
        items
            .par_chunks_mut(chunk_len)
            .zip(with.par_chunks_mut(chunk_len))
            .with_max_len(1)
            .enumerate()
            .map(|(k, (items, with))| f(k, items, with))
            .collect_into_vec(out);
        return;
    }
    out.clear();
    out.extend(
        items
            .chunks_mut(chunk_len)
            .zip(with.chunks_mut(chunk_len))
            .enumerate()
            .map(|(k, (items, with))| f(k, items, with)),
    );
}

/// Calls `f(r, part r of out)` for every part of `out[..total]` on as many threads as the pool has: part
/// `r` is `out[starts[r]..starts[r + 1]]` (the last one ends at `total`; `starts` ascending from 0, none past
/// `total`). The parts are cut by halving the list of parts (`rayon::join`, nothing allocated), down to one
/// part per task. For parts whose lengths are known before they are written: each written straight into
/// its place.
#[inline]
pub fn for_each_part_mut<T, F>(out: &mut [T], starts: &[usize], total: usize, f: F)
where
    T: Send,
    F: Fn(usize, &mut [T]) + Sync + Send,
{
    // A list of zero-sized items: nothing is allocated.
    let mut none = vec![(); total];
    for_each_part_zip_mut(out, &mut none, starts, total, |r, part, _| f(r, part));
}

/// [`for_each_part_mut`] over two lists cut into the same parts: `f(r, part r of out, part r of with)`
/// (both at least `total` long, else nothing is called). For a part written with a buffer of its own.
#[inline]
pub fn for_each_part_zip_mut<T, U, F>(
    out: &mut [T],
    with: &mut [U],
    starts: &[usize],
    total: usize,
    f: F,
) where
    T: Send,
    U: Send,
    F: Fn(usize, &mut [T], &mut [U]) + Sync + Send,
{
    let (Some(out), Some(with)) = (out.get_mut(..total), with.get_mut(..total)) else {
        return;
    };
    // The pool's halving measures parts from `starts[0]`, the loop below from 0: the same parts only for
    // starts ascending from 0, as documented.
    debug_assert!(starts.first().is_none_or(|&s| s == 0) && starts.is_sorted());
    #[cfg(feature = "parallel")]
    if is_parallel() && starts.len() > 1 {
        parts::split(out, with, starts, 0, &f);
        return;
    }
    let (mut rest, mut rest_with) = (out, with);
    let mut at = 0;
    for r in 0..starts.len() {
        let end = starts.get(r + 1).copied().unwrap_or(total).clamp(at, total);
        let (part, tail) = rest.split_at_mut(end - at);
        let (part_with, tail_with) = rest_with.split_at_mut(end - at);
        f(r, part, part_with);
        rest = tail;
        rest_with = tail_with;
        at = end;
    }
}

#[cfg(feature = "parallel")]
mod parts {
    /// [`super::for_each_part_zip_mut`] over the parts `first..first + starts.len()`, both lists beginning
    /// at the first one's start: the list of parts halved, each half a task, down to one part.
    pub(super) fn split<T: Send, U: Send, F: Fn(usize, &mut [T], &mut [U]) + Sync + Send>(
        out: &mut [T],
        with: &mut [U],
        starts: &[usize],
        first: usize,
        f: &F,
    ) {
        let base = starts.first().copied().unwrap_or(0);
        if starts.len() <= 1 {
            if !starts.is_empty() {
                f(first, out, with);
            }
            return;
        }
        let half = starts.len() / 2;
        let cut = starts
            .get(half)
            .map_or(out.len(), |&s| s.saturating_sub(base).min(out.len()));
        let (low, high) = out.split_at_mut(cut);
        let (low_with, high_with) = with.split_at_mut(cut);
        let (low_starts, high_starts) = starts.split_at(half);
        rayon::join(
            || split(low, low_with, low_starts, first, f),
            || split(high, high_with, high_starts, first + half, f),
        );
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
///
/// When `a` ends while another thread still runs `b`, this thread spins until `b` ends (looking for the
/// pool's pending tasks every few spins) before it leaves the wait to rayon, whose waiting thread yields its
/// core a few dozen times and then sleeps: on a machine whose idle cores halt, a sleep and a wake inside a
/// step cost more than a small scene's whole task. The spin is bounded by a count (`spin::SPINS`), not a
/// time; `b` not yet taken up by another thread is run here at once, as rayon does.
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
        return spin::join(a, b);
    }
    (a(), b())
}

#[cfg(feature = "parallel")]
pub(crate) mod spin {
    use std::sync::atomic::{AtomicU8, Ordering};

    /// Spins, a pause each, a thread waits for the other half of a join (or a team member for a phase)
    /// before it yields its core: a count, not a time, chosen longer than any wait between two tasks of one
    /// step when each thread has a core, so the yield only comes into play when the pool has more threads
    /// than the machine has free cores.
    pub(crate) const SPINS: u64 = 1 << 16;

    /// Spins between two looks for the pool's pending tasks: a waiting thread takes up a task within a
    /// fraction of a microsecond, not after the whole spin.
    pub(crate) const SPINS_BETWEEN_LOOKS: u64 = 16;

    /// `b`'s state, as the thread running `a` sees it.
    const WAITING: u8 = 0;
    const RUNNING: u8 = 1;
    const ENDED: u8 = 2;

    /// [`super::join`] on the pool.
    pub(super) fn join<A, B, RA, RB>(a: A, b: B) -> (RA, RB)
    where
        A: FnOnce() -> RA + Send,
        B: FnOnce() -> RB + Send,
        RA: Send,
        RB: Send,
    {
        let state = AtomicU8::new(WAITING);
        rayon::join(
            || {
                let ra = a();
                // Only a hint of when rayon's own wait would find `b` done (rayon's latch orders the
                // results): spin while another thread runs `b`; if none has taken it, rayon runs it here.
                let mut spins = 0;
                while state.load(Ordering::Acquire) == RUNNING && spins < SPINS {
                    spins += 1;
                    if spins.is_multiple_of(SPINS_BETWEEN_LOOKS)
                        && rayon::yield_now() == Some(rayon::Yield::Executed)
                    {
                        continue;
                    }
                    std::hint::spin_loop();
                }
                ra
            },
            || {
                state.store(RUNNING, Ordering::Relaxed);
                // Ended also when `b` unwinds, so that `a`'s thread does not spin for nothing.
                let _ended = EndOnDrop(&state);
                b()
            },
        )
    }

    /// Calls `f(start, part)` on parts of `items` (`start` the index of `part`'s first item in the whole)
    /// that cover it once: `items` is halved, each half by a [`join`], until there is a part for each of
    /// `threads` or a part would be shorter than `min_len`. One task a thread, against rayon's adaptive
    /// split into several: a section of a small step is over in microseconds, each further task is one
    /// more hand-over between threads, and the items these functions serve (bodies, slots, joints) cost
    /// about the same each. Each join's wait spins instead of sleeping ([`join`]).
    pub(super) fn split_mut<T: Send>(
        items: &mut [T],
        start: usize,
        min_len: usize,
        threads: usize,
        f: &(dyn Fn(usize, &mut [T]) + Sync),
    ) {
        // [`split_both_mut`] beside an empty second list.
        split_both_mut::<T, (), _>(
            items,
            &mut [],
            start,
            min_len,
            threads,
            &|start, part, _| {
                f(start, part);
            },
        );
    }

    /// [`split_mut`] over two lists of one length, split alike.
    pub(super) fn split_both_mut<T: Send, U: Send, F>(
        items: &mut [T],
        with: &mut [U],
        start: usize,
        min_len: usize,
        threads: usize,
        f: &F,
    ) where
        F: Fn(usize, &mut [T], &mut [U]) + Sync,
    {
        if threads <= 1 || items.len() < 2 * min_len.max(1) {
            f(start, items, with);
            return;
        }
        let left = threads / 2;
        let mid = items.len() * left / threads;
        let (a, b) = items.split_at_mut(mid);
        let (wa, wb) = with.split_at_mut(mid.min(with.len()));
        join(
            || split_both_mut(a, wa, start, min_len, left, f),
            || split_both_mut(b, wb, start + mid, min_len, threads - left, f),
        );
    }

    /// Marks `b` ended when dropped.
    struct EndOnDrop<'a>(&'a AtomicU8);

    impl Drop for EndOnDrop<'_> {
        fn drop(&mut self) {
            self.0.store(ENDED, Ordering::Release);
        }
    }
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

    /// Failed looks for pending work, a pause after each, between two yields of the core while a spinner
    /// waits: a count, not a time, chosen longer than the serial stretches of a step (each look is a try at
    /// every queue of the pool), so the spinner keeps its core through the
    /// step (a yield can hand the core to another process for a whole time slice) and only gives it away
    /// now and then when the step's thread keeps it waiting longer.
    const LOOKS_BEFORE_YIELD: u32 = 1 << 12;

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
mod tests;
