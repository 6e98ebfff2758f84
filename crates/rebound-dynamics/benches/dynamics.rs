//! Micro-benchmarks of the dynamics stages: velocity and position integration of 10k bodies, and the contact
//! kernel (warm start + solve + relax) over 10k hand-made contacts. Run: `cargo bench -p rebound-dynamics`.
//!
//! Criterion reports time per batch; divide by 10,000 for the time per body or per contact.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rebound_dynamics::contact::Bias;
use rebound_dynamics::integrate::{integrate_positions, integrate_velocities};
use rebound_dynamics::{
    BodyDesc, BodyParams, Contact, ContactPoint, ContactSolver, MassProperties, RigidBody,
    SolverBody, SolverSettings, StepContext,
};
use rebound_math::{Quat, Vec3};
use std::hint::black_box;

const N: usize = 10_000;

fn bodies() -> Vec<RigidBody> {
    let mass = MassProperties::cuboid(1.0, Vec3::new(0.5, 0.25, 0.75)).expect("valid bench box");
    (0..N)
        .map(|i| {
            let f = i as f32;
            RigidBody::new(
                &BodyDesc::dynamic()
                    .with_mass_properties(mass)
                    .with_position(Vec3::new(f, 0.0, 0.0))
                    .with_rotation(Quat::from_rotation_y(f * 0.1))
                    .with_linear_velocity(Vec3::new(0.0, 1.0, 0.0))
                    .with_angular_velocity(Vec3::new(0.3, 1.0 + f * 1e-4, 0.2)),
            )
            .expect("valid bench body")
        })
        .collect()
}

fn integration(c: &mut Criterion) {
    let bodies = bodies();
    let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
    let start: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
    let ctx = StepContext::new(1.0 / 60.0, &SolverSettings::default());
    let mut group = c.benchmark_group("integrate_10k");
    group.throughput(Throughput::Elements(N as u64));
    let mut states = start.clone();
    group.bench_function("velocities_with_gyroscopic", |b| {
        b.iter(|| integrate_velocities(black_box(&mut states), &params, &ctx));
    });
    let no_gyro: Vec<BodyParams> = params
        .iter()
        .map(|p| BodyParams {
            gyroscopic: false,
            ..*p
        })
        .collect();
    group.bench_function("velocities_without_gyroscopic", |b| {
        b.iter(|| integrate_velocities(black_box(&mut states), &no_gyro, &ctx));
    });
    group.bench_function("positions", |b| {
        b.iter(|| integrate_positions(black_box(&mut states), &params, &ctx));
    });
    group.finish();
}

fn contact_kernel(c: &mut Criterion) {
    // 10k boxes each resting on its own fixed ground body via a 4-point manifold.
    let mut bodies = bodies();
    let ground = RigidBody::new(&BodyDesc::fixed()).expect("valid ground");
    bodies.push(ground);
    let ground_index = bodies.len() - 1;
    let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
    let states: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
    let contacts: Vec<Contact> = (0..N)
        .map(|i| {
            let mut contact = Contact::new(ground_index, i, Vec3::Y, 0.6, 0.0);
            let com = bodies[i].center_of_mass();
            for (k, corner) in [(-0.5, -0.75), (0.5, -0.75), (0.5, 0.75), (-0.5, 0.75)]
                .into_iter()
                .enumerate()
            {
                let p = com + Vec3::new(corner.0, -0.25, corner.1);
                contact.push_point(ContactPoint {
                    anchor_a: p,
                    anchor_b: p - com,
                    separation: -0.001,
                    normal_impulse: 0.01,
                    feature_id: k as u32,
                    ..ContactPoint::default()
                });
            }
            contact
        })
        .collect();
    let ctx = StepContext::new(1.0 / 60.0, &SolverSettings::default());
    let mut solver = ContactSolver::new();
    let mut group = c.benchmark_group("contacts_10k");
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function("prepare", |b| {
        b.iter(|| solver.prepare(black_box(&contacts), &states, &params, &ctx));
    });
    let mut working = states.clone();
    group.bench_function("warm_start_solve_relax", |b| {
        b.iter(|| {
            solver.warm_start(&mut working);
            solver.solve(&mut working, &ctx, Bias::On);
            solver.solve(&mut working, &ctx, Bias::Off);
        });
    });
    group.finish();
}

criterion_group!(benches, integration, contact_kernel);
criterion_main!(benches);
