//! Each shape's mass properties (computed by parry, converted at one place) against the closed forms, within
//! 1 %; placement on the body (parallel-axis theorem); sums over several colliders; density 0, disabled and
//! removed colliders giving the body back its own mass properties.

#![allow(
    clippy::unwrap_used,
    clippy::print_stdout,
    reason = "test helpers build known-good scenes (a failed setup fails the test) and print what they measured"
)]

use core::f32::consts::PI;
use rebound::prelude::*;
use rebound::{MassProperties, Mat3};

/// Relative error of `got` against `want`, with `want = 0` compared absolutely.
fn rel(got: f32, want: f32) -> f32 {
    if want == 0.0 {
        got.abs()
    } else {
        ((got - want) / want).abs()
    }
}

fn diagonal(m: Mat3) -> Vec3 {
    Vec3::new(m.x_axis.x, m.y_axis.y, m.z_axis.z)
}

/// The mass properties a single collider gives a fresh dynamic body.
fn body_mass(desc: ColliderDesc) -> MassProperties {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let body = world.insert_body(BodyDesc::dynamic()).unwrap();
    world.insert_collider(desc, body).unwrap();
    *world.body(body).unwrap().mass_properties()
}

fn assert_close(what: &str, got: MassProperties, mass: f32, com: Vec3, inertia: Vec3) {
    let tolerance = 0.01;
    assert!(
        rel(got.mass(), mass) < tolerance,
        "{what}: mass {} vs {mass}",
        got.mass()
    );
    assert!(
        got.local_center_of_mass()
            .abs_diff_eq(com, 1e-4 + tolerance * com.length()),
        "{what}: centre {} vs {com}",
        got.local_center_of_mass()
    );
    let i = diagonal(got.local_inertia());
    for axis in 0..3 {
        assert!(
            rel(i[axis], inertia[axis]) < tolerance,
            "{what}: inertia {i} vs {inertia} (axis {axis})"
        );
    }
    println!(
        "{what:9}: mass {:.6} (closed form {mass:.6}), inertia {i:.6} (closed form {inertia:.6})",
        got.mass()
    );
}

#[test]
fn every_primitive_matches_its_closed_form_within_one_percent() {
    let density = 2.5;

    let r = 0.5;
    let m = density * 4.0 / 3.0 * PI * r * r * r;
    assert_close(
        "ball",
        body_mass(ColliderDesc::ball(r).with_density(density)),
        m,
        Vec3::ZERO,
        Vec3::splat(0.4 * m * r * r),
    );

    let h = Vec3::new(0.5, 1.0, 1.5);
    let m = density * 8.0 * h.x * h.y * h.z;
    assert_close(
        "cuboid",
        body_mass(ColliderDesc::cuboid(h).with_density(density)),
        m,
        Vec3::ZERO,
        Vec3::new(
            m / 3.0 * (h.y * h.y + h.z * h.z),
            m / 3.0 * (h.x * h.x + h.z * h.z),
            m / 3.0 * (h.x * h.x + h.y * h.y),
        ),
    );

    // Capsule: a cylinder of length 2h plus a ball, with the hemispheres' parallel-axis terms.
    let (r, hh) = (0.3, 0.6);
    let (m_cyl, m_ball) = (
        density * PI * r * r * 2.0 * hh,
        density * 4.0 / 3.0 * PI * r * r * r,
    );
    let i_axis = m_cyl * r * r / 2.0 + 0.4 * m_ball * r * r;
    let i_side = m_cyl * (3.0 * r * r + 4.0 * hh * hh) / 12.0
        + m_ball * (0.4 * r * r + hh * hh + 0.75 * hh * r);
    assert_close(
        "capsule",
        body_mass(ColliderDesc::capsule(r, hh).with_density(density)),
        m_cyl + m_ball,
        Vec3::ZERO,
        Vec3::new(i_side, i_axis, i_side),
    );

    let (r, hh) = (0.4, 0.7);
    let m = density * PI * r * r * 2.0 * hh;
    let side = m * (3.0 * r * r + 4.0 * hh * hh) / 12.0;
    assert_close(
        "cylinder",
        body_mass(ColliderDesc::cylinder(r, hh).with_density(density)),
        m,
        Vec3::ZERO,
        Vec3::new(side, m * r * r / 2.0, side),
    );

    // Cone of height H = 2·hh: centre of mass H/4 above the base (at −hh), so at y = −hh/2.
    let (r, hh) = (0.5, 0.8);
    let height = 2.0 * hh;
    let m = density * PI * r * r * height / 3.0;
    let side = 3.0 / 20.0 * m * r * r + 3.0 / 80.0 * m * height * height;
    assert_close(
        "cone",
        body_mass(ColliderDesc::cone(r, hh).with_density(density)),
        m,
        Vec3::new(0.0, -hh / 2.0, 0.0),
        Vec3::new(side, 0.3 * m * r * r, side),
    );

    // The convex hull of a box's corners is the box.
    let h = Vec3::new(0.3, 0.2, 0.1);
    let corners: Vec<Vec3> = (0..8)
        .map(|i| {
            Vec3::new(
                if i & 1 == 0 { -h.x } else { h.x },
                if i & 2 == 0 { -h.y } else { h.y },
                if i & 4 == 0 { -h.z } else { h.z },
            )
        })
        .collect();
    let m = density * 8.0 * h.x * h.y * h.z;
    assert_close(
        "hull",
        body_mass(ColliderDesc::convex_hull(corners).with_density(density)),
        m,
        Vec3::ZERO,
        Vec3::new(
            m / 3.0 * (h.y * h.y + h.z * h.z),
            m / 3.0 * (h.x * h.x + h.z * h.z),
            m / 3.0 * (h.x * h.x + h.y * h.y),
        ),
    );

    // A compound of two half-boxes is the whole box.
    let half = ColliderShape::Cuboid {
        half_extents: Vec3::new(0.25, 0.5, 0.5),
    };
    let m = density * 1.0 * 1.0 * 1.0;
    assert_close(
        "compound",
        body_mass(
            ColliderDesc::compound(vec![
                (
                    Pose::from_position(Vec3::new(-0.25, 0.0, 0.0)),
                    half.clone(),
                ),
                (Pose::from_position(Vec3::new(0.25, 0.0, 0.0)), half),
            ])
            .with_density(density),
        ),
        m,
        Vec3::ZERO,
        Vec3::splat(m / 6.0),
    );
}

