//! The cost of recording and reading one frame of the SCENES.md 4,096-ball pile, once the pile has formed
//! (200 steps): compare with `cargo bench --bench scenes -- balls` for the step itself.
//!
//! ```text
//! cargo bench -p rebound-record --bench record
//! ```

use std::hint::black_box;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use rebound_record::{FrameReader, Recorder};
use rebound_suite::scenes::{Balls, Scene, SceneOptions, balls};

/// Steps before measuring: the balls have landed and the pile's contacts exist.
const SETTLE_STEPS: usize = 200;

fn settled_pile() -> Balls {
    let mut scene =
        Balls::new(SceneOptions::default(), balls::SIDE).expect("the balls scene builds");
    for _ in 0..SETTLE_STEPS {
        scene.step();
    }
    scene
}

fn bench(c: &mut Criterion) {
    let scene = settled_pile();
    let world = scene.world();
    let mut group = c.benchmark_group("record");
    group.sample_size(20);
    let mut recorder = Recorder::new(world, std::io::sink()).expect("a sink never fails");
    group.bench_function("balls/record_frame", |b| {
        b.iter(|| {
            recorder
                .record(black_box(world))
                .expect("a sink never fails");
        });
    });
    let mut bytes = Vec::new();
    let mut to_memory = Recorder::new(world, &mut bytes).expect("memory never fails");
    to_memory.record(world).expect("memory never fails");
    drop(to_memory);
    group.bench_function("balls/read_frame", |b| {
        // The manifest is read in the untimed setup; only the frame's decoding is timed.
        b.iter_batched(
            || FrameReader::new(bytes.as_slice()).expect("a valid file"),
            |mut reader| reader.next_frame().expect("a valid frame"),
            BatchSize::LargeInput,
        );
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
