//! The golden digest: a mixed scene through the facade — boxes, balls, capsules, a convex hull and a
//! triangle-mesh ramp on the ground, and a joint of every kind (a swing–twist ball joint with an orientation
//! motor, a limited and driven six-DOF joint, a hinge with limits and a motor, a prismatic joint with limits,
//! a wheel, a fixed joint, a rope, a rod and a spring) — stepped 300 times gives bit-identical states when
//! built twice, stays physical (bounds below), and, with the `enhanced-determinism` feature, ends in a state
//! whose digest equals a constant: the same bits on every platform, in debug and release (CI runs both), and
//! with any other feature of the facade (a thread pool must not change it either).
//!
//! Without `enhanced-determinism` the last bits depend on the platform's maths library and on glam's SIMD
//! paths, so the default build checks repeatability and the bounds only.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound::prelude::*;
use rebound::{Axis, PhysicsWorld};

const DT: f32 = 1.0 / 60.0;
const STEPS: usize = 300;

/// The digest of [`mixed_scene`] after [`STEPS`] steps under `enhanced-determinism`. Update it only when a
/// change of behaviour is intended, and say why in the commit.
#[cfg(feature = "enhanced-determinism")]
const EXPECTED_DIGEST: u64 = 0x929e_70fe_da00_b10c;

/// Rod length (m), rope length (m) and the rod's bodies, the fixed joint's bodies with their initial
/// distance (m), the rope's bodies: what the bounds check.
struct Mixed {
    world: PhysicsWorld,
    rod: (BodyHandle, BodyHandle, f32),
    glued: (BodyHandle, BodyHandle, f32),
    rope: (BodyHandle, BodyHandle, f32),
}

fn dynamic(world: &mut PhysicsWorld, position: Vec3, shape: ColliderDesc) -> BodyHandle {
    let body = world
        .insert_body(BodyDesc::dynamic().with_position(position))
        .unwrap();
    world.insert_collider(shape, body).unwrap();
    body
}

fn fixed(world: &mut PhysicsWorld, position: Vec3, shape: Option<ColliderDesc>) -> BodyHandle {
    let body = world
        .insert_body(BodyDesc::fixed().with_position(position))
        .unwrap();
    if let Some(shape) = shape {
        world.insert_collider(shape, body).unwrap();
    }
    body
}

/// A joint between `a` and `b` as they are now, anchored at the world point `at`, axes along the world's.
fn joint_at(
    world: &PhysicsWorld,
    kind: JointKind,
    a: BodyHandle,
    b: BodyHandle,
    at: Vec3,
) -> Joint {
    let (pa, pb) = (world.body(a).unwrap().pose(), world.body(b).unwrap().pose());
    Joint::from_world(kind, pa, pb, at, at, Quat::IDENTITY).unwrap()
}

/// A joint between `a` and `b` at their centres (the distance joints).
fn joint_between(world: &PhysicsWorld, kind: JointKind, a: BodyHandle, b: BodyHandle) -> Joint {
    let (pa, pb) = (world.body(a).unwrap().pose(), world.body(b).unwrap().pose());
    Joint::from_world(kind, pa, pb, pa.position, pb.position, Quat::IDENTITY).unwrap()
}

