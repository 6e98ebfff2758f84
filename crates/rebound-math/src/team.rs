//! A team of the pool's threads walking one list of *phases* together, inside one parallel section: the
//! solver's substeps open one section a step instead of one per colour group and pass.
//!
//! A phase is a number of *chunks*; the chunks of one phase may run at once, and a phase starts only once
//! every chunk of the phases before it has ended (a barrier). Chunks are numbered across the whole list —
//! phase `p` holds the numbers `ends[p − 1] .. ends[p]` — and every member takes the next number from one
//! counter and, before running it, waits until a second counter (the chunks ended) reaches its phase's first
//! number. The chunks of the phases before `p` hold the smaller numbers, were all taken before any of `p`'s,
//! and none of `p`'s ends before they have: so the ended count reaches `ends[p − 1]` exactly when they all
//! have. The wait spins on that counter, looking for the pool's pending tasks every few spins; only after a
//! fixed number of spins (a count, not a time: the same on every run) does it also yield the core, which
//! a phase's wait never reaches when the members have cores of their own. A waiting member so neither
//! sleeps nor gives its core to another process inside a step: on a machine whose idle cores halt, waking
//! one costs more than a small scene's phase.
//!
//! Which member runs which chunk is decided by who takes the number first; the results may not depend on
//! it, and the solver's do not: a chunk computes the same values whichever thread runs it (see the callers).
//! A member only ever waits for chunks other members have taken and are running, and a chunk never waits,
//! so the team cannot deadlock however many of its members the pool gets round to starting: the calling
//! thread alone runs every chunk when the others are busy. Members are rayon jobs of the current pool, so
//! the world's thread-pool setting rules. A chunk may call into rayon (a
//! joint path solved from both ends as two tasks), and a waiting member runs the pool's pending tasks
//! (`rayon::yield_now`), so such a chunk's second task is taken up by a member that would otherwise only
//! wait. A member job that starts on a thread already in a team — picked up while that thread waits, or
//! inside a chunk — returns at once: a thread is a member of one team at a time, so no member waits on a
//! chunk further up its own stack. The other members are the second halves of nested joins on the
//! caller's stack, so a team allocates nothing.
//!
//! In the serial build, in a pool of one thread, and for a list whose every phase is one chunk (nothing
//! could run beside it), [`run`] is the plain loop over the phases and chunks.

#[cfg(feature = "parallel")]
use std::sync::atomic::{AtomicBool, AtomicU32, Ordering};

// A waiting member looks for the pool's tasks every `SPINS_BETWEEN_LOOKS` spins (a chunk's own tasks, a
// path solved from both ends, are taken up within a fraction of a microsecond) and also yields its core
// after `SPINS_BEFORE_YIELD`: longer than a phase of a step, so the yield comes into play when the pool has
// more threads than the machine has free cores (a member waiting on a chunk whose thread lost its core),
// not between a step's phases.
#[cfg(feature = "parallel")]
use crate::par::spin::{SPINS as SPINS_BEFORE_YIELD, SPINS_BETWEEN_LOOKS};

/// The number of threads a team started here would have: the current pool's (1 in the serial build).
#[must_use]
pub fn size() -> usize {
    #[cfg(feature = "parallel")]
    if crate::par::is_parallel() {
        return rayon::current_num_threads();
    }
    1
}

/// Runs `work(phase, chunk)` for every chunk of every phase: phase `p` has `ends[p] − ends[p − 1]` chunks
/// (`ends[0]` for `p = 0`; `ends` does not decrease), numbered from 0 within it. The chunks of one phase run
/// on the pool's threads at once; each phase after all of the one before it.
///
/// A chunk that panics ends the team: the members still waiting stop, and the panic is raised here once
/// every member has returned.
pub fn run(ends: &[u32], work: &(dyn Fn(usize, u32) + Sync)) {
    #[cfg(feature = "parallel")]
    if crate::par::is_parallel() && widest(ends) > 1 {
        run_on_pool(ends, work);
        return;
    }
    let mut start = 0;
    for (phase, &end) in ends.iter().enumerate() {
        for chunk in 0..end.saturating_sub(start) {
            work(phase, chunk);
        }
        start = start.max(end);
    }
}

