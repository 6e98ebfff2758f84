//! Micro-benchmarks of the joint solver: one full step (prepare, 4 substeps of integrate velocities, apply
//! forces, warm start, solve, integrate positions, relax, then restitution, store and write-back) of a
//! 1,000-link rope chain swinging from a fixed point, and of 1,000 damped spring pairs (docs/scenes.md, `springs`:
//! 1 kg balls, rest length 1 m, k = 1e4 N/m, c = 10 N·s/m, zero gravity) in both spring models.
//! Run: `cargo bench -p rebound-constraints`.
//!
//! Each iteration steps a fresh copy of the scene taken after a warm-up (a second of simulation), so every
//! sample times the same, moving state: stepping one scene thousands of times would let the damped springs
//! decay into subnormal numbers, which are 10–100× slower on x86 and would time the FPU instead of the solver.
//! Criterion reports time per step (the copy is not timed).

#[path = "../tests/support/mod.rs"]
mod support;

use criterion::{BatchSize, Criterion, criterion_group, criterion_main};
use rebound_constraints::{Joint, JointSettings, Rope, Spring, SpringModel};
use rebound_dynamics::{BodyDesc, MassProperties, SolverSettings};
use rebound_math::Vec3;
use std::hint::black_box;
use support::Harness;

const DT: f32 = 1.0 / 60.0;

fn ball(mass: f32, position: Vec3) -> BodyDesc {
    let inertia =
        MassProperties::new(mass, Vec3::ZERO, Vec3::splat(0.004 * mass)).expect("valid bench ball");
    BodyDesc::dynamic()
        .with_mass_properties(inertia)
        .with_position(position)
}

/// 1,000 balls of 1 kg on ropes of 0.25 m, laid out horizontally from a fixed point and released.
fn chain(settings: JointSettings) -> Harness {
    let mut h = Harness::new(SolverSettings::default()).with_joint_settings(settings);
    let mut previous = h.world_anchor();
    for i in 0..1_000 {
        let b = h.add(&ball(1.0, Vec3::new((i + 1) as f32 * 0.25, 0.0, 0.0)));
        h.join(
            Joint::new(Rope::new(0.25).expect("valid rope")),
            previous,
            b,
        );
        previous = b;
    }
    warm_up(h)
}

/// A second of simulation, so that the scene is moving and the warm-start impulses are those of a running
/// scene.
fn warm_up(mut h: Harness) -> Harness {
    for _ in 0..60 {
        h.step(DT);
    }
    h
}

/// docs/scenes.md, `springs`: 1,000 pairs on a 10 × 10 × 10 grid, initial length 1.5 m.
fn springs(model: SpringModel) -> Harness {
    let mut h = Harness::new(SolverSettings {
        gravity: Vec3::ZERO,
        ..SolverSettings::default()
    });
    for i in 0..10 {
        for j in 0..10 {
            for k in 0..10 {
                let c = 4.0 * Vec3::new(i as f32, j as f32, k as f32);
                let a = h.add(&ball(1.0, c - Vec3::new(0.75, 0.0, 0.0)));
                let b = h.add(&ball(1.0, c + Vec3::new(0.75, 0.0, 0.0)));
                h.join(
                    Joint::new(Spring::new(1.0, model).expect("valid spring")),
                    a,
                    b,
                );
            }
        }
    }
    // The pairs oscillate at 22 Hz, lightly damped (ζ = 0.07): still moving after the warm-up.
    warm_up(h)
}

/// Times one step of copies of `scene`.
fn bench_step(
    group: &mut criterion::BenchmarkGroup<'_, criterion::measurement::WallTime>,
    name: &str,
    scene: &Harness,
) {
    group.bench_function(name, |bench| {
        bench.iter_batched_ref(
            || scene.clone(),
            |h| black_box(h.step(DT)),
            BatchSize::LargeInput,
        );
    });
}

fn joint_steps(c: &mut Criterion) {
    let mut group = c.benchmark_group("step");
    bench_step(
        &mut group,
        "chain_1000_ropes",
        &chain(JointSettings::default()),
    );
    let no_tethers = JointSettings {
        tethers: false,
        ..JointSettings::default()
    };
    bench_step(
        &mut group,
        "chain_1000_ropes_no_tethers",
        &chain(no_tethers),
    );
    // Joint by joint (Gauss–Seidel only, the solver before the direct solve of paths): what that costs.
    let joint_by_joint = JointSettings {
        direct_chains: false,
        ..JointSettings::default()
    };
    bench_step(
        &mut group,
        "chain_1000_ropes_joint_by_joint",
        &chain(joint_by_joint),
    );
    let soft = SpringModel::soft_stiffness(1.0e4, 10.0).expect("valid");
    bench_step(&mut group, "springs_1000_soft", &springs(soft));
    let force = SpringModel::force(1.0e4, 10.0).expect("valid");
    bench_step(&mut group, "springs_1000_force", &springs(force));
    // The same 2,000 bodies without joints: the harness's own cost (copy-in, integration, write-back).
    let mut bodies = Harness::new(SolverSettings::default());
    for i in 0..2_000 {
        bodies.add(&ball(1.0, Vec3::new(i as f32, 0.0, 0.0)));
    }
    bench_step(&mut group, "bodies_2000_no_joints", &bodies);
    group.finish();
}

criterion_group!(benches, joint_steps);
criterion_main!(benches);
