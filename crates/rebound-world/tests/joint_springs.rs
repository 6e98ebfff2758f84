//! The springs of hinge, prismatic and wheel joints take the oscillator step of the distance spring
//! (`docs/physics.md`, "Springs without numerical damping"), stepped by the world: undamped at h·ω = 0.5 per
//! substep they keep their mean energy per period within 2 % over 50 periods, damped they lose it as
//! `exp(−2ζωt)` within 5 % over five time constants, and at k = 10⁹ on 1 kg (or 1 kg·m²) at dt = 1/30 s they
//! never diverge. Zero gravity; one body on a joint to the world, its coordinate started at `X0`.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use core::f64::consts::TAU;
use rebound_constraints::{HingeJoint, Joint, JointSpring, PrismaticJoint, SoftSpring, WheelJoint};
use rebound_dynamics::{BodyDesc, MassProperties, RigidBody};
use rebound_math::{Quat, Vec3};
use rebound_world::{BodyHandle, World, WorldSettings};

/// The substep (s) of the energy tests: one substep per step, so that every substep is sampled.
const H: f32 = 1.0 / 240.0;
/// The coordinate's start (rad for the hinge, m for the others).
const X0: f32 = 0.1;

/// Which joint coordinate carries the spring.
#[derive(Debug, Clone, Copy)]
enum Kind {
    /// A hinge about X: the angle.
    Hinge,
    /// A prismatic joint along X: the slide.
    Prismatic,
    /// A wheel with its suspension along Y.
    Wheel,
}

impl Kind {
    const ALL: [Self; 3] = [Self::Hinge, Self::Prismatic, Self::Wheel];

    fn joint(self, spring: SoftSpring) -> Joint {
        match self {
            Self::Hinge => {
                Joint::new(HingeJoint::new().with_spring(JointSpring::new(0.0, spring).unwrap()))
            }
            Self::Prismatic => Joint::new(
                PrismaticJoint::new().with_spring(JointSpring::new(0.0, spring).unwrap()),
            ),
            Self::Wheel => Joint::new(WheelJoint::new(spring).unwrap()),
        }
    }

    /// A 1 kg body with unit inertia (so `m_eff` = 1 kg or 1 kg·m² on every row) at the coordinate `x`.
    fn body(self, x: f32) -> BodyDesc {
        let desc = BodyDesc::dynamic()
            .with_mass_properties(MassProperties::new(1.0, Vec3::ZERO, Vec3::ONE).unwrap());
        match self {
            Self::Hinge => desc.with_rotation(Quat::from_rotation_x(x)),
            Self::Prismatic => desc.with_position(Vec3::new(x, 0.0, 0.0)),
            Self::Wheel => desc.with_position(Vec3::new(0.0, x, 0.0)),
        }
    }

    /// The coordinate and its rate.
    fn state(self, body: &RigidBody) -> (f64, f64) {
        let (x, v) = match self {
            Self::Hinge => {
                let q = body.rotation();
                (2.0 * q.x.atan2(q.w), body.angular_velocity().x)
            }
            Self::Prismatic => (body.position().x, body.linear_velocity().x),
            Self::Wheel => (body.position().y, body.linear_velocity().y),
        };
        (f64::from(x), f64::from(v))
    }
}

fn world(kind: Kind, spring: SoftSpring, substep_count: u32) -> (World, BodyHandle) {
    let mut world = World::new(WorldSettings {
        gravity: Vec3::ZERO,
        substep_count,
        ..WorldSettings::default()
    })
    .unwrap();
    let body = world.insert_body(&kind.body(X0)).unwrap();
    world.insert_world_joint(kind.joint(spring), body).unwrap();
    (world, body)
}

/// `(t, E)` after every substep for `duration` (s), `E = ½·k·x² + ½·v²` (J, unit mass or inertia).
fn energy_samples(kind: Kind, spring: SoftSpring, k: f64, duration: f64) -> Vec<(f64, f64)> {
    let (mut world, body) = world(kind, spring, 1);
    let steps = (duration / f64::from(H)).ceil() as usize;
    (1..=steps)
        .map(|n| {
            world.step(H);
            let (x, v) = kind.state(world.body(body).unwrap());
            (n as f64 * f64::from(H), 0.5 * k * x * x + 0.5 * v * v)
        })
        .collect()
}

