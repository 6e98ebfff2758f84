//! Queries against known geometry: ray distances exact to 1e-5 m, all-hits ordering, every filter
//! (groups, excluded body, sensors, disabled colliders), shape casts, point projection, overlaps, picking,
//! and queries after `body_mut` moved a body without a step.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use rebound::prelude::*;

/// Ground (top at y = 0), three unit cubes on it centred at x = 0, 3, 6 (faces at x = −0.5, 2.5, 5.5), a
/// sensor ball of radius 0.5 at x = −2.
struct Scene {
    world: PhysicsWorld,
    ground: BodyHandle,
    cubes: Vec<BodyHandle>,
    cube_colliders: Vec<ColliderHandle>,
    sensor: ColliderHandle,
}

fn scene() -> Scene {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0)), ground)
        .unwrap();
    let mut cubes = Vec::new();
    let mut cube_colliders = Vec::new();
    for (i, groups) in [
        CollisionGroups::ALL,
        CollisionGroups::new(0b10, u32::MAX),
        CollisionGroups::ALL,
    ]
    .into_iter()
    .enumerate()
    {
        let cube = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(3.0 * i as f32, 0.5, 0.0)))
            .unwrap();
        cube_colliders.push(
            world
                .insert_collider(
                    ColliderDesc::cuboid(Vec3::splat(0.5)).with_groups(groups),
                    cube,
                )
                .unwrap(),
        );
        cubes.push(cube);
    }
    let post = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(-2.0, 0.5, 0.0)))
        .unwrap();
    let sensor = world
        .insert_collider(ColliderDesc::ball(0.5).with_sensor(true), post)
        .unwrap();
    Scene {
        world,
        ground,
        cubes,
        cube_colliders,
        sensor,
    }
}

const ORIGIN: Vec3 = Vec3::new(-5.0, 0.5, 0.0);
const SOLIDS: QueryFilter = QueryFilter {
    groups: CollisionGroups::ALL,
    exclude_body: None,
    exclude_sensors: true,
};

#[test]
fn ray_casts_find_the_first_hit_and_all_hits_in_order() {
    let s = scene();
    let w = &s.world;
    // The sensor ball is hit first (its surface at x = −2.5), unless sensors are excluded.
    let hit = w
        .cast_ray(ORIGIN, Vec3::X, f32::INFINITY, &QueryFilter::new())
        .unwrap()
        .unwrap();
    assert_eq!(hit.collider, s.sensor);
    assert!((hit.distance - 2.5).abs() < 1e-5, "{}", hit.distance);

    let hit = w
        .cast_ray(ORIGIN, Vec3::X, f32::INFINITY, &SOLIDS)
        .unwrap()
        .unwrap();
    assert_eq!(hit.collider, s.cube_colliders[0]);
    assert_eq!(hit.body, s.cubes[0]);
    println!("first solid hit at {} m (exact 4.5)", hit.distance);
    assert!((hit.distance - 4.5).abs() < 1e-5);
    assert!(hit.point.abs_diff_eq(Vec3::new(-0.5, 0.5, 0.0), 1e-5));
    assert!(hit.normal.abs_diff_eq(-Vec3::X, 1e-5));

    // A non-unit direction is normalised: distances stay in metres.
    let scaled = w
        .cast_ray(ORIGIN, Vec3::X * 7.0, 100.0, &SOLIDS)
        .unwrap()
        .unwrap();
    assert!((scaled.distance - 4.5).abs() < 1e-5);
    // Out of range.
    assert!(w.cast_ray(ORIGIN, Vec3::X, 4.4, &SOLIDS).unwrap().is_none());

    let all = w.cast_ray_all(ORIGIN, Vec3::X, 100.0, &SOLIDS).unwrap();
    let distances: Vec<f32> = all.iter().map(|h| h.distance).collect();
    println!("all hits: {distances:?}");
    assert_eq!(
        all.iter().map(|h| h.collider).collect::<Vec<_>>(),
        s.cube_colliders,
        "nearest first"
    );
    for (d, want) in distances.iter().zip([4.5, 7.5, 10.5]) {
        assert!((d - want).abs() < 1e-5, "{d} vs {want}");
    }
    // Straight down onto the ground between the cubes.
    let down = w
        .cast_ray(Vec3::new(1.5, 10.0, 0.0), -Vec3::Y, f32::INFINITY, &SOLIDS)
        .unwrap()
        .unwrap();
    assert_eq!(down.body, s.ground);
    assert!((down.distance - 10.0).abs() < 1e-5);
}