fn mixed_scene() -> Mixed {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    // With the `parallel` feature, every step on the pool, however small the scene.
    #[cfg(feature = "parallel")]
    world.set_min_work_for_threads(0);
    let w = &mut world;
    fixed(
        w,
        Vec3::new(0.0, -0.5, 0.0),
        Some(ColliderDesc::cuboid(Vec3::new(12.0, 0.5, 12.0))),
    );
    // A ramp of two triangles rising along +x from the ground.
    let ramp = vec![
        Vec3::new(3.0, 0.0, -2.0),
        Vec3::new(8.0, 2.0, -2.0),
        Vec3::new(8.0, 2.0, 2.0),
        Vec3::new(3.0, 0.0, 2.0),
    ];
    fixed(
        w,
        Vec3::ZERO,
        Some(ColliderDesc::trimesh(ramp, vec![[0, 2, 1], [0, 3, 2]])),
    );
    // A stack of three boxes, a hull on top; balls and capsules dropped beside it and onto the ramp.
    for k in 0..3 {
        let tilt = 0.05 * k as f32;
        dynamic(
            w,
            Vec3::new(-3.0 + tilt, 0.5 + 1.02 * k as f32, tilt),
            ColliderDesc::cuboid(Vec3::splat(0.5)),
        );
    }
    let hull = [
        Vec3::new(0.4, 0.0, 0.0),
        Vec3::new(-0.4, 0.0, 0.1),
        Vec3::new(0.0, 0.5, 0.0),
        Vec3::new(0.0, -0.4, 0.1),
        Vec3::new(0.1, 0.0, 0.45),
        Vec3::new(0.0, 0.1, -0.4),
    ];
    dynamic(
        w,
        Vec3::new(-3.0, 3.6, 0.0),
        ColliderDesc::convex_hull(hull),
    );
    for k in 0..4 {
        let x = k as f32;
        dynamic(
            w,
            Vec3::new(-1.0 + 0.3 * x, 1.0 + 0.9 * x, 1.5),
            ColliderDesc::ball(0.3),
        );
    }
    dynamic(w, Vec3::new(6.0, 3.5, 0.3), ColliderDesc::ball(0.4));
    dynamic(
        w,
        Vec3::new(5.0, 3.0, -0.5),
        ColliderDesc::capsule(0.25, 0.4),
    );
    dynamic(
        w,
        Vec3::new(-1.0, 2.0, -1.5),
        ColliderDesc::capsule_x(0.2, 0.5),
    );

    // Joints on a fixed post above the ground.
    let post = fixed(w, Vec3::new(0.0, 5.0, 4.0), None);
    let door = dynamic(
        w,
        Vec3::new(1.0, 5.0, 4.0),
        ColliderDesc::cuboid(Vec3::new(0.5, 0.4, 0.05)),
    );
    let hinge = HingeJoint::new()
        .with_limits(-1.0, 0.8)
        .unwrap()
        .with_motor(Motor::new(0.5, 5.0).unwrap());
    let door_joint = joint_at(w, hinge.into(), post, door, Vec3::new(0.5, 5.0, 4.0));
    w.insert_joint(door_joint, post, door).unwrap();

    let slider = dynamic(
        w,
        Vec3::new(-1.0, 5.0, 4.0),
        ColliderDesc::cuboid(Vec3::splat(0.2)),
    );
    let prismatic = PrismaticJoint::new().with_limits(Limits::new(-0.5, 0.3).unwrap());
    let slide = joint_at(w, prismatic.into(), post, slider, Vec3::new(-1.0, 5.0, 4.0))
        .with_local_axes(Vec3::Y, Vec3::Y)
        .unwrap();
    w.insert_joint(slide, post, slider).unwrap();

    // Rope then rod: post → bob → second bob, started sideways so that they swing.
    let bob = dynamic(w, Vec3::new(1.5, 4.0, 2.5), ColliderDesc::ball(0.2));
    let rope_length = 1.05 * Vec3::new(1.5, -1.0, -1.5).length();
    let rope = joint_between(w, Rope::new(rope_length).unwrap().into(), post, bob);
    w.insert_joint(rope, post, bob).unwrap();
    let tail = dynamic(w, Vec3::new(2.5, 4.0, 2.5), ColliderDesc::ball(0.2));
    let rod = joint_between(w, Rod::new(1.0).unwrap().into(), bob, tail);
    w.insert_joint(rod, bob, tail).unwrap();

    let hanging = dynamic(
        w,
        Vec3::new(0.0, 3.5, 5.0),
        ColliderDesc::cuboid(Vec3::splat(0.25)),
    );
    let spring = Spring::new(1.2, SpringModel::soft_frequency(2.0, 0.2).unwrap()).unwrap();
    let spring = joint_between(w, spring.into(), post, hanging);
    w.insert_joint(spring, post, hanging).unwrap();

    // A cart: a box on a wheel, a second box fixed to it, falling onto the ground.
    let cart = dynamic(
        w,
        Vec3::new(3.0, 1.5, -4.0),
        ColliderDesc::cuboid(Vec3::new(0.6, 0.15, 0.3)),
    );
    let wheel = dynamic(
        w,
        Vec3::new(3.5, 1.0, -4.0),
        ColliderDesc::cylinder_z(0.3, 0.1),
    );
    let axle = joint_at(
        w,
        WheelJoint::default().into(),
        cart,
        wheel,
        Vec3::new(3.5, 1.0, -4.0),
    );
    w.insert_joint(axle, cart, wheel).unwrap();
    let cargo = dynamic(
        w,
        Vec3::new(2.8, 1.9, -4.0),
        ColliderDesc::cuboid(Vec3::splat(0.2)),
    );
    let glue = joint_at(
        w,
        FixedJoint::new().into(),
        cart,
        cargo,
        Vec3::new(2.8, 1.65, -4.0),
    );
    w.insert_joint(glue, cart, cargo).unwrap();

    // A capsule on a swing–twist ball joint with an orientation motor, and a box on a six-DOF joint, both
    // hung from the world.
    let limits = SwingTwistLimits::new()
        .with_cone(0.5, 0.7)
        .unwrap()
        .with_twist(-0.3, 0.3)
        .unwrap()
        .with_restitution(0.2)
        .unwrap();
    let motor = OrientationMotor::new(
        Quat::from_rotation_z(0.3),
        SoftSpring::frequency(1.0, 0.5).unwrap(),
        f32::INFINITY,
    )
    .unwrap();
    let arm = w
        .insert_body(
            BodyDesc::dynamic()
                .with_position(Vec3::new(-4.0, 4.0, -3.0))
                .with_linear_velocity(Vec3::new(1.5, 0.0, 0.7)),
        )
        .unwrap();
    w.insert_collider(ColliderDesc::capsule(0.15, 0.5), arm)
        .unwrap();
    let shoulder = Joint::new(BallJoint::new().with_limits(limits).with_motor(motor))
        .with_local_anchors(Vec3::new(-4.0, 5.0, -3.0), Vec3::Y)
        .unwrap()
        .with_local_axes(-Vec3::Y, -Vec3::Y)
        .unwrap();
    w.insert_world_joint(shoulder, arm).unwrap();
    let six_body = dynamic(
        w,
        Vec3::new(-6.0, 4.0, -3.0),
        ColliderDesc::cuboid(Vec3::splat(0.2)),
    );
    let six = SixDofJoint::locked()
        .with_motion(
            Axis::LinearY,
            AxisMotion::Limited(Limits::new(-0.4, 0.4).unwrap()),
        )
        .unwrap()
        .with_drive(
            Axis::LinearY,
            Some(AxisDrive::Velocity {
                target_speed: 0.2,
                max_force: 50.0,
            }),
        )
        .unwrap()
        .with_motion(
            Axis::AngularZ,
            AxisMotion::Limited(Limits::new(-0.5, 0.5).unwrap()),
        )
        .unwrap()
        .with_motion(Axis::AngularY, AxisMotion::Free)
        .unwrap();
    let six = Joint::new(six)
        .with_local_anchors(Vec3::new(-6.0, 5.0, -3.0), Vec3::Y)
        .unwrap();
    w.insert_world_joint(six, six_body).unwrap();

    let glued_distance = distance(&world, (cart, cargo));
    Mixed {
        world,
        rod: (bob, tail, 1.0),
        glued: (cart, cargo, glued_distance),
        rope: (post, bob, rope_length),
    }
}

