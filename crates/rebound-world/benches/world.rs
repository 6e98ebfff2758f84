//! Whole-world step benchmarks without parry: a joint-only rope chain, a hinged bridge, and a settled pile of
//! balls stepped awake versus asleep (sleeping bodies should cost almost nothing). Run:
//! `cargo bench -p rebound-world --bench world`.

use criterion::{Criterion, criterion_group, criterion_main};
use rebound_constraints::{HingeJoint, Joint, Rope};
use rebound_dynamics::{BodyDesc, MassProperties};
use rebound_math::Vec3;
use rebound_world::testing::SimpleBackend;
use rebound_world::{World, WorldSettings};
use std::hint::black_box;

const DT: f32 = 1.0 / 60.0;

/// Joint-only scenes are measured awake: sleep would let the bridge rest and skip it.
fn awake_settings() -> WorldSettings {
    WorldSettings {
        sleep_enabled: false,
        ..WorldSettings::default()
    }
}

fn chain(links: usize) -> World {
    let mut world = World::new(awake_settings()).expect("valid settings");
    let mass = MassProperties::ball(1000.0, 0.1).expect("valid mass");
    let mut previous = None;
    for i in 0..links {
        let body = world
            .insert_body(
                &BodyDesc::dynamic()
                    .with_position(Vec3::new((i + 1) as f32 * 0.25, 0.0, 0.0))
                    .with_mass_properties(mass),
            )
            .expect("valid body");
        let rope = Joint::new(Rope::new(0.25).expect("valid rope"));
        match previous {
            None => world.insert_world_joint(rope, body),
            Some(prev) => world.insert_joint(rope, prev, body),
        }
        .expect("valid joint");
        previous = Some(body);
    }
    world
}

fn bridge(planks: usize) -> World {
    let mut world = World::new(awake_settings()).expect("valid settings");
    let mass = MassProperties::cuboid(1.0, Vec3::new(0.25, 0.1, 1.0)).expect("valid mass");
    let hinge = |a: Vec3, b: Vec3| {
        Joint::new(HingeJoint::new())
            .with_local_anchors(a, b)
            .and_then(|j| j.with_local_axes(Vec3::Z, Vec3::Z))
            .expect("valid hinge")
    };
    let mut previous = None;
    for i in 0..planks {
        let x = i as f32 * 0.5 + 0.25;
        let body = world
            .insert_body(
                &BodyDesc::dynamic()
                    .with_position(Vec3::new(x, 10.0, 0.0))
                    .with_mass_properties(mass),
            )
            .expect("valid body");
        match previous {
            None => world.insert_world_joint(
                hinge(Vec3::new(0.0, 10.0, 0.0), Vec3::new(-0.25, 0.0, 0.0)),
                body,
            ),
            Some(prev) => world.insert_joint(
                hinge(Vec3::new(0.25, 0.0, 0.0), Vec3::new(-0.25, 0.0, 0.0)),
                prev,
                body,
            ),
        }
        .expect("valid joint");
        previous = Some(body);
    }
    if let Some(last) = previous {
        let end = planks as f32 * 0.5;
        world
            .insert_world_joint(
                hinge(Vec3::new(end, 10.0, 0.0), Vec3::new(0.25, 0.0, 0.0)),
                last,
            )
            .expect("valid joint");
    }
    world
}

/// 400 balls settled on the ground (2 s of simulation), with sleep on or off.
fn settled_pile(sleep: bool) -> World<SimpleBackend> {
    let settings = WorldSettings {
        sleep_enabled: sleep,
        ..WorldSettings::default()
    };
    let mut world = World::with_backend(settings, SimpleBackend::new()).expect("valid settings");
    let ground = world.insert_body(&BodyDesc::fixed()).expect("valid body");
    world
        .backend_mut()
        .add_half_space(ground, Vec3::Y, 0.5, 0.0);
    let mass = MassProperties::ball(1000.0, 0.25).expect("valid mass");
    for i in 0..20 {
        for k in 0..20 {
            let ball = world
                .insert_body(
                    &BodyDesc::dynamic()
                        .with_position(Vec3::new(i as f32 * 0.6, 0.3, k as f32 * 0.6))
                        .with_mass_properties(mass),
                )
                .expect("valid body");
            world.backend_mut().add_sphere(ball, 0.25, 0.5, 0.0);
        }
    }
    for _ in 0..120 {
        world.step(DT);
    }
    world
}

fn joint_scenes(c: &mut Criterion) {
    let mut group = c.benchmark_group("world_step");
    let mut world = chain(100);
    group.bench_function("rope_chain_100", |b| b.iter(|| black_box(world.step(DT))));
    let mut world = bridge(100);
    group.bench_function("hinge_bridge_100", |b| b.iter(|| black_box(world.step(DT))));
    group.finish();
}

fn sleeping(c: &mut Criterion) {
    let mut group = c.benchmark_group("settled_pile_400");
    let mut awake = settled_pile(false);
    group.bench_function("awake", |b| b.iter(|| black_box(awake.step(DT))));
    let mut asleep = settled_pile(true);
    group.bench_function("asleep", |b| b.iter(|| black_box(asleep.step(DT))));
    group.finish();
}

criterion_group!(benches, joint_scenes, sleeping);
criterion_main!(benches);