#[test]
fn filters_exclude_what_they_should() {
    let mut s = scene();
    let first = |w: &PhysicsWorld, f: &QueryFilter| {
        w.cast_ray(ORIGIN, Vec3::X, 100.0, f)
            .unwrap()
            .map(|h| h.collider)
    };
    // Excluding the first cube's body: the second cube.
    let skip_first = SOLIDS.excluding_body(s.cubes[0]);
    assert_eq!(first(&s.world, &skip_first), Some(s.cube_colliders[1]));
    // Also excluding group 2 (the second cube's only membership): the third cube.
    let only_group_1 = skip_first.with_groups(CollisionGroups::new(u32::MAX, 0b01));
    assert_eq!(first(&s.world, &only_group_1), Some(s.cube_colliders[2]));
    // A query whose memberships the colliders' filters reject sees nothing.
    let nobody = SOLIDS.with_groups(CollisionGroups::new(0, u32::MAX));
    assert_eq!(first(&s.world, &nobody), None);
    // Disabled colliders are never seen.
    s.world
        .set_collider_enabled(s.cube_colliders[0], false)
        .unwrap();
    assert_eq!(first(&s.world, &SOLIDS), Some(s.cube_colliders[1]));
    let all = s
        .world
        .cast_ray_all(ORIGIN, Vec3::X, 100.0, &QueryFilter::new())
        .unwrap();
    assert_eq!(all.len(), 3, "sensor, second and third cube");
    assert!(
        s.world
            .intersect_shape(
                &ColliderShape::Ball { radius: 0.1 },
                Pose::from_position(Vec3::new(0.0, 0.5, 0.0)),
                &QueryFilter::new()
            )
            .unwrap()
            .is_empty()
    );
}

#[test]
fn shape_casts_projections_overlaps_and_picking() {
    let s = scene();
    let w = &s.world;
    // A ball of radius 0.25 swept along +x touches the first cube after 4.25 m.
    let ball = ColliderShape::Ball { radius: 0.25 };
    let hit = w
        .cast_shape(&ball, Pose::from_position(ORIGIN), Vec3::X, 20.0, &SOLIDS)
        .unwrap()
        .unwrap();
    println!("shape cast: {} m (exact 4.25)", hit.distance);
    assert_eq!(hit.collider, s.cube_colliders[0]);
    assert!((hit.distance - 4.25).abs() < 1e-3);
    assert!(
        hit.point.abs_diff_eq(Vec3::new(-0.5, 0.5, 0.0), 1e-3),
        "{}",
        hit.point
    );
    assert!(hit.normal.abs_diff_eq(-Vec3::X, 1e-3), "{}", hit.normal);
    // Too short a sweep misses.
    assert!(
        w.cast_shape(&ball, Pose::from_position(ORIGIN), Vec3::X, 4.0, &SOLIDS)
            .unwrap()
            .is_none()
    );

    // The closest point to (3, 3, 0) is the top of the second cube, 2 m below.
    let p = w
        .project_point(Vec3::new(3.0, 3.0, 0.0), f32::INFINITY, &SOLIDS)
        .unwrap()
        .unwrap();
    assert_eq!(p.collider, s.cube_colliders[1]);
    assert!((p.distance - 2.0).abs() < 1e-5 && p.point.abs_diff_eq(Vec3::new(3.0, 1.0, 0.0), 1e-5));
    assert!(!p.is_inside);
    let inside = w
        .project_point(Vec3::new(6.0, 0.5, 0.0), 0.0, &SOLIDS)
        .unwrap()
        .unwrap();
    assert!(inside.is_inside && inside.distance == 0.0);
    assert!(
        w.project_point(Vec3::new(3.0, 3.0, 0.0), 1.0, &SOLIDS)
            .unwrap()
            .is_none()
    );

    // A ball of radius 1 at the second cube's centre overlaps that cube and the ground only.
    let mut found = w
        .intersect_shape(
            &ColliderShape::Ball { radius: 1.0 },
            Pose::from_position(Vec3::new(3.0, 0.5, 0.0)),
            &QueryFilter::new(),
        )
        .unwrap();
    found.sort_unstable();
    let ground_collider = w.colliders().of_body(s.ground)[0];
    let mut want = vec![ground_collider, s.cube_colliders[1]];
    want.sort_unstable();
    assert_eq!(found, want);

    // Picking from above: the third cube, held at its top face centre.
    let pick = w
        .pick_body(Vec3::new(6.0, 10.0, 0.0), -Vec3::Y, 100.0)
        .unwrap()
        .unwrap();
    assert_eq!(pick.body, s.cubes[2]);
    assert!(pick.local_point.abs_diff_eq(Vec3::new(0.0, 0.5, 0.0), 1e-5));
    // The ground is fixed: nothing to pick there. The sensor is looked through.
    assert!(
        w.pick_body(Vec3::new(1.5, 10.0, 0.0), -Vec3::Y, 100.0)
            .unwrap()
            .is_none()
    );
    assert_eq!(
        w.pick_body(ORIGIN, Vec3::X, 100.0).unwrap().map(|p| p.body),
        Some(s.cubes[0])
    );
}