/// The mean of `E` over each whole period `period` (s) of the samples: `(middle of the period, mean)`.
fn mean_per_period(samples: &[(f64, f64)], period: f64) -> Vec<(f64, f64)> {
    let periods = (samples.last().map_or(0.0, |s| s.0) / period).floor() as usize;
    (0..periods)
        .map(|p| {
            let (start, end) = (p as f64 * period, (p + 1) as f64 * period);
            let (sum, count) = samples
                .iter()
                .filter(|s| s.0 > start && s.0 <= end)
                .fold((0.0, 0usize), |(sum, count), s| (sum + s.1, count + 1));
            (0.5 * (start + end), sum / count as f64)
        })
        .collect()
}

/// ω = 0.5/h = 120 rad/s on unit mass: k = 14,400 N/m (N·m/rad), period 52 ms.
fn resolved_omega() -> f64 {
    0.5 / f64::from(H)
}

#[test]
fn undamped_joint_springs_at_h_omega_one_half_keep_their_mean_energy_for_50_periods() {
    let omega = resolved_omega();
    let (k, period) = (omega * omega, TAU / omega);
    for kind in Kind::ALL {
        for spring in [
            SoftSpring::stiffness(k as f32, 0.0).unwrap(),
            SoftSpring::frequency((omega / TAU) as f32, 0.0).unwrap(),
        ] {
            let means = mean_per_period(&energy_samples(kind, spring, k, 51.0 * period), period);
            assert!(means.len() >= 50);
            // The orbit's mean energy sits 1/(1 − (h·ω/2)²) = 1.067 above the start's ½·k·x0² (a substep's
            // end lies on the ellipse of the step's invariant, not of E), and stays there.
            let e0 = means[0].1;
            let start = 0.5 * k * f64::from(X0 * X0);
            assert!(
                (e0 / start - 1.0 / (1.0 - 0.0625)).abs() < 0.01,
                "{kind:?} {spring:?}: first period {e0} J vs {start} J"
            );
            for (n, &(t, e)) in means.iter().enumerate() {
                assert!(
                    (e / e0 - 1.0).abs() < 0.02,
                    "{kind:?} {spring:?}: period {n} (t = {t:.3} s): mean energy {e:.5} J vs {e0:.5} J"
                );
            }
        }
    }
}

#[test]
fn damped_joint_springs_lose_their_energy_as_exp_minus_two_zeta_omega_t() {
    // ζ = 0.05 on the 120 rad/s spring: five time constants (1/(ζω) each, of the amplitude) are 0.83 s.
    let omega = resolved_omega();
    let zeta = 0.05;
    let (k, period) = (omega * omega, TAU / omega);
    for kind in Kind::ALL {
        for spring in [
            SoftSpring::stiffness(k as f32, (2.0 * zeta * omega) as f32).unwrap(),
            SoftSpring::frequency((omega / TAU) as f32, zeta as f32).unwrap(),
        ] {
            let samples = energy_samples(kind, spring, k, 5.0 / (zeta * omega) + period);
            let means = mean_per_period(&samples, period);
            // The law fixes the ratio to the first period's mean, whatever the windowing does to the
            // absolute value.
            let (t0, e0) = means[0];
            for &(t, e) in &means[1..] {
                let law = (-2.0 * zeta * omega * (t - t0)).exp();
                assert!(
                    (e / e0 / law - 1.0).abs() < 0.05,
                    "{kind:?} {spring:?}, t = {t:.3} s: E/E(t0) = {:.4e}, exp(−2ζωΔt) = {law:.4e}",
                    e / e0
                );
            }
            assert!(means.last().map_or(0.0, |m| m.0) - t0 >= 4.5 / (zeta * omega));
        }
    }
}

#[test]
fn joint_springs_of_1e9_at_30_hz_never_diverge() {
    // k = 10⁹ on unit mass at dt = 1/30 s with the default four substeps: h·ω = 264. The step keeps at most
    // `1/(h·ω)` of the stretch per substep: the coordinate never grows, and is gone within a step.
    let dt = 1.0 / 30.0;
    for kind in Kind::ALL {
        let spring = SoftSpring::stiffness(1.0e9, 0.0).unwrap();
        let (mut world, body) = world(kind, spring, WorldSettings::default().substep_count);
        let mut largest = 0.0f64;
        for step in 1..=600 {
            world.step(dt);
            let (x, v) = kind.state(world.body(body).unwrap());
            assert!(
                x.is_finite() && v.is_finite() && x.abs() <= f64::from(X0) && v.abs() < 10.0,
                "{kind:?}, step {step}: coordinate {x}, rate {v}"
            );
            if step > 1 {
                largest = largest.max(x.abs());
            }
        }
        assert!(
            largest < 1e-6,
            "{kind:?}: coordinate up to {largest} after the first step"
        );
    }
}
