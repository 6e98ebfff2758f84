//! The `parallel` feature gives the same bits for any number of threads: the five peer scenes of
//! docs/scenes.md stepped on pools of 1, 2, 3 and 8 threads end in the same state digest. A pool of one
//! thread runs the serial build's code (every `rebound_math::par` helper is then the plain loop the serial
//! build compiles), so equal digests also mean equal to the serial build.
//!
//! Run with `cargo test -p rebound-suite --features parallel --test thread_count` (the serial
//! `cargo test --workspace` skips it).

use rebound::math::par::rayon::{ThreadPool, ThreadPoolBuilder};
use rebound::prelude::*;
use rebound_suite::scenes::{self, DEFAULT_SCENES, SceneOptions};
use std::sync::Arc;

/// Steps per scene: the balls' lowest layers land and the pile starts to press (contacts in every colour
/// group large enough to be split among threads), the pyramid and the joints load up.
const STEPS: usize = 40;

/// The thread counts compared; 1 is the serial code.
const THREADS: [usize; 4] = [1, 2, 3, 8];

fn pool(threads: usize) -> ThreadPool {
    ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("the test machine starts threads")
}

/// The scene's digest after [`STEPS`] steps run inside `pool`, and its contact count at the end.
fn digest_on(name: &str, pool: &ThreadPool) -> (u64, usize) {
    let mut scene = scenes::build(name, SceneOptions::default())
        .expect("the scene builds")
        .expect("a peer scene");
    // Every step on the pool, however small the scene.
    scene.world_mut().set_min_work_for_threads(0);
    let mut contacts = 0;
    for _ in 0..STEPS {
        contacts = pool.install(|| scene.step()).contact_count;
    }
    (scene.world().state_digest(), contacts)
}

#[test]
fn peer_scenes_have_one_digest_for_1_2_3_and_8_threads() {
    let pools = THREADS.map(pool);
    for name in DEFAULT_SCENES {
        let (serial, contacts) = digest_on(name, &pools[0]);
        for (threads, pool) in THREADS.iter().zip(&pools).skip(1) {
            let (digest, _) = digest_on(name, pool);
            assert_eq!(
                digest, serial,
                "{name}: {threads} threads end in another state than 1 thread"
            );
        }
        if name == "balls" || name == "pyramid" {
            assert!(
                contacts > 200,
                "{name}: only {contacts} contacts were solved"
            );
        }
    }
}

/// 256 balls over the ground, touching it and each other (the ball–ground manifolds make one colour of 64
/// batches: split among threads).
fn ball_pile() -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).expect("default settings");
    world.set_min_work_for_threads(0);
    let ground = world.insert_body(BodyDesc::fixed()).expect("a fixed body");
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(50.0, 0.5, 50.0)), ground)
        .expect("a box");
    for i in 0..256_u16 {
        let (x, z, y) = (f32::from(i % 8), f32::from((i / 8) % 8), f32::from(i / 64));
        let ball = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(
                x,
                1.0 + y * 1.01,
                z + 0.1 * y,
            )))
            .expect("a ball");
        world
            .insert_collider(ColliderDesc::ball(0.5), ball)
            .expect("a ball collider");
    }
    world
}

#[test]
fn a_world_steps_on_its_own_pool_with_the_same_bits() {
    let run = |pool: Option<Arc<ThreadPool>>| {
        let mut world = ball_pile();
        world.set_thread_pool(pool);
        for _ in 0..STEPS {
            world.step(scenes::DT);
        }
        world.state_digest()
    };
    let one = run(Some(Arc::new(pool(1))));
    assert_eq!(run(Some(Arc::new(pool(3)))), one);
    let mut world = ball_pile();
    world.set_thread_count(2).expect("two threads start");
    assert!(
        world
            .thread_pool()
            .is_some_and(|p| p.current_num_threads() == 2)
    );
    let mut contacts = 0;
    for _ in 0..STEPS {
        contacts = world.step(scenes::DT).contact_count;
    }
    assert!(contacts >= 256, "only {contacts} contacts");
    assert_eq!(world.state_digest(), one);
}

#[test]
fn a_thread_count_of_zero_is_refused_and_changes_nothing() {
    let mut world = PhysicsWorld::new(WorldSettings::default()).expect("default settings");
    world.set_min_work_for_threads(0);
    let error = world.set_thread_count(0);
    assert!(
        matches!(error, Err(Error::ThreadPool { count: 0, .. })),
        "{error:?}"
    );
    assert!(world.thread_pool().is_none());
}

