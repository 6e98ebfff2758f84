//! Drawing a live world: contacts at the engine's points with normals and impulses of the stated lengths,
//! joints' anchors, axes and limits where the joint frame puts them, what the settings switch off, and
//! sleeping bodies in their own colour.

use rebound::prelude::*;
use rebound_debug::{DebugDraw, DebugSettings, JointGeometry, JointView, Layer, draw_world};

const EPS: f32 = 1e-5;

fn ball_on_ground() -> Result<(PhysicsWorld, BodyHandle), Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let ground = world.insert_body(BodyDesc::fixed())?;
    world.insert_collider(
        ColliderDesc::cuboid(Vec3::new(5.0, 0.5, 5.0)).with_position(Vec3::new(0.0, -0.5, 0.0)),
        ground,
    )?;
    let ball = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.5, 0.0)))?;
    world.insert_collider(ColliderDesc::ball(0.5), ball)?;
    for _ in 0..30 {
        world.step(1.0 / 60.0);
    }
    Ok((world, ball))
}

#[test]
fn contacts_are_drawn_at_the_engines_points_with_normal_and_impulse_lengths() {
    let (world, _) = ball_on_ground().unwrap();
    let settings = DebugSettings::default();
    let draw = draw_world(&world, &settings);
    let manifold = &world.contacts()[0];
    let point = &manifold.points[0];
    let pose = |h| world.body(h).unwrap().pose();
    let at = point.world_point(pose(manifold.body_a), pose(manifold.body_b));
    // A resting ball touches the ground just below its centre.
    assert!(
        at.x.abs() < 1e-3 && at.z.abs() < 1e-3 && at.y.abs() < 0.02,
        "{at}"
    );
    let lines: Vec<_> = draw.lines_of(Layer::Contact).collect();
    let from_point: Vec<_> = lines.iter().filter(|l| l.a.distance(at) < EPS).collect();
    let normal = from_point
        .iter()
        .find(|l| l.color == settings.colors.contact_normal)
        .unwrap();
    assert!((normal.b - (at + manifold.normal * settings.normal_length)).length() < EPS);
    let impulse = from_point
        .iter()
        .find(|l| l.color == settings.colors.contact_impulse)
        .unwrap();
    let expected = at + manifold.normal * settings.impulse_scale * point.normal_impulse;
    assert!((impulse.b - expected).length() < EPS);
    // The stored impulse is the last substep's: the ball's weight over one substep, J = m·g·h with
    // h = dt / substeps and m = 4/3·π·0.5³ kg at density 1.
    let h = 1.0 / 60.0 / world.settings().substep_count as f32;
    let weight_impulse = 4.0 / 3.0 * std::f32::consts::PI * 0.125 * 9.81 * h;
    assert!(
        (point.normal_impulse - weight_impulse).abs() < 0.05 * weight_impulse,
        "{}",
        point.normal_impulse
    );
    // Three segments of the cross, the normal and the impulse per point.
    let points: usize = world.contacts().iter().map(|m| m.point_count).sum();
    let with_impulse = world
        .contacts()
        .iter()
        .flat_map(|m| &m.points[..m.point_count])
        .filter(|p| p.normal_impulse > 0.0)
        .count();
    assert_eq!(lines.len(), 4 * points + with_impulse);
}

#[test]
fn settings_choose_what_is_drawn() {
    let (world, _) = ball_on_ground().unwrap();
    let none = DebugSettings {
        outlines: false,
        contacts: false,
        joints: false,
        joint_axes: false,
        joint_limits: false,
        ..DebugSettings::default()
    };
    let draw = draw_world(&world, &none);
    assert!(draw.lines.is_empty() && draw.triangles.is_empty());
    let boxes = draw_world(
        &world,
        &DebugSettings {
            bounding_boxes: true,
            ..none.clone()
        },
    );
    assert_eq!(boxes.lines_of(Layer::BoundingBox).count(), 2 * 12);
    assert_eq!(boxes.lines.len(), 2 * 12);
    let solids = draw_world(
        &world,
        &DebugSettings {
            solids: true,
            ..none
        },
    );
    assert!(solids.lines.is_empty() && !solids.triangles.is_empty());
    let all = draw_world(&world, &DebugSettings::default());
    assert!(all.lines_of(Layer::Shape).count() > 0 && all.lines_of(Layer::Contact).count() > 0);
}

