//! A world with every collider shape and every joint kind, and bit-exact comparisons of frames.

#![allow(
    dead_code,
    clippy::unwrap_used,
    reason = "test fixtures: each test file uses part of them, and a failure to build one is a failed test"
)]

use rebound::prelude::*;
use rebound_record::{Frame, Recorder};

/// Time step of the tests (s).
pub const DT: f32 = 1.0 / 60.0;

/// A world holding each shape kind on a body and each joint kind.
pub fn menagerie() -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let ground = world.insert_body(BodyDesc::fixed()).unwrap();
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0))
                .with_position(Vec3::new(0.0, -0.5, 0.0)),
            ground,
        )
        .unwrap();
    let terrain = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(30.0, 0.0, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::heightfield(
                3,
                3,
                vec![0.0, 0.1, 0.0, 0.2, 0.3, 0.2, 0.0, 0.1, 0.0],
                Vec3::new(4.0, 1.0, 4.0),
            ),
            terrain,
        )
        .unwrap();
    let ramp = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(-30.0, 0.0, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::trimesh(
                vec![
                    Vec3::ZERO,
                    Vec3::X * 4.0,
                    Vec3::new(0.0, 1.0, 4.0),
                    Vec3::new(4.0, 1.0, 4.0),
                ],
                vec![[0, 2, 1], [1, 2, 3]],
            ),
            ramp,
        )
        .unwrap();
    let shapes = [
        ColliderDesc::ball(0.5),
        ColliderDesc::cuboid(Vec3::new(0.5, 0.25, 0.75)).with_rotation(Quat::from_rotation_z(0.3)),
        ColliderDesc::capsule(0.3, 0.4),
        ColliderDesc::cylinder(0.4, 0.3).with_friction(0.9),
        ColliderDesc::cone(0.4, 0.5).with_restitution(0.5),
        ColliderDesc::convex_hull(vec![
            Vec3::ZERO,
            Vec3::X,
            Vec3::Y,
            Vec3::Z,
            Vec3::new(0.7, 0.7, 0.7),
        ]),
        ColliderDesc::compound(vec![
            (Pose::IDENTITY, ColliderShape::Ball { radius: 0.3 }),
            (
                Pose::new(Vec3::new(0.5, 0.0, 0.0), Quat::from_rotation_y(0.5)),
                ColliderShape::Cuboid {
                    half_extents: Vec3::splat(0.2),
                },
            ),
        ]),
    ];
    let mut bodies = Vec::new();
    for (i, shape) in shapes.into_iter().enumerate() {
        let body = world
            .insert_body(
                BodyDesc::dynamic()
                    .with_position(Vec3::new(i as f32 * 2.0 - 6.0, 1.5, 0.0))
                    .with_linear_velocity(Vec3::new(0.1, 0.0, -0.2))
                    .with_angular_velocity(Vec3::new(0.0, 1.0, 0.5)),
            )
            .unwrap();
        world.insert_collider(shape, body).unwrap();
        bodies.push(body);
    }
    let sensor = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(-6.0, 0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(1.0)).with_sensor(true),
            sensor,
        )
        .unwrap();
    // Joints: a chain of links hanging from the world.
    let mut links = Vec::new();
    for i in 0..8 {
        let link = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(i as f32, 8.0, 6.0)))
            .unwrap();
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.2)), link)
            .unwrap();
        links.push(link);
    }
    world
        .insert_world_joint(
            Joint::new(HingeJoint::new().with_limits(-1.0, 1.0).unwrap())
                .with_local_anchors(Vec3::new(-1.0, 8.0, 6.0), Vec3::ZERO)
                .unwrap()
                .with_local_axes(Vec3::Z, Vec3::Z)
                .unwrap(),
            links[0],
        )
        .unwrap();
    let kinds: [Joint; 7] = [
        Joint::new(Rope::new(1.2).unwrap()),
        Joint::new(Rod::new(1.0).unwrap()),
        Joint::new(Spring::new(1.0, SpringModel::soft_frequency(3.0, 0.1).unwrap()).unwrap()),
        Joint::new(BallJoint::new())
            .with_local_anchors(Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0))
            .unwrap(),
        Joint::new(FixedJoint::new())
            .with_local_anchors(Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0))
            .unwrap()
            .with_break_force(1.0e6)
            .unwrap(),
        Joint::new(PrismaticJoint::new().with_limits(Limits::new(-0.5, 0.5).unwrap()))
            .with_local_anchors(Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0))
            .unwrap(),
        Joint::new(WheelJoint::new(SoftSpring::frequency(4.0, 0.7).unwrap()).unwrap())
            .with_local_anchors(Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0))
            .unwrap(),
    ];
    for (i, joint) in kinds.into_iter().enumerate() {
        world.insert_joint(joint, links[i], links[i + 1]).unwrap();
    }
    world
}

