//! Random sequences of API calls — bodies, colliders of every shape, joints, steps, setters, queries,
//! snapshots — with random and partly invalid values (NaN, ±∞, zero, negative, huge). After every call:
//! no panic, and every body's pose and velocities are finite; query results are finite too.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use proptest::prelude::*;
use rebound::prelude::*;

/// Mostly ordinary values, sometimes the ones that break things.
fn scalar() -> impl Strategy<Value = f32> {
    prop_oneof![
        12 => -4.0f32..4.0,
        1 => Just(f32::NAN),
        1 => Just(f32::INFINITY),
        1 => Just(f32::NEG_INFINITY),
        1 => Just(0.0f32),
        1 => Just(1.0e30f32),
        1 => Just(-1.0e-30f32),
    ]
}

fn size() -> impl Strategy<Value = f32> {
    prop_oneof![
        12 => 0.05f32..1.5,
        1 => Just(f32::NAN),
        1 => Just(0.0f32),
        1 => Just(-0.5f32),
        1 => Just(1.0e9f32),
        1 => Just(1.0e-20f32),
    ]
}

fn vec3() -> impl Strategy<Value = Vec3> {
    prop_oneof![
        4 => small_vec3(),
        1 => (scalar(), scalar(), scalar()).prop_map(|(x, y, z)| Vec3::new(x, y, z)),
    ]
}

fn small_vec3() -> impl Strategy<Value = Vec3> {
    (-2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0).prop_map(|(x, y, z)| Vec3::new(x, y, z))
}

fn primitive() -> impl Strategy<Value = ColliderShape> {
    prop_oneof![
        size().prop_map(|radius| ColliderShape::Ball { radius }),
        (size(), size(), size()).prop_map(|(x, y, z)| ColliderShape::Cuboid {
            half_extents: Vec3::new(x, y, z)
        }),
        (size(), size()).prop_map(|(radius, half_height)| ColliderShape::Capsule {
            radius,
            half_height
        }),
        (size(), size()).prop_map(|(radius, half_height)| ColliderShape::Cylinder {
            radius,
            half_height
        }),
        (size(), size()).prop_map(|(radius, half_height)| ColliderShape::Cone {
            radius,
            half_height
        }),
        prop::collection::vec(small_vec3(), 2..9)
            .prop_map(|points| ColliderShape::ConvexHull { points }),
    ]
}

fn shape() -> impl Strategy<Value = ColliderShape> {
    prop_oneof![
        6 => primitive(),
        1 => (prop::collection::vec(small_vec3(), 0..6), prop::collection::vec([0u32..7, 0u32..7, 0u32..7], 0..5))
            .prop_map(|(vertices, indices)| ColliderShape::TriMesh { vertices, indices }),
        1 => (0usize..4, 0usize..4, prop::collection::vec(scalar(), 0..12), size())
            .prop_map(|(rows, cols, heights, s)| ColliderShape::HeightField { rows, cols, heights, scale: Vec3::new(4.0, s, 4.0) }),
        1 => prop::collection::vec((small_vec3(), primitive()), 0..3)
            .prop_map(|parts| ColliderShape::Compound { parts: parts.into_iter().map(|(p, s)| (Pose::from_position(p), s)).collect() }),
    ]
}

#[derive(Debug, Clone)]
enum Op {
    InsertBody {
        kind: u8,
        position: Vec3,
        velocity: Vec3,
    },
    RemoveBody(usize),
    InsertCollider {
        body: usize,
        shape: ColliderShape,
        density: f32,
        friction: f32,
        restitution: f32,
        sensor: bool,
        offset: Vec3,
    },
    RemoveCollider(usize),
    InsertJoint {
        a: usize,
        b: usize,
        length: f32,
        to_world: bool,
        hinge: bool,
    },
    RemoveJoint(usize),
    JointContacts(usize, bool),
    Step(f32),
    Advance(f32),
    SetVelocity(usize, Vec3),
    SetPosition(usize, Vec3),
    Impulse(usize, Vec3),
    SetDensity(usize, f32),
    SetFriction(usize, f32),
    SetEnabled(usize, bool),
    SetSensor(usize, bool),
    SetLocalPose(usize, Vec3, f32),
    Ray(Vec3, Vec3, f32),
    Project(Vec3, f32),
    Overlap(ColliderShape, Vec3),
    ShapeCast(ColliderShape, Vec3, Vec3, f32),
    Pick(Vec3, Vec3),
    Snapshot,
    Restore,
}

