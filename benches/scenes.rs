//! Whole-scene criterion benchmarks: the five peer scenes of docs/scenes.md and the scaling series (balls at 1,024,
//! 4,096 and 16,384; pyramids of base 20, 40 and 80), through the `rebound` facade, one thread.
//!
//! ```text
//! cargo bench --bench scenes                 # everything, a few minutes on 2 cores
//! cargo bench --bench scenes -- scenes/      # the peer scenes only
//! ```
//!
//! One iteration is one [`Scene::step`] of 1/60 s, timed alone. Each scene is built and stepped 60 steps
//! (the warm-up that the comparison's statistics leave out too) before it is measured, and it is rebuilt,
//! outside the timing, once it reaches step 600: every measured step lies in steps 60..600, the window the
//! `compare` binary and the rapier side report, and a scene never runs on into states the comparison never
//! sees (the damped springs decaying into subnormal floats, for one).
//!
//! For Rebound against rapier in the same run, use `cargo run --release --bin compare`.

use std::hint::black_box;
use std::time::{Duration, Instant};

use criterion::{Criterion, SamplingMode, criterion_group, criterion_main};
use rebound_suite::scenes::{
    self, Balls, DEFAULT_SCENES, Pyramid, Scene, SceneOptions, balls, pyramid,
};

/// Steps stepped before measuring.
const WARMUP_STEPS: usize = 60;
/// A scene is rebuilt once it has run this many steps.
const RUN_STEPS: usize = 600;

/// Builds a fresh scene.
type Builder = Box<dyn Fn() -> Box<dyn Scene>>;

/// A scene that criterion steps, built on first use (so a filtered-out bench costs nothing) and rebuilt,
/// untimed, whenever it reaches [`RUN_STEPS`].
struct Stepper {
    build: Builder,
    scene: Option<Box<dyn Scene>>,
    steps: usize,
}

impl Stepper {
    fn new(build: Builder) -> Self {
        Self {
            build,
            scene: None,
            steps: 0,
        }
    }

    /// Steps `iters` times and returns the time spent inside [`Scene::step`] only.
    fn time(&mut self, iters: u64) -> Duration {
        let mut total = Duration::ZERO;
        for _ in 0..iters {
            let scene = match &mut self.scene {
                Some(scene) if self.steps < RUN_STEPS => scene,
                slot => {
                    let mut fresh = (self.build)();
                    for _ in 0..WARMUP_STEPS {
                        fresh.step();
                    }
                    self.steps = WARMUP_STEPS;
                    slot.insert(fresh)
                }
            };
            let start = Instant::now();
            black_box(scene.step());
            total += start.elapsed();
            self.steps += 1;
        }
        total
    }
}

/// Small samples: a scene step is milliseconds, and the whole file should run in a few minutes.
fn configure(group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>) {
    group
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .sampling_mode(SamplingMode::Flat);
}

fn peer_scenes(c: &mut Criterion) {
    let mut group = c.benchmark_group("scenes");
    configure(&mut group);
    for name in DEFAULT_SCENES {
        let mut stepper = Stepper::new(Box::new(move || {
            scenes::build(name, SceneOptions::default())
                .expect("the peer scenes build")
                .expect("a known scene name")
        }));
        group.bench_function(name, |b| b.iter_custom(|iters| stepper.time(iters)));
    }
    group.finish();
}

fn scaling(c: &mut Criterion) {
    let mut group = c.benchmark_group("scaling");
    configure(&mut group);
    for side in [8, balls::SIDE, 32] {
        let count = side * balls::LAYERS * side;
        let mut stepper = Stepper::new(Box::new(move || {
            Box::new(Balls::new(SceneOptions::default(), side).expect("the balls scene builds"))
        }));
        group.bench_function(format!("balls_{count}"), |b| {
            b.iter_custom(|iters| stepper.time(iters));
        });
    }
    for base in [20, pyramid::BASE, 80] {
        let mut stepper = Stepper::new(Box::new(move || {
            Box::new(Pyramid::new(SceneOptions::default(), base).expect("the pyramid builds"))
        }));
        group.bench_function(format!("pyramid_base_{base}"), |b| {
            b.iter_custom(|iters| stepper.time(iters));
        });
    }
    group.finish();
}

criterion_group!(benches, peer_scenes, scaling);
criterion_main!(benches);