/// Records `steps` steps of `world` after its initial state; returns the bytes and the frames as the
/// recorder wrote them.
pub fn record(world: &mut PhysicsWorld, steps: usize) -> (Vec<u8>, Vec<Frame>) {
    let mut recorder = Recorder::new(world, Vec::new()).unwrap();
    let mut frames = Vec::new();
    recorder.record(world).unwrap();
    frames.push(recorder.last_frame().unwrap().clone());
    for _ in 0..steps {
        recorder.step(world, DT).unwrap();
        frames.push(recorder.last_frame().unwrap().clone());
    }
    (recorder.finish().unwrap(), frames)
}

/// Every number of a frame as raw bits, in a fixed order, so that two frames compare bit for bit
/// (`-0.0` and `0.0` differ, NaNs compare by payload).
pub fn bits(frame: &Frame) -> Vec<u64> {
    let mut out = vec![frame.step, frame.time.to_bits()];
    let v = |out: &mut Vec<u64>, v: Vec3| out.extend(v.to_array().map(|c| u64::from(c.to_bits())));
    for b in &frame.bodies {
        v(&mut out, b.position);
        out.extend(b.rotation.to_array().map(|c| u64::from(c.to_bits())));
        v(&mut out, b.linear_velocity);
        v(&mut out, b.angular_velocity);
        out.extend([
            u64::from(b.present),
            u64::from(b.sleeping),
            u64::from(b.kind.code()),
        ]);
    }
    for c in &frame.contacts {
        out.extend([u64::from(c.body_a), u64::from(c.body_b)]);
        v(&mut out, c.point);
        v(&mut out, c.normal);
        out.extend([
            u64::from(c.normal_impulse.to_bits()),
            u64::from(c.separation.to_bits()),
        ]);
    }
    for j in &frame.joints {
        v(&mut out, j.anchor_a);
        v(&mut out, j.anchor_b);
        out.extend([j.error, j.reaction_force, j.reaction_torque].map(|x| u64::from(x.to_bits())));
        out.extend([u64::from(j.present), u64::from(j.broken)]);
    }
    let d = &frame.diagnostics;
    out.extend(
        [
            d.kinetic_energy,
            d.potential_energy,
            d.spring_energy,
            d.worst_joint_error,
            d.deepest_penetration,
        ]
        .map(|x| u64::from(x.to_bits())),
    );
    v(&mut out, d.linear_momentum);
    v(&mut out, d.angular_momentum);
    out
}

/// A ball of radius 0.5 m with its centre `height` (m) above the centre of a fixed 10 × 1 × 10 m box (whose
/// top is at 0.5 m).
pub fn ball_on_ground(height: f32) -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let ground = world.insert_body(BodyDesc::fixed()).unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(5.0, 0.5, 5.0)), ground)
        .unwrap();
    let ball = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, height, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.5), ball)
        .unwrap();
    world
}

/// A small recording with bodies, a joint, contacts and events: a ball dropped on the ground next to a
/// pendulum.
pub fn small() -> Vec<u8> {
    let mut world = ball_on_ground(1.0);
    let bob = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(3.0, 3.0, 0.0)))
        .unwrap();
    world.insert_collider(ColliderDesc::ball(0.2), bob).unwrap();
    world
        .insert_world_joint(
            Joint::new(Rod::new(1.0).unwrap())
                .with_local_anchors(Vec3::new(2.0, 3.0, 0.0), Vec3::ZERO)
                .unwrap(),
            bob,
        )
        .unwrap();
    record(&mut world, 5).0
}

pub fn word(bytes: &[u8], at: usize) -> u32 {
    u32::from_le_bytes(bytes[at..at + 4].try_into().unwrap())
}

/// The file offsets where frames start, and the end.
pub fn frame_starts(bytes: &[u8]) -> Vec<usize> {
    let mut at = 16 + word(bytes, 12) as usize;
    let mut starts = vec![at];
    while at < bytes.len() {
        at += 4 + word(bytes, at) as usize;
        starts.push(at);
    }
    starts
}