#[test]
fn a_collider_placed_off_centre_moves_the_centre_and_adds_the_parallel_axis_term() {
    let (r, d) = (0.5, Vec3::new(0.0, 0.0, 2.0));
    let got = body_mass(
        ColliderDesc::ball(r)
            .with_position(d)
            .with_rotation(Quat::from_rotation_x(0.7)),
    );
    let m = 4.0 / 3.0 * PI * r * r * r;
    // The body's centre of mass is the ball's centre; the tensor is about it.
    assert_close("placed", got, m, d, Vec3::splat(0.4 * m * r * r));

    // Two balls at ±d: centre at the origin, I_xx = I_yy = 2·(I_ball + m·d²), I_zz = 2·I_ball.
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let body = world.insert_body(BodyDesc::dynamic()).unwrap();
    world
        .insert_collider(ColliderDesc::ball(r).with_position(d), body)
        .unwrap();
    world
        .insert_collider(ColliderDesc::ball(r).with_position(-d), body)
        .unwrap();
    let both = *world.body(body).unwrap().mass_properties();
    let i_ball = 0.4 * m * r * r;
    assert_close(
        "two balls",
        both,
        2.0 * m,
        Vec3::ZERO,
        Vec3::new(
            2.0 * (i_ball + m * 4.0),
            2.0 * (i_ball + m * 4.0),
            2.0 * i_ball,
        ),
    );
}

#[test]
fn bodies_keep_their_own_mass_without_massive_colliders_and_recompute_on_every_change() {
    let own = MassProperties::new(7.0, Vec3::new(0.0, 0.1, 0.0), Vec3::splat(0.5)).unwrap();
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let body = world
        .insert_body(BodyDesc::dynamic().with_mass_properties(own))
        .unwrap();
    let mass = |w: &PhysicsWorld| *w.body(body).unwrap().mass_properties();

    // Density 0: the body keeps its own mass properties.
    let massless = world
        .insert_collider(ColliderDesc::cuboid(Vec3::ONE).with_density(0.0), body)
        .unwrap();
    assert_eq!(mass(&world), own);

    // A massive collider replaces them; a second one adds to it.
    let ball = world
        .insert_collider(ColliderDesc::ball(0.5).with_density(3.0), body)
        .unwrap();
    let m_ball = 3.0 * 4.0 / 3.0 * PI * 0.125;
    assert!(rel(mass(&world).mass(), m_ball) < 1e-5);
    let cube = world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(0.5))
                .with_density(2.0)
                .with_position(Vec3::X),
            body,
        )
        .unwrap();
    assert!(rel(mass(&world).mass(), m_ball + 2.0) < 1e-5);
    assert!(rel(mass(&world).local_center_of_mass().x, 2.0 / (m_ball + 2.0)) < 1e-5);

    // Disabling, changing the density, removing: recomputed each time.
    world.set_collider_enabled(cube, false).unwrap();
    assert!(rel(mass(&world).mass(), m_ball) < 1e-5);
    world.set_collider_enabled(cube, true).unwrap();
    world.set_collider_density(cube, 4.0).unwrap();
    assert!(rel(mass(&world).mass(), m_ball + 4.0) < 1e-5);
    world.remove_collider(cube).unwrap();
    assert!(rel(mass(&world).mass(), m_ball) < 1e-5);
    world.remove_collider(ball).unwrap();
    assert_eq!(mass(&world), own, "back to the body's own mass properties");
    world.remove_collider(massless).unwrap();
    assert_eq!(mass(&world), own);

    // Setting the own mass applies while no collider has mass.
    let other = MassProperties::new(2.0, Vec3::ZERO, Vec3::splat(0.2)).unwrap();
    world.set_body_mass_properties(body, other).unwrap();
    assert_eq!(mass(&world), other);
}

#[test]
fn height_fields_and_open_meshes_give_a_dynamic_body_no_mass_only_with_density_0() {
    let own = MassProperties::new(3.0, Vec3::ZERO, Vec3::splat(0.3)).unwrap();
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let body = world
        .insert_body(BodyDesc::dynamic().with_mass_properties(own))
        .unwrap();
    let field = ColliderDesc::heightfield(2, 2, vec![0.0; 4], Vec3::new(4.0, 1.0, 4.0));
    let sheet = ColliderDesc::trimesh(vec![Vec3::ZERO, Vec3::X, Vec3::Z], vec![[0, 2, 1]]);
    // With a density they would have to give mass and cannot: refused, not silently massless.
    for desc in [field.clone(), sheet.clone()] {
        let error = world.insert_collider(desc, body).unwrap_err();
        assert!(
            matches!(error, Error::Shape(ShapeError::NoVolume { .. })),
            "{error}"
        );
    }
    // With density 0 they add none, and the body keeps its own mass properties.
    for desc in [field, sheet] {
        world.insert_collider(desc.with_density(0.0), body).unwrap();
    }
    assert_eq!(*world.body(body).unwrap().mass_properties(), own);
}
