//! Snapshots: restore into a fresh world and step on in lockstep with the original (digests equal at every
//! step, serialised snapshots byte-identical); roll back in place after diverging (impulse, insert, remove).

#![cfg(feature = "serde")]
#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound_dynamics::{BodyDesc, MassProperties};
use rebound_math::Vec3;
use rebound_world::testing::SimpleBackend;
use rebound_world::{BodyHandle, World, WorldSettings, WorldSnapshot};

const DT: f32 = 1.0 / 60.0;

/// A pile of 12 balls dropping onto the ground with some sideways velocity, so contacts, friction, warm
/// starting and (later) sleep all carry state.
fn scene() -> (World<SimpleBackend>, Vec<BodyHandle>) {
    let mut world = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let ground = world.insert_body(&BodyDesc::fixed()).unwrap();
    world
        .backend_mut()
        .add_half_space(ground, Vec3::Y, 0.6, 0.0);
    let mut balls = Vec::new();
    for i in 0..12 {
        let f = i as f32;
        let ball = world
            .insert_body(
                &BodyDesc::dynamic()
                    .with_position(Vec3::new(
                        (f * 0.37).sin() * 0.6,
                        0.3 + f * 0.55,
                        (f * 0.71).cos() * 0.6,
                    ))
                    .with_linear_velocity(Vec3::new(0.3 * (f * 1.3).sin(), 0.0, 0.2))
                    .with_mass_properties(MassProperties::ball(500.0 + 50.0 * f, 0.25).unwrap()),
            )
            .unwrap();
        world.backend_mut().add_sphere(ball, 0.25, 0.5, 0.2);
        balls.push(ball);
    }
    // An unbreakable rope between two balls: its +∞ break limits must survive JSON.
    let rope = rebound_constraints::Joint::new(rebound_constraints::Rope::new(1.0).unwrap());
    world.insert_joint(rope, balls[0], balls[1]).unwrap();
    (world, balls)
}

/// A deck of six hinged balls hung between two fixed anchors 2.9 m apart (3 m of deck: it sags), with a
/// ball dropped onto it: a path the joint solver solves directly, whose hinge rows it carries from each step
/// into the next — state a snapshot must hold.
fn deck() -> World<SimpleBackend> {
    let mut world = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let hinge = |anchor_a: Vec3, anchor_b: Vec3| {
        rebound_constraints::Joint::new(rebound_constraints::HingeJoint::new())
            .with_local_anchors(anchor_a, anchor_b)
            .unwrap()
            .with_local_axes(Vec3::Z, Vec3::Z)
            .unwrap()
    };
    let left = world
        .insert_body(&BodyDesc::fixed().with_position(Vec3::new(-1.45, 2.0, 0.0)))
        .unwrap();
    let right = world
        .insert_body(&BodyDesc::fixed().with_position(Vec3::new(1.45, 2.0, 0.0)))
        .unwrap();
    let mass = MassProperties::ball(800.0, 0.2).unwrap();
    let mut previous = (left, Vec3::ZERO);
    for i in 0..6 {
        let x = -1.45 + 0.25 + 0.5 * i as f32;
        let link = world
            .insert_body(
                &BodyDesc::dynamic()
                    .with_position(Vec3::new(x, 2.0, 0.0))
                    .with_mass_properties(mass),
            )
            .unwrap();
        world.backend_mut().add_sphere(link, 0.2, 0.5, 0.0);
        let joint = hinge(previous.1, Vec3::new(-0.25, 0.0, 0.0));
        world.insert_joint(joint, previous.0, link).unwrap();
        previous = (link, Vec3::new(0.25, 0.0, 0.0));
    }
    world
        .insert_joint(hinge(previous.1, Vec3::ZERO), previous.0, right)
        .unwrap();
    let ball = world
        .insert_body(
            &BodyDesc::dynamic()
                .with_position(Vec3::new(0.3, 3.0, 0.05))
                .with_mass_properties(MassProperties::ball(500.0, 0.15).unwrap()),
        )
        .unwrap();
    world.backend_mut().add_sphere(ball, 0.15, 0.5, 0.0);
    world
}