#[test]
fn sleeping_bodies_and_sensors_get_their_own_colours() {
    let (mut world, ball) = ball_on_ground().unwrap();
    let sensor_body = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(3.0, 1.0, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.5).with_sensor(true), sensor_body)
        .unwrap();
    for _ in 0..600 {
        world.step(1.0 / 60.0);
    }
    assert_eq!(
        world.is_sleeping(ball),
        Some(true),
        "the resting ball falls asleep"
    );
    let settings = DebugSettings::default();
    let draw = draw_world(&world, &settings);
    let ball_pos = world.body(ball).unwrap().position();
    let ball_lines: Vec<_> = draw
        .lines_of(Layer::Shape)
        .filter(|l| (l.a.distance(ball_pos) - 0.5).abs() < 1e-4)
        .collect();
    assert_eq!(ball_lines.len(), 3 * settings.circle_segments as usize);
    assert!(
        ball_lines
            .iter()
            .all(|l| l.color == settings.colors.sleeping)
    );
    let sensor_lines = draw
        .lines
        .iter()
        .filter(|l| l.color == settings.colors.sensor)
        .count();
    assert_eq!(sensor_lines, 3 * settings.circle_segments as usize);
    let unmarked = draw_world(
        &world,
        &DebugSettings {
            mark_sleeping: false,
            sensors: false,
            ..settings.clone()
        },
    );
    assert!(
        unmarked
            .lines
            .iter()
            .all(|l| l.color != settings.colors.sleeping && l.color != settings.colors.sensor)
    );
}

#[test]
fn a_hinge_draws_its_anchors_axis_and_limit_arc_in_its_frame() {
    let frame = Quat::from_rotation_y(0.6);
    let anchor = Vec3::new(1.0, 2.0, 3.0);
    let view = JointView {
        anchor_a: anchor,
        anchor_b: anchor + Vec3::new(0.0, 0.01, 0.0),
        frame_a: frame,
        frame_b: frame,
        geometry: JointGeometry::Hinge {
            limits: Some((-0.5, 1.0)),
        },
        broken: false,
    };
    let settings = DebugSettings::default();
    let mut draw = DebugDraw::new();
    draw.joint(&view, &settings);
    let colors = &settings.colors;
    let length = settings.joint_axis_length;
    let axis: Vec<_> = draw
        .lines
        .iter()
        .filter(|l| l.color == colors.joint_axis)
        .collect();
    assert_eq!(axis.len(), 1);
    let x = frame * Vec3::X;
    assert!((axis[0].a - (anchor - x * 0.5 * length)).length() < EPS);
    assert!((axis[0].b - (anchor + x * 0.5 * length)).length() < EPS);
    // The arc: every point at the axis length from the anchor, in the plane across the axis, from the
    // lower to the upper angle measured from the frame's y towards its z.
    let (y, z) = (frame * Vec3::Y, frame * Vec3::Z);
    let limit: Vec<_> = draw
        .lines
        .iter()
        .filter(|l| l.color == colors.joint_limit)
        .collect();
    let at = |angle: f32| anchor + (y * angle.cos() + z * angle.sin()) * length;
    assert!((limit[0].b - at(-0.5)).length() < EPS && (limit[1].b - at(1.0)).length() < EPS);
    for l in &limit[2..] {
        for p in [l.a, l.b] {
            assert!((p.distance(anchor) - length).abs() < EPS);
            assert!((p - anchor).dot(x).abs() < EPS);
        }
    }
    assert!((limit.last().unwrap().b - at(1.0)).length() < EPS);
    // Anchors: a cross at each, and the line between them.
    assert_eq!(
        draw.lines
            .iter()
            .filter(|l| l.color == colors.joint)
            .count(),
        7
    );
}

