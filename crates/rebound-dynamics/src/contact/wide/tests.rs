//! The wide contact path against the scalar path: the lanes solve the scalar equations and hold bit for bit
//! the scalar path's prepared points and patches, and the colouring puts every manifold in exactly one place,
//! never a moving body twice in one batch.

use super::coloring::CHUNK;
use super::lanes::Vec3x4;
use crate::contact::patch::{Patch, PatchShare};
use crate::contact::prepared::PrepareInput;
use crate::contact::scalar::PreparedPoint;
use crate::contact::{Contact, ContactPoint, ContactSolver};
use crate::{Bias, BodyDesc, BodyParams, RigidBody, SolverBody, SolverSettings, StepContext};
use rebound_math::{Quat, Vec3};

/// `n` dynamic bodies in a row over one fixed body (index `n`), each touching the ground with four
/// points and its right neighbour with two, moving and spinning differently.
fn scene(n: usize) -> (Vec<SolverBody>, Vec<BodyParams>, Vec<Contact>) {
    let mut bodies = Vec::new();
    let mut params = Vec::new();
    for i in 0..n {
        let f = i as f32;
        let body = RigidBody::new(
            &BodyDesc::dynamic()
                .with_position(Vec3::new(f, 0.5, 0.0))
                .with_rotation(Quat::from_rotation_y(0.1 * f))
                .with_linear_velocity(Vec3::new(0.3 * f - 1.0, -2.0 + 0.1 * f, 0.2))
                .with_angular_velocity(Vec3::new(0.1, 0.5 - 0.2 * f, 0.05 * f)),
        )
        .expect("valid body");
        let mut state = SolverBody::from_body(&body);
        // A substep already under way: the bodies have moved and turned since the step began.
        state.delta_position = Vec3::new(0.001 * f, -0.002, 0.0005);
        state.delta_rotation = Quat::from_rotation_z(0.01 + 0.002 * f);
        bodies.push(state);
        params.push(BodyParams::from_body(&body));
    }
    bodies.push(SolverBody::STATIC);
    params.push(BodyParams::WORLD);
    let mut contacts = Vec::new();
    for i in 0..n {
        let mut ground = Contact::new(n, i, Vec3::Y, 0.6, 0.0);
        for (k, (x, z)) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
            .into_iter()
            .enumerate()
        {
            ground.push_point(ContactPoint {
                anchor_a: Vec3::new(i as f32 + x, 0.0, z),
                anchor_b: Vec3::new(x, -0.5, z),
                separation: -0.01 + 0.004 * k as f32,
                normal_impulse: 0.05 * k as f32,
                tangent_impulse: Vec3::new(0.01, 0.0, -0.02),
                feature_id: k as u32,
            });
        }
        contacts.push(ground);
        if i + 1 < n {
            let mut side = Contact::new(i, i + 1, Vec3::X, 0.4, 0.0);
            for z in [-0.5, 0.5] {
                side.push_point(ContactPoint {
                    anchor_a: Vec3::new(0.5, 0.0, z),
                    anchor_b: Vec3::new(-0.5, 0.0, z),
                    separation: 0.002 * z,
                    ..ContactPoint::default()
                });
            }
            contacts.push(side);
        }
    }
    (bodies, params, contacts)
}

/// Runs one substep's contact passes, wide or all scalar.
fn run(wide: bool, n: usize, only_ground: bool) -> (Vec<SolverBody>, Vec<Contact>) {
    let (mut bodies, params, mut contacts) = scene(n);
    if only_ground {
        contacts.retain(|c| c.body_a == n);
    }
    let ctx = StepContext::new(1.0 / 60.0, &SolverSettings::default());
    let mut solver = ContactSolver::new();
    solver.coloring.scalar_only = !wide;
    solver.prepare(&contacts, &bodies, &params, &ctx);
    assert_eq!(solver.batches.batches.is_empty(), !wide);
    solver.warm_start(&mut bodies);
    solver.solve(&mut bodies, &ctx, Bias::On);
    solver.solve(&mut bodies, &ctx, Bias::Off);
    solver.store_impulses(&mut contacts);
    (bodies, contacts)
}

