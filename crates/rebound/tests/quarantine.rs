//! The quarantine: one body with a finite but extreme state (a velocity of `f32::MAX`, an angular velocity
//! of 10²⁰, a mass of `f32::MAX`, a kinematic target 10³⁵ m away, a motor at `f32::MAX`, an explicit spring
//! past its stability limit) is taken out of the step with an event and a report entry, and every other
//! body moves bit for bit as in the same scene without it. Nothing non-finite is ever stored: bodies,
//! manifold impulses, joint states, and the JSON snapshot holds no `null`.

#![allow(
    clippy::unwrap_used,
    reason = "test scenes are built from known-good values; a failed setup fails the test"
)]

mod support;

use rebound::JointState;
use rebound::prelude::*;
use rebound::{MIN_STEP_DT, QuarantineReason, StepSkipped};
use support::{assert_finite, ball, fixed_box, quarantine_events};

const DT: f32 = 1.0 / 60.0;

/// A scene every case shares: a ground, a stack of three boxes, a row of balls, a ball on a rope, a
/// kinematic paddle sweeping the floor — ten moving bodies meeting contacts, a joint and a kinematic body.
fn base_scene() -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    fixed_box(
        &mut world,
        Vec3::new(0.0, -0.5, 0.0),
        Vec3::new(40.0, 0.5, 40.0),
    );
    for i in 0..3 {
        let b = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(
                0.0,
                0.5 + 1.01 * i as f32,
                0.0,
            )))
            .unwrap();
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)), b)
            .unwrap();
    }
    for i in 0..5 {
        let position = Vec3::new(3.0 + 0.9 * i as f32, 0.4 + 0.3 * i as f32, 0.0);
        ball(
            &mut world,
            position,
            0.4,
            Vec3::new(-0.5, 0.0, 0.2),
            Vec3::ZERO,
        );
    }
    let swing = ball(
        &mut world,
        Vec3::new(-3.0, 3.0, 0.0),
        0.3,
        Vec3::ZERO,
        Vec3::ZERO,
    );
    world
        .insert_world_joint(
            Joint::new(Rope::new(2.0).unwrap())
                .with_local_anchors(Vec3::new(-4.5, 4.0, 0.0), Vec3::ZERO)
                .unwrap(),
            swing,
        )
        .unwrap();
    let paddle = world
        .insert_body(BodyDesc::kinematic().with_position(Vec3::new(-1.6, 0.3, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(0.1, 0.3, 1.0)), paddle)
        .unwrap();
    world
}

/// Steps the paddle of [`base_scene`] by a kinematic target each step (it sweeps into the stack).
fn drive(world: &mut PhysicsWorld, paddle: BodyHandle, step: u32) {
    let x = -1.6 + 0.01 * step as f32;
    world
        .set_kinematic_target(paddle, Pose::from_position(Vec3::new(x, 0.3, 0.0)))
        .unwrap();
}

/// FNV-1a over the bits of every body's pose and velocities except `skip`, with its slot index.
fn digest_without(world: &PhysicsWorld, skip: Option<BodyHandle>) -> u64 {
    let mut hash = 0xcbf2_9ce4_8422_2325_u64;
    let mut write = |x: u32| {
        for byte in x.to_le_bytes() {
            hash ^= u64::from(byte);
            hash = hash.wrapping_mul(0x0000_0100_0000_01b3);
        }
    };
    for (handle, body) in world.bodies().iter() {
        if Some(handle) == skip {
            continue;
        }
        write(handle.into_raw_parts().0);
        let pose = body.pose();
        for v in [
            pose.position,
            body.linear_velocity(),
            body.angular_velocity(),
        ] {
            for x in v.to_array() {
                write(x.to_bits());
            }
        }
        for x in pose.rotation.to_array() {
            write(x.to_bits());
        }
    }
    hash
}

/// How a case adds its bad body (last, so the other bodies keep their handles) and what happens to it.
struct Case {
    /// Adds the bad body (and whatever it needs) to the scene; returns its handle.
    add: fn(&mut PhysicsWorld) -> BodyHandle,
    /// Run for this many steps.
    steps: u32,
    /// The reasons the quarantine may give.
    reasons: &'static [QuarantineReason],
}

