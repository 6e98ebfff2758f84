//! Contact recycling: a box pair whose bodies moved less than 1 mm and turned less than 0.5° since its
//! manifold was computed keeps the manifold's points (material points of each body) and measures only their
//! separations again, which are then exact for the kept points; beyond that, or after a collider edit, the
//! manifold is computed from scratch.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;

/// No gravity, no sleep: a unit cube resting exactly on a fixed box's top face (y = 0.5) stays where it is
/// put, so every relative pose in the tests is the one they set.
fn cube_on_a_slab() -> (PhysicsWorld, BodyHandle, ColliderHandle) {
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        sleep_enabled: false,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    let slab = world.insert_body(BodyDesc::fixed()).unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(2.0, 0.5, 2.0)), slab)
        .unwrap();
    let cube = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.1, 1.0, -0.2)))
        .unwrap();
    let collider = world
        .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)), cube)
        .unwrap();
    (world, cube, collider)
}

/// Puts the cube at `pose`, at rest.
fn place(world: &mut PhysicsWorld, cube: BodyHandle, pose: Pose) {
    let body = world.body_mut(cube).unwrap();
    body.set_pose(pose).unwrap();
    body.set_linear_velocity(Vec3::ZERO).unwrap();
    body.set_angular_velocity(Vec3::ZERO).unwrap();
}

/// The one manifold of the scene.
fn manifold(world: &PhysicsWorld) -> ContactManifold {
    assert_eq!(world.contacts().len(), 1, "{:?}", world.contacts());
    world.contacts()[0]
}

#[test]
fn a_pair_that_barely_moved_keeps_its_points_and_measures_them_exactly() {
    let (mut world, cube, _) = cube_on_a_slab();
    world.step(DT);
    let fresh = manifold(&world);
    let basis = fresh.basis.expect("a box pair's manifold has a basis");
    assert_eq!(fresh.point_count, 4);
    // 0.4 mm lower, turned 0.3° about z (under 1 mm and 0.5°): recycled.
    let moved = Pose::new(
        Vec3::new(0.1, 1.0 - 4.0e-4, -0.2),
        Quat::from_rotation_z(0.3f32.to_radians()),
    );
    place(&mut world, cube, moved);
    world.step(DT);
    let recycled = manifold(&world);
    assert_eq!(recycled.basis, Some(basis), "the basis is kept");
    for (old, new) in fresh.points().iter().zip(recycled.points()) {
        assert_eq!(new.feature_id, old.feature_id);
        assert_eq!(
            new.local_anchor_b, old.local_anchor_b,
            "a material point of the cube"
        );
        // The slab is body A (inserted first) and did not move: the separation of a kept point is the height of
        // the cube's material corner above the slab's top face.
        let expected = moved.transform_point(new.local_anchor_b).y - 0.5;
        assert!(
            (new.separation - expected).abs() < 1.0e-6,
            "{} against {expected}",
            new.separation
        );
    }
    // The corners on the side the cube turned down on went in, the others came up.
    let depths: Vec<f32> = recycled.points().iter().map(|p| p.separation).collect();
    assert!(depths.iter().any(|&s| s < -1.0e-3) && depths.iter().any(|&s| s > 1.0e-3));
}

#[test]
fn a_pair_that_moved_farther_is_computed_from_scratch() {
    let (mut world, cube, _) = cube_on_a_slab();
    world.step(DT);
    let basis = manifold(&world).basis.unwrap();
    // 2 mm sideways: beyond the 1 mm the points are kept for.
    let moved = Pose::from_position(Vec3::new(0.102, 1.0, -0.2));
    place(&mut world, cube, moved);
    world.step(DT);
    let renewed = manifold(&world).basis.unwrap();
    assert_ne!(renewed, basis);
    // The new basis is the cube's pose in the slab's frame (the slab sits at the origin).
    assert!((renewed.translation - moved.position).length() < 1.0e-6);
    assert!((renewed.local_normal - Vec3::Y).length() < 1.0e-6);
    // Turned 1° in place: beyond the 0.5° the points are kept for.
    let turned = Pose::new(moved.position, Quat::from_rotation_y(1f32.to_radians()));
    place(&mut world, cube, turned);
    world.step(DT);
    let turned_basis = manifold(&world).basis.unwrap();
    assert!((turned_basis.rotation.dot(turned.rotation).abs() - 1.0).abs() < 1.0e-6);
}

#[test]
fn a_collider_edit_is_not_hidden_by_recycling() {
    let (mut world, cube, collider) = cube_on_a_slab();
    world.step(DT);
    for p in manifold(&world).points() {
        assert!((p.local_anchor_b.x.abs() - 0.5).abs() < 1.0e-6);
    }
    // The cube's box moved 30 cm along x on its body: the body did not move, so only the edit tells that the
    // kept points (the box's old corners) are no longer on the box.
    world
        .set_collider_local_pose(collider, Pose::from_position(Vec3::new(0.3, 0.0, 0.0)))
        .unwrap();
    place(
        &mut world,
        cube,
        Pose::from_position(Vec3::new(0.1, 1.0, -0.2)),
    );
    world.step(DT);
    for p in manifold(&world).points() {
        // The moved box's bottom corners, in the body frame: x = 0.3 ± 0.5.
        assert!(
            (p.local_anchor_b.x - 0.3).abs() - 0.5 < 1.0e-6
                && (p.local_anchor_b.x - 0.3).abs() > 0.5 - 1.0e-6,
            "{:?}",
            p.local_anchor_b
        );
    }
}
