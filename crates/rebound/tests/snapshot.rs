//! Snapshots include the colliders: a world restored from a serialised snapshot (into a fresh world, or in
//! place after diverging) steps bit-identically to the one that never stopped — digests and events equal at
//! every step for 120 steps — although its narrow-phase pair cache and BVH start empty.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

mod support;

use rebound::prelude::*;
use support::{ball, fixed_box};

const DT: f32 = 1.0 / 60.0;

/// A break force no joint here reaches. The default, +∞, is written by serde_json as `null` and cannot be
/// read back (a limit of JSON, reported to the constraints crate), so the JSON round trips use this.
const BREAKS_NEVER: f32 = 1.0e30;

/// Every shape kind, materials, a sensor, a kinematic body, joints (one without contacts) and a tumbling
/// pile, so that contacts, warm starting, sensors, sleep and the pair cache all carry state.
fn scene() -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0)).with_friction(0.7),
            ground,
        )
        .unwrap();
    // Terrain: a mesh ramp and a bumpy height field.
    let terrain = world.insert_body(BodyDesc::fixed()).unwrap();
    world
        .insert_collider(
            ColliderDesc::trimesh(
                vec![
                    Vec3::new(4.0, 0.0, -2.0),
                    Vec3::new(8.0, 1.5, -2.0),
                    Vec3::new(8.0, 1.5, 2.0),
                    Vec3::new(4.0, 0.0, 2.0),
                ],
                vec![[0, 2, 1], [0, 3, 2]],
            ),
            terrain,
        )
        .unwrap();
    let heights: Vec<f32> = (0..25).map(|i| ((i * 7) % 5) as f32 * 0.08).collect();
    world
        .insert_collider(
            ColliderDesc::heightfield(5, 5, heights, Vec3::new(6.0, 1.0, 6.0))
                .with_position(Vec3::new(-7.0, 0.01, 0.0)),
            terrain,
        )
        .unwrap();
    // A trigger.
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::new(1.5, 1.0, 0.5))
                .with_sensor(true)
                .with_position(Vec3::new(0.0, 1.0, -1.5)),
            terrain,
        )
        .unwrap();
    let hull: Vec<Vec3> = (0..10)
        .map(|i| {
            let a = i as f32 * 1.3;
            Vec3::new(0.35 * a.cos(), 0.3 * (a * 0.7).sin(), 0.35 * a.sin())
        })
        .collect();
    let shapes = [
        ColliderDesc::ball(0.3).with_restitution(0.4),
        ColliderDesc::cuboid(Vec3::new(0.3, 0.25, 0.35)),
        ColliderDesc::capsule(0.2, 0.3).with_rolling_friction(0.01),
        ColliderDesc::cylinder(0.3, 0.2),
        ColliderDesc::cone(0.3, 0.3),
        ColliderDesc::convex_hull(hull),
        ColliderDesc::compound(vec![
            (
                Pose::from_position(Vec3::new(-0.3, 0.0, 0.0)),
                ColliderShape::Ball { radius: 0.2 },
            ),
            (
                Pose::new(Vec3::new(0.3, 0.0, 0.0), Quat::from_rotation_z(0.3)),
                ColliderShape::Cuboid {
                    half_extents: Vec3::splat(0.2),
                },
            ),
        ]),
    ];
    for (i, shape) in shapes.iter().enumerate() {
        for layer in 0..3 {
            let f = (i * 3 + layer) as f32;
            let position = Vec3::new(
                -9.0 + (i as f32) * 2.6 + (f * 0.37).sin() * 0.3,
                1.0 + layer as f32 * 0.9,
                (f * 0.71).cos() * 1.5,
            );
            let body = world
                .insert_body(
                    BodyDesc::dynamic()
                        .with_position(position)
                        .with_rotation(
                            Quat::from_rotation_y(f * 0.4) * Quat::from_rotation_x(f * 0.2),
                        )
                        .with_linear_velocity(Vec3::new((f * 1.3).sin(), 0.0, 0.5)),
                )
                .unwrap();
            world
                .insert_collider(shape.clone().with_density(1.0 + f * 0.1), body)
                .unwrap();
        }
    }
    // A chain of two boxes on a hinge whose contacts are disabled, hung from a world joint.
    let a = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(2.0, 3.0, -4.0)))
        .unwrap();
    let b = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(2.9, 3.0, -4.0)))
        .unwrap();
    for body in [a, b] {
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::new(0.5, 0.1, 0.5)), body)
            .unwrap();
    }
    let hinge = world
        .insert_joint(
            Joint::new(HingeJoint::new())
                .with_local_anchors(Vec3::new(0.45, 0.0, 0.0), Vec3::new(-0.45, 0.0, 0.0))
                .unwrap()
                .with_local_axes(Vec3::Z, Vec3::Z)
                .unwrap()
                .with_break_force(BREAKS_NEVER)
                .unwrap()
                .with_break_torque(BREAKS_NEVER)
                .unwrap(),
            a,
            b,
        )
        .unwrap();
    world.set_joint_contacts_enabled(hinge, false).unwrap();
    world
        .insert_world_joint(
            Joint::new(Rope::new(1.0).unwrap())
                .with_local_anchors(Vec3::new(1.5, 4.0, -4.0), Vec3::new(-0.5, 0.0, 0.0))
                .unwrap()
                .with_break_force(BREAKS_NEVER)
                .unwrap()
                .with_break_torque(BREAKS_NEVER)
                .unwrap(),
            a,
        )
        .unwrap();
    // A kinematic paddle sweeping through the pile.
    let paddle = world
        .insert_body(
            BodyDesc::kinematic()
                .with_position(Vec3::new(0.0, 0.5, -3.0))
                .with_linear_velocity(Vec3::new(0.0, 0.0, 1.0)),
        )
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(6.0, 0.3, 0.1)), paddle)
        .unwrap();
    world
}

