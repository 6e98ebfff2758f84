//! Picture benchmarks: one 640×480 frame of the 820-box pyramid (SCENES.md scene 2, settled for 60 steps),
//! the scene gathered from the world and drawn, and drawn alone; and one step of the same pyramid, so the
//! two can be read side by side (the goal: a frame costs at most ten steps; docs/performance.md).
//!
//! ```text
//! cargo bench -p rebound-render --bench render
//! ```

use std::hint::black_box;

use criterion::{Criterion, criterion_group, criterion_main};
use rebound::prelude::Vec3;
use rebound_render::{Camera, RenderOptions, RenderScene, render};
use rebound_suite::scenes::{Pyramid, Scene, SceneOptions, pyramid};

/// The pyramid settled for 60 steps.
fn settled_pyramid() -> Pyramid {
    let mut scene = Pyramid::new(SceneOptions::default(), pyramid::BASE).expect("the scene builds");
    for _ in 0..60 {
        scene.step();
    }
    scene
}

/// The whole pyramid in a 640×480 view.
fn camera() -> Camera {
    Camera {
        position: Vec3::new(25.0, 28.0, 62.0),
        target: Vec3::new(0.0, 16.0, 0.0),
        fov_y: 0.8,
        width: 640,
        height: 480,
    }
}

fn benches(c: &mut Criterion) {
    let mut group = c.benchmark_group("render");
    group.sample_size(20);
    let mut stepped = settled_pyramid();
    group.bench_function("pyramid_step", |b| {
        b.iter(|| black_box(stepped.step()));
    });
    let scene = settled_pyramid();
    let (camera, options) = (camera(), RenderOptions::default());
    group.bench_function("pyramid_frame_640x480", |b| {
        b.iter(|| {
            let picture = RenderScene::from_world(scene.world()).expect("valid shapes");
            black_box(render(&picture, &camera, &options).expect("valid camera"))
        });
    });
    let picture = RenderScene::from_world(scene.world()).expect("valid shapes");
    group.bench_function("pyramid_draw_640x480", |b| {
        b.iter(|| black_box(render(&picture, &camera, &options).expect("valid camera")));
    });
    group.finish();
}

criterion_group!(render_benches, benches);
criterion_main!(render_benches);