#[test]
fn lanes_solve_the_scalar_equations() {
    // Manifolds without a moving body in common: the order does not matter, so the wide path must give
    // the scalar path's velocities and impulses to rounding.
    let (wide, wide_contacts) = run(true, 6, true);
    let (scalar, scalar_contacts) = run(false, 6, true);
    for (w, s) in wide.iter().zip(&scalar) {
        for (a, b) in [
            (w.linear_velocity, s.linear_velocity),
            (w.angular_velocity, s.angular_velocity),
        ] {
            assert!((a - b).length() <= 1e-5 * (1.0 + b.length()), "{a} vs {b}");
        }
    }
    for (w, s) in wide_contacts.iter().zip(&scalar_contacts) {
        for (p, q) in w.points().iter().zip(s.points()) {
            assert!((p.normal_impulse - q.normal_impulse).abs() <= 1e-5);
            assert!((p.tangent_impulse - q.tangent_impulse).length() <= 1e-5);
        }
    }
    // And they did push: the bodies fall at 2 m/s into the ground.
    assert!(
        wide_contacts
            .iter()
            .all(|c| c.points[0].normal_impulse > 0.0)
    );
}

#[test]
fn lanes_are_prepared_bit_for_bit_as_the_scalar_points() {
    let (bodies, params, contacts) = scene(9);
    let ctx = StepContext::new(1.0 / 60.0, &SolverSettings::default());
    let mut solver = ContactSolver::new();
    solver.prepare(&contacts, &bodies, &params, &ctx);
    let input = PrepareInput {
        contacts: &contacts,
        bodies: &bodies,
        params: &params,
        ctx: &ctx,
    };
    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
    let mut compared = 0;
    let wide = &solver.batches;
    for (b, batch) in wide.batches.iter().enumerate() {
        let info = &wide.infos[b];
        let lanes = usize::from(batch.lanes);
        for (l, &index) in info.contacts[..lanes].iter().enumerate() {
            let c = &solver.contacts[index as usize];
            assert_eq!(info.sources[l] as usize, c.source);
            assert_eq!(info.point_counts[l] as usize, c.point_count);
            let points = contacts[c.source].points();
            let lane_of = |v: &Vec3x4| v.lane(l);
            let patch = Patch::new(&input, c, points);
            let x4 = &wide.patches[b];
            assert!(
                batch.twist,
                "every manifold of the scene has two points or more"
            );
            let twist = wide.twists[batch.first_twist as usize];
            assert_eq!(bits(lane_of(&info.center_a)), bits(patch.center_a));
            assert_eq!(bits(lane_of(&x4.wt_a[0])), bits(patch.wt_a[0]));
            assert_eq!(bits(lane_of(&x4.wt_b[1])), bits(patch.wt_b[1]));
            assert_eq!(bits(lane_of(&twist.twist_b)), bits(patch.twist_b));
            for (wide, scalar) in [
                (info.spread, patch.spread),
                (x4.tangent_mass[0], patch.tangent_mass[0]),
                (x4.tangent_mass[1], patch.tangent_mass[1]),
                (x4.tangent_impulse[0], patch.tangent_impulse.x),
                (x4.tangent_impulse[1], patch.tangent_impulse.y),
                (twist.impulse, patch.twist_impulse),
                (twist.mass, patch.twist_mass),
            ] {
                assert_eq!(wide[l].to_bits(), scalar.to_bits());
            }
            for (k, point) in points.iter().enumerate() {
                let scalar = PreparedPoint::new(&input, c, point, patch.center_a);
                let slot = &wide.slots[batch.first_slot as usize + k];
                assert_eq!(bits(lane_of(&slot.wn_a)), bits(scalar.wn_a));
                assert_eq!(bits(lane_of(&slot.wn_b)), bits(scalar.wn_b));
                for (wide, scalar) in [
                    (slot.normal_mass, scalar.normal_mass),
                    (slot.normal_impulse, scalar.normal_impulse),
                    (slot.twist_radius, scalar.twist_radius),
                ] {
                    assert_eq!(wide[l].to_bits(), scalar.to_bits());
                }
                compared += 1;
            }
        }
    }
    assert!(compared >= 9 * 4, "{compared} points compared");
}

