//! The position projection of directly solved joint paths (`JointSolver::project_positions`): exact on a
//! straight chain whatever the masses, never worse on a bent one.

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

use proptest::prelude::*;
use rebound_constraints::{Joint, JointBodies, JointSolver, JointState, Rope};
use rebound_dynamics::{
    BodyDesc, BodyParams, MassProperties, RigidBody, SolverBody, SolverSettings, StepContext,
};
use rebound_math::{EulerRot, Quat, Vec3};

const LINK: f32 = 0.25;

/// A chain hanging from a fixed body at the origin through balls at `points` (their masses `masses`), joined
/// by ropes of `LINK`; returns the link lengths after one position projection.
fn project(points: &[Vec3], masses: &[f32]) -> Vec<f32> {
    let mut bodies = vec![RigidBody::new(&BodyDesc::fixed()).unwrap()];
    for (p, m) in points.iter().zip(masses) {
        let desc = BodyDesc::dynamic().with_position(*p).with_mass_properties(
            MassProperties::new(*m, Vec3::ZERO, Vec3::splat(0.01 * m)).unwrap(),
        );
        bodies.push(RigidBody::new(&desc).unwrap());
    }
    let joints: Vec<Joint> = (0..points.len())
        .map(|_| Joint::new(Rope::new(LINK).unwrap()))
        .collect();
    let states = vec![JointState::default(); joints.len()];
    let pairs: Vec<JointBodies> = (0..joints.len())
        .map(|i| JointBodies { a: i, b: i + 1 })
        .collect();
    let mut solver_bodies: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
    let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
    let ctx = StepContext::new(1.0 / 60.0, &SolverSettings::default());
    let mut solver = JointSolver::new();
    assert_eq!(
        solver.prepare(&joints, &states, &pairs, &solver_bodies, &params, &ctx),
        0
    );
    solver.project_positions(&mut solver_bodies, &ctx);
    let position = |i: usize| bodies[i].position() + solver_bodies[i].delta_position;
    (0..joints.len())
        .map(|i| position(i).distance(position(i + 1)))
        .collect()
}

/// Points of a chain from the origin: each link turned from the last by (yaw, pitch)·`bend` (rad) and
/// `1 + stretch` times `LINK` long; with the balls' masses.
fn chain(links: &[(f32, f32, f32, f32)], bend: f32) -> (Vec<Vec3>, Vec<f32>) {
    let mut direction = Vec3::X;
    let mut point = Vec3::ZERO;
    let (mut points, mut masses) = (Vec::new(), Vec::new());
    for (yaw, pitch, stretch, mass) in links {
        let turn = Quat::from_euler(EulerRot::YZX, yaw * bend, pitch * bend, 0.0);
        direction = (turn * direction).normalize();
        point += direction * LINK * (1.0 + stretch);
        points.push(point);
        masses.push(*mass);
    }
    (points, masses)
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Random taut chains — each link up to 10 % too long, turned by up to 1 rad from the last, masses from
    /// 0.5 to 5 kg — never come out of a projection with a worse worst stretch: a Newton step that would make
    /// it worse is halved, and Gauss–Seidel sweeps that would are undone. (How much better they come out
    /// varies: a light ball between two nearly aligned links is where the linearisation is worst; the
    /// projection of the next step takes up what is left.)
    #[test]
    fn the_projection_never_makes_the_worst_stretch_worse(
        links in prop::collection::vec((-1.0f32..1.0, -1.0f32..1.0, 0.0f32..0.1, 0.5f32..5.0), 2..40),
        bend in 0.0f32..1.0,
    ) {
        let (points, masses) = chain(&links, bend);
        let before = links.iter().map(|l| l.2).fold(0.0f32, f32::max);
        let lengths = project(&points, &masses);
        let after = lengths.iter().map(|l| l / LINK - 1.0).fold(0.0f32, f32::max);
        prop_assert!(after <= before + 1e-5, "worst stretch {before} -> {after}");
    }
}

/// A straight chain is linear in the projection: the direct solve is exact, whatever the masses — every link
/// back within its length (a slack link may take up the correction of its neighbours).
#[test]
fn a_straight_chain_is_projected_exactly() {
    let links: Vec<(f32, f32, f32, f32)> = (0..30)
        .map(|i| {
            let stretch = [0.08, 0.0, -0.05, 0.02, 0.0][i % 5];
            let mass = [0.5, 4.0, 1.0][i % 3];
            (0.0, 0.0, stretch, mass)
        })
        .collect();
    let (points, masses) = chain(&links, 0.0);
    let lengths = project(&points, &masses);
    for (i, (length, link)) in lengths.iter().zip(&links).enumerate() {
        assert!(
            *length <= LINK + 5e-5,
            "link {i}: {length} m, started at {} m",
            LINK * (1.0 + link.2)
        );
    }
}

/// A nearly straight chain — twenty links turned from the last by at most 0.04 rad, some stretched by up to
/// 9.6 %, masses from 0.5 to 5 kg, light balls between heavy ones — is nearly linear in the projection: its
/// Newton steps converge, and every link comes back within the projection's tolerance of its length
/// (0.1 mm, `PROJECTION_TOLERANCE`), not merely no worse than it started.
#[test]
fn a_nearly_straight_chain_is_projected_within_the_tolerance() {
    let links = [
        (0.0, 0.0, 0.09587559, 0.5),
        (0.0, 0.0, 0.0, 0.5),
        (0.0, 0.0, 0.0, 0.5),
        (0.0, 0.8566509, 0.0, 0.5),
        (0.0, 0.0, 0.0, 0.5),
        (0.0, 0.0, 0.0, 0.5),
        (0.0, 0.0, 0.06554179, 3.1886485),
        (0.0, 0.0, 0.063268885, 0.5),
        (-0.7517345, 0.0, 0.039544787, 1.6749425),
        (0.0, 0.0, 0.044235025, 4.9088874),
        (0.0, 0.0, 0.018205171, 0.5),
        (-0.53722703, 0.5757638, 0.043998662, 0.5),
        (0.0, 0.93959844, 0.0, 3.4708068),
        (0.0, 0.0, 0.0, 3.43208),
        (0.0, 0.0, 0.0, 3.9724329),
        (0.0, 0.0, 0.0, 1.3201593),
        (0.0, 0.0, 0.026194545, 3.9926975),
        (0.0, 0.0, 0.0, 0.99092996),
        (-0.9807038, 0.0, 0.05493557, 2.7797172),
        (0.0, 0.0, 0.07902125, 0.5992975),
    ];
    let (points, masses) = chain(&links, 0.04);
    let lengths = project(&points, &masses);
    for (i, (length, link)) in lengths.iter().zip(&links).enumerate() {
        assert!(
            *length <= LINK + 1e-4,
            "link {i}: {length} m after the projection, started at {} m",
            LINK * (1.0 + link.2)
        );
    }
}
