//! The step's phases proven by behaviour on a half-space: a ball dropped from 2 m bounces to C_r²·2 m
//! (the bounce inside the contact solve), comes to rest and falls asleep (islands and sleep); a column of five
//! spheres settles without jitter (soft contacts, relax, warm starting); every wake trigger works.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound_dynamics::{BodyDesc, MassProperties};
use rebound_math::{Pose, Vec3};
use rebound_world::testing::SimpleBackend;
use rebound_world::{BodyHandle, Event, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;
const RADIUS: f32 = 0.25;

fn ground_world() -> (World<SimpleBackend>, BodyHandle) {
    let mut world = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let ground = world.insert_body(&BodyDesc::fixed()).unwrap();
    world
        .backend_mut()
        .add_half_space(ground, Vec3::Y, 0.5, 0.0);
    (world, ground)
}

fn add_ball(world: &mut World<SimpleBackend>, position: Vec3, restitution: f32) -> BodyHandle {
    let ball = world
        .insert_body(
            &BodyDesc::dynamic()
                .with_position(position)
                .with_mass_properties(MassProperties::ball(1000.0, RADIUS).unwrap()),
        )
        .unwrap();
    world
        .backend_mut()
        .add_sphere(ball, RADIUS, 0.5, restitution);
    ball
}

#[test]
fn a_dropped_ball_bounces_to_restitution_squared_then_rests_and_sleeps() {
    for restitution in [0.5f32, 0.8] {
        let (mut world, _) = ground_world();
        let drop = 2.0;
        let ball = add_ball(&mut world, Vec3::new(0.0, RADIUS + drop, 0.0), restitution);
        let mut apex = 0.0f32;
        let mut bounced = false;
        let mut fell_asleep_at = None;
        for step in 0..900 {
            world.step(DT);
            let b = world.body(ball).unwrap();
            if !bounced && b.linear_velocity().y > 0.0 {
                bounced = true;
            }
            if bounced && apex >= 0.0 {
                let height = b.position().y - RADIUS;
                if b.linear_velocity().y < 0.0 && apex > 0.0 {
                    let expected = restitution * restitution * drop;
                    assert!(
                        (apex - expected).abs() < 0.03 * expected,
                        "C_r = {restitution}: first apex {apex} m, expected {expected} m ± 3 %"
                    );
                    apex = -1.0; // measured once
                } else if apex >= 0.0 {
                    apex = apex.max(height);
                }
            }
            if world
                .events()
                .iter()
                .any(|e| matches!(e, Event::BodyFellAsleep { body } if *body == ball))
            {
                fell_asleep_at = Some(step);
                break;
            }
        }
        assert!(apex < 0.0, "the ball never reached its first apex");
        let step = fell_asleep_at.expect("the ball should fall asleep once at rest");
        let b = world.body(ball).unwrap();
        assert!(b.is_sleeping());
        assert!(
            (b.position().y - RADIUS).abs() < 2e-3,
            "asleep on the ground, at {}",
            b.position().y
        );
        // Asleep means skipped: stepping on does not move it by a single bit.
        let digest = world.state_digest();
        for _ in 0..60 {
            let report = world.step(DT);
            assert_eq!(report.awake_body_count, 0);
        }
        assert_eq!(
            world.state_digest(),
            digest,
            "a sleeping world does not change (slept at step {step})"
        );
    }
}

#[test]
fn a_stack_of_five_spheres_settles_without_jitter() {
    // A column of five spheres on the ground. Ideal spheres make it an unstable equilibrium — an inverted
    // pendulum that rounding noise topples exactly as noise topples a real one — so the contacts carry a
    // little rolling resistance (5 mm lever arm), as real balls have.
    let (mut world, _) = ground_world();
    world.backend_mut().rolling_friction = 0.005;
    let balls: Vec<_> = (0..5)
        .map(|i| {
            let y = RADIUS + 2.0 * RADIUS * i as f32 + 0.01 * i as f32;
            add_ball(&mut world, Vec3::new(0.0, y, 0.0), 0.0)
        })
        .collect();
    let mut settings = *world.settings();
    settings.sleep_enabled = false;
    world.set_settings(settings).unwrap();
    for _ in 0..120 {
        world.step(DT);
    }
    let mut max_speed = 0.0f32;
    for _ in 0..120 {
        world.step(DT);
        for &b in &balls {
            let body = world.body(b).unwrap();
            max_speed = max_speed
                .max(body.linear_velocity().length() + RADIUS * body.angular_velocity().length());
        }
    }
    assert!(max_speed < 1e-3, "jitter: {max_speed} m/s");
    // A soft contact of natural frequency f holds a load F with the overlap of a spring of stiffness
    // m_eff·ω² (ω = 2πf): s = F / (m_eff·ω²). Ground contacts (one body immovable: m_eff = m, twice the
    // frequency) carry all five balls; the contact above ball i carries 4 − i balls between two equal
    // balls (m_eff = m/2). Preloaded with that load, a resting contact keeps at most the resting overlap ε:
    // it overlaps min(ε, s) (docs/physics.md, "Contacts under load").
    let g = 9.81f32;
    let omega = core::f32::consts::TAU * settings.contact_frequency_hz;
    let resting = settings.resting_overlap.unwrap_or(f32::INFINITY);
    let mut expected = RADIUS - (5.0 * g / (2.0 * omega).powi(2)).min(resting);
    for (i, &b) in balls.iter().enumerate() {
        if i > 0 {
            let load = (5 - i) as f32;
            expected += 2.0 * RADIUS - (load * g / (0.5 * omega * omega)).min(resting);
        }
        let p = world.body(b).unwrap().position();
        assert!(
            (p.y - expected).abs() < 1e-4,
            "ball {i} at {}, soft-contact prediction {expected}",
            p.y
        );
        assert!(
            Vec3::new(p.x, 0.0, p.z).length() < 1e-4,
            "ball {i} drifted sideways to {p}"
        );
    }
}

/// Builds a resting ball, lets it fall asleep, and returns the world.
fn sleeping_ball() -> (World<SimpleBackend>, BodyHandle, BodyHandle) {
    let (mut world, ground) = ground_world();
    let ball = add_ball(&mut world, Vec3::new(0.0, RADIUS, 0.0), 0.0);
    for _ in 0..120 {
        world.step(DT);
    }
    assert!(
        world.is_sleeping(ball).unwrap(),
        "the resting ball should be asleep after 2 s"
    );
    (world, ground, ball)
}

fn woke(world: &World<SimpleBackend>, ball: BodyHandle) -> bool {
    world
        .events()
        .iter()
        .any(|e| matches!(e, Event::BodyWoke { body } if *body == ball))
}

#[test]
fn every_wake_trigger_wakes_the_island() {
    // A force.
    let (mut world, _, ball) = sleeping_ball();
    world
        .body_mut(ball)
        .unwrap()
        .apply_force(Vec3::new(50.0, 0.0, 0.0))
        .unwrap();
    world.step(DT);
    assert!(
        !world.is_sleeping(ball).unwrap() && woke(&world, ball),
        "force"
    );
    assert!(world.body(ball).unwrap().linear_velocity().x > 0.0);

    // An impulse.
    let (mut world, _, ball) = sleeping_ball();
    world
        .body_mut(ball)
        .unwrap()
        .apply_impulse(Vec3::new(0.0, 1.0, 0.0))
        .unwrap();
    world.step(DT);
    assert!(
        !world.is_sleeping(ball).unwrap() && woke(&world, ball),
        "impulse"
    );

    // A setter.
    let (mut world, _, ball) = sleeping_ball();
    world
        .body_mut(ball)
        .unwrap()
        .set_linear_velocity(Vec3::new(0.0, 0.0, 1.0))
        .unwrap();
    world.step(DT);
    assert!(
        !world.is_sleeping(ball).unwrap() && woke(&world, ball),
        "setter"
    );

    // A touch: another ball dropped onto it.
    let (mut world, _, ball) = sleeping_ball();
    let other = add_ball(&mut world, Vec3::new(0.0, 3.0 * RADIUS + 0.3, 0.0), 0.0);
    let mut touched = false;
    for _ in 0..60 {
        world.step(DT);
        if woke(&world, ball) {
            touched = true;
            break;
        }
    }
    assert!(touched, "touch");
    assert!(world.body(other).is_some());

    // The explicit call.
    let (mut world, _, ball) = sleeping_ball();
    world.wake_body(ball).unwrap();
    world.step(DT);
    assert!(woke(&world, ball), "wake_body");
}

#[test]
fn a_kinematic_body_pushes_a_dynamic_one_and_is_not_pushed_back() {
    let (mut world, _) = ground_world();
    let ball = add_ball(&mut world, Vec3::new(0.0, RADIUS, 0.0), 0.0);
    let pusher = world
        .insert_body(&BodyDesc::kinematic().with_position(Vec3::new(-1.0, RADIUS, 0.0)))
        .unwrap();
    world.backend_mut().add_sphere(pusher, RADIUS, 0.0, 0.0);
    // Drive the pusher by target poses at 1 m/s along +x for 1.5 s.
    for step in 1..=90 {
        let target = Pose::from_position(Vec3::new(-1.0 + step as f32 * DT, RADIUS, 0.0));
        world.set_kinematic_target(pusher, target).unwrap();
        world.step(DT);
        let p = world.body(pusher).unwrap().position();
        assert!(
            (p - target.position).length() < 1e-5,
            "the pusher follows its targets exactly: {p}"
        );
    }
    let x = world.body(ball).unwrap().position().x;
    // The pusher ends at x = 0.5; the ball must be ahead of it by at least the two radii.
    assert!(x >= 0.5 + 2.0 * RADIUS - 0.01, "the ball was pushed to {x}");
}

#[test]
fn advance_runs_whole_fixed_steps_and_returns_the_interpolation_factor() {
    let (mut world, _) = ground_world();
    let report = world.advance(0.04);
    assert_eq!(report.steps, 2, "0.04 s holds two 1/60 s steps");
    assert!((report.alpha - (0.04 - 2.0 / 60.0) * 60.0).abs() < 1e-4);
    let report = world.advance(0.012);
    assert_eq!(
        report.steps, 1,
        "the leftover 0.0067 s plus 0.012 s make one more step"
    );
    assert_eq!(world.step_count(), 3);
    // A huge frame is capped at max_steps_per_advance and the excess is dropped, not queued.
    let report = world.advance(10.0);
    assert_eq!(report.steps, 8);
    assert!(report.dropped_time > 9.0);
    assert!(report.alpha < 1.0);
    // Nonsense time adds nothing.
    assert_eq!(world.advance(f32::NAN).steps, 0);
    assert_eq!(world.advance(-1.0).steps, 0);
}

#[test]
fn contact_events_report_begin_with_approach_speed_and_end() {
    let (mut world, ground) = ground_world();
    let ball = add_ball(&mut world, Vec3::new(0.0, RADIUS + 1.0, 0.0), 0.5);
    let mut began = None;
    for _ in 0..120 {
        world.step(DT);
        for event in world.events() {
            if let Event::ContactBegan {
                body_a,
                body_b,
                approach_speed,
            } = *event
            {
                assert_eq!((body_a, body_b), (ground, ball));
                began.get_or_insert(approach_speed);
            }
        }
        if began.is_some() {
            break;
        }
    }
    // Falling 1 m: v = √(2·g·h) = 4.43 m/s (the contact begins within a step of arrival).
    let speed = began.expect("the ball should touch the ground");
    assert!(
        (speed - (2.0f32 * 9.81).sqrt()).abs() < 0.25,
        "approach speed {speed}"
    );
    // Lift it away: the contact ends.
    world
        .body_mut(ball)
        .unwrap()
        .set_position(Vec3::new(0.0, 5.0, 0.0))
        .unwrap();
    world.step(DT);
    assert!(world
        .events()
        .iter()
        .any(|e| matches!(e, Event::ContactEnded { body_a, body_b } if (*body_a, *body_b) == (ground, ball))));
}

#[test]
fn a_joint_to_an_awake_body_wakes_a_sleeping_island() {
    let (mut world, _, ball) = sleeping_ball();
    // A new body swinging on a rope attached to the sleeping ball: the joint wakes it when inserted...
    let swinger = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(1.0, 2.0, 0.0)))
        .unwrap();
    let rope = rebound_constraints::Joint::new(rebound_constraints::Rope::new(2.0).unwrap());
    world.insert_joint(rope, ball, swinger).unwrap();
    world.step(DT);
    assert!(
        woke(&world, ball),
        "inserting a joint to an awake body wakes the sleeper"
    );
    // ...and while the swinger moves, the pair stays awake: they share an island through the joint.
    for _ in 0..60 {
        world.step(DT);
    }
    assert!(!world.is_sleeping(ball).unwrap());
    assert!(!world.is_sleeping(swinger).unwrap());
}
