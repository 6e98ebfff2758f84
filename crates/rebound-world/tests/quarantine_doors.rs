//! The quarantine's start-of-step check sees every way a body can leave the bounds between two steps.
//!
//! The step compares each body it writes back with the bounds, and the next step's start looks at the bodies
//! again only when something could have changed them since (an edit, a restore, a release, other limits, a
//! kinematic target, a sleeping body already beyond them). Each test here warms a world up with steps whose
//! bodies all stay within the bounds, then puts one body beyond them through one door, and asserts that the
//! very next step quarantines that body for that reason — as a world that checked every body at every step
//! start would.
//!
//! A speed set beyond its bound is also caught by the check after the solver passes; a position only by the
//! start check, so the position cases are the ones that tell a skipped check.
//!
//! No door puts a non-finite number into a body: every setter and `apply_*` refuses one (see
//! `bad_input.rs`), a target must be finite and a restored snapshot is checked. The doors below are those
//! that accept finite values beyond the bounds.

#![allow(
    clippy::unwrap_used,
    reason = "the set-up fails loudly on the first unexpected error"
)]

use rebound_dynamics::BodyDesc;
use rebound_math::{Pose, Vec3};
use rebound_world::testing::SimpleBackend;
use rebound_world::{BodyHandle, Event, QuarantineReason, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;

/// Far beyond the default position bound of 10⁶ m.
const FAR: f32 = 2.0e6;

/// A ball resting on a ground plane and a second ball falling beside it, stepped until both have been
/// written back a few times within the bounds.
fn warm_world() -> (World<SimpleBackend>, BodyHandle, BodyHandle) {
    let mut world = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let ground = world.insert_body(&BodyDesc::fixed()).unwrap();
    world
        .backend_mut()
        .add_half_space(ground, Vec3::Y, 0.5, 0.0);
    let resting = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.5, 0.0)))
        .unwrap();
    world.backend_mut().add_sphere(resting, 0.5, 0.5, 0.0);
    let falling = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(3.0, 4.0, 0.0)))
        .unwrap();
    world.backend_mut().add_sphere(falling, 0.5, 0.5, 0.0);
    step_clean(&mut world, 5);
    (world, resting, falling)
}

/// `count` steps that quarantine nothing.
fn step_clean<B: rebound_world::CollisionBackend>(world: &mut World<B>, count: usize) {
    for _ in 0..count {
        let report = world.step(DT);
        assert_eq!(report.quarantined_body_count, 0);
    }
}

/// Steps once and asserts that exactly `body` was quarantined, for `reason`, with its event.
fn assert_next_step_quarantines<B: rebound_world::CollisionBackend>(
    world: &mut World<B>,
    body: BodyHandle,
    reason: QuarantineReason,
) {
    let report = world.step(DT);
    assert_eq!(report.quarantined_body_count, 1, "{:?}", world.events());
    assert_eq!(world.is_quarantined(body), Some(true));
    let quarantined: Vec<_> = world
        .events()
        .iter()
        .filter_map(|e| match *e {
            Event::BodyQuarantined { body, reason } => Some((body, reason)),
            _ => None,
        })
        .collect();
    assert_eq!(quarantined, [(body, reason)]);
}

#[test]
fn a_position_set_beyond_the_bounds_between_steps_is_caught_at_the_next_step() {
    let (mut world, resting, _) = warm_world();
    world
        .body_mut(resting)
        .unwrap()
        .set_position(Vec3::new(FAR, 0.5, 0.0))
        .unwrap();
    assert_next_step_quarantines(&mut world, resting, QuarantineReason::Position);
}

#[test]
fn a_velocity_set_beyond_the_bounds_between_steps_is_caught_at_the_next_step() {
    let (mut world, _, falling) = warm_world();
    world
        .body_mut(falling)
        .unwrap()
        .set_linear_velocity(Vec3::new(0.0, 0.0, 2.0e4))
        .unwrap();
    assert_next_step_quarantines(&mut world, falling, QuarantineReason::Speed);
}

#[test]
fn an_angular_velocity_set_beyond_the_bounds_between_steps_is_caught_at_the_next_step() {
    let (mut world, resting, _) = warm_world();
    world
        .body_mut(resting)
        .unwrap()
        .set_angular_velocity(Vec3::new(0.0, 3.0e4, 0.0))
        .unwrap();
    assert_next_step_quarantines(&mut world, resting, QuarantineReason::AngularSpeed);
}

#[test]
fn an_impulse_beyond_the_bounds_between_steps_is_caught_at_the_next_step() {
    let (mut world, _, falling) = warm_world();
    // Three times the speed bound, whatever the mass of the ball.
    let mass = 1.0 / world.body(falling).unwrap().inv_mass();
    world
        .body_mut(falling)
        .unwrap()
        .apply_impulse(Vec3::new(3.0e4 * mass, 0.0, 0.0))
        .unwrap();
    assert_next_step_quarantines(&mut world, falling, QuarantineReason::Speed);
}