/// 256 balls resting on one kinematic plate that turns about +Y and has velocity components of −0: every
/// ball–plate manifold of a colour shares the plate, so several batches on several threads each add `0·λ`
/// to the plate's velocity; the plate must come out of the step with the same bits for any thread count.
fn balls_on_a_turning_plate() -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).expect("default settings");
    world.set_min_work_for_threads(0);
    let plate = world
        .insert_body(
            BodyDesc::kinematic()
                .with_linear_velocity(Vec3::new(-0.0, -0.0, -0.0))
                .with_angular_velocity(Vec3::new(-0.0, 0.2, -0.0)),
        )
        .expect("a kinematic plate");
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0)), plate)
        .expect("a box");
    for i in 0..256_u16 {
        let (x, z) = (f32::from(i % 16), f32::from(i / 16));
        let ball = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(x - 7.5, 0.99, z - 7.5)))
            .expect("a ball");
        world
            .insert_collider(ColliderDesc::ball(0.5), ball)
            .expect("a ball collider");
    }
    world
}

#[test]
fn a_kinematic_body_shared_by_batches_on_threads_keeps_the_bits_of_one_thread() {
    let run = |threads: usize| {
        let mut world = balls_on_a_turning_plate();
        world.set_thread_pool(Some(Arc::new(pool(threads))));
        let mut contacts = 0;
        for _ in 0..STEPS {
            contacts = world.step(scenes::DT).contact_count;
        }
        assert!(contacts >= 256, "only {contacts} contacts");
        world.state_digest()
    };
    let one = run(1);
    for threads in [2, 3, 8] {
        assert_eq!(run(threads), one, "{threads} threads");
    }
}

/// 256 balls over the ground as [`ball_pile`], with every pass of the substeps' team in play: every seventh
/// ball's rotations locked (the axis locks after each pass), every fifth bouncing (restitution: the scalar
/// path after the colour groups) and every third reporting contact forces (the impulse sums after each
/// substep).
fn ball_pile_of_every_pass() -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).expect("default settings");
    world.set_min_work_for_threads(0);
    let ground = world.insert_body(BodyDesc::fixed()).expect("a fixed body");
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(50.0, 0.5, 50.0)), ground)
        .expect("a box");
    for i in 0..256_u16 {
        let (x, z, y) = (f32::from(i % 8), f32::from((i / 8) % 8), f32::from(i / 64));
        let mut body = BodyDesc::dynamic().with_position(Vec3::new(x, 1.0 + y * 1.01, z + 0.1 * y));
        if i % 7 == 0 {
            body = body.with_locked_axes(LockedAxes::ALL_ROTATION);
        }
        let ball = world.insert_body(body).expect("a ball");
        let mut collider = ColliderDesc::ball(0.5);
        if i % 5 == 0 {
            collider = collider.with_restitution(0.3);
        }
        if i % 3 == 0 {
            collider = collider.with_force_event_threshold(1.0);
        }
        world
            .insert_collider(collider, ball)
            .expect("a ball collider");
    }
    world
}

#[test]
fn a_pile_with_locks_bounces_and_force_events_keeps_the_bits_of_one_thread() {
    let run = |threads: usize| {
        let mut world = ball_pile_of_every_pass();
        world.set_thread_pool(Some(Arc::new(pool(threads))));
        let (mut contacts, mut forces) = (0, 0);
        for _ in 0..STEPS {
            contacts = world.step(scenes::DT).contact_count;
            forces += world
                .events()
                .iter()
                .filter(|e| matches!(e, Event::ContactForce { .. }))
                .count();
        }
        assert!(contacts >= 256, "only {contacts} contacts");
        assert!(forces > 0, "no contact force event");
        world.state_digest()
    };
    let one = run(1);
    for threads in [2, 3, 8] {
        assert_eq!(run(threads), one, "{threads} threads");
    }
}

/// A scene below `MIN_WORK_FOR_THREADS` (the bridge: 150 bodies), whose steps run on one thread by default
/// even on a pool of two, ends in the state of every step on the pool and of one thread.
#[test]
fn a_scene_below_the_work_bound_ends_in_the_state_of_the_pool_and_of_one_thread() {
    let run = |threads: usize, min_work: usize| {
        let mut scene = scenes::build("bridge", SceneOptions::default())
            .expect("the scene builds")
            .expect("a peer scene");
        assert_eq!(
            scene.world().min_work_for_threads(),
            rebound::MIN_WORK_FOR_THREADS
        );
        scene.world_mut().set_min_work_for_threads(min_work);
        let pool = pool(threads);
        let mut report = None;
        for _ in 0..STEPS {
            report = Some(pool.install(|| scene.step()));
        }
        let report = report.expect("steps ran");
        let work = report.awake_body_count + report.contact_count;
        (scene.world().state_digest(), work)
    };
    let (gated, work) = run(2, rebound::MIN_WORK_FOR_THREADS);
    assert!(
        work < rebound::MIN_WORK_FOR_THREADS,
        "the bridge moved {work} bodies and manifolds: not a small scene"
    );
    assert_eq!(run(2, 0).0, gated, "on the pool the bridge ends elsewhere");
    assert_eq!(
        run(1, 0).0,
        gated,
        "on one thread the bridge ends elsewhere"
    );
}
