//! Bad input gets a typed error that names the field and the value, and leaves the world unchanged: invalid
//! shapes (sizes, hull points, meshes, height fields, compounds), materials, local poses, stale and foreign
//! handles. Nothing here may panic, including inside parry.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use rebound::prelude::*;
use rebound::{MAX_SHAPE_COORDINATE, MathError};

fn world_with_body() -> (PhysicsWorld, BodyHandle) {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let body = world.insert_body(BodyDesc::dynamic()).unwrap();
    world
        .insert_collider(ColliderDesc::ball(0.5), body)
        .unwrap();
    (world, body)
}

fn cube_corners() -> Vec<Vec3> {
    (0..8)
        .map(|i| Vec3::new((i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32))
        .collect()
}

/// A description, a string the error message must contain, and a check of the error's variant.
type Case = (ColliderDesc, &'static str, fn(&Error) -> bool);

#[test]
fn invalid_colliders_are_refused_with_the_field_named() {
    let nested = ColliderShape::Compound {
        parts: vec![(Pose::IDENTITY, ColliderShape::Ball { radius: 1.0 })],
    };
    // (description, a string the message must contain, the error must match)
    let table: Vec<Case> = vec![
        (
            ColliderDesc::ball(0.0),
            "`radius` must be > 0, got 0",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::Math(MathError::NotPositive {
                        field: "radius",
                        ..
                    }))
                )
            },
        ),
        (
            ColliderDesc::ball(-1.0),
            "`radius` must be > 0, got -1",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::Math(MathError::NotPositive { .. }))
                )
            },
        ),
        (
            ColliderDesc::ball(f32::NAN),
            "`radius` must be finite, got NaN",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::Math(MathError::NonFinite { .. }))
                )
            },
        ),
        (
            ColliderDesc::ball(f32::INFINITY),
            "`radius` must be finite",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::Math(MathError::NonFinite { .. }))
                )
            },
        ),
        (
            ColliderDesc::ball(MAX_SHAPE_COORDINATE * 2.0),
            "`radius` must be at most 1000000 m in magnitude, got 2000000",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::TooLarge {
                        field: "radius",
                        ..
                    })
                )
            },
        ),
        (
            ColliderDesc::cuboid(Vec3::new(1.0, 0.0, 1.0)),
            "`half_extents` must be > 0, got 0",
            |e| matches!(e, Error::Shape(ShapeError::Math(_))),
        ),
        (
            ColliderDesc::cuboid(Vec3::new(1.0, f32::NAN, 1.0)),
            "`half_extents` must be finite",
            |e| matches!(e, Error::Shape(ShapeError::Math(_))),
        ),
        (
            ColliderDesc::cuboid(Vec3::new(-1.0, 1.0, 1.0)),
            "`half_extents` must be > 0, got -1",
            |e| matches!(e, Error::Shape(_)),
        ),
        (
            ColliderDesc::capsule(0.5, -0.1),
            "`half_height` must be >= 0, got -0.1",
            |e| matches!(e, Error::Shape(_)),
        ),
        (
            ColliderDesc::capsule(0.0, 1.0),
            "`radius` must be > 0",
            |e| matches!(e, Error::Shape(_)),
        ),
        (
            ColliderDesc::cylinder(0.5, 0.0),
            "`half_height` must be > 0, got 0",
            |e| matches!(e, Error::Shape(_)),
        ),
        (
            ColliderDesc::cone(f32::NAN, 1.0),
            "`radius` must be finite",
            |e| matches!(e, Error::Shape(_)),
        ),
        (
            ColliderDesc::convex_hull(cube_corners()[..3].to_vec()),
            "at least 4 points that are not coplanar, got 3",
            |e| matches!(e, Error::Shape(ShapeError::DegenerateHull { count: 3, .. })),
        ),
        (
            ColliderDesc::convex_hull(vec![
                Vec3::ZERO,
                Vec3::X,
                Vec3::Z,
                Vec3::new(1.0, 0.0, 1.0),
                Vec3::new(0.5, 0.0, 0.3),
            ]),
            "not coplanar, got 5 points",
            |e| matches!(e, Error::Shape(ShapeError::DegenerateHull { count: 5, .. })),
        ),
        (
            ColliderDesc::convex_hull(vec![Vec3::ZERO; 6]),
            "not coplanar",
            |e| matches!(e, Error::Shape(ShapeError::DegenerateHull { .. })),
        ),
        (
            ColliderDesc::convex_hull({
                let mut p = cube_corners();
                p[5].y = f32::NAN;
                p
            }),
            "`points[5]` must be finite",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::NonFiniteVertex { index: 5, .. })
                )
            },
        ),
        (
            ColliderDesc::trimesh(vec![Vec3::ZERO, Vec3::X, Vec3::Z], vec![[0, 1, 3]]),
            "`indices[0]` names vertex 3, but the mesh has only 3 vertices",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::IndexOutOfRange {
                        triangle: 0,
                        index: 3,
                        vertex_count: 3
                    })
                )
            },
        ),
        (
            ColliderDesc::trimesh(
                vec![Vec3::ZERO, Vec3::X, Vec3::new(0.0, f32::INFINITY, 0.0)],
                vec![[0, 1, 2]],
            ),
            "`vertices[2]` must be finite",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::NonFiniteVertex { index: 2, .. })
                )
            },
        ),
        (
            ColliderDesc::trimesh(vec![Vec3::ZERO], Vec::new()),
            "needs vertices and triangles, got 1 vertices and 0 triangles",
            |e| matches!(e, Error::Shape(ShapeError::EmptyMesh { .. })),
        ),
        (
            ColliderDesc::heightfield(1, 5, vec![0.0; 5], Vec3::ONE),
            "rows ≥ 2, cols ≥ 2",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::HeightFieldSize {
                        rows: 1,
                        cols: 5,
                        ..
                    })
                )
            },
        ),
        (
            ColliderDesc::heightfield(3, 3, vec![0.0; 8], Vec3::ONE),
            "with 8 heights",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::HeightFieldSize {
                        height_count: 8,
                        ..
                    })
                )
            },
        ),
        (
            ColliderDesc::heightfield(2, 2, vec![0.0, 0.0, f32::NAN, 0.0], Vec3::ONE),
            "`heights[2]` (row 1, column 0) must be finite, got NaN",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::NonFiniteHeight {
                        index: 2,
                        row: 1,
                        col: 0,
                        ..
                    })
                )
            },
        ),
        (
            ColliderDesc::heightfield(2, 2, vec![0.0; 4], Vec3::new(1.0, 0.0, 1.0)),
            "`scale` must be > 0, got 0",
            |e| matches!(e, Error::Shape(_)),
        ),
        (
            ColliderDesc::compound(Vec::new()),
            "at least one part",
            |e| matches!(e, Error::Shape(ShapeError::EmptyCompound)),
        ),
        (
            ColliderDesc::compound(vec![(Pose::IDENTITY, nested)]),
            "compound part 0 is a compound",
            |e| {
                matches!(
                    e,
                    Error::Shape(ShapeError::NestedComposite { index: 0, .. })
                )
            },
        ),
        (
            ColliderDesc::compound(vec![
                (Pose::IDENTITY, ColliderShape::Ball { radius: 1.0 }),
                (Pose::IDENTITY, ColliderShape::Ball { radius: -2.0 }),
            ]),
            "compound part 1: `radius` must be > 0, got -2",
            |e| matches!(e, Error::Shape(ShapeError::InvalidPart { index: 1, .. })),
        ),
        (
            ColliderDesc::compound(vec![(
                Pose::new(Vec3::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 3.0)),
                ColliderShape::Ball { radius: 1.0 },
            )]),
            "compound part 0: `pose` must be a unit quaternion",
            |e| matches!(e, Error::Shape(ShapeError::InvalidPart { .. })),
        ),
        (
            ColliderDesc::ball(1.0).with_density(-1.0),
            "`density` must be >= 0, got -1",
            |e| {
                matches!(
                    e,
                    Error::Math(MathError::Negative {
                        field: "density",
                        ..
                    })
                )
            },
        ),
        (
            ColliderDesc::ball(1.0).with_density(f32::NAN),
            "`density` must be finite",
            |e| matches!(e, Error::Math(_)),
        ),
        (
            ColliderDesc::ball(1.0).with_friction(-0.5),
            "`friction` must be >= 0, got -0.5",
            |e| matches!(e, Error::Math(_)),
        ),
        (
            ColliderDesc::ball(1.0).with_restitution(1.5),
            "`restitution` must lie in [0, 1], got 1.5",
            |e| {
                matches!(
                    e,
                    Error::OutOfRange {
                        field: "restitution",
                        ..
                    }
                )
            },
        ),
        (
            ColliderDesc::ball(1.0).with_rolling_friction(f32::INFINITY),
            "`rolling_friction` must be finite",
            |e| matches!(e, Error::Math(_)),
        ),
        (
            ColliderDesc::ball(1.0).with_position(Vec3::new(f32::NAN, 0.0, 0.0)),
            "`local_pose` must be finite",
            |e| matches!(e, Error::Shape(ShapeError::Math(_))),
        ),
        (
            ColliderDesc::ball(1.0).with_rotation(Quat::from_xyzw(0.0, 0.0, 0.0, 0.0)),
            "`local_pose` must be a unit quaternion",
            |e| matches!(e, Error::Shape(ShapeError::Math(_))),
        ),
        (
            ColliderDesc::ball(1.0e5).with_density(1.0e30),
            "mass properties of the shape at density 1000000000000000000000000000000",
            |e| matches!(e, Error::Shape(ShapeError::MassProperties { .. })),
        ),
        (
            // Tiny but positive: a mass of 8e-41 kg, whose inverse overflows.
            ColliderDesc::cuboid(Vec3::splat(1.0e-13)).with_density(0.01),
            "`mass` must be at least",
            |e| matches!(e, Error::Shape(ShapeError::MassProperties { .. })),
        ),
    ];
    let (mut world, body) = world_with_body();
    let before = (
        world.colliders().len(),
        *world.body(body).unwrap().mass_properties(),
        world.state_digest(),
    );
    for (i, (desc, message, is_expected)) in table.into_iter().enumerate() {
        let error = world
            .insert_collider(desc.clone(), body)
            .expect_err(&format!("case {i}"));
        let text = error.to_string();
        assert!(
            text.contains(message),
            "case {i}: `{text}` does not contain `{message}`"
        );
        assert!(is_expected(&error), "case {i}: unexpected {error:?}");
        let after = (
            world.colliders().len(),
            *world.body(body).unwrap().mass_properties(),
            world.state_digest(),
        );
        assert_eq!(after, before, "case {i} changed the world");
        // The same checks reject the shape in queries.
        assert!(
            world
                .intersect_shape(&desc.shape, Pose::IDENTITY, &QueryFilter::new())
                .is_err()
                || desc.shape.validate().is_ok()
        );
    }
}