/// Runs the scene with and without the case's body and checks: the body is quarantined once (event and
/// report), every other body ends bit-identical to the scene without it at every step, the bad body ends at
/// rest and finite, and nothing non-finite is stored.
fn check(case: &Case) {
    let mut good = base_scene();
    let mut bad = base_scene();
    // Handles carry a per-world base: each world's own paddle.
    let paddle = |w: &PhysicsWorld| w.bodies().iter().last().unwrap().0;
    let (paddle_good, paddle_bad) = (paddle(&good), paddle(&bad));
    let body = (case.add)(&mut bad);
    let mut quarantined_at = None;
    for step in 0..case.steps {
        drive(&mut good, paddle_good, step);
        drive(&mut bad, paddle_bad, step);
        good.step(DT);
        let report = bad.step(DT);
        let events = quarantine_events(&bad);
        assert_eq!(report.quarantined_body_count, events.len());
        if let Some(&(b, reason)) = events.first() {
            assert_eq!(events.len(), 1, "one body quarantined, once: {events:?}");
            assert_eq!(b, body);
            assert!(case.reasons.contains(&reason), "{reason:?}");
            assert!(quarantined_at.is_none(), "quarantined twice");
            quarantined_at = Some(step);
        }
        assert_eq!(
            digest_without(&good, None),
            digest_without(&bad, Some(body)),
            "the other bodies differ at step {step}"
        );
        assert_finite(&bad, &step);
    }
    assert!(quarantined_at.is_some(), "never quarantined");
    assert_eq!(bad.is_quarantined(body), Some(true));
    // Its joints' impulses were cleared, and stay so: the joint is in no step.
    for (h, _) in bad.world().joints() {
        let (a, b) = bad.joint_bodies(h).unwrap();
        if b == body || a == Some(body) {
            assert_eq!(bad.joint_state(h), Some(&JointState::default()));
        }
    }
    let b = bad.body(body).unwrap();
    assert_eq!(b.linear_velocity(), Vec3::ZERO);
    assert_eq!(b.angular_velocity(), Vec3::ZERO);
    // What the snapshot holds of bodies, contacts and joint states is finite: it goes through JSON and back
    // unchanged (a non-finite number would be written as `null` and not read back). The joints'
    // descriptions, whose default break limits are ∞, are another matter.
    let states: Vec<JointState> = bad
        .world()
        .joints()
        .map(|(h, _)| *bad.joint_state(h).unwrap())
        .collect();
    let bodies: rebound::BodySet =
        serde_json::from_str(&serde_json::to_string(bad.bodies()).unwrap()).unwrap();
    assert_eq!(&bodies, bad.bodies());
    let contacts: Vec<ContactManifold> =
        serde_json::from_str(&serde_json::to_string(bad.contacts()).unwrap()).unwrap();
    assert_eq!(contacts, bad.contacts());
    let back: Vec<JointState> =
        serde_json::from_str(&serde_json::to_string(&states).unwrap()).unwrap();
    assert_eq!(back, states);
}

#[test]
fn a_body_at_the_largest_speed_is_quarantined_and_the_rest_moves_as_without_it() {
    check(&Case {
        // Beside the stack, touching it.
        add: |w| {
            ball(
                w,
                Vec3::new(0.0, 0.4, 0.9),
                0.4,
                Vec3::new(f32::MAX, 0.0, 0.0),
                Vec3::ZERO,
            )
        },
        steps: 60,
        reasons: &[QuarantineReason::Speed],
    });
}

#[test]
fn a_body_spinning_at_1e20_rad_s_is_quarantined_and_the_rest_moves_as_without_it() {
    check(&Case {
        add: |w| {
            ball(
                w,
                Vec3::new(3.9, 1.5, 0.0),
                0.4,
                Vec3::ZERO,
                Vec3::new(0.0, 1.0e20, 0.0),
            )
        },
        steps: 60,
        reasons: &[QuarantineReason::AngularSpeed],
    });
}

#[test]
fn a_kinematic_target_1e35_m_away_quarantines_the_kinematic_body_and_freezes_nothing() {
    check(&Case {
        // Touching the stack; its target makes it move 6·10³⁶ m/s.
        add: |w| {
            let b = w
                .insert_body(BodyDesc::kinematic().with_position(Vec3::new(0.0, 0.5, 1.0)))
                .unwrap();
            w.insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)), b)
                .unwrap();
            w.set_kinematic_target(b, Pose::from_position(Vec3::new(1.0e35, 0.5, 1.0)))
                .unwrap();
            b
        },
        // The scene stayed frozen for 300 steps.
        steps: 300,
        reasons: &[QuarantineReason::Speed],
    });
}

