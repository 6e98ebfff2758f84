//! The cost of one 640×480 picture of the 820-box pyramid against one step of it, for callgrind (the
//! renderer's speed goal: a frame costs at most ten steps; docs/performance.md).
//!
//! ```text
//! cargo build --release -p rebound-render --example frame_cost
//! valgrind --tool=callgrind --callgrind-out-file=frame.out target/release/examples/frame_cost
//! callgrind_annotate --inclusive=yes frame.out | grep -E 'frame_cost::(step|picture)'
//! target/release/examples/frame_cost 10 10 pyramid.png   # steps, pictures, and the last picture saved
//! ```
//!
//! The pyramid is stepped 60 steps first (settled, as the scene benchmarks measure it); then the steps
//! (10 unless given) go through [`step`] and the pictures (10 unless given) through [`picture`] (scene built
//! from the world, then drawn), each its own function so callgrind reports their instructions apart. The
//! median wall time of each is printed to stderr too (noisy on a loaded machine: the instruction counts are
//! the measure).

use std::hint::black_box;
use std::time::Instant;

use rebound::PhysicsWorld;
use rebound_render::{Camera, Image, RenderOptions, RenderScene, render};
use rebound_suite::scenes::{Pyramid, Scene, SceneOptions, pyramid};

/// Steps measured unless the first argument says otherwise.
const STEPS: usize = 10;
/// Pictures measured unless the second argument says otherwise.
const FRAMES: usize = 10;

/// The camera the measurement uses: the whole pyramid in a 640×480 view.
#[must_use]
fn camera() -> Camera {
    Camera {
        position: rebound::prelude::Vec3::new(25.0, 28.0, 62.0),
        target: rebound::prelude::Vec3::new(0.0, 16.0, 0.0),
        fov_y: 0.8,
        width: 640,
        height: 480,
    }
}

/// One step of the scene.
#[inline(never)]
fn step(scene: &mut Pyramid) {
    black_box(scene.step());
}

/// One picture of the world: the scene gathered from it, then drawn.
#[inline(never)]
fn picture(world: &PhysicsWorld, camera: &Camera, options: &RenderOptions) -> Image {
    let scene = RenderScene::from_world(world).expect("the world's shapes are valid");
    render(&scene, camera, options).expect("a valid camera")
}

/// The median of `samples` (sorted in place).
fn median(samples: &mut [f64]) -> f64 {
    samples.sort_by(f64::total_cmp);
    samples.get(samples.len() / 2).copied().unwrap_or(f64::NAN)
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let count = |i: usize, default: usize| {
        args.get(i)
            .map_or(Some(default), |a| a.parse().ok())
            .expect("counts are whole numbers")
    };
    let (steps, frames) = (count(0, STEPS), count(1, FRAMES));
    let mut scene = Pyramid::new(SceneOptions::default(), pyramid::BASE).expect("the scene builds");
    for _ in 0..60 {
        scene.step();
    }
    let mut step_ms = Vec::with_capacity(steps);
    for _ in 0..steps {
        let start = Instant::now();
        step(&mut scene);
        step_ms.push(start.elapsed().as_secs_f64() * 1e3);
    }
    let (camera, options) = (camera(), RenderOptions::default());
    let mut frame_ms = Vec::with_capacity(frames);
    for _ in 0..frames {
        let start = Instant::now();
        black_box(picture(scene.world(), &camera, &options));
        frame_ms.push(start.elapsed().as_secs_f64() * 1e3);
    }
    let (step_median, frame_median) = (median(&mut step_ms), median(&mut frame_ms));
    eprintln!(
        "median wall time: step {step_median:.2} ms, frame {frame_median:.2} ms ({:.1} steps)",
        frame_median / step_median
    );
    if let Some(path) = args.get(2) {
        picture(scene.world(), &camera, &options)
            .save_png(path)
            .expect("the picture is written");
    }
}