#[test]
fn stale_and_foreign_handles_are_errors() {
    let (mut world, body) = world_with_body();
    let collider = world.colliders().of_body(body)[0];
    let (mut other, other_body) = world_with_body();
    let other_collider = other.colliders().of_body(other_body)[0];
    // A handle from another world is refused.
    assert!(world.collider(other_collider).is_none());
    assert!(matches!(
        world.remove_collider(other_collider),
        Err(Error::StaleCollider(_))
    ));
    assert!(matches!(
        world.set_collider_friction(other_collider, 0.3),
        Err(Error::StaleCollider(_))
    ));
    assert!(matches!(
        world.insert_collider(ColliderDesc::ball(1.0), other_body),
        Err(Error::World(WorldError::StaleBody(_)))
    ));
    // Removing a body removes its colliders: their handles go stale.
    world.remove_body(body).unwrap();
    assert!(world.collider(collider).is_none());
    assert!(world.colliders().is_empty());
    assert!(matches!(
        world.set_collider_enabled(collider, false),
        Err(Error::StaleCollider(_))
    ));
    assert!(matches!(
        world.remove_body(body),
        Err(Error::World(WorldError::StaleBody(_)))
    ));
    assert!(
        world
            .set_joint_contacts_enabled(JointHandle::invalid(), false)
            .is_err()
    );
    assert!(world.collider(ColliderHandle::invalid()).is_none());
    // A slot reused by a new collider does not answer to the old handle.
    let body = world.insert_body(BodyDesc::dynamic()).unwrap();
    let fresh = world
        .insert_collider(ColliderDesc::ball(1.0), body)
        .unwrap();
    assert_eq!(fresh.into_raw_parts().0, collider.into_raw_parts().0);
    assert!(world.collider(collider).is_none() && world.collider(fresh).is_some());
    // Setters check their values and change nothing on error.
    let desc = world.collider(fresh).unwrap().desc().clone();
    assert!(world.set_collider_friction(fresh, f32::NAN).is_err());
    assert!(world.set_collider_restitution(fresh, -0.1).is_err());
    assert!(world.set_collider_density(fresh, f32::INFINITY).is_err());
    assert!(
        world
            .set_collider_local_pose(
                fresh,
                Pose::new(Vec3::ZERO, Quat::from_xyzw(1.0, 1.0, 0.0, 0.0))
            )
            .is_err()
    );
    assert_eq!(world.collider(fresh).unwrap().desc(), &desc);
    other.step(1.0 / 60.0);
}

#[test]
fn the_step_never_fails() {
    let (mut world, body) = world_with_body();
    for dt in [0.0, -1.0, f32::NAN, f32::INFINITY] {
        let report = world.step(dt);
        assert!(report.skipped.is_some());
    }
    assert_eq!(world.body(body).unwrap().position(), Vec3::ZERO);
    let report = world.advance(f32::NAN);
    assert_eq!(report.steps, 0);
    let report = world.advance(0.1);
    assert_eq!(report.steps, 6);
}
