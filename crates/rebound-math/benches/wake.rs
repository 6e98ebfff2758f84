//! How long a parallel section of two chunks takes when it starts after a serial stretch of the step:
//! with the pool's other thread asleep (it went to sleep during the stretch) and with it kept awake
//! (`par::with_pool_awake`). Run: `cargo bench -p rebound-math --features parallel --bench wake`.
//!
//! Each section is two chunks of about 5 µs of arithmetic, on a pool of two threads; the serial stretch
//! before it (not timed) is 0 or 200 µs of the same arithmetic on the calling thread. On an idle machine
//! with two cores, a section whose second thread is awake takes about one chunk's time; one that has to
//! wake it, up to both chunks' (the caller runs both while the other thread wakes up).

use criterion::{Criterion, criterion_group, criterion_main};
use rebound_math::par::rayon;
use rebound_math::{par, team};
use std::hint::black_box;
use std::time::{Duration, Instant};

/// About `n` × 1 ns of dependent arithmetic.
fn work(n: u32) -> u32 {
    let mut x = black_box(1_u32);
    for i in 0..n {
        x = x.wrapping_mul(1_664_525).wrapping_add(i);
    }
    black_box(x)
}

/// One section: two chunks of `CHUNK` work, one phase.
fn section() {
    team::run(&[2], &|_, _| {
        black_box(work(CHUNK));
    });
}

const CHUNK: u32 = 5_000;

fn sections(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap_or_else(|e| panic!("no pool: {e}"));
    let mut group = c.benchmark_group("section_after_serial_stretch");
    for gap in [0_u32, 200_000] {
        for awake in [false, true] {
            let name = format!(
                "gap_{}us_{}",
                gap / 1000,
                if awake { "awake" } else { "asleep" }
            );
            group.bench_function(name, |b| {
                b.iter_custom(|iters| {
                    pool.install(|| {
                        let timed = || {
                            let mut total = Duration::ZERO;
                            for _ in 0..iters {
                                black_box(work(gap));
                                let start = Instant::now();
                                section();
                                total += start.elapsed();
                            }
                            total
                        };
                        if awake {
                            par::with_pool_awake(timed)
                        } else {
                            timed()
                        }
                    })
                });
            });
        }
    }
    group.finish();
}

criterion_group!(benches, sections);
criterion_main!(benches);