#[test]
fn queries_see_bodies_moved_by_hand_and_by_steps() {
    let mut s = scene();
    // Teleport the first cube 1 m towards the ray origin: no step, the BVH is stale, the answer is not.
    s.world
        .body_mut(s.cubes[0])
        .unwrap()
        .set_position(Vec3::new(-1.0, 0.5, 0.0))
        .unwrap();
    let hit = s
        .world
        .cast_ray(ORIGIN, Vec3::X, 100.0, &SOLIDS)
        .unwrap()
        .unwrap();
    assert!((hit.distance - 3.5).abs() < 1e-5, "{}", hit.distance);
    s.world.refresh_queries();
    let hit = s
        .world
        .cast_ray(ORIGIN, Vec3::X, 100.0, &SOLIDS)
        .unwrap()
        .unwrap();
    assert!((hit.distance - 3.5).abs() < 1e-5);
    // After a step the tree holds the new poses (a cube given a velocity has moved).
    s.world
        .body_mut(s.cubes[0])
        .unwrap()
        .set_linear_velocity(Vec3::new(0.0, 6.0, 0.0))
        .unwrap();
    s.world.step(1.0 / 60.0);
    let y = s.world.body(s.cubes[0]).unwrap().position().y;
    let hit = s
        .world
        .cast_ray(Vec3::new(-1.0, 10.0, 0.0), -Vec3::Y, 100.0, &SOLIDS)
        .unwrap()
        .unwrap();
    assert_eq!(hit.body, s.cubes[0]);
    assert!((hit.distance - (10.0 - (y + 0.5))).abs() < 1e-5);
    // The tree may keep the box the step's pair search fattened by the cube's motion (it still contains the
    // cube): a ray passing 1 cm over the moved cube, inside that box, hits nothing.
    let over = s
        .world
        .cast_ray(Vec3::new(-5.0, y + 0.51, 0.0), Vec3::X, 100.0, &SOLIDS)
        .unwrap();
    assert!(over.is_none(), "{over:?}");
}

#[test]
fn bad_query_input_is_an_error() {
    let s = scene();
    let w = &s.world;
    let f = QueryFilter::new();
    assert!(w.cast_ray(Vec3::NAN, Vec3::X, 1.0, &f).is_err());
    assert!(w.cast_ray(ORIGIN, Vec3::ZERO, 1.0, &f).is_err());
    assert!(w.cast_ray(ORIGIN, Vec3::X, -1.0, &f).is_err());
    assert!(w.cast_ray_all(ORIGIN, Vec3::X, f32::NAN, &f).is_err());
    assert!(w.project_point(Vec3::INFINITY, 1.0, &f).is_err());
    let ball = ColliderShape::Ball { radius: 0.5 };
    assert!(
        w.cast_shape(&ball, Pose::IDENTITY, Vec3::X, f32::INFINITY, &f)
            .is_err()
    );
    assert!(
        w.cast_shape(
            &ColliderShape::Ball { radius: -1.0 },
            Pose::IDENTITY,
            Vec3::X,
            1.0,
            &f
        )
        .is_err()
    );
    assert!(
        w.intersect_shape(
            &ball,
            Pose::new(Vec3::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 2.0)),
            &f
        )
        .is_err()
    );
    assert!(w.pick_body(ORIGIN, Vec3::NAN, 1.0).is_err());
}