fn json(snapshot: &PhysicsSnapshot) -> String {
    serde_json::to_string(snapshot).unwrap()
}

#[test]
fn a_restored_world_steps_bit_identically_to_the_original() {
    let mut original = scene();
    for _ in 0..40 {
        original.step(DT);
    }
    let snapshot = original.snapshot();
    let text = json(&snapshot);
    let loaded: PhysicsSnapshot = serde_json::from_str(&text).unwrap();
    assert_eq!(loaded, snapshot);
    assert_eq!(json(&loaded), text, "re-serialising gives the same bytes");
    assert_eq!(loaded.collider_count(), original.colliders().len());

    // A fresh world (its own handle bases, an empty pair cache and BVH) restored from the text.
    let mut restored = PhysicsWorld::new(WorldSettings::default()).unwrap();
    restored.restore(&loaded).unwrap();
    assert_eq!(restored.state_digest(), original.state_digest());
    assert_eq!(restored.world().backend().cached_pair_count(), 0);
    let mut contact_steps = 0;
    let mut sensor_events = 0;
    // Recycled manifolds (a box pair that barely moved keeps its basis): restored from the snapshot, they must
    // recycle as in the original.
    let mut recycled = 0;
    // The original's tree keeps leaves that still hold their fat boxes (with slack for slow bodies), the
    // restored one starts from tight boxes: the candidate pairs may differ, never the contacts.
    let mut candidates_differ = 0;
    for step in 0..120 {
        let bases: Vec<_> = original
            .contacts()
            .iter()
            .filter_map(|m| m.basis.map(|b| (m.order_key(), b)))
            .collect();
        original.step(DT);
        restored.step(DT);
        recycled += original
            .contacts()
            .iter()
            .filter(|m| m.basis.is_some_and(|b| bases.contains(&(m.order_key(), b))))
            .count();
        assert_eq!(
            restored.state_digest(),
            original.state_digest(),
            "diverged {} steps after the restore",
            step + 1
        );
        assert_eq!(
            restored.events(),
            original.events(),
            "events differ at step {}",
            step + 1
        );
        assert_eq!(restored.contacts(), original.contacts());
        candidates_differ += usize::from(
            restored.world().backend().candidate_pairs()
                != original.world().backend().candidate_pairs(),
        );
        contact_steps += usize::from(!original.contacts().is_empty());
        sensor_events += original
            .events()
            .iter()
            .filter(|e| matches!(e, Event::SensorEntered { .. } | Event::SensorExited { .. }))
            .count();
    }
    println!(
        "120 steps in lockstep; {} manifolds at the end, {contact_steps} steps with contacts, {sensor_events} sensor events, {candidates_differ} steps with other candidate pairs",
        original.contacts().len()
    );
    assert!(
        original.contacts().len() > 10,
        "the scene keeps many contacts"
    );
    assert!(sensor_events > 0);
    assert!(recycled > 0, "the scene recycles box contacts");
    assert!(
        candidates_differ > 0,
        "the kept leaves give the original other candidate pairs than the restored world"
    );
    assert_eq!(json(&restored.snapshot()), json(&original.snapshot()));
}