#[test]
fn a_slider_draws_its_range_along_its_axis_and_a_broken_joint_only_its_anchors() {
    let mut world = PhysicsWorld::new(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    })
    .unwrap();
    let a = world.insert_body(BodyDesc::dynamic()).unwrap();
    let b = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(1.0, 0.0, 0.0)))
        .unwrap();
    let joint = Joint::new(PrismaticJoint::new().with_limits(Limits::new(-0.25, 0.75).unwrap()))
        .with_local_axes(Vec3::Z, Vec3::Z)
        .unwrap();
    let handle = world.insert_joint(joint, a, b).unwrap();
    let settings = DebugSettings::default();
    let draw = draw_world(&world, &settings);
    let range = draw
        .lines
        .iter()
        .find(|l| l.color == settings.colors.joint_limit)
        .unwrap();
    assert!(
        (range.a - Vec3::new(0.0, 0.0, -0.25)).length() < EPS,
        "{range:?}"
    );
    assert!((range.b - Vec3::new(0.0, 0.0, 0.75)).length() < EPS);
    let view = JointView::new(
        world.joint(handle).unwrap(),
        Some(Pose::IDENTITY),
        Pose::from_position(Vec3::X),
        true,
    );
    let mut broken = DebugDraw::new();
    broken.joint(&view, &settings);
    assert_eq!(broken.lines.len(), 7);
    assert!(
        broken
            .lines
            .iter()
            .all(|l| l.color == settings.colors.broken_joint)
    );
}

/// Whether `draw` has a joint segment from `a` to `b` (either way round) in `color`.
fn has_joint_line(draw: &DebugDraw, a: Vec3, b: Vec3, color: rebound_debug::Color) -> bool {
    draw.lines_of(Layer::Joint).any(|l| {
        l.color == color
            && ((l.a.distance(a) < EPS && l.b.distance(b) < EPS)
                || (l.a.distance(b) < EPS && l.b.distance(a) < EPS))
    })
}

