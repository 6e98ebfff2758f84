//! Energy of constrained motion, with the default settings: a 1 kg bob on a 3 m rope and on a 3 m rod,
//! released from 80°, keeps its energy within 0.5 % over 20 periods and swings with the large-amplitude
//! period `T = 4·√(L/g)·K(sin(θ₀/2))` to 0.5 %; a double pendulum of two rods keeps its energy within 1 % over
//! 10 s. Both are paths solved directly and projected after every step (`docs/physics.md`, "Energy of
//! constrained motion").

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound_constraints::{Joint, Rod, Rope};
use rebound_dynamics::{BodyDesc, MassProperties};
use rebound_math::Vec3;
use rebound_world::{BodyHandle, World, WorldSettings};

const DT: f32 = 1.0 / 60.0;
const G: f64 = 9.81;
const LENGTH: f32 = 3.0;
const RELEASE_DEGREES: f32 = 80.0;

/// The complete elliptic integral of the first kind, `K(k) = π / (2·AGM(1, √(1 − k²)))`: the
/// arithmetic–geometric mean converges quadratically, so a handful of iterations reach f64 rounding.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..32 {
        if (a - b).abs() <= 1e-15 * a {
            break;
        }
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    core::f64::consts::PI / (2.0 * a)
}

/// A 1 kg ball (a small sphere's inertia) at `position`, at rest.
fn bob(position: Vec3) -> BodyDesc {
    BodyDesc::dynamic()
        .with_position(position)
        .with_mass_properties(MassProperties::new(1.0, Vec3::ZERO, Vec3::splat(0.004)).unwrap())
}

/// Kinetic plus potential energy of 1 kg bodies (J), the potential measured from `floor` (m).
fn energy(world: &World, bodies: &[BodyHandle], floor: f64) -> f64 {
    bodies
        .iter()
        .map(|&h| {
            let b = world.body(h).unwrap();
            0.5 * f64::from(b.linear_velocity().length_squared())
                + 0.5 * 0.004 * f64::from(b.angular_velocity().length_squared())
                + G * (f64::from(b.position().y) - floor)
        })
        .sum()
}

/// Releases a bob on `joint` (anchored at the world origin, length `LENGTH`) from `RELEASE_DEGREES` and
/// runs it through 20 periods: (worst |E/E₀ − 1| after any step, the mean period from the crossings of the
/// vertical in one direction, the worst distance from the anchor).
fn swing(joint: Joint) -> (f64, f64, f32) {
    let mut world = World::new(WorldSettings::default()).unwrap();
    let angle = RELEASE_DEGREES.to_radians();
    let start = Vec3::new(LENGTH * angle.sin(), -LENGTH * angle.cos(), 0.0);
    let handle = world.insert_body(&bob(start)).unwrap();
    world.insert_world_joint(joint, handle).unwrap();
    // The energy of the swing: measured from the lowest point, so that it is the release height's m·g·Δh.
    let floor = -f64::from(LENGTH);
    let e0 = energy(&world, &[handle], floor);
    let (mut worst, mut furthest) = (0.0f64, 0.0f32);
    let mut crossings = Vec::new();
    let mut previous_x = start.x;
    let mut step = 0u32;
    while crossings.len() < 21 && step < 100 * 60 {
        world.step(DT);
        step += 1;
        let p = world.body(handle).unwrap().position();
        worst = worst.max((energy(&world, &[handle], floor) / e0 - 1.0).abs());
        furthest = furthest.max(p.length());
        if previous_x > 0.0 && p.x <= 0.0 {
            let t = (f64::from(step) - 1.0 + f64::from(previous_x / (previous_x - p.x)))
                * f64::from(DT);
            crossings.push(t);
        }
        previous_x = p.x;
    }
    assert_eq!(crossings.len(), 21, "crossings {crossings:?}");
    let period = (crossings[20] - crossings[0]) / 20.0;
    (worst, period, furthest)
}

/// `T = 4·√(L/g)·K(sin(θ₀/2))` (s).
fn large_amplitude_period() -> f64 {
    let half = f64::from(RELEASE_DEGREES).to_radians() / 2.0;
    4.0 * (f64::from(LENGTH) / G).sqrt() * elliptic_k(half.sin())
}

#[test]
fn the_elliptic_integral_by_the_arithmetic_geometric_mean_matches_its_known_values() {
    // K(0) = π/2; K(sin 45°) = Γ(1/4)²/(4·√π) = 1.854074677301372.
    assert!((elliptic_k(0.0) - core::f64::consts::FRAC_PI_2).abs() < 1e-15);
    assert!((elliptic_k(core::f64::consts::FRAC_1_SQRT_2) - 1.854_074_677_301_372).abs() < 1e-13);
}

fn check_swing(joint: Joint, what: &str) {
    let (worst, period, furthest) = swing(joint);
    let expected = large_amplitude_period();
    assert!(
        worst <= 0.005,
        "{what}: energy off by {:.3} % within 20 periods",
        worst * 100.0
    );
    assert!(
        (period / expected - 1.0).abs() <= 0.005,
        "{what}: period {period} s against 4·√(L/g)·K(sin(θ₀/2)) = {expected} s"
    );
    assert!(
        furthest <= LENGTH * 1.001,
        "{what}: {furthest} m from the anchor"
    );
}

#[test]
fn a_rope_pendulum_released_from_80_degrees_keeps_its_energy_and_its_large_amplitude_period() {
    check_swing(Joint::new(Rope::new(LENGTH).unwrap()), "rope");
}

#[test]
fn a_rod_pendulum_released_from_80_degrees_keeps_its_energy_and_its_large_amplitude_period() {
    check_swing(Joint::new(Rod::new(LENGTH).unwrap()), "rod");
}

#[test]
fn a_double_pendulum_of_two_rods_released_level_keeps_its_energy_for_10_s() {
    // Two 1 kg bobs on 1 m rods, both rods level at the start (chaotic from the first swing).
    let mut world = World::new(WorldSettings::default()).unwrap();
    let first = world.insert_body(&bob(Vec3::new(1.0, 0.0, 0.0))).unwrap();
    let second = world.insert_body(&bob(Vec3::new(2.0, 0.0, 0.0))).unwrap();
    world
        .insert_world_joint(Joint::new(Rod::new(1.0).unwrap()), first)
        .unwrap();
    world
        .insert_joint(Joint::new(Rod::new(1.0).unwrap()), first, second)
        .unwrap();
    // Measured from the hanging pose (bobs at y = −1 and −2 m): each bob's potential from y = −1.5 m sums
    // to the same, 29.43 J at the start.
    let floor = -1.5;
    let e0 = energy(&world, &[first, second], floor);
    let mut worst = 0.0f64;
    for _ in 0..600 {
        world.step(DT);
        worst = worst.max((energy(&world, &[first, second], floor) / e0 - 1.0).abs());
    }
    assert!(
        worst <= 0.01,
        "energy off by {:.3} % within 10 s",
        worst * 100.0
    );
}