/// The team's two counters, each on its own cache line pair (the adjacent-line prefetcher pulls lines in
/// twos), so that taking a number does not evict the line the waiting members spin on.
#[cfg(feature = "parallel")]
#[derive(Default)]
#[repr(C, align(128))]
struct Padded<T>(T);

#[cfg(feature = "parallel")]
#[derive(Default)]
struct Counters {
    /// The next chunk number to take.
    taken: Padded<AtomicU32>,
    /// How many chunks have ended.
    ended: Padded<AtomicU32>,
    /// A chunk panicked: members stop waiting.
    failed: AtomicBool,
}

/// The most chunks of one phase of `ends`.
#[cfg(feature = "parallel")]
fn widest(ends: &[u32]) -> u32 {
    let (mut widest, mut start) = (0, 0);
    for &end in ends {
        widest = widest.max(end.saturating_sub(start));
        start = start.max(end);
    }
    widest
}

#[cfg(feature = "parallel")]
fn run_on_pool(ends: &[u32], work: &(dyn Fn(usize, u32) + Sync)) {
    let counters = Counters::default();
    // The caller is one member: a phase of `w` chunks needs `w − 1` more.
    let others = (rayon::current_num_threads().saturating_sub(1))
        .min(widest(ends).saturating_sub(1) as usize);
    with_members(others, &counters, ends, work);
}

/// Offers `others` more members to the pool, then walks the list as a member itself; returns once every
/// other member has returned. Each is the second half of a join (`par::join`: a member still on its last
/// chunk is waited for by spinning), on this thread's stack (nothing is allocated), which another thread
/// steals or this one runs itself when its own walk is over (the numbers are gone then: it returns at
/// once).
#[cfg(feature = "parallel")]
fn with_members(
    others: usize,
    counters: &Counters,
    ends: &[u32],
    work: &(dyn Fn(usize, u32) + Sync),
) {
    let Some(more) = others.checked_sub(1) else {
        member(counters, ends, work);
        return;
    };
    crate::par::join(
        || with_members(more, counters, ends, work),
        || {
            // No other member is needed for progress: one started on a thread already in a team leaves.
            if !IN_TEAM.get() {
                member(counters, ends, work);
            }
        },
    );
}

#[cfg(feature = "parallel")]
thread_local! {
    /// Whether this thread is a member of a team (further down its stack).
    static IN_TEAM: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Marks the thread a member of a team while it lives, and gives it back its outer state when dropped
/// (returning or unwinding).
#[cfg(feature = "parallel")]
struct InTeam(bool);

#[cfg(feature = "parallel")]
impl InTeam {
    fn enter() -> Self {
        Self(IN_TEAM.replace(true))
    }
}

#[cfg(feature = "parallel")]
impl Drop for InTeam {
    fn drop(&mut self) {
        IN_TEAM.set(self.0);
    }
}

/// One member's walk: take a number, wait for the phases before it, run it, count it ended; until the
/// numbers run out.
#[cfg(feature = "parallel")]
fn member(counters: &Counters, ends: &[u32], work: &(dyn Fn(usize, u32) + Sync)) {
    let _member = InTeam::enter();
    let total = ends.last().copied().unwrap_or(0);
    let (mut phase, mut phase_start) = (0, 0);
    loop {
        // Relaxed: the number only picks the chunk; the ended count orders the work.
        let ticket = counters.taken.0.fetch_add(1, Ordering::Relaxed);
        if ticket >= total {
            return;
        }
        while ends.get(phase).is_some_and(|&end| end <= ticket) {
            phase_start = phase_start.max(ends[phase]);
            phase += 1;
        }
        if !wait_for(counters, phase_start) {
            return;
        }
        let guard = FailOnUnwind(&counters.failed);
        work(phase, ticket - phase_start);
        std::mem::forget(guard);
        // Release: what the chunk wrote is seen by whoever reads this count with Acquire (a release sequence:
        // every later increment carries it on).
        counters.ended.0.fetch_add(1, Ordering::Release);
    }
}

/// Waits until `count` chunks have ended (the barrier before a phase); `false` if a chunk panicked.
#[cfg(feature = "parallel")]
fn wait_for(counters: &Counters, count: u32) -> bool {
    let mut spins = 0_u64;
    while counters.ended.0.load(Ordering::Acquire) < count {
        if counters.failed.load(Ordering::Relaxed) {
            return false;
        }
        spins += 1;
        if spins.is_multiple_of(SPINS_BETWEEN_LOOKS) {
            match rayon::yield_now() {
                Some(rayon::Yield::Executed) => continue,
                // Nothing of the pool's to run meanwhile, for long: give the core away now and then.
                _ if spins >= SPINS_BEFORE_YIELD => std::thread::yield_now(),
                _ => {}
            }
        }
        std::hint::spin_loop();
    }
    true
}

/// Sets the flag when dropped while the chunk unwinds (forgotten when it returns).
#[cfg(feature = "parallel")]
struct FailOnUnwind<'a>(&'a AtomicBool);

