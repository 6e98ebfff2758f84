//! Tests of the pool helpers: order, coverage and bits on pools of any size.

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

/// A pool of `threads` threads (the parallel build).
#[cfg(feature = "parallel")]
fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap_or_else(|e| panic!("no pool: {e}"))
}

/// Runs `f` on pools of 1, 2 and 3 threads (the parallel build; the serial build runs it once).
fn on_pools(f: impl Fn() + Send + Sync) {
    #[cfg(feature = "parallel")]
    for threads in [1, 2, 3] {
        let pool = pool(threads);
        pool.install(&f);
    }
    #[cfg(not(feature = "parallel"))]
    f();
}

#[test]
fn map_chunks_zip_hands_out_each_chunk_once_in_order() {
    on_pools(|| {
        for len in [0_usize, 1, 63, 64, 65, 1000] {
            let mut items: Vec<u32> = (0..len as u32).collect();
            let mut with = vec![0_u32; len];
            let mut out = vec![(usize::MAX, 0)];
            map_chunks_zip_mut(&mut items, &mut with, 64, &mut out, |k, chunk, w| {
                for (x, y) in chunk.iter_mut().zip(w.iter_mut()) {
                    *y = *x + 1;
                    *x = k as u32;
                }
                (k, chunk.len())
            });
            let expected: Vec<_> = (0..len.div_ceil(64))
                .map(|k| (k, (len - 64 * k).min(64)))
                .collect();
            assert_eq!(out, expected, "{len} items");
            assert!(items.iter().enumerate().all(|(i, &k)| k as usize == i / 64));
            assert!(with.iter().enumerate().all(|(i, &y)| y as usize == i + 1));
        }
    });
}

#[test]
fn for_each_part_hands_out_each_part_alone() {
    on_pools(|| {
        // Parts of lengths 3, 0, 1, 0, 196, 0 (the last one empty, at the end).
        let starts = [0, 3, 3, 4, 4, 200];
        let mut out = vec![u32::MAX; 210];
        for_each_part_mut(&mut out, &starts, 200, |r, part| {
            part.iter_mut().for_each(|x| *x = r as u32);
        });
        let expected: Vec<u32> = (0..200_u32)
            .map(|i| match i {
                0..3 => 0,
                3 => 2,
                _ => 4,
            })
            .collect();
        assert_eq!(out[..200], expected[..]);
        assert!(out[200..].iter().all(|&x| x == u32::MAX), "past the total");
        // Many parts, some empty: every item written once, by its own part.
        let starts: Vec<usize> = (0..100).map(|r| r * r / 10).collect();
        let total = 99 * 99 / 10 + 7;
        let mut out = vec![u32::MAX; total];
        for_each_part_mut(&mut out, &starts, total, |r, part| {
            part.iter_mut().for_each(|x| *x = r as u32);
        });
        for (i, &x) in out.iter().enumerate() {
            let r = starts.partition_point(|&s| s <= i) - 1;
            assert_eq!(x as usize, r, "item {i}");
        }
    });
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
        let pool = pool(threads);
        let sums = pool.install(|| {
            with_pool_awake(|| {
                (0..50)
                    .map(|round| {
                        let mut out = Vec::new();
                        let items: Vec<u64> = (0..4096).collect();
                        map_collect_in_order(&items, &mut out, 64, |i, &x| x * round + i as u64);
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
    let pool = pool(2);
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

/// The sum of `0..n` by halving joins down to single items.
#[cfg(feature = "parallel")]
fn sum_by_joins(range: std::ops::Range<u64>) -> u64 {
    if range.end - range.start <= 1 {
        return range.start * u64::from(range.end > range.start);
    }
    let mid = range.start + (range.end - range.start) / 2;
    let (a, b) = join(
        || sum_by_joins(range.start..mid),
        || sum_by_joins(mid..range.end),
    );
    a + b
}

#[cfg(feature = "parallel")]
#[test]
fn for_each_visits_every_item_once_on_pools_of_any_size() {
    for threads in [2, 3, 8] {
        let pool = pool(threads);
        for len in [0, 1, 63, 64, 65, 129, 1000] {
            pool.install(for_each_visits_every_item_once_of(len));
        }
    }
}

/// [`for_each_visits_every_item_once`] on `len` items.
#[cfg(feature = "parallel")]
fn for_each_visits_every_item_once_of(len: usize) -> impl FnOnce() + Send {
    move || {
        let mut items = vec![0_u32; len];
        for_each_mut(&mut items, 8, |i, x| *x += i as u32 + 1);
        assert!(items.iter().enumerate().all(|(i, &x)| x == i as u32 + 1));
        let mut with: Vec<u32> = (0..len as u32 + 5).collect();
        for_each_zip_mut(&mut items, &with, 8, |x, &w| *x -= w);
        assert!(items.iter().all(|&x| x == 1));
        for_each_indexed_zip_both_mut(&mut items, &mut with, 8, |i, x, w| {
            *w += *x + i as u32;
            *x = 0;
        });
        assert!(items.iter().all(|&x| x == 0));
        assert!(
            with[..len]
                .iter()
                .enumerate()
                .all(|(i, &w)| w == 2 * i as u32 + 1)
        );
        assert!(
            with[len..]
                .iter()
                .enumerate()
                .all(|(i, &w)| w == (len + i) as u32)
        );
    }
}

#[cfg(feature = "parallel")]
#[test]
fn nested_joins_on_pools_of_any_size() {
    for threads in [1, 2, 3, 8] {
        let pool = pool(threads);
        let sum = pool.install(|| with_pool_awake(|| sum_by_joins(0..10_000)));
        assert_eq!(sum, (0..10_000).sum::<u64>(), "{threads} threads");
    }
}

#[cfg(feature = "parallel")]
#[test]
fn a_panicking_half_of_a_join_reaches_the_caller() {
    let pool = pool(2);
    let result = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        pool.install(|| join(|| sum_by_joins(0..1_000), || panic!("b fails")))
    }));
    assert!(result.is_err());
    assert_eq!(pool.install(|| join(|| 1, || 2)), (1, 2));
}

#[test]
fn serially_runs_every_helper_on_the_calling_thread_and_ends_with_the_call() {
    on_pools(|| {
        let before = is_parallel();
        let caller = std::thread::current().id();
        let mut items = vec![0_u32; 1000];
        let (inside, same_thread) = serially(|| {
            let same = std::sync::atomic::AtomicBool::new(true);
            for_each_mut(&mut items, 8, |i, x| {
                *x = i as u32;
                if std::thread::current().id() != caller {
                    same.store(false, std::sync::atomic::Ordering::Relaxed);
                }
            });
            (is_parallel(), same.into_inner())
        });
        assert!(!inside, "is_parallel inside serially");
        assert!(
            same_thread,
            "a helper inside serially ran on another thread"
        );
        assert!(items.iter().enumerate().all(|(i, &x)| x == i as u32));
        assert_eq!(is_parallel(), before, "serially left the flag set");
        // A panic inside puts the flag back too.
        let caught = std::panic::catch_unwind(|| serially(|| panic!("inside")));
        assert!(caught.is_err());
        assert_eq!(
            is_parallel(),
            before,
            "a panic inside serially left the flag set"
        );
    });
}