fn op() -> impl Strategy<Value = Op> {
    prop_oneof![
        4 => (0u8..3, vec3(), vec3()).prop_map(|(kind, position, velocity)| Op::InsertBody { kind, position, velocity }),
        1 => any::<usize>().prop_map(Op::RemoveBody),
        6 => (
            any::<usize>(),
            shape(),
            prop_oneof![6 => 0.1f32..3.0, 1 => scalar()],
            prop_oneof![6 => 0.0f32..1.0, 1 => scalar()],
            prop_oneof![6 => 0.0f32..1.0, 1 => scalar()],
            prop::bool::weighted(0.15),
            prop_oneof![3 => Just(Vec3::ZERO), 1 => small_vec3()],
        )
            .prop_map(|(body, shape, density, friction, restitution, sensor, offset)| Op::InsertCollider { body, shape, density, friction, restitution, sensor, offset }),
        1 => any::<usize>().prop_map(Op::RemoveCollider),
        2 => (any::<usize>(), any::<usize>(), scalar(), any::<bool>(), any::<bool>()).prop_map(|(a, b, length, to_world, hinge)| Op::InsertJoint { a, b, length, to_world, hinge }),
        1 => any::<usize>().prop_map(Op::RemoveJoint),
        1 => (any::<usize>(), any::<bool>()).prop_map(|(j, on)| Op::JointContacts(j, on)),
        8 => prop_oneof![6 => Just(1.0f32 / 60.0), 1 => scalar(), 1 => 0.0f32..0.2].prop_map(Op::Step),
        1 => scalar().prop_map(Op::Advance),
        1 => (any::<usize>(), vec3()).prop_map(|(b, v)| Op::SetVelocity(b, v)),
        1 => (any::<usize>(), vec3()).prop_map(|(b, v)| Op::SetPosition(b, v)),
        1 => (any::<usize>(), vec3()).prop_map(|(b, v)| Op::Impulse(b, v)),
        1 => (any::<usize>(), scalar()).prop_map(|(c, v)| Op::SetDensity(c, v)),
        1 => (any::<usize>(), scalar()).prop_map(|(c, v)| Op::SetFriction(c, v)),
        1 => (any::<usize>(), any::<bool>()).prop_map(|(c, v)| Op::SetEnabled(c, v)),
        1 => (any::<usize>(), any::<bool>()).prop_map(|(c, v)| Op::SetSensor(c, v)),
        1 => (any::<usize>(), vec3(), scalar()).prop_map(|(c, p, a)| Op::SetLocalPose(c, p, a)),
        1 => (vec3(), vec3(), scalar()).prop_map(|(o, d, m)| Op::Ray(o, d, m)),
        1 => (vec3(), scalar()).prop_map(|(p, m)| Op::Project(p, m)),
        1 => (primitive(), vec3()).prop_map(|(s, p)| Op::Overlap(s, p)),
        1 => (primitive(), vec3(), vec3(), scalar()).prop_map(|(s, p, d, m)| Op::ShapeCast(s, p, d, m)),
        1 => (vec3(), vec3()).prop_map(|(o, d)| Op::Pick(o, d)),
        1 => Just(Op::Snapshot),
        1 => Just(Op::Restore),
    ]
}

fn pick<T: Copy>(items: &[T], i: usize) -> Option<T> {
    (!items.is_empty()).then(|| items[i % items.len()])
}

fn assert_finite_state(world: &PhysicsWorld, op: &Op) {
    for (handle, body) in world.bodies().iter() {
        let pose = body.pose();
        assert!(
            pose.position.is_finite()
                && pose.rotation.is_finite()
                && body.linear_velocity().is_finite()
                && body.angular_velocity().is_finite()
                && body.mass_properties().mass().is_finite()
                && body.mass_properties().local_inertia().is_finite(),
            "body {handle:?} not finite after {op:?}: {body:?}"
        );
    }
    for manifold in world.contacts() {
        assert!(manifold.normal.is_finite());
    }
}

