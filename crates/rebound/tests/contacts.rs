//! Contacts through the parry backend: a box settles on the ground on a 4-point cuboid-cuboid manifold;
//! speculative contacts stop a 100 m/s ball at a 0.1 m wall; colliders on one body, collision groups and
//! joints that disable contacts keep pairs apart; every shape kind collides with the ground.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;

fn ground(world: &mut PhysicsWorld) -> BodyHandle {
    // Top face at y = 0.
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0)), ground)
        .unwrap();
    ground
}

#[test]
fn a_box_settles_on_the_ground_on_a_four_point_manifold() {
    // Sleep off: the box must come to rest by itself, not by being put to sleep.
    let settings = WorldSettings {
        sleep_enabled: false,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    ground(&mut world);
    let cube = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.6, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)), cube)
        .unwrap();
    for _ in 0..60 {
        world.step(DT);
    }
    let body = world.body(cube).unwrap();
    let (v, w) = (
        body.linear_velocity().length(),
        body.angular_velocity().length(),
    );
    let y = body.position().y;
    println!("after 1 s: |v| = {v:e} m/s, |ω| = {w:e} rad/s, y = {y}");
    assert!(v < 1e-3 && w < 1e-3, "still moving: |v| = {v}, |ω| = {w}");
    assert!((y - 0.5).abs() < 5e-3, "resting on the top face: y = {y}");
    let manifolds = world.contacts();
    assert_eq!(manifolds.len(), 1);
    let manifold = &manifolds[0];
    assert_eq!(manifold.point_count, 4, "face-face: the four corners");
    assert!(
        manifold.normal.abs_diff_eq(Vec3::Y, 1e-4) || manifold.normal.abs_diff_eq(-Vec3::Y, 1e-4)
    );
    // The four anchors on the cube are its four bottom corners (body frame), all different feature ids.
    let cube_is_b = manifold.body_b == cube;
    let mut ids: Vec<u32> = manifold.points().iter().map(|p| p.feature_id).collect();
    ids.sort_unstable();
    ids.dedup();
    assert_eq!(ids.len(), 4);
    for p in manifold.points() {
        let anchor = if cube_is_b {
            p.local_anchor_b
        } else {
            p.local_anchor_a
        };
        assert!((anchor.x.abs() - 0.5).abs() < 1e-4 && (anchor.z.abs() - 0.5).abs() < 1e-4);
        assert!((anchor.y + 0.5).abs() < 1e-2, "{anchor}");
    }
}

#[test]
fn speculative_contacts_stop_a_100_m_s_ball_at_a_10_cm_wall() {
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    let wall = world.insert_body(BodyDesc::fixed()).unwrap();
    // Wall: x in [−0.05, 0.05].
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(0.05, 2.0, 2.0)), wall)
        .unwrap();
    let (radius, speed, x0) = (0.1, 100.0, -5.5);
    // Without continuous collision the ball would tunnel: sampled at step ends it is at x0 + k·1.667 m —
    // −3.83, −2.17, −0.50, +1.17 — never overlapping the wall.
    let step = speed * DT;
    for k in 1..=4 {
        let x = x0 + k as f32 * step;
        assert!(
            x + radius < -0.05 || x - radius > 0.05,
            "sample {k} at {x} overlaps"
        );
    }
    let ball = world
        .insert_body(
            BodyDesc::dynamic()
                .with_position(Vec3::new(x0, 0.0, 0.0))
                .with_linear_velocity(Vec3::new(speed, 0.0, 0.0)),
        )
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(radius), ball)
        .unwrap();
    let mut max_x = f32::MIN;
    let mut stopped_at = None;
    for i in 0..60 {
        world.step(DT);
        let body = world.body(ball).unwrap();
        max_x = max_x.max(body.position().x);
        if stopped_at.is_none() && body.linear_velocity().x < 1.0 {
            stopped_at = Some((i, world.contacts().to_vec()));
        }
    }
    let face = -0.05 - radius;
    println!("furthest centre x = {max_x} (wall face at {face})");
    assert!(
        max_x <= face + 1e-3,
        "the ball passed the wall face: {max_x}"
    );
    // It was stopped by a speculative contact: a manifold reported while the ball was still 0.35 m away.
    let (step, manifolds) = stopped_at.expect("the ball stops");
    let separation = manifolds.first().map(|m| m.points()[0].separation);
    println!("stopped in step {step} by a manifold with separation {separation:?} m");
    assert!(separation.is_some_and(|s| (s - 0.35).abs() < 1e-3));
    let v = world.body(ball).unwrap().linear_velocity();
    assert!(v.length() < 1e-3, "stopped (restitution 0): {v}");
}

