//! A step allocates nothing once the scene's buffers have grown (issue 7: "no allocation per step — prove it
//! with a counting-allocator test"). This binary installs a counting global allocator, warms each peer scene
//! (docs/scenes.md) up (buffers grow to the scene's size), then counts the allocations of further steps: zero (in a
//! window of steps without the one-time amortised growth of a buffer; see the test).
//!
//! With the `parallel` feature every scene also steps inside a pool of two threads (`cargo test -p
//! rebound-suite --features parallel --test no_allocation`), and the pool's threads are counted too: the
//! parallel stages keep their scratch from step to step as the serial ones do.
//!
//! One test function only: the allocator is global to the binary, and a second test running on another
//! thread would be counted too.

use rebound_suite::scenes::{self, Balls, Scene, SceneOptions};
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};
use std::alloc::System;

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// Steps before counting: contacts appear, piles form and chains fold, and buffers grow to fit them. (While
/// a pile still spreads, its number of contact pairs still grows, and so do the buffers.)
const WARM_UP: usize = 240;
/// Steps counted per window.
const COUNTED: usize = 30;
/// Windows counted at most (see the test).
const WINDOWS: usize = 3;

/// Runs `f` on a pool of `threads` threads (the parallel build; the serial build has no pool and runs `f`
/// on the calling thread, for one thread only).
#[cfg(feature = "parallel")]
fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    use rebound::math::par::rayon::ThreadPoolBuilder;
    ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("the test machine starts threads")
        .install(f)
}

#[cfg(not(feature = "parallel"))]
fn on_threads<R: Send>(threads: usize, f: impl FnOnce() -> R + Send) -> R {
    assert_eq!(threads, 1, "the serial build has one thread");
    f()
}

/// The thread counts the scenes step on: one, and with the `parallel` feature a pool of two.
#[cfg(feature = "parallel")]
const THREADS: [usize; 2] = [1, 2];
#[cfg(not(feature = "parallel"))]
const THREADS: [usize; 1] = [1];

#[test]
fn stepping_a_warmed_up_scene_allocates_nothing() {
    let mut report = Vec::new();
    for threads in THREADS {
        on_threads(threads, || count_scenes(threads, &mut report));
    }
    check(&report);
}

/// Allocations, reallocations and bytes of the last window counted, per scene and thread count.
type Report = Vec<(&'static str, usize, usize, usize, usize)>;

/// Warms up and counts every scene on the current pool (`threads` threads) into `report`.
fn count_scenes(threads: usize, report: &mut Report) {
    for name in scenes::ALL_SCENES {
        // The balls scene at an eighth of its size (8 × 8 × 8), so that its pile settles within the warm-up
        // in a debug build.
        let built: Option<Box<dyn Scene>> = if name == "balls" {
            Balls::new(SceneOptions::default(), 8)
                .ok()
                .map(|b| Box::new(b) as Box<dyn Scene>)
        } else {
            scenes::build(name, SceneOptions::default()).ok().flatten()
        };
        let Some(mut scene) = built else {
            panic!("scene {name} does not build");
        };
        // Every step on the pool, however small the scene.
        #[cfg(feature = "parallel")]
        scene.world_mut().set_min_work_for_threads(0);
        for _ in 0..WARM_UP {
            scene.step();
        }
        // Up to three windows of COUNTED steps, until one allocates nothing; the last one is judged. A buffer
        // that grows amortised (doubling) grows a bounded number of times and then never again — parry's BVH
        // optimisation keeps a breadth-first queue that grows to about √(leaf count) entries the first time
        // the tree's top is that wide, which may happen after the warm-up (measured: once, 128 bytes) — while
        // an allocation in every step shows up in every window.
        let mut change = None;
        for _ in 0..WINDOWS {
            let region = Region::new(GLOBAL);
            for _ in 0..COUNTED {
                scene.step();
            }
            let counted = region.change();
            let clean = counted.allocations + counted.reallocations == 0;
            change = Some(counted);
            if clean {
                break;
            }
        }
        let Some(change) = change else {
            panic!("no window was counted");
        };
        report.push((
            name,
            threads,
            change.allocations,
            change.reallocations,
            change.bytes_allocated,
        ));
    }
}

/// The verdict on every scene and thread count counted.
fn check(report: &Report) {
    for (name, threads, allocations, reallocations, bytes) in report {
        // The piles (balls, pyramid) and the springs allocate nothing at all. The joint scenes keep making
        // contacts they never had — a swinging chain folds onto itself, the bridge's balls roll onto new
        // planks — and when more of them exist than ever before, the step's buffers grow to hold them
        // (measured: under 1 per step on one thread; on two, the pool's per-task lists grow each on its
        // own: up to 6 per step). A steady scene's step allocates nothing, on one thread or a pool (the
        // solver stage's team starts its other members as halves of `rayon::join`s on the stack,
        // `rebound_math::team`).
        let steady = matches!(*name, "balls" | "pyramid" | "springs");
        let allowed = match (steady, *threads > 1) {
            (true, _) => 0,
            (false, false) => 3 * COUNTED,
            (false, true) => 8 * COUNTED,
        };
        if steady {
            assert!(
                *reallocations == 0 && *allocations == 0,
                "{name} on {threads} thread(s): {allocations} allocations and {reallocations} \
                 reallocations ({bytes} bytes) in {COUNTED} steps (allowed none); every scene: \
                 {report:?}"
            );
        }
        assert!(
            *allocations + *reallocations <= allowed,
            "{name} on {threads} thread(s): {allocations} allocations and {reallocations} reallocations \
             ({bytes} bytes) in {COUNTED} steps (allowed {allowed}); every scene: {report:?}"
        );
    }
}
