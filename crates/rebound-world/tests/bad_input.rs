//! Bad input gets a typed error that names the field and changes nothing; stale and foreign handles are
//! refused; `step` never fails.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound_dynamics::{BodyDesc, MassProperties};
use rebound_math::{Pose, Quat, Vec3};
use rebound_world::testing::SimpleBackend;
use rebound_world::{BodyHandle, StepSkipped, World, WorldError, WorldSettings};

const BAD_SCALARS: [f32; 4] = [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -1.0];

fn world() -> (World<SimpleBackend>, BodyHandle) {
    let mut world = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let ground = world.insert_body(&BodyDesc::fixed()).unwrap();
    world
        .backend_mut()
        .add_half_space(ground, Vec3::Y, 0.5, 0.0);
    let ball = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(0.0, 1.0, 0.0)))
        .unwrap();
    world.backend_mut().add_sphere(ball, 0.5, 0.5, 0.0);
    for _ in 0..5 {
        world.step(1.0 / 60.0);
    }
    (world, ball)
}

fn bad_vectors() -> Vec<Vec3> {
    vec![
        Vec3::new(f32::NAN, 0.0, 0.0),
        Vec3::new(0.0, f32::INFINITY, 0.0),
        Vec3::new(0.0, 0.0, f32::NEG_INFINITY),
    ]
}

#[test]
fn every_setter_refuses_non_finite_input_and_changes_nothing() {
    let (mut world, ball) = world();
    let digest = world.state_digest();
    let snapshot = world.snapshot();
    for v in bad_vectors() {
        let body = world.body_mut(ball).unwrap();
        assert!(body.set_position(v).is_err());
        assert!(body.set_linear_velocity(v).is_err());
        assert!(body.set_angular_velocity(v).is_err());
        assert!(body.apply_force(v).is_err());
        assert!(body.apply_force_at_point(Vec3::X, v).is_err());
        assert!(body.apply_torque(v).is_err());
        assert!(body.apply_impulse(v).is_err());
        assert!(body.apply_impulse_at_point(v, Vec3::ZERO).is_err());
        assert!(body.apply_angular_impulse(v).is_err());
        assert!(
            world
                .set_kinematic_target(ball, Pose::from_position(v))
                .is_err()
        );
    }
    for x in BAD_SCALARS {
        let body = world.body_mut(ball).unwrap();
        assert!(body.set_linear_damping(x).is_err());
        assert!(body.set_angular_damping(x).is_err());
        if !x.is_finite() {
            assert!(body.set_gravity_scale(x).is_err());
        }
    }
    for q in [
        Quat::from_xyzw(0.0, 0.0, 0.0, 0.0),
        Quat::from_xyzw(f32::NAN, 0.0, 0.0, 1.0),
        Quat::from_xyzw(0.0, 0.0, 0.0, 2.0),
    ] {
        assert!(world.body_mut(ball).unwrap().set_rotation(q).is_err());
    }
    assert_eq!(
        world.state_digest(),
        digest,
        "no failed call changed the state"
    );
    assert_eq!(
        world.snapshot(),
        snapshot,
        "nor anything else the world holds"
    );
}

#[test]
fn invalid_descriptions_are_refused_with_the_field_named() {
    let (mut world, _) = world();
    let snapshot = world.snapshot();
    let cases: Vec<(BodyDesc, &str)> = vec![
        (
            BodyDesc::dynamic().with_position(Vec3::splat(f32::NAN)),
            "position",
        ),
        (
            BodyDesc::dynamic().with_linear_velocity(Vec3::splat(f32::INFINITY)),
            "linear_velocity",
        ),
        (
            BodyDesc::dynamic().with_angular_velocity(Vec3::splat(f32::NAN)),
            "angular_velocity",
        ),
        (
            BodyDesc::dynamic().with_rotation(Quat::from_xyzw(0.0, 0.0, 0.0, 0.0)),
            "rotation",
        ),
        (
            BodyDesc::dynamic().with_linear_damping(-1.0),
            "linear_damping",
        ),
        (
            BodyDesc::dynamic().with_angular_damping(f32::NAN),
            "angular_damping",
        ),
        (
            BodyDesc::dynamic().with_gravity_scale(f32::INFINITY),
            "gravity_scale",
        ),
    ];
    for (desc, field) in cases {
        let err = world.insert_body(&desc).unwrap_err();
        assert!(err.to_string().contains(field), "{field}: {err}");
    }
    for (density, radius) in [
        (0.0, 1.0),
        (-1.0, 1.0),
        (1.0, 0.0),
        (1.0, -2.0),
        (f32::NAN, 1.0),
    ] {
        assert!(MassProperties::ball(density, radius).is_err());
    }
    assert_eq!(world.snapshot(), snapshot);
}