#[test]
fn every_joint_kind_in_a_world_draws_at_its_anchors_with_its_axes_and_limits() {
    let mut world = PhysicsWorld::new(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    })
    .unwrap();
    let spring = Spring::new(1.0, SpringModel::soft_frequency(2.0, 0.5).unwrap()).unwrap();
    let wheel = WheelJoint::new(SoftSpring::default())
        .unwrap()
        .with_suspension_limits(Limits::new(-0.2, 0.3).unwrap());
    let kinds: Vec<JointKind> = vec![
        spring.into(),
        Rope::new(2.0).unwrap().into(),
        Rod::new(1.2).unwrap().into(),
        BallJoint::new().into(),
        HingeJoint::new().with_limits(-0.5, 1.0).unwrap().into(),
        FixedJoint::new().into(),
        PrismaticJoint::new()
            .with_limits(Limits::new(-0.25, 0.75).unwrap())
            .into(),
        wheel.into(),
    ];
    let settings = DebugSettings::default();
    let colors = &settings.colors;
    let (size, length) = (settings.marker_size, settings.joint_axis_length);
    // Each joint on its own pair of turned bodies, 10 m apart; the last one also as a world joint.
    let mut expected = Vec::new();
    for (i, kind) in kinds.into_iter().enumerate() {
        let origin = Vec3::new(10.0 * i as f32, 0.0, 0.0);
        let pose_a = Pose::new(origin, Quat::from_rotation_z(0.3));
        let pose_b = Pose::new(
            origin + Vec3::new(1.0, 0.5, -0.25),
            Quat::from_rotation_x(-0.7),
        );
        let a = world
            .insert_body(
                BodyDesc::dynamic()
                    .with_position(pose_a.position)
                    .with_rotation(pose_a.rotation),
            )
            .unwrap();
        let b = world
            .insert_body(
                BodyDesc::dynamic()
                    .with_position(pose_b.position)
                    .with_rotation(pose_b.rotation),
            )
            .unwrap();
        let joint = Joint::new(kind)
            .with_local_anchors(Vec3::new(0.1, 0.2, 0.3), Vec3::new(-0.2, 0.0, 0.1))
            .unwrap()
            .with_local_bases(Quat::from_rotation_y(0.4), Quat::from_rotation_y(0.4))
            .unwrap();
        world.insert_joint(joint, a, b).unwrap();
        expected.push((joint, Some(pose_a), pose_b));
        if i == 7 {
            let world_joint = joint
                .with_local_anchors(Vec3::new(70.0, 3.0, 0.0), Vec3::ZERO)
                .unwrap();
            world.insert_world_joint(world_joint, b).unwrap();
            expected.push((world_joint, None, pose_b));
        }
    }
    let draw = draw_world(&world, &settings);
    assert!(draw.lines_of(Layer::Shape).next().is_none(), "no colliders");
    let mut lines = 0;
    for (joint, pose_a, pose_b) in &expected {
        let frame = pose_a.map_or(Pose::IDENTITY, |p| p).rotation * joint.local_basis_a();
        let anchor_a = pose_a.map_or(joint.local_anchor_a(), |p| {
            p.transform_point(joint.local_anchor_a())
        });
        let anchor_b = pose_b.transform_point(joint.local_anchor_b());
        let name = joint.kind().name();
        // A cross at each anchor and the line between them, for every kind.
        for at in [anchor_a, anchor_b] {
            for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
                let (from, to) = (at - axis * size, at + axis * size);
                assert!(
                    has_joint_line(&draw, from, to, colors.joint),
                    "{name}: cross at {at}"
                );
            }
        }
        assert!(
            has_joint_line(&draw, anchor_a, anchor_b, colors.joint),
            "{name}: link"
        );
        lines += 7;
        let (x, y, z) = (frame * Vec3::X, frame * Vec3::Y, frame * Vec3::Z);
        let axis_line = |axis: Vec3| {
            has_joint_line(
                &draw,
                anchor_a - axis * 0.5 * length,
                anchor_a + axis * 0.5 * length,
                colors.joint_axis,
            )
        };
        let range = |axis: Vec3, tick: Vec3, (lower, upper): (f32, f32)| {
            let (from, to) = (anchor_a + axis * lower, anchor_a + axis * upper);
            has_joint_line(&draw, from, to, colors.joint_limit)
                && [from, to].iter().all(|&end| {
                    has_joint_line(
                        &draw,
                        end - tick * size,
                        end + tick * size,
                        colors.joint_limit,
                    )
                })
        };
        match joint.kind() {
            JointKind::Hinge(_) => {
                assert!(axis_line(x), "{name}: axis");
                let at = |angle: f32| anchor_a + (y * angle.cos() + z * angle.sin()) * length;
                assert!(has_joint_line(
                    &draw,
                    anchor_a,
                    at(-0.5),
                    colors.joint_limit
                ));
                assert!(has_joint_line(&draw, anchor_a, at(1.0), colors.joint_limit));
                // The arc's segments: both ends at the axis length from the anchor, across the axis.
                let arc = draw
                    .lines_of(Layer::Joint)
                    .filter(|l| l.color == colors.joint_limit)
                    .filter(|l| {
                        [l.a, l.b].iter().all(|p| {
                            (p.distance(anchor_a) - length).abs() < EPS
                                && (*p - anchor_a).dot(x).abs() < EPS
                        })
                    })
                    .count();
                assert!(arc >= 6, "{name}: 1.5 rad of arc in {arc} segments");
                lines += 1 + 2 + arc;
            }
            JointKind::Prismatic(_) => {
                assert!(axis_line(x), "{name}: axis");
                assert!(range(x, y, (-0.25, 0.75)), "{name}: range");
                lines += 1 + 3;
            }
            JointKind::Wheel(_) => {
                assert!(axis_line(x) && axis_line(y), "{name}: axle and suspension");
                assert!(range(y, x, (-0.2, 0.3)), "{name}: travel");
                lines += 2 + 3;
            }
            _ => {}
        }
    }
    assert_eq!(
        draw.lines_of(Layer::Joint).count(),
        lines,
        "nothing else is drawn"
    );
    assert_eq!(draw.lines.len(), lines);
}
