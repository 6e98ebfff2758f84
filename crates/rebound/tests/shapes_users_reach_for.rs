//! The shapes users reach for: capsules and cylinders along x and z rest on the ground at their radius with
//! their axis where it was asked for; a half-space holds a box at its surface, tilted or not; a shape that
//! encloses no volume is refused on a dynamic body with a typed error, and a closed mesh gets its mass.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use rebound::Mat3;
use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;

fn world_on(ground: ColliderDesc) -> PhysicsWorld {
    let settings = WorldSettings {
        sleep_enabled: false,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    let body = world.insert_body(BodyDesc::fixed()).unwrap();
    world.insert_collider(ground, body).unwrap();
    world
}

/// Drops `desc` from 0.6 m onto a half-space floor at y = 0 and lets it settle for 2 s; returns the body's
/// height and the contact points' world positions.
fn settle(desc: ColliderDesc) -> (f32, Vec<Vec3>) {
    let mut world = world_on(ColliderDesc::half_space(Vec3::Y));
    let body = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.6, 0.0)))
        .unwrap();
    world.insert_collider(desc, body).unwrap();
    for _ in 0..120 {
        world.step(DT);
    }
    let b = world.body(body).unwrap();
    let points = world
        .contacts()
        .iter()
        .flat_map(|m| {
            let (pa, pb) = (
                world.body(m.body_a).unwrap().pose(),
                world.body(m.body_b).unwrap().pose(),
            );
            m.points()
                .iter()
                .map(move |p| p.world_point(pa, pb))
                .collect::<Vec<_>>()
        })
        .collect();
    (b.position().y, points)
}

#[test]
fn capsules_and_cylinders_along_x_and_z_lie_on_their_side_at_their_radius() {
    let (radius, half) = (0.2, 0.5);
    for (desc, axis) in [
        (ColliderDesc::capsule_x(radius, half), 0),
        (ColliderDesc::capsule_z(radius, half), 2),
        (ColliderDesc::cylinder_x(radius, half), 0),
        (ColliderDesc::cylinder_z(radius, half), 2),
    ] {
        let kind = format!("{:?}", desc.shape);
        let (y, points) = settle(desc);
        // Lying on its side: the axis is horizontal, so the centre is one radius up (soft contact: 1 mm).
        assert!((y - radius).abs() < 1e-3, "{kind}: y = {y}");
        // The contact spans the axis: points at ±half_height along it (a capsule's two cap points, a
        // cylinder's rim), none beyond.
        let extent = points
            .iter()
            .map(|p| p[axis])
            .fold(0.0f32, |m, x| m.max(x.abs()));
        assert!(
            (extent - half).abs() < 1e-2,
            "{kind}: contact reaches {extent} m along its axis"
        );
        let other = 2 - axis;
        assert!(
            points.iter().all(|p| p[other].abs() <= radius + 1e-3),
            "{kind}: {points:?}"
        );
    }
}

#[test]
fn a_box_rests_on_a_half_space_tilted_or_not() {
    for tilt in [0.0f32, 0.3] {
        let normal = Vec3::new(tilt.sin(), tilt.cos(), 0.0);
        let mut world = world_on(ColliderDesc::half_space(normal).with_friction(1.0));
        // A unit box, turned with the plane, 1 cm above it: friction 1.0 > tan(0.3) holds it.
        let rotation = Quat::from_rotation_z(-tilt);
        let body = world
            .insert_body(
                BodyDesc::dynamic()
                    .with_position(normal * 0.51)
                    .with_rotation(rotation),
            )
            .unwrap();
        world
            .insert_collider(
                ColliderDesc::cuboid(Vec3::splat(0.5)).with_friction(1.0),
                body,
            )
            .unwrap();
        for _ in 0..120 {
            world.step(DT);
        }
        let b = world.body(body).unwrap();
        let height = b.position().dot(normal);
        assert!(
            (height - 0.5).abs() < 2e-3,
            "tilt {tilt}: centre {height} m above the plane"
        );
        assert!(
            b.linear_velocity().length() < 1e-2,
            "tilt {tilt}: {}",
            b.linear_velocity()
        );
    }
}