#[cfg(feature = "parallel")]
impl Drop for FailOnUnwind<'_> {
    fn drop(&mut self) {
        self.0.store(true, Ordering::Relaxed);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;

    /// The order in which the phases' chunks ran: every chunk once, each phase after the one before.
    fn record(ends: &[u32]) -> Vec<(usize, u32)> {
        let log = Mutex::new(Vec::new());
        run(ends, &|phase, chunk| {
            log.lock()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
                .push((phase, chunk));
        });
        log.into_inner()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    fn check(ends: &[u32], log: &[(usize, u32)]) {
        let mut expected: Vec<(usize, u32)> = Vec::new();
        let mut start = 0;
        for (p, &end) in ends.iter().enumerate() {
            expected.extend((0..end - start).map(|c| (p, c)));
            start = end;
        }
        let mut sorted = log.to_vec();
        sorted.sort_unstable();
        assert_eq!(sorted, expected);
        assert!(
            log.windows(2).all(|w| w[0].0 <= w[1].0),
            "a phase ran early"
        );
    }

    #[test]
    fn every_chunk_once_phase_after_phase() {
        let ends = [1, 3, 3, 7, 8, 12];
        check(&ends, &record(&ends));
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn on_a_pool_every_chunk_once_phase_after_phase() {
        let ends: Vec<u32> = (1..=200).map(|p| p * 3 - (p % 3)).collect();
        for threads in [2, 3, 8] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap_or_else(|e| panic!("no pool: {e}"));
            let log = pool.install(|| record(&ends));
            check(&ends, &log);
        }
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn chunks_may_call_into_the_pool() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap_or_else(|e| panic!("no pool: {e}"));
        let ends: Vec<u32> = (1..=100).map(|p| p * 2).collect();
        let sums = pool.install(|| {
            let sums = Mutex::new(0_u64);
            run(&ends, &|phase, chunk| {
                let (a, b) = rayon::join(|| phase as u64, || u64::from(chunk));
                *sums
                    .lock()
                    .unwrap_or_else(std::sync::PoisonError::into_inner) += a + b;
            });
            sums.into_inner()
                .unwrap_or_else(std::sync::PoisonError::into_inner)
        });
        assert_eq!(sums, 2 * (0..100).sum::<u64>() + 100);
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn a_panicking_chunk_ends_the_team() {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap_or_else(|e| panic!("no pool: {e}"));
        let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
            pool.install(|| {
                run(&[2, 4, 6], &|phase, _| assert_ne!(phase, 1, "chunk fails"));
            });
        }));
        assert!(result.is_err());
    }
}