/// Steps both worlds `steps` times, asserting equal digests after every step.
fn step_in_lockstep(
    original: &mut World<SimpleBackend>,
    restored: &mut World<SimpleBackend>,
    steps: usize,
) {
    for step in 0..steps {
        original.step(DT);
        restored.step(DT);
        assert_eq!(
            restored.state_digest(),
            original.state_digest(),
            "diverged {} steps after the restore",
            step + 1
        );
    }
}

fn to_json(snapshot: &WorldSnapshot) -> String {
    serde_json::to_string(snapshot).unwrap()
}

#[test]
fn a_restored_world_steps_in_lockstep_with_the_original() {
    let (mut original, _) = scene();
    for _ in 0..20 {
        original.step(DT);
    }
    let snapshot = original.snapshot();
    let json = to_json(&snapshot);
    let loaded: WorldSnapshot = serde_json::from_str(&json).unwrap();
    assert_eq!(
        to_json(&loaded),
        json,
        "re-serialising a loaded snapshot gives the same bytes"
    );
    assert_eq!(loaded, snapshot);

    // A fresh world with the same colliders, restored from the deserialised snapshot.
    let mut restored =
        World::with_backend(WorldSettings::default(), original.backend().clone()).unwrap();
    restored.restore(&loaded).unwrap();
    assert_eq!(restored.state_digest(), original.state_digest());
    step_in_lockstep(&mut original, &mut restored, 120);
    assert_eq!(to_json(&restored.snapshot()), to_json(&original.snapshot()));
}

#[test]
fn rollback_in_place_undoes_impulses_insertions_and_removals() {
    let (mut world, balls) = scene();
    for _ in 0..20 {
        world.step(DT);
    }
    let snapshot = world.snapshot();
    let digest = world.state_digest();

    // Diverge.
    world
        .body_mut(balls[3])
        .unwrap()
        .apply_impulse(Vec3::new(0.0, 50.0, 0.0))
        .unwrap();
    let newcomer = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(3.0, 3.0, 0.0)))
        .unwrap();
    let removed = world.remove_body(balls[5]).unwrap();
    assert!(removed.joints.is_empty());
    for _ in 0..10 {
        world.step(DT);
    }
    assert_ne!(world.state_digest(), digest);

    world.restore(&snapshot).unwrap();
    assert_eq!(
        world.state_digest(),
        digest,
        "rollback restores the exact state"
    );
    for &ball in &balls {
        assert!(
            world.body(ball).is_some(),
            "handles from before the snapshot resolve again"
        );
    }
    assert!(
        world.body(newcomer).is_none(),
        "a handle created after the snapshot is stale"
    );
    // And stepping on matches a world that never diverged.
    let (mut reference, _) = scene();
    for _ in 0..20 {
        reference.step(DT);
    }
    for _ in 0..30 {
        world.step(DT);
        reference.step(DT);
    }
    assert_eq!(world.state_digest(), reference.state_digest());
}

#[test]
fn the_same_calls_give_bit_identical_states_at_every_step() {
    let (mut a, _) = scene();
    let (mut b, _) = scene();
    for step in 0..300 {
        a.step(DT);
        b.step(DT);
        assert_eq!(a.state_digest(), b.state_digest(), "step {step}");
    }
}

#[test]
fn a_restored_deck_steps_in_lockstep_with_its_kept_joint_rows() {
    let mut original = deck();
    for _ in 0..30 {
        original.step(DT);
    }
    let snapshot = original.snapshot();
    assert_eq!(
        snapshot.kept_joint_rows().len(),
        7,
        "every hinge of the deck keeps its rows for the next step"
    );
    let loaded: WorldSnapshot = serde_json::from_str(&to_json(&snapshot)).unwrap();
    assert_eq!(loaded, snapshot);
    let mut restored =
        World::with_backend(WorldSettings::default(), original.backend().clone()).unwrap();
    restored.restore(&loaded).unwrap();
    step_in_lockstep(&mut original, &mut restored, 120);
    // Rolled back in place, after stepping on, the world retraces the same steps too.
    let again = original.snapshot();
    let digests: Vec<u64> = (0..30)
        .map(|_| {
            original.step(DT);
            original.state_digest()
        })
        .collect();
    original.restore(&again).unwrap();
    for (step, &digest) in digests.iter().enumerate() {
        original.step(DT);
        assert_eq!(
            original.state_digest(),
            digest,
            "rollback diverged at step {}",
            step + 1
        );
    }
}