#[test]
fn invalid_settings_are_refused_and_the_old_ones_stay() {
    let (mut world, _) = world();
    let good = *world.settings();
    let bad = [
        WorldSettings {
            gravity: Vec3::splat(f32::NAN),
            ..good
        },
        WorldSettings {
            substep_count: 0,
            ..good
        },
        WorldSettings {
            contact_frequency_hz: 0.0,
            ..good
        },
        WorldSettings {
            contact_damping_ratio: -1.0,
            ..good
        },
        WorldSettings {
            max_push_out_speed: f32::INFINITY,
            ..good
        },
        WorldSettings {
            fixed_dt: 0.0,
            ..good
        },
        WorldSettings {
            time_to_sleep: f32::NAN,
            ..good
        },
        WorldSettings {
            linear_sleep_threshold: -0.1,
            ..good
        },
        WorldSettings {
            max_steps_per_advance: 0,
            ..good
        },
    ];
    for settings in bad {
        assert!(world.set_settings(settings).is_err(), "{settings:?}");
        assert!(World::new(settings).is_err());
    }
    assert_eq!(*world.settings(), good);
}

#[test]
fn stale_and_foreign_handles_are_refused() {
    let (mut world, ball) = world();
    let (other, foreign) = world_pair();
    assert!(
        world.body(foreign).is_none(),
        "a handle from another world does not resolve"
    );
    assert!(matches!(
        world.remove_body(foreign),
        Err(WorldError::StaleBody(_))
    ));
    assert!(other.body(foreign).is_some());

    world.backend_mut().remove_body(ball);
    let removed = world.remove_body(ball).unwrap();
    assert!(removed.body.position().is_finite());
    assert!(world.body(ball).is_none());
    assert!(world.body_mut(ball).is_none());
    assert!(matches!(
        world.remove_body(ball),
        Err(WorldError::StaleBody(_))
    ));
    assert!(world.wake_body(ball).is_err());
    assert!(world.set_kinematic_target(ball, Pose::IDENTITY).is_err());
    // The slot is reused with a new generation; the old handle still finds nothing.
    let newcomer = world.insert_body(&BodyDesc::dynamic()).unwrap();
    assert_eq!(newcomer.into_raw_parts().0, ball.into_raw_parts().0);
    assert!(world.body(ball).is_none());
    assert!(world.body(BodyHandle::invalid()).is_none());
}

fn world_pair() -> (World<SimpleBackend>, BodyHandle) {
    let mut other = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let _ = other.insert_body(&BodyDesc::fixed()).unwrap();
    let foreign = other.insert_body(&BodyDesc::dynamic()).unwrap();
    (other, foreign)
}

#[test]
fn step_never_fails_and_reports_a_bad_dt() {
    let (mut world, _) = world();
    let digest = world.state_digest();
    for dt in [0.0f32, -1.0 / 60.0] {
        let report = world.step(dt);
        assert_eq!(report.skipped, Some(StepSkipped::NonPositiveDt(dt)));
    }
    assert!(matches!(
        world.step(f32::NAN).skipped,
        Some(StepSkipped::NonFiniteDt(_))
    ));
    assert!(matches!(
        world.step(f32::INFINITY).skipped,
        Some(StepSkipped::NonFiniteDt(_))
    ));
    assert_eq!(world.state_digest(), digest, "nothing moved");
    assert!(world.step(1.0 / 60.0).skipped.is_none());
}