#[test]
fn a_kinematic_target_beyond_the_speed_bound_is_caught_in_its_step() {
    let (mut world, _, _) = warm_world();
    let platform = world
        .insert_body(&BodyDesc::kinematic().with_position(Vec3::new(-3.0, 1.0, 0.0)))
        .unwrap();
    step_clean(&mut world, 3);
    // An ordinary target first: no quarantine.
    world
        .set_kinematic_target(platform, Pose::from_position(Vec3::new(-3.0, 1.1, 0.0)))
        .unwrap();
    step_clean(&mut world, 1);
    // 1000 m in a sixtieth of a second: 6·10⁴ m/s.
    world
        .set_kinematic_target(platform, Pose::from_position(Vec3::new(997.0, 1.1, 0.0)))
        .unwrap();
    assert_next_step_quarantines(&mut world, platform, QuarantineReason::Speed);
}

#[test]
fn tighter_limits_set_between_steps_are_applied_at_the_next_step() {
    let (mut world, _, falling) = warm_world();
    // The falling ball is 3 m from the origin along x, the resting one at the origin.
    assert!((world.body(falling).unwrap().position().x - 3.0).abs() < 1e-3);
    let mut settings = *world.settings();
    settings.limits.max_position = 2.5;
    world.set_settings(settings).unwrap();
    assert_next_step_quarantines(&mut world, falling, QuarantineReason::Position);
}

#[test]
fn a_restored_snapshot_with_a_body_beyond_the_bounds_is_caught_at_the_next_step() {
    let (mut world, resting, _) = warm_world();
    // A snapshot that holds a body beyond the bounds, taken before any step saw it there.
    let near = world.body(resting).unwrap().position();
    world
        .body_mut(resting)
        .unwrap()
        .set_position(Vec3::new(FAR, 0.5, 0.0))
        .unwrap();
    let far = world.snapshot();
    world.body_mut(resting).unwrap().set_position(near).unwrap();
    step_clean(&mut world, 3);
    world.restore(&far).unwrap();
    assert_next_step_quarantines(&mut world, resting, QuarantineReason::Position);
}

#[test]
fn a_released_body_still_beyond_the_bounds_is_quarantined_again_at_the_next_step() {
    let (mut world, resting, _) = warm_world();
    world
        .body_mut(resting)
        .unwrap()
        .set_position(Vec3::new(FAR, 0.5, 0.0))
        .unwrap();
    assert_next_step_quarantines(&mut world, resting, QuarantineReason::Position);
    step_clean(&mut world, 3);
    world.release_quarantine(resting).unwrap();
    assert_eq!(world.is_quarantined(resting), Some(false));
    assert_next_step_quarantines(&mut world, resting, QuarantineReason::Position);
}

#[test]
fn a_sleeping_body_beyond_the_bounds_is_caught_at_the_step_after_it_wakes() {
    let (mut world, _, _) = warm_world();
    let mut desc = BodyDesc::dynamic().with_position(Vec3::new(FAR, 0.5, 0.0));
    desc.sleeping = true;
    let sleeper = world.insert_body(&desc).unwrap();
    // Asleep, it is in no step and not checked.
    step_clean(&mut world, 5);
    assert_eq!(world.is_sleeping(sleeper), Some(true));
    // Woken without an edit of the body.
    world.wake_body(sleeper).unwrap();
    assert_next_step_quarantines(&mut world, sleeper, QuarantineReason::Position);
}

#[test]
fn a_body_inserted_beyond_the_bounds_is_caught_at_the_next_step() {
    let (mut world, _, _) = warm_world();
    let far = world
        .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(0.0, -FAR, 0.0)))
        .unwrap();
    assert_next_step_quarantines(&mut world, far, QuarantineReason::Position);
}

#[test]
fn a_body_the_step_carries_beyond_the_bounds_is_caught_at_the_next_step() {
    let (mut world, _, falling) = warm_world();
    // Just inside the position bound and moving out at 600 m/s: 10 m beyond after one step, with every
    // speed within its bound, so only the next step's start check can see it.
    world
        .body_mut(falling)
        .unwrap()
        .set_position(Vec3::new(1.0e6 - 0.5, 4.0, 0.0))
        .unwrap();
    world
        .body_mut(falling)
        .unwrap()
        .set_linear_velocity(Vec3::new(600.0, 0.0, 0.0))
        .unwrap();
    step_clean(&mut world, 1);
    assert!(world.body(falling).unwrap().position().x > 1.0e6);
    assert_next_step_quarantines(&mut world, falling, QuarantineReason::Position);
}