#[test]
fn colliders_of_one_body_never_collide_and_groups_filter_pairs() {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    ground(&mut world);
    // Two overlapping colliders on one body: no manifold between them.
    let body = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 3.0, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.5), body)
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.4)), body)
        .unwrap();
    world.step(DT);
    assert!(world.contacts().is_empty());

    // Group 1 ignores group 2 (its filter lacks bit 2): a group-2 ball falls through a group-1 floor,
    // a group-1 ball lands on it.
    let floor = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(10.0, 1.0, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::new(3.0, 0.1, 3.0))
                .with_groups(CollisionGroups::new(0b01, 0b01)),
            floor,
        )
        .unwrap();
    let mut balls = Vec::new();
    for (x, groups) in [
        (9.0, CollisionGroups::new(0b10, u32::MAX)),
        (11.0, CollisionGroups::new(0b01, u32::MAX)),
    ] {
        let ball = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(x, 2.0, 0.0)))
            .unwrap();
        world
            .insert_collider(ColliderDesc::ball(0.25).with_groups(groups), ball)
            .unwrap();
        balls.push(ball);
    }
    for _ in 0..90 {
        world.step(DT);
    }
    let y: Vec<f32> = balls
        .iter()
        .map(|b| world.body(*b).unwrap().position().y)
        .collect();
    println!(
        "ball heights after 1.5 s: group 2 {}, group 1 {}",
        y[0], y[1]
    );
    assert!(
        y[0] < 0.5,
        "the group-2 ball fell through to the ground: {}",
        y[0]
    );
    assert!(
        (y[1] - 1.35).abs() < 0.02,
        "the group-1 ball rests on the floor: {}",
        y[1]
    );
}

#[test]
fn joints_can_disable_contacts_between_their_bodies() {
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    // Two overlapping boxes held by a ball joint.
    let a = world.insert_body(BodyDesc::dynamic()).unwrap();
    let b = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.8, 0.0, 0.0)))
        .unwrap();
    for body in [a, b] {
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)), body)
            .unwrap();
    }
    let joint = world
        .insert_joint(
            Joint::new(BallJoint::new())
                .with_local_anchors(Vec3::new(0.4, 0.0, 0.0), Vec3::new(-0.4, 0.0, 0.0))
                .unwrap(),
            a,
            b,
        )
        .unwrap();
    assert_eq!(world.joint_contacts_enabled(joint), Some(true));
    world.step(DT);
    assert_eq!(
        world.contacts().len(),
        1,
        "jointed bodies collide by default"
    );

    world.set_joint_contacts_enabled(joint, false).unwrap();
    world.step(DT);
    assert!(world.contacts().is_empty());
    assert!(
        world
            .events()
            .iter()
            .any(|e| matches!(e, Event::ContactEnded { .. }))
    );
    assert!(world.world().backend().disabled_body_pairs().len() == 1);

    // Removing the joint lifts the restriction.
    world.remove_joint(joint).unwrap();
    world.step(DT);
    assert_eq!(world.contacts().len(), 1);
    assert!(world.world().backend().disabled_body_pairs().is_empty());
}

#[test]
fn every_shape_kind_comes_to_rest_on_the_ground() {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    ground(&mut world);
    let hull: Vec<Vec3> = (0..12)
        .map(|i| {
            let a = i as f32 * 0.9;
            Vec3::new(
                0.4 * a.cos(),
                if i % 2 == 0 { -0.3 } else { 0.3 },
                0.4 * a.sin(),
            )
        })
        .collect();
    let shapes = [
        ColliderDesc::ball(0.3),
        ColliderDesc::cuboid(Vec3::new(0.3, 0.2, 0.4)),
        ColliderDesc::capsule(0.2, 0.3),
        ColliderDesc::cylinder(0.3, 0.2),
        ColliderDesc::cone(0.3, 0.3),
        ColliderDesc::convex_hull(hull),
        ColliderDesc::compound(vec![
            (
                Pose::from_position(Vec3::new(-0.3, 0.0, 0.0)),
                ColliderShape::Ball { radius: 0.2 },
            ),
            (
                Pose::from_position(Vec3::new(0.3, 0.0, 0.0)),
                ColliderShape::Cuboid {
                    half_extents: Vec3::splat(0.2),
                },
            ),
        ]),
    ];
    let mut bodies = Vec::new();
    for (i, shape) in shapes.into_iter().enumerate() {
        let body = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(
                i as f32 * 2.0 - 6.0,
                1.5,
                0.0,
            )))
            .unwrap();
        world.insert_collider(shape, body).unwrap();
        bodies.push(body);
    }
    // A mesh ramp and a height field as fixed terrain further along z, with a ball on each.
    let terrain = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, 0.5, 8.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::trimesh(
                vec![
                    Vec3::new(-2.0, 0.0, -2.0),
                    Vec3::new(2.0, 0.0, -2.0),
                    Vec3::new(2.0, 0.0, 2.0),
                    Vec3::new(-2.0, 0.0, 2.0),
                ],
                vec![[0, 2, 1], [0, 3, 2]],
            ),
            terrain,
        )
        .unwrap();
    let field = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(8.0, 0.5, 8.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::heightfield(3, 3, vec![0.0; 9], Vec3::new(4.0, 1.0, 4.0)),
            field,
        )
        .unwrap();
    for x in [0.0, 8.0] {
        let ball = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(x, 2.0, 8.0)))
            .unwrap();
        world
            .insert_collider(ColliderDesc::ball(0.25), ball)
            .unwrap();
        bodies.push(ball);
    }
    for _ in 0..180 {
        world.step(DT);
    }
    for (i, &body) in bodies.iter().enumerate() {
        let b = world.body(body).unwrap();
        let y = b.position().y;
        assert!(
            b.linear_velocity().length() < 0.05,
            "body {i} still moving: {}",
            b.linear_velocity()
        );
        assert!(y > 0.05 && y < 1.0, "body {i} at y = {y}");
    }
    // The two balls on the terrain rest at its surface (y = 0.5) plus their radius.
    for &ball in &bodies[7..] {
        let y = world.body(ball).unwrap().position().y;
        assert!((y - 0.75).abs() < 0.01, "ball on terrain at {y}");
    }
}