/// A backend that reports the manifolds it is given, whatever they hold.
struct Faulty(Vec<rebound_world::ContactManifold>);

impl rebound_world::CollisionBackend for Faulty {
    fn collide(
        &mut self,
        _: &rebound_world::BodySet,
        _: &WorldSettings,
        _: f32,
        _: &[rebound_world::ContactManifold],
        out: &mut rebound_world::ManifoldWriter<'_>,
    ) {
        out.extend_from_slice(&self.0);
    }
}

#[test]
fn a_backends_non_finite_malformed_or_stale_manifolds_are_rejected_and_change_nothing() {
    use rebound_world::{ContactManifold, ManifoldPoint};
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    };
    let mut world = World::with_backend(settings, Faulty(Vec::new())).unwrap();
    let ground = world.insert_body(&BodyDesc::fixed()).unwrap();
    let ball = world
        .insert_body(
            &BodyDesc::dynamic()
                .with_position(Vec3::new(0.0, 1.0, 0.0))
                .with_mass_properties(MassProperties::ball(1000.0, 0.5).unwrap()),
        )
        .unwrap();
    // A point 1 cm deep, pushing the ball up if the manifold were used.
    let good_point = ManifoldPoint {
        local_anchor_a: Vec3::new(0.0, 0.5, 0.0),
        local_anchor_b: Vec3::new(0.0, -0.5, 0.0),
        separation: -0.01,
        ..ManifoldPoint::default()
    };
    let manifold = |point: ManifoldPoint, normal: Vec3| {
        let mut m = ContactManifold::new(ground, ball, 0, normal, 0.5, 0.0);
        m.push_point(good_point);
        m.push_point(point);
        m
    };
    let mut bad = Vec::new();
    for value in [f32::NAN, f32::INFINITY, f32::NEG_INFINITY] {
        let mut p = good_point;
        p.separation = value;
        bad.push(manifold(p, Vec3::Y));
        for axis in 0..3 {
            let mut p = good_point;
            p.local_anchor_a[axis] = value;
            bad.push(manifold(p, Vec3::Y));
            let mut p = good_point;
            p.local_anchor_b[axis] = value;
            bad.push(manifold(p, Vec3::Y));
        }
        bad.push(manifold(good_point, Vec3::new(value, 1.0, 0.0)));
    }
    // Not a unit normal; a body against itself.
    bad.push(manifold(good_point, Vec3::new(0.0, 2.0, 0.0)));
    let mut own = manifold(good_point, Vec3::Y);
    own.body_a = ball;
    bad.push(own);
    // More points than a manifold holds; a body that is gone.
    let mut overfull = manifold(good_point, Vec3::Y);
    overfull.point_count = rebound_world::MAX_MANIFOLD_POINTS + 5;
    bad.push(overfull);
    let gone = world.insert_body(&BodyDesc::dynamic()).unwrap();
    world.remove_body(gone).unwrap();
    let mut stale = manifold(good_point, Vec3::Y);
    stale.body_b = gone;
    bad.push(stale);
    let count = bad.len();
    world.backend_mut().0 = bad;
    let report = world.step(1.0 / 60.0);
    assert_eq!(report.rejected_contact_count, count);
    assert_eq!(report.contact_count, 0);
    let body = world.body(ball).unwrap();
    assert_eq!(
        body.linear_velocity(),
        Vec3::ZERO,
        "no rejected manifold pushed"
    );
    assert_eq!(body.position(), Vec3::new(0.0, 1.0, 0.0));
    // The same manifold with finite numbers is used: it pushes the ball out (up).
    world.backend_mut().0 = vec![manifold(good_point, Vec3::Y)];
    let report = world.step(1.0 / 60.0);
    assert_eq!(report.rejected_contact_count, 0);
    assert_eq!(report.contact_count, 1);
    let y = world.body(ball).unwrap().position().y;
    assert!(y > 1.0, "{y}");
}