#[test]
fn rolling_back_in_place_replays_the_same_bits() {
    let mut world = scene();
    for _ in 0..20 {
        world.step(DT);
    }
    let snapshot = world.snapshot();
    let mut first_run = Vec::new();
    for _ in 0..60 {
        world.step(DT);
        first_run.push(world.state_digest());
    }
    // Diverge: remove a collider, add a body and collider, push something.
    let some_collider = world.colliders().iter().nth(12).map(|(h, _)| h).unwrap();
    world.remove_collider(some_collider).unwrap();
    let extra = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 5.0, 0.0)))
        .unwrap();
    let extra_collider = world
        .insert_collider(ColliderDesc::ball(0.5), extra)
        .unwrap();
    world.step(DT);

    world.restore(&snapshot).unwrap();
    assert!(
        world.collider(some_collider).is_some(),
        "the removed collider is back"
    );
    assert!(world.body(extra).is_none() && world.collider(extra_collider).is_none());
    for (step, want) in first_run.iter().enumerate() {
        world.step(DT);
        assert_eq!(
            world.state_digest(),
            *want,
            "replay differs at step {}",
            step + 1
        );
    }
}

#[test]
fn bad_snapshots_are_refused_and_change_nothing() {
    let mut world = scene();
    world.step(DT);
    let digest = world.state_digest();
    let snapshot = world.snapshot();
    let mut value: serde_json::Value = serde_json::to_value(&snapshot).unwrap();
    value["version"] = serde_json::json!(99);
    let wrong_version: PhysicsSnapshot = serde_json::from_value(value.clone()).unwrap();
    assert!(matches!(
        world.restore(&wrong_version),
        Err(Error::BadSnapshot(_))
    ));
    // A collider with a negative radius.
    value["version"] = serde_json::json!(1);
    let text =
        serde_json::to_string(&value)
            .unwrap()
            .replacen("\"radius\":0.3", "\"radius\":-0.3", 1);
    let bad_collider: PhysicsSnapshot = serde_json::from_str(&text).unwrap();
    let error = world.restore(&bad_collider).unwrap_err();
    assert!(error.to_string().contains("radius"), "{error}");
    assert_eq!(world.state_digest(), digest);
    world.step(DT);
}

#[test]
fn two_worlds_built_by_the_same_calls_step_identically() {
    // Each world numbers its handles' generations from its own base; nothing may depend on it.
    let mut first = scene();
    let _unrelated = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let mut second = scene();
    for step in 0..120 {
        first.step(DT);
        second.step(DT);
        assert_eq!(
            first.state_digest(),
            second.state_digest(),
            "differ at step {}",
            step + 1
        );
    }
}

/// The scene with a snapshot of it, stepped 30 times while checking that `revision` does not move, and a
/// check that tells whether `revision` moved since it was last called.
fn stepped_scene(
    revision: fn(&PhysicsWorld) -> u64,
) -> (
    PhysicsWorld,
    PhysicsSnapshot,
    impl FnMut(&PhysicsWorld) -> bool,
) {
    let mut world = scene();
    let snapshot = world.snapshot();
    let mut last = revision(&world);
    let mut moved = move |world: &PhysicsWorld| {
        let now = revision(world);
        let changed = now != last;
        last = now;
        changed
    };
    for _ in 0..30 {
        world.step(DT);
        assert!(!moved(&world), "a step changed the revision");
    }
    (world, snapshot, moved)
}