#[test]
fn removing_the_ground_under_a_sleeping_box_wakes_it() {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let ground = ground(&mut world);
    let cube = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)), cube)
        .unwrap();
    for _ in 0..120 {
        world.step(DT);
    }
    assert_eq!(world.is_sleeping(cube), Some(true));
    let floor = world.colliders().of_body(ground)[0];
    world.remove_collider(floor).unwrap();
    assert_eq!(world.is_sleeping(cube), Some(false), "woken by the removal");
    for _ in 0..30 {
        world.step(DT);
    }
    assert!(world.body(cube).unwrap().position().y < 0.0, "falls");
}

#[test]
fn a_broken_joint_stops_disabling_contacts() {
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    let a = world.insert_body(BodyDesc::dynamic()).unwrap();
    let b = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.9, 0.0, 0.0)))
        .unwrap();
    for body in [a, b] {
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)), body)
            .unwrap();
    }
    // A weld that gives way at 1 N.
    let weld = world
        .insert_joint(
            Joint::new(FixedJoint::new())
                .with_local_anchors(Vec3::new(0.45, 0.0, 0.0), Vec3::new(-0.45, 0.0, 0.0))
                .unwrap()
                .with_break_force(1.0)
                .unwrap(),
            a,
            b,
        )
        .unwrap();
    world.set_joint_contacts_enabled(weld, false).unwrap();
    assert_eq!(world.world().backend().disabled_body_pairs().len(), 1);
    let mut broke = false;
    for _ in 0..10 {
        // Pulling b away with 100 N: the weld would have to carry about 50 N.
        world
            .body_mut(b)
            .unwrap()
            .apply_force(Vec3::new(0.0, 100.0, 0.0))
            .unwrap();
        world.step(DT);
        if world.events().contains(&Event::JointBroken { joint: weld }) {
            broke = true;
            break;
        }
        assert!(world.contacts().is_empty());
    }
    assert!(broke);
    assert!(world.world().backend().disabled_body_pairs().is_empty());
    world.step(DT);
    assert_eq!(
        world.contacts().len(),
        1,
        "the overlapping boxes collide again"
    );
}

#[test]
fn balls_moving_together_are_no_candidates_but_closing_ones_are() {
    // Three balls of radius 0.1 m in a row along x, 0.5 m apart, all moving at 30 m/s along z: each fat box
    // (speculative margin + 30 m/s · dt = 0.52 m) overlaps the next one's, but balls that move together can
    // close by no more than the margin (0.02 m) this step, and the 0.3 m gap stays. Then the middle ball
    // moves toward the first at 30 m/s: it can close 0.5 m this step, so that pair is a candidate (and gets a
    // speculative contact), the pair it leaves behind too (their relative speed is as large).
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        sleep_enabled: false,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    let balls: Vec<BodyHandle> = (0..3)
        .map(|i| {
            let body = world
                .insert_body(
                    BodyDesc::dynamic()
                        .with_position(Vec3::new(0.5 * i as f32, 0.0, 0.0))
                        .with_linear_velocity(Vec3::new(0.0, 0.0, 30.0)),
                )
                .unwrap();
            world
                .insert_collider(ColliderDesc::ball(0.1), body)
                .unwrap();
            body
        })
        .collect();
    world.step(DT);
    let pairs = world.world().backend().candidate_pairs();
    assert!(pairs.is_empty(), "balls moving together: {pairs:?}");
    assert!(world.contacts().is_empty());

    world
        .body_mut(balls[1])
        .unwrap()
        .set_linear_velocity(Vec3::new(-30.0, 0.0, 30.0))
        .unwrap();
    world.step(DT);
    let pairs = world.world().backend().candidate_pairs().len();
    assert_eq!(
        pairs, 2,
        "the middle ball closing on the first and leaving the last"
    );
    assert!(
        world
            .contacts()
            .iter()
            .any(|m| [m.body_a, m.body_b] == [balls[0], balls[1]]
                || [m.body_a, m.body_b] == [balls[1], balls[0]]),
        "the closing pair has a speculative contact"
    );
}