/// Two balls hung from the world: one by a ball joint with a swing–twist cone, a twist range and an
/// orientation motor, one by a 6-DOF joint with a limited, driven slide and a limited swing.
fn limited_joints() -> World<SimpleBackend> {
    use rebound_constraints::{
        Axis, AxisDrive, AxisMotion, BallJoint, Joint, Limits, OrientationMotor, SixDofJoint,
        SoftSpring, SwingTwistLimits,
    };
    let mut world = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let ball = |x: f32| {
        BodyDesc::dynamic()
            .with_position(Vec3::new(x, 1.0, 0.0))
            .with_linear_velocity(Vec3::new(1.5, 0.0, 0.7))
            .with_mass_properties(MassProperties::ball(500.0, 0.2).unwrap())
    };
    let a = world.insert_body(&ball(0.0)).unwrap();
    let b = world.insert_body(&ball(2.0)).unwrap();
    let limits = SwingTwistLimits::new()
        .with_cone(0.4, 0.7)
        .unwrap()
        .with_twist(-0.2, 0.3)
        .unwrap()
        .with_restitution(0.3)
        .unwrap();
    let motor = OrientationMotor::new(
        rebound_math::Quat::from_rotation_z(0.2),
        SoftSpring::frequency(1.0, 0.5).unwrap(),
        f32::INFINITY,
    )
    .unwrap();
    let joint = Joint::new(BallJoint::new().with_limits(limits).with_motor(motor))
        .with_local_anchors(Vec3::new(0.0, 2.0, 0.0), Vec3::Y)
        .unwrap()
        .with_local_axes(-Vec3::Y, -Vec3::Y)
        .unwrap();
    world.insert_world_joint(joint, a).unwrap();
    let six = SixDofJoint::locked()
        .with_motion(
            Axis::LinearY,
            AxisMotion::Limited(Limits::new(-0.3, 0.3).unwrap()),
        )
        .unwrap()
        .with_drive(
            Axis::LinearY,
            Some(AxisDrive::Velocity {
                target_speed: 0.1,
                max_force: f32::INFINITY,
            }),
        )
        .unwrap()
        .with_motion(
            Axis::AngularZ,
            AxisMotion::Limited(Limits::new(-0.5, 0.5).unwrap()),
        )
        .unwrap();
    let joint = Joint::new(six)
        .with_local_anchors(Vec3::new(2.0, 2.0, 0.0), Vec3::Y)
        .unwrap();
    world.insert_world_joint(joint, b).unwrap();
    world
}

#[test]
fn limited_ball_and_six_dof_joints_survive_json_and_step_in_lockstep() {
    let mut original = limited_joints();
    for _ in 0..20 {
        original.step(DT);
    }
    let json = to_json(&original.snapshot());
    let loaded: WorldSnapshot = serde_json::from_str(&json).unwrap();
    assert_eq!(loaded, original.snapshot());
    let mut restored =
        World::with_backend(WorldSettings::default(), original.backend().clone()).unwrap();
    restored.restore(&loaded).unwrap();
    step_in_lockstep(&mut original, &mut restored, 60);
    // An out-of-range half-angle written into the file is refused when the file is read.
    let bad = json.replacen("0.4,0.7", "4.0,0.7", 1);
    assert_ne!(bad, json, "the cone's half-angles are in the snapshot");
    let error = serde_json::from_str::<WorldSnapshot>(&bad)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(error.contains("half_angle_y"), "{error}");
}