#[test]
fn no_batch_holds_a_moving_body_twice() {
    check_batches(9);
}

#[test]
fn chunked_colouring_keeps_batches_independent() {
    // 2 · 2100 − 1 manifolds: more than one chunk, and a chunk boundary inside the run of bodies.
    let (_, _, contacts) = scene(2100);
    assert!(contacts.len() > CHUNK);
    check_batches(2100);
}

/// Every manifold of `scene(n)` solved exactly once (in a batch or by the scalar path), and no batch
/// holding a moving body in two lanes.
fn check_batches(n: usize) {
    let (bodies, params, contacts) = scene(n);
    let ctx = StepContext::new(1.0 / 60.0, &SolverSettings::default());
    let mut solver = ContactSolver::new();
    solver.prepare(&contacts, &bodies, &params, &ctx);
    let mut solved = vec![0; contacts.len()];
    for (batch, info) in solver.batches.batches.iter().zip(&solver.batches.infos) {
        let used = usize::from(batch.lanes);
        let lanes = &batch.body_a[..used]
            .iter()
            .chain(&batch.body_b[..used])
            .filter(|&&b| params[b as usize].is_dynamic())
            .collect::<Vec<_>>();
        let mut unique = lanes.clone();
        unique.sort_unstable();
        unique.dedup();
        assert_eq!(unique.len(), lanes.len(), "a body twice in one batch");
        for &c in &info.contacts[..used] {
            solved[c as usize] += 1;
        }
    }
    for &c in &solver.scalar {
        solved[c] += 1;
    }
    assert!(solved.iter().all(|&n| n == 1), "every manifold solved once");
    assert!(!solver.batches.batches.is_empty());
}

#[test]
fn lanes_read_back_the_scalar_friction_shares_bit_for_bit() {
    // After a substep's passes, the friction each point reports is `PatchShare::at` of its lane's patch.
    let (mut bodies, params, contacts) = scene(9);
    let ctx = StepContext::new(1.0 / 60.0, &SolverSettings::default());
    let mut solver = ContactSolver::new();
    solver.prepare(&contacts, &bodies, &params, &ctx);
    solver.warm_start(&mut bodies);
    solver.solve(&mut bodies, &ctx, Bias::On);
    solver.solve(&mut bodies, &ctx, Bias::Off);
    let wide = &solver.batches;
    let mut expected = Vec::new();
    for (b, batch) in wide.batches.iter().enumerate() {
        let (info, patch) = (&wide.infos[b], &wide.patches[b]);
        let twist = batch
            .twist
            .then(|| wide.twists[batch.first_twist as usize].impulse);
        for l in 0..usize::from(batch.lanes) {
            let c = &solver.contacts[info.contacts[l] as usize];
            let share = PatchShare::new(
                c.normal,
                c.tangents,
                [patch.tangent_impulse[0][l], patch.tangent_impulse[1][l]],
                twist.map_or(0.0, |t| t[l]),
                info.spread[l],
                c.point_count,
            );
            for k in 0..c.point_count {
                let slot = &wide.slots[batch.first_slot as usize + k];
                let rho = slot.anchor_a.lane(l) - info.center_a.lane(l);
                expected.push((c.source, k, share.at(rho)));
            }
        }
    }
    let mut read = Vec::new();
    solver.for_each_point_result(|source, k, _, tangent, _| read.push((source, k, tangent)));
    let bits = |v: Vec3| v.to_array().map(f32::to_bits);
    let twisted = expected.iter().filter(|e| e.2 != expected[0].2).count();
    assert!(twisted > 0, "the shares differ between points");
    assert_eq!(read.len(), expected.len());
    for (r, e) in read.iter().zip(&expected) {
        assert_eq!((r.0, r.1, bits(r.2)), (e.0, e.1, bits(e.2)));
    }
}