fn run(ops: &[Op]) {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    // Handles ever issued, removed ones included (they must be refused, not panic).
    let mut bodies = Vec::new();
    let mut colliders = Vec::new();
    // A ground and a small pile to start from, so that random calls meet contacts.
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -2.5, 0.0)))
        .unwrap();
    colliders.push(
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::new(10.0, 0.5, 10.0)), ground)
            .unwrap(),
    );
    bodies.push(ground);
    for i in 0..3 {
        let body = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(
                0.3 * i as f32,
                -1.5 + 0.9 * i as f32,
                0.0,
            )))
            .unwrap();
        colliders.push(
            world
                .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.4)), body)
                .unwrap(),
        );
        bodies.push(body);
    }
    let mut joints = Vec::new();
    let mut snapshot = None;
    let filter = QueryFilter::new();
    for op in ops {
        match op.clone() {
            Op::InsertBody {
                kind,
                position,
                velocity,
            } => {
                let desc = match kind {
                    0 => BodyDesc::dynamic(),
                    1 => BodyDesc::fixed(),
                    _ => BodyDesc::kinematic(),
                };
                if let Ok(h) =
                    world.insert_body(desc.with_position(position).with_linear_velocity(velocity))
                {
                    bodies.push(h);
                }
            }
            Op::RemoveBody(i) => {
                if let Some(h) = pick(&bodies, i) {
                    let _ = world.remove_body(h);
                }
            }
            Op::InsertCollider {
                body,
                shape,
                density,
                friction,
                restitution,
                sensor,
                offset,
            } => {
                let Some(b) = pick(&bodies, body) else {
                    continue;
                };
                let desc = ColliderDesc::new(shape)
                    .with_density(density)
                    .with_friction(friction)
                    .with_restitution(restitution)
                    .with_sensor(sensor)
                    .with_position(offset);
                if let Ok(h) = world.insert_collider(desc, b) {
                    colliders.push(h);
                }
            }
            Op::RemoveCollider(i) => {
                if let Some(h) = pick(&colliders, i) {
                    let _ = world.remove_collider(h);
                }
            }
            Op::InsertJoint {
                a,
                b,
                length,
                to_world,
                hinge,
            } => {
                let (Some(a), Some(b)) = (pick(&bodies, a), pick(&bodies, b)) else {
                    continue;
                };
                let joint = if hinge {
                    Some(Joint::new(HingeJoint::new()))
                } else {
                    Rope::new(length).ok().map(Joint::new)
                };
                let Some(joint) = joint else { continue };
                let result = if to_world {
                    world.insert_world_joint(joint, b)
                } else {
                    world.insert_joint(joint, a, b)
                };
                if let Ok(h) = result {
                    joints.push(h);
                }
            }
            Op::RemoveJoint(i) => {
                if let Some(h) = pick(&joints, i) {
                    let _ = world.remove_joint(h);
                }
            }
            Op::JointContacts(i, on) => {
                if let Some(h) = pick(&joints, i) {
                    let _ = world.set_joint_contacts_enabled(h, on);
                }
            }
            Op::Step(dt) => {
                let _ = world.step(dt);
            }
            Op::Advance(elapsed) => {
                let _ = world.advance(elapsed);
            }
            Op::SetVelocity(i, v) => {
                if let Some(b) = pick(&bodies, i).and_then(|h| world.body_mut(h)) {
                    let _ = b.set_linear_velocity(v);
                }
            }
            Op::SetPosition(i, p) => {
                if let Some(b) = pick(&bodies, i).and_then(|h| world.body_mut(h)) {
                    let _ = b.set_position(p);
                }
            }
            Op::Impulse(i, j) => {
                if let Some(b) = pick(&bodies, i).and_then(|h| world.body_mut(h)) {
                    let _ = b.apply_impulse(j);
                }
            }
            Op::SetDensity(i, v) => {
                if let Some(c) = pick(&colliders, i) {
                    let _ = world.set_collider_density(c, v);
                }
            }
            Op::SetFriction(i, v) => {
                if let Some(c) = pick(&colliders, i) {
                    let _ = world.set_collider_friction(c, v);
                }
            }
            Op::SetEnabled(i, v) => {
                if let Some(c) = pick(&colliders, i) {
                    let _ = world.set_collider_enabled(c, v);
                }
            }
            Op::SetSensor(i, v) => {
                if let Some(c) = pick(&colliders, i) {
                    let _ = world.set_collider_sensor(c, v);
                }
            }
            Op::SetLocalPose(i, p, angle) => {
                if let Some(c) = pick(&colliders, i) {
                    let _ = world
                        .set_collider_local_pose(c, Pose::new(p, Quat::from_rotation_y(angle)));
                }
            }
            Op::Ray(origin, direction, max) => {
                if let Ok(hits) = world.cast_ray_all(origin, direction, max, &filter) {
                    for hit in &hits {
                        assert!(
                            hit.distance.is_finite()
                                && hit.point.is_finite()
                                && hit.normal.is_finite(),
                            "{hit:?}"
                        );
                    }
                    let first = world.cast_ray(origin, direction, max, &filter).unwrap();
                    assert_eq!(first, hits.first().copied());
                }
            }
            Op::Project(point, max) => {
                if let Ok(Some(hit)) = world.project_point(point, max, &filter) {
                    assert!(hit.point.is_finite() && hit.distance.is_finite(), "{hit:?}");
                }
            }
            Op::Overlap(shape, position) => {
                let _ = world.intersect_shape(&shape, Pose::from_position(position), &filter);
            }
            Op::ShapeCast(shape, position, direction, max) => {
                if let Ok(Some(hit)) = world.cast_shape(
                    &shape,
                    Pose::from_position(position),
                    direction,
                    max,
                    &filter,
                ) {
                    assert!(hit.point.is_finite() && hit.distance.is_finite(), "{hit:?}");
                }
            }
            Op::Pick(origin, direction) => {
                if let Ok(Some(hit)) = world.pick_body(origin, direction, 100.0) {
                    assert!(hit.local_point.is_finite());
                }
            }
            Op::Snapshot => snapshot = Some(world.snapshot()),
            Op::Restore => {
                if let Some(s) = &snapshot {
                    world.restore(s).unwrap();
                }
            }
        }
        assert_finite_state(&world, op);
    }
    // Whatever happened, the world still steps.
    for _ in 0..3 {
        world.step(1.0 / 60.0);
        assert_finite_state(&world, &Op::Step(1.0 / 60.0));
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn random_api_calls_never_panic_and_keep_the_state_finite(ops in prop::collection::vec(op(), 1..40)) {
        run(&ops);
    }
}