#[test]
fn a_body_of_mass_f32_max_landing_on_the_ground_is_quarantined_and_the_rest_moves_as_without_it() {
    check(&Case {
        // Dropped from 1 m: at impact its contact's impulse, effective mass (3·10³⁸ kg) times closing
        // speed, overflows.
        add: |w| {
            let b = w
                .insert_body(BodyDesc::dynamic().with_position(Vec3::new(8.0, 1.5, 4.0)))
                .unwrap();
            // No density: the body's own mass properties count.
            w.insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)).with_density(0.0), b)
                .unwrap();
            let heavy = MassProperties::new(f32::MAX, Vec3::ZERO, Vec3::splat(f32::MAX)).unwrap();
            w.set_body_mass_properties(b, heavy).unwrap();
            b
        },
        steps: 60,
        reasons: &[QuarantineReason::NotFinite, QuarantineReason::Speed],
    });
}

#[test]
fn a_hinge_motor_at_f32_max_quarantines_its_body_and_the_rest_moves_as_without_it() {
    check(&Case {
        add: |w| {
            let b = w
                .insert_body(BodyDesc::dynamic().with_position(Vec3::new(8.0, 3.0, -5.0)))
                .unwrap();
            w.insert_collider(ColliderDesc::cuboid(Vec3::new(0.5, 0.1, 0.1)), b)
                .unwrap();
            let mut hinge = HingeJoint::new();
            hinge.set_motor(Some(Motor::new(f32::MAX, f32::MAX).unwrap()));
            let joint = Joint::new(hinge)
                .with_local_anchors(Vec3::new(8.0, 3.0, -5.0), Vec3::ZERO)
                .unwrap();
            w.insert_world_joint(joint, b).unwrap();
            b
        },
        steps: 60,
        reasons: &[
            QuarantineReason::NotFinite,
            QuarantineReason::AngularSpeed,
            QuarantineReason::Speed,
        ],
    });
}

#[test]
fn an_explicit_spring_past_its_stability_limit_quarantines_its_body_and_the_rest_moves_as_without_it()
 {
    check(&Case {
        // h·√(k/m) = (1/240 s)·√(10⁹ N/m / 0.27 kg) ≈ 250, far past the explicit limit of 2.
        add: |w| {
            let b = ball(w, Vec3::new(10.0, 3.0, 5.0), 0.4, Vec3::ZERO, Vec3::ZERO);
            let spring = Spring::new(1.0, SpringModel::force(1.0e9, 0.0).unwrap()).unwrap();
            let joint = Joint::new(spring)
                .with_local_anchors(Vec3::new(10.0, 4.5, 5.0), Vec3::ZERO)
                .unwrap();
            w.insert_world_joint(joint, b).unwrap();
            b
        },
        steps: 60,
        reasons: &[
            QuarantineReason::NotFinite,
            QuarantineReason::Speed,
            QuarantineReason::AngularSpeed,
        ],
    });
}

#[test]
fn a_step_of_1e_38_s_is_skipped_and_changes_nothing() {
    let mut world = base_scene();
    for _ in 0..10 {
        world.step(DT);
    }
    let before = world.state_digest();
    let report = world.step(1.0e-38);
    assert_eq!(report.skipped, Some(StepSkipped::DtTooSmall(1.0e-38)));
    assert_eq!(world.state_digest(), before);
    assert_finite(&world, &"the step");
    // The shortest step that still runs moves nothing visibly and poisons nothing.
    let report = world.step(MIN_STEP_DT);
    assert_eq!(report.skipped, None);
    assert_eq!(report.quarantined_body_count, 0);
    assert_finite(&world, &"the step");
}

#[test]
fn a_released_body_steps_again_from_rest() {
    let mut world = base_scene();
    let b = ball(
        &mut world,
        Vec3::new(12.0, 5.0, 0.0),
        0.4,
        Vec3::new(0.0, f32::MAX, 0.0),
        Vec3::ZERO,
    );
    world.step(DT);
    assert_eq!(world.is_quarantined(b), Some(true));
    let at = world.body(b).unwrap().position();
    world.step(DT);
    assert_eq!(
        world.body(b).unwrap().position(),
        at,
        "a quarantined body does not move"
    );
    world.release_quarantine(b).unwrap();
    world.step(DT);
    // Free fall from rest for one step: v = g·dt (symplectic Euler over the substeps).
    let v = world.body(b).unwrap().linear_velocity();
    assert!((v.y + 9.81 * DT).abs() < 1.0e-5, "{v}");
    assert_eq!(world.is_quarantined(b), Some(false));
}