/// The collider revision, by which an observer notices edits without comparing descriptions, moves on with
/// every insertion, edit, removal and restore, and not with a step.
#[test]
fn the_collider_revision_moves_with_every_edit_and_restore_but_not_a_step() {
    let (mut world, snapshot, mut moved) = stepped_scene(|w| w.colliders().revision());
    let body = world.insert_body(BodyDesc::dynamic()).unwrap();
    assert!(!moved(&world), "a body without colliders changed it");
    let collider = world
        .insert_collider(ColliderDesc::ball(0.5), body)
        .unwrap();
    assert!(moved(&world), "insertion");
    world.set_collider_friction(collider, 0.2).unwrap();
    assert!(moved(&world), "edit");
    world.remove_collider(collider).unwrap();
    assert!(moved(&world), "removal");
    world.restore(&snapshot).unwrap();
    assert!(moved(&world), "restore");
}

/// The body revision, by which an observer notices body edits (mass properties, gravity scale) without
/// comparing bodies, moves on with every insertion, mutable access, removal and restore, and not with a
/// step; a body setter reached through the facade moves it too.
#[test]
fn the_body_revision_moves_with_every_edit_and_restore_but_not_a_step() {
    let (mut world, snapshot, mut moved) = stepped_scene(|w| w.bodies().revision());
    let body = world.insert_body(BodyDesc::dynamic()).unwrap();
    assert!(moved(&world), "insertion");
    world
        .insert_collider(ColliderDesc::ball(0.5), body)
        .unwrap();
    assert!(
        moved(&world),
        "a collider with a density changed the body's mass"
    );
    world
        .body_mut(body)
        .unwrap()
        .set_gravity_scale(0.5)
        .unwrap();
    assert!(moved(&world), "gravity scale");
    let mass = *world.body(body).unwrap().mass_properties();
    world.set_body_mass_properties(body, mass).unwrap();
    assert!(moved(&world), "mass properties");
    assert!(world.body_mut(body).is_some());
    assert!(moved(&world), "a mutable access counts as an edit");
    world.remove_body(body).unwrap();
    assert!(moved(&world), "removal");
    assert!(world.body_mut(body).is_none());
    assert!(!moved(&world), "a stale handle edits nothing");
    world.restore(&snapshot).unwrap();
    assert!(moved(&world), "restore");
}

/// A ball dropped 0.3 m onto a ground, stepped until it sleeps.
fn sleeping_ball() -> (PhysicsWorld, BodyHandle) {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    fixed_box(
        &mut world,
        Vec3::new(0.0, -0.5, 0.0),
        Vec3::new(10.0, 0.5, 10.0),
    );
    let ball = ball(
        &mut world,
        Vec3::new(0.0, 0.8, 0.0),
        0.5,
        Vec3::ZERO,
        Vec3::ZERO,
    );
    for _ in 0..600 {
        world.step(DT);
        if world.is_sleeping(ball) == Some(true) {
            return (world, ball);
        }
    }
    panic!("the ball never slept");
}

#[test]
fn a_restored_world_wakes_the_same_bodies_on_an_edit_as_the_original() {
    // The original's query tree holds the fattened box the ball's leaf got while it moved; the restored
    // world's holds the tight one. A collider inserted beside the sleeping ball, or edited, wakes what its box
    // (grown by the speculative margin, 0.02 m) overlaps: for every gap, both worlds must wake the same
    // bodies and step on alike.
    let mut woke = 0;
    for i in 0..40 {
        let gap = 0.0025 * i as f32;
        let (mut original, ball) = sleeping_ball();
        let mut restored = PhysicsWorld::new(WorldSettings::default()).unwrap();
        restored.restore(&original.snapshot()).unwrap();
        for world in [&mut original, &mut restored] {
            let wall = fixed_box(
                world,
                Vec3::new(0.6 + gap, 0.5, 0.0),
                Vec3::new(0.1, 0.5, 0.5),
            );
            let collider = world.colliders().of_body(wall)[0];
            world.step(DT);
            world.set_collider_friction(collider, 0.9).unwrap();
        }
        assert_eq!(
            original.is_sleeping(ball),
            restored.is_sleeping(ball),
            "gap {gap} m"
        );
        woke += usize::from(original.is_sleeping(ball) == Some(false));
        for step in 0..30 {
            original.step(DT);
            restored.step(DT);
            assert_eq!(
                original.state_digest(),
                restored.state_digest(),
                "gap {gap} m, step {step}"
            );
        }
    }
    // The near walls woke the ball, the far ones did not.
    assert!(woke > 0 && woke < 40, "{woke} of 40 woke the ball");
}
