//! Bounded work per step: a pile of balls created at one point (n·(n − 1)/2 overlapping pairs) is handled
//! within the caps of `StepLimits` — candidate pairs and contact points — and pushed apart no faster than
//! `max_push_out_speed`; the same calls give the same result bit for bit.

#![allow(
    clippy::unwrap_used,
    reason = "test scenes are built from known-good values; a failed setup fails the test"
)]

use rebound::StepLimits;
use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;

/// `n` balls of radius 0.5 created at one point, in zero gravity, with `limits`.
fn coincident_pile(n: usize, limits: StepLimits) -> PhysicsWorld {
    let settings = WorldSettings {
        gravity: Vec3::ZERO,
        limits,
        ..WorldSettings::default()
    };
    let mut world = PhysicsWorld::new(settings).unwrap();
    for _ in 0..n {
        let b = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 5.0, 0.0)))
            .unwrap();
        world.insert_collider(ColliderDesc::ball(0.5), b).unwrap();
    }
    world
}

fn fastest(world: &PhysicsWorld) -> f32 {
    world
        .bodies()
        .iter()
        .map(|(_, b)| b.linear_velocity().length())
        .fold(0.0, f32::max)
}

#[test]
fn a_pile_of_coincident_balls_stays_within_the_caps_and_the_push_out_speed() {
    // 400 balls: 79,800 overlapping pairs, capped at 20,000.
    let limits = StepLimits {
        max_candidate_pairs: 20_000,
        max_contact_points: 15_000,
        ..StepLimits::default()
    };
    let mut world = coincident_pile(400, limits);
    let max_push_out_speed = world.settings().max_push_out_speed;
    let mut spread = 0.0f32;
    for step in 0..20 {
        let report = world.step(DT);
        assert!(report.contact_count <= 15_000, "{report:?}");
        assert!(report.contact_point_count <= 15_000, "{report:?}");
        if step == 0 {
            assert_eq!(report.capped_pair_count, 79_800 - 20_000);
            // The pairs kept are whole manifolds of one point each, up to the point cap.
            assert_eq!(report.contact_point_count, 15_000);
            assert_eq!(report.capped_manifold_count, 20_000 - 15_000);
        }
        // A ball is pushed out of all its overlaps together at no more than the push-out speed (and there
        // is nothing else to move it).
        let v = fastest(&world);
        assert!(v <= max_push_out_speed, "step {step}: {v} m/s");
        let top = world
            .bodies()
            .iter()
            .map(|(_, b)| b.position().y)
            .fold(f32::MIN, f32::max);
        spread = top - 5.0;
    }
    // The push-out moved the pile (its positions, not its velocities: the relax passes take the push-out
    // velocity back) no farther than the push-out speed allows in 20 steps.
    assert!(
        spread > 0.0 && spread <= max_push_out_speed * 20.0 * DT,
        "{spread}"
    );
}

#[test]
fn a_capped_step_is_deterministic() {
    let limits = StepLimits {
        max_candidate_pairs: 5_000,
        ..StepLimits::default()
    };
    let mut a = coincident_pile(200, limits);
    let mut b = coincident_pile(200, limits);
    for _ in 0..10 {
        let (ra, rb) = (a.step(DT), b.step(DT));
        assert_eq!(ra.capped_pair_count, rb.capped_pair_count);
        assert_eq!(a.state_digest(), b.state_digest());
    }
    // A restored snapshot (a new broad-phase tree, whose traversal order differs) keeps the same pairs.
    let snapshot = a.snapshot();
    let mut c = coincident_pile(0, limits);
    c.restore(&snapshot).unwrap();
    for _ in 0..5 {
        a.step(DT);
        c.step(DT);
        assert_eq!(a.state_digest(), c.state_digest());
    }
}

/// The pile of the issue: 10,000 balls at one point, 49,995,000 overlapping pairs. The step keeps the
/// default cap of 131,072 pairs; the process's peak resident memory is printed (Linux). Slow in a debug
/// build (about 10 s a step): `cargo test --release -p rebound --test bounded_work -- --ignored --nocapture`.
#[test]
#[ignore = "10,000 coincident balls: seconds per step; run with --ignored (see the doc comment)"]
fn ten_thousand_coincident_balls_step_in_bounded_memory() {
    let mut world = coincident_pile(10_000, StepLimits::default());
    let max_push_out_speed = world.settings().max_push_out_speed;
    for _ in 0..3 {
        let report = world.step(DT);
        assert_eq!(report.contact_count, 131_072);
        assert!(fastest(&world) <= max_push_out_speed);
    }
    let status = std::fs::read_to_string("/proc/self/status").unwrap_or_default();
    let peak = status
        .lines()
        .find(|l| l.starts_with("VmHWM"))
        .unwrap_or("VmHWM: unknown");
    eprintln!("10,000 coincident balls, 3 steps: peak {peak}");
}