#[test]
fn a_box_resting_on_a_body_driven_by_a_motor_at_f32_max_is_not_quarantined_with_it() {
    // The plank the motor drives poisons the box on it within the pass (their contact's impulse is not
    // finite); the quarantine lets each suspect back in turn, so only the plank is taken out and the box
    // falls as if the plank had never been there.
    let resting = |w: &mut PhysicsWorld| {
        let b = w
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(8.3, 3.3, -5.0)))
            .unwrap();
        w.insert_collider(ColliderDesc::cuboid(Vec3::splat(0.2)), b)
            .unwrap();
        b
    };
    let mut good = base_scene();
    let mut bad = base_scene();
    resting(&mut good);
    let on_plank = resting(&mut bad);
    let plank = bad
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(8.0, 3.0, -5.0)))
        .unwrap();
    bad.insert_collider(ColliderDesc::cuboid(Vec3::new(0.5, 0.1, 0.1)), plank)
        .unwrap();
    let mut hinge = HingeJoint::new();
    hinge.set_motor(Some(Motor::new(f32::MAX, f32::MAX).unwrap()));
    let joint = Joint::new(hinge)
        .with_local_anchors(Vec3::new(8.0, 3.0, -5.0), Vec3::ZERO)
        .unwrap();
    bad.insert_world_joint(joint, plank).unwrap();
    // The box touches the plank from the first step.
    bad.step(DT);
    good.step(DT);
    assert!(
        bad.events()
            .iter()
            .any(|e| matches!(*e, Event::BodyQuarantined { body, .. } if body == plank))
    );
    let mut quarantined = Vec::new();
    for step in 0..60 {
        good.step(DT);
        bad.step(DT);
        quarantined.extend(quarantine_events(&bad));
        assert_eq!(
            digest_without(&good, None),
            digest_without(&bad, Some(plank))
        );
        assert_finite(&bad, &step);
    }
    assert!(quarantined.is_empty(), "{quarantined:?}");
    assert_eq!(bad.is_quarantined(on_plank), Some(false));
    assert!(
        bad.body(on_plank).unwrap().position().y < 2.0,
        "the box fell"
    );
}

#[test]
fn a_quarantine_leaves_no_non_finite_joint_rows_in_the_snapshot() {
    // Two boxes on a hinge, the first also on an explicit spring of 10³⁰ N/m to a third: the spring's pass
    // drives the boxes to non-finite values, and the hinge's rows built in it (kept for the next step, and in
    // the snapshot) held them, so that the world's own snapshot held a NaN and was refused on restore.
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let boxes: Vec<BodyHandle> = (0..3)
        .map(|i| {
            let b = world
                .insert_body(BodyDesc::dynamic().with_position(Vec3::new(
                    0.3 * i as f32,
                    0.9 * i as f32,
                    0.0,
                )))
                .unwrap();
            world
                .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.4)), b)
                .unwrap();
            b
        })
        .collect();
    world
        .insert_joint(Joint::new(HingeJoint::new()), boxes[0], boxes[1])
        .unwrap();
    let spring = Spring::new(1.0, SpringModel::force(1.0e30, 0.0).unwrap()).unwrap();
    world
        .insert_joint(Joint::new(spring), boxes[0], boxes[2])
        .unwrap();
    let report = world.step(DT);
    assert!(report.quarantined_body_count > 0, "{report:?}");
    assert_finite(&world, &"the step");
    let snapshot = world.snapshot();
    // A snapshot unequal to its copy holds a NaN.
    assert!(snapshot == snapshot.clone(), "the snapshot holds a NaN");
    let json = serde_json::to_string(&snapshot).unwrap();
    let loaded: PhysicsSnapshot = serde_json::from_str(&json).unwrap();
    let mut restored = PhysicsWorld::new(WorldSettings::default()).unwrap();
    restored.restore(&loaded).unwrap();
    world.restore(&snapshot).unwrap();
    for step in 0..30 {
        world.step(DT);
        restored.step(DT);
        assert_eq!(world.state_digest(), restored.state_digest(), "step {step}");
        assert_finite(&world, &"the step");
    }
}