#[test]
fn a_bad_half_space_normal_is_refused() {
    let mut world = world_on(ColliderDesc::cuboid(Vec3::splat(1.0)));
    let fixed = world.insert_body(BodyDesc::fixed()).unwrap();
    for normal in [Vec3::ZERO, Vec3::new(f32::NAN, 1.0, 0.0)] {
        let error = world
            .insert_collider(ColliderDesc::half_space(normal), fixed)
            .unwrap_err();
        assert!(error.to_string().contains("normal"), "{error}");
    }
}

/// An open mesh: one square of two triangles.
fn square() -> ColliderShape {
    ColliderShape::TriMesh {
        vertices: vec![
            Vec3::new(-1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, -1.0),
            Vec3::new(1.0, 0.0, 1.0),
            Vec3::new(-1.0, 0.0, 1.0),
        ],
        indices: vec![[0, 2, 1], [0, 3, 2]],
    }
}

/// A closed unit cube of twelve outward triangles.
fn cube() -> ColliderShape {
    let v: Vec<Vec3> = (0..8)
        .map(|i| Vec3::new((i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2) as f32) - Vec3::splat(0.5))
        .collect();
    let indices = vec![
        [0, 2, 1],
        [1, 2, 3],
        [4, 5, 6],
        [5, 7, 6],
        [0, 1, 4],
        [1, 5, 4],
        [2, 6, 3],
        [3, 6, 7],
        [0, 4, 2],
        [2, 4, 6],
        [1, 3, 5],
        [3, 7, 5],
    ];
    ColliderShape::TriMesh {
        vertices: v,
        indices,
    }
}

#[test]
fn a_shape_without_volume_on_a_dynamic_body_is_refused_and_a_closed_mesh_gets_its_mass() {
    let mut world = world_on(ColliderDesc::half_space(Vec3::Y));
    let dynamic = world.insert_body(BodyDesc::dynamic()).unwrap();
    let before = world.world().backend().colliders().iter().count();
    for shape in [
        square(),
        ColliderShape::HalfSpace { normal: Vec3::Y },
        ColliderShape::HeightField {
            rows: 2,
            cols: 2,
            heights: vec![0.0; 4],
            scale: Vec3::ONE,
        },
    ] {
        let kind = shape.kind_name();
        let error = world
            .insert_collider(ColliderDesc::new(shape.clone()), dynamic)
            .unwrap_err();
        assert!(
            matches!(error, Error::Shape(ShapeError::NoVolume { kind: k }) if k == kind),
            "{error}"
        );
        assert!(error.to_string().contains("encloses no volume"), "{error}");
        // Density 0 (the body keeps its own mass) and fixed bodies are fine.
        let desc = ColliderDesc {
            density: 0.0,
            ..ColliderDesc::new(shape.clone())
        };
        let kept = world.insert_collider(desc, dynamic).unwrap();
        world.remove_collider(kept).unwrap();
        let fixed = world.insert_body(BodyDesc::fixed()).unwrap();
        world
            .insert_collider(ColliderDesc::new(shape), fixed)
            .unwrap();
    }
    assert_eq!(
        world.world().backend().colliders().iter().count(),
        before + 3
    );
    // A closed unit cube of density 2: 2 kg, the inertia of a unit cube m/6 = 1/3 kg·m².
    world
        .insert_collider(ColliderDesc::new(cube()).with_density(2.0), dynamic)
        .unwrap();
    let mass = world.body(dynamic).unwrap().mass_properties();
    assert!((mass.mass() - 2.0).abs() < 1e-4, "{}", mass.mass());
    let inertia = mass.local_inertia();
    assert!(
        inertia.abs_diff_eq(Mat3::from_diagonal(Vec3::splat(1.0 / 3.0)), 1e-4),
        "{inertia}"
    );
}