/// The distance between the centres of `a` and `b` (m).
fn distance(world: &PhysicsWorld, (a, b): (BodyHandle, BodyHandle)) -> f32 {
    world
        .body(a)
        .unwrap()
        .position()
        .distance(world.body(b).unwrap().position())
}

#[test]
fn the_mixed_scene_built_twice_is_bit_identical_at_every_step() {
    let (mut a, mut b) = (mixed_scene().world, mixed_scene().world);
    for step in 0..STEPS {
        a.step(DT);
        b.step(DT);
        assert_eq!(
            a.state_digest(),
            b.state_digest(),
            "diverged at step {step}"
        );
    }
}

#[test]
fn the_mixed_scene_stays_physical_and_ends_at_the_golden_digest() {
    let Mixed {
        mut world,
        rod,
        glued,
        rope,
    } = mixed_scene();
    let mut contacts = 0;
    for _ in 0..STEPS {
        contacts = contacts.max(world.step(DT).contact_count);
    }
    assert!(
        contacts >= 10,
        "the scene must collide: {contacts} contacts"
    );
    // No body tunnelled into the ground, none flew off, the joints hold (rod length within 2 %, the fixed
    // pair's distance within 1 cm, the rope no longer than its length + 2 %).
    for (_, body) in world.bodies().iter().filter(|(_, b)| b.is_dynamic()) {
        let p = body.position();
        assert!(
            p.is_finite() && p.y > -0.05 && p.y < 6.0 && p.length() < 12.0,
            "a body at {p}"
        );
    }
    let rod_length = distance(&world, (rod.0, rod.1));
    assert!(
        (rod_length - rod.2).abs() < 0.02 * rod.2,
        "rod length {rod_length}"
    );
    let glued_distance = distance(&world, (glued.0, glued.1));
    assert!(
        (glued_distance - glued.2).abs() < 0.01,
        "fixed pair {glued_distance}"
    );
    let rope_length = distance(&world, (rope.0, rope.1));
    assert!(rope_length < 1.02 * rope.2, "rope length {rope_length}");

    let digest = world.state_digest();
    #[cfg(feature = "enhanced-determinism")]
    assert_eq!(
        digest, EXPECTED_DIGEST,
        "the golden digest changed: {digest:#018x}; if the change of behaviour is intended, update EXPECTED_DIGEST"
    );
    #[cfg(not(feature = "enhanced-determinism"))]
    let _ = digest;
}
