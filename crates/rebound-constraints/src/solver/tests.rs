//! Tests of the joint solver's stages: passes that keep rows and factorisations give the bits of passes
//! that rebuild them, paths kept into the next step, closed paths, carried hinge rows.

#![allow(
    clippy::unwrap_used,
    reason = "the scene is built from known-valid inputs; a failure is a test failure"
)]

use super::JointSolver;
use super::path_pass::{build_site, carry, rows_at};
use crate::ball::BallJoint;
use crate::hinge::HingeJoint;
use crate::hinge::PreparedHinge;
use crate::joint::{Joint, JointBodies};
use crate::motor::Motor;
use crate::path::{CARRY_ANGLE, Link, PoseKey, empty_link};
use crate::prismatic::PrismaticJoint;
use crate::rope::Rope;
use crate::settings::JointSettings;
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::integrate::{integrate_positions, integrate_velocities};
use rebound_dynamics::{Bias, BodyParams, SolverBody, StepContext};
use rebound_dynamics::{BodyDesc, MassProperties, RigidBody, SolverSettings};
use rebound_math::Quat;
use rebound_math::Vec3;

/// Two paths: a deck of hinges, a rope and a ball joint between two fixed bodies (the block sweep, with
/// one-row and three-row links padded, and a slack rope whose rigid row makes the softness non-uniform),
/// and a chain of eight ropes from a fixed body, some slack (the scalar sweep, with links leaving and
/// joining the system). Twenty steps in the world's order; with `rebuild` every pass builds its rows and
/// factorisations again. Hinges are never carried (`carry_angle` 0): this is about rows and
/// factorisations kept at an unchanged pose. Returns the bodies and the joint states as text (`{:?}` of an
/// `f32` tells any two bit patterns but NaNs apart).
fn steps(rebuild: bool) -> String {
    const STEPS: usize = 20;
    let mut bodies = Vec::new();
    let mut add = |desc: BodyDesc| {
        bodies.push(RigidBody::new(&desc).unwrap());
        bodies.len() - 1
    };
    let ball = |x: f32, y: f32, spin: f32| {
        BodyDesc::dynamic()
            .with_position(Vec3::new(x, y, 0.0))
            .with_rotation(Quat::from_rotation_z(0.1 * x))
            .with_angular_velocity(Vec3::new(0.0, spin, spin))
            .with_mass_properties(
                MassProperties::new(1.0 + x, Vec3::ZERO, Vec3::new(0.2, 0.3, 0.25)).unwrap(),
            )
    };
    let deck: Vec<usize> = [
        add(BodyDesc::fixed()),
        add(ball(1.0, 0.0, 0.5)),
        add(ball(2.0, 0.1, -0.3)),
        add(ball(2.9, 0.0, 0.2)),
        add(ball(4.0, -0.1, 0.0)),
        add(BodyDesc::fixed().with_position(Vec3::new(5.0, 0.0, 0.0))),
    ]
    .to_vec();
    // Ropes alternately stretched and slack, so that links join and leave the system from pass to pass.
    let lengths = [0.95, 0.3, 0.5, 0.6, 0.45, 0.7, 0.5, 0.4];
    let mut chain = vec![add(
        BodyDesc::fixed().with_position(Vec3::new(0.0, 5.0, 0.0))
    )];
    for k in 1..=lengths.len() {
        let wobble = [0.1, -0.2, 0.0, 0.15][k % 4];
        chain.push(add(ball(0.5 * k as f32, 5.0 + wobble, 0.1 * wobble)));
    }
    let hinge = |x: f32| {
        Joint::new(HingeJoint::new())
            .with_local_anchors(Vec3::new(x, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0))
            .unwrap()
            .with_local_axes(Vec3::Z, Vec3::Z)
            .unwrap()
    };
    // The first hinge's motor has no torque, but it keeps the deck from being a closed path (one relaxed
    // in the last substep only), so that its rows are reused in every substep.
    let limited = Joint::new(HingeJoint::new().with_motor(Motor::new(0.0, 0.0).unwrap()))
        .with_local_anchors(Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0))
        .unwrap()
        .with_local_axes(Vec3::Z, Vec3::Z)
        .unwrap();
    let mut joints = vec![
        limited,
        hinge(0.5),
        Joint::new(Rope::new(1.0).unwrap()),
        hinge(0.5),
        Joint::new(BallJoint::new())
            .with_local_anchors(Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0))
            .unwrap(),
    ];
    joints.extend(lengths.map(|length| Joint::new(Rope::new(length).unwrap())));
    let pairs: Vec<JointBodies> = deck
        .windows(2)
        .chain(chain.windows(2))
        .map(|w| JointBodies { a: w[0], b: w[1] })
        .collect();
    let mut states = vec![JointState::default(); joints.len()];
    let settings = SolverSettings::default();
    let mut solver = JointSolver::new();
    solver.carry_angle = 0.0;
    let mut broken = Vec::new();
    let mut reused = 0;
    let ctx = StepContext::new(1.0 / 60.0, &settings);
    for _ in 0..STEPS {
        let mut solver_bodies: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
        let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
        let skipped = solver.prepare(&joints, &states, &pairs, &solver_bodies, &params, &ctx);
        assert_eq!((skipped, solver.topology.paths.len()), (0, 2));
        assert_eq!(
            solver.topology.closed,
            [false, true],
            "the deck has a motor, the chain is closed"
        );
        assert_eq!(solver.reusable_links(&solver_bodies), 0, "prepare forgets");
        for _ in 0..ctx.substep_count {
            integrate_velocities(&mut solver_bodies, &params, &ctx);
            solver.apply_forces(&mut solver_bodies, &ctx);
            // Counted before the warm start, which changes velocities only; forgotten before it, so
            // that the rebuilding run warm-starts its ropes from their own rows, the other from the
            // links' rows.
            reused += solver.reusable_links(&solver_bodies);
            if rebuild {
                solver.forget_rows();
            }
            solver.warm_start(&mut solver_bodies);
            solver.solve(&mut solver_bodies, &ctx, Bias::On);
            integrate_positions(&mut solver_bodies, &params, &ctx);
            reused += solver.reusable_links(&solver_bodies);
            if rebuild {
                solver.forget_rows();
            }
            solver.solve(&mut solver_bodies, &ctx, Bias::Off);
        }
        reused += solver.reusable_links(&solver_bodies);
        if rebuild {
            solver.forget_rows();
        }
        solver.project_positions(&mut solver_bodies, &ctx);
        solver.apply_restitution(&mut solver_bodies, &ctx);
        solver.store_impulses(&mut states, &mut broken);
        for (body, (state, params)) in bodies.iter_mut().zip(solver_bodies.iter().zip(&params)) {
            assert!(params.write_back(state, body));
        }
    }
    // Every deck link is reusable in the solve pass of substeps 2 to 4 and in the projection (the relax
    // pass left the pose), none after the world moved the bodies; the closed chain is relaxed in the last
    // substep only, so its links are reusable in the projection alone.
    let (deck_links, chain_links) = (5, lengths.len());
    assert_eq!(
        reused,
        STEPS * (ctx.substep_count as usize * deck_links + chain_links)
    );
    format!("{bodies:?} {states:?}")
}

#[test]
fn passes_that_reuse_rows_and_factorisations_give_the_bits_of_passes_that_rebuild_them() {
    assert_eq!(steps(false), steps(true));
}

/// The substeps of a step for the joints alone (velocities, warm start, solve, positions, relax), calling
/// `after_relax` after each relax pass.
fn substeps(
    solver: &mut JointSolver,
    solver_bodies: &mut [SolverBody],
    params: &[BodyParams],
    ctx: &StepContext,
    mut after_relax: impl FnMut(&JointSolver, &[SolverBody]),
) {
    for _ in 0..ctx.substep_count {
        integrate_velocities(solver_bodies, params, ctx);
        solver.warm_start(solver_bodies);
        solver.solve(solver_bodies, ctx, Bias::On);
        integrate_positions(solver_bodies, params, ctx);
        solver.solve(solver_bodies, ctx, Bias::Off);
        after_relax(solver, solver_bodies);
    }
}

/// Four planks hinged between two fixed bodies 3.9 m apart (4 m of deck): its bodies, joints and pairs.
fn hinge_deck(plank_mass: f32) -> (Vec<RigidBody>, Vec<Joint>, Vec<JointBodies>) {
    let mut bodies = vec![RigidBody::new(&BodyDesc::fixed()).unwrap()];
    for k in 1..=4 {
        let plank = BodyDesc::dynamic()
            .with_position(Vec3::new(k as f32 - 0.5, 0.0, 0.0))
            .with_mass_properties(
                MassProperties::new(plank_mass, Vec3::ZERO, Vec3::new(0.1, 0.2, 0.3)).unwrap(),
            );
        bodies.push(RigidBody::new(&plank).unwrap());
    }
    let right = BodyDesc::fixed().with_position(Vec3::new(3.9, 0.0, 0.0));
    bodies.push(RigidBody::new(&right).unwrap());
    let joints: Vec<Joint> = (0..5)
        .map(|k| {
            let a = if k == 0 { 0.0 } else { 0.5 };
            let b = if k == 4 { 0.0 } else { -0.5 };
            Joint::new(HingeJoint::new())
                .with_local_anchors(Vec3::new(a, 0.0, 0.0), Vec3::new(b, 0.0, 0.0))
                .unwrap()
                .with_local_axes(Vec3::Z, Vec3::Z)
                .unwrap()
        })
        .collect();
    let pairs: Vec<JointBodies> = (0..5).map(|k| JointBodies { a: k, b: k + 1 }).collect();
    (bodies, joints, pairs)
}

/// A path is closed when its joints' rows are all in the direct solve and nothing else acts on its
/// dynamic bodies; a fixed body may be shared.
#[test]
fn a_path_is_closed_only_if_nothing_else_acts_on_its_dynamic_bodies() {
    let settings = SolverSettings::default();
    let ctx = StepContext::new(1.0 / 60.0, &settings);
    let closed = |bodies: &[RigidBody], joints: &[Joint], pairs: &[JointBodies]| {
        let solver_bodies: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
        let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
        let states = vec![JointState::default(); joints.len()];
        let mut solver = JointSolver::new();
        let skipped = solver.prepare(joints, &states, pairs, &solver_bodies, &params, &ctx);
        assert_eq!(skipped, 0);
        solver.topology.closed
    };
    let (mut bodies, mut joints, mut pairs) = hinge_deck(1.0);
    assert_eq!(closed(&bodies, &joints, &pairs), [true]);
    // A rope from the deck's left anchor to a ball of its own: a second path, sharing a fixed body only.
    bodies.push(
        RigidBody::new(&BodyDesc::dynamic().with_position(Vec3::new(0.0, -1.0, 0.0))).unwrap(),
    );
    joints.push(Joint::new(Rope::new(1.0).unwrap()));
    pairs.push(JointBodies {
        a: 0,
        b: bodies.len() - 1,
    });
    assert_eq!(closed(&bodies, &joints, &pairs), [true, true]);
    // A prismatic joint (not solved directly) on the second plank: the deck is still a path, not a closed
    // one.
    joints.push(Joint::new(PrismaticJoint::new()));
    pairs.push(JointBodies {
        a: 2,
        b: bodies.len() - 1,
    });
    assert_eq!(closed(&bodies, &joints, &pairs), [false, false]);
    // A limit on one hinge: its limit row is in the direct solve, the deck still closed; a motor on it is
    // solved by Gauss–Seidel beside the path's rows, and so is a limit too narrow for the direct solve.
    let (bodies, mut joints, pairs) = hinge_deck(1.0);
    let mut on_third = |hinge: HingeJoint| {
        joints[2] = Joint::new(hinge)
            .with_local_anchors(Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0))
            .unwrap()
            .with_local_axes(Vec3::Z, Vec3::Z)
            .unwrap();
        closed(&bodies, &joints, &pairs)
    };
    assert_eq!(
        on_third(HingeJoint::new().with_limits(-1.0, 1.0).unwrap()),
        [true]
    );
    let motor = Motor::new(1.0, 10.0).unwrap();
    assert_eq!(on_third(HingeJoint::new().with_motor(motor)), [false]);
    assert_eq!(
        on_third(HingeJoint::new().with_limits(0.2, 0.25).unwrap()),
        [false]
    );
}

/// A solver prepared step after step keeps its paths, graphs and closed marks while its joints keep their
/// shapes, and finds them again when they change: after each of a run of changed scenes (a joint added, one
/// not solved directly, a motor, a plank made fixed, the joints reordered, a rope chain, a ladder and a deck
/// between two fixed bodies that are graphs), prepared once and again unchanged, it has the topology of a
/// solver prepared on that scene alone, searched for the changed scene and not again for the unchanged one
/// (but for a graph, which is always searched).
#[test]
fn paths_kept_from_the_last_step_are_those_a_fresh_search_finds() {
    let settings = SolverSettings::default();
    let ctx = StepContext::new(1.0 / 60.0, &settings);
    let topology = |solver: &JointSolver| {
        let t = &solver.topology;
        (
            t.paths.clone(),
            t.path_joints.clone(),
            t.closed.clone(),
            t.graph_of.clone(),
        )
    };
    let prepare = |solver: &mut JointSolver, (bodies, joints, pairs): &Scene| {
        let solver_bodies: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
        let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
        let states = vec![JointState::default(); joints.len()];
        solver.prepare(joints, &states, pairs, &solver_bodies, &params, &ctx);
    };
    type Scene = (Vec<RigidBody>, Vec<Joint>, Vec<JointBodies>);
    let mut scenes: Vec<Scene> = Vec::new();
    // The deck between two fixed bodies (more rows than degrees of freedom: a graph), then, its last body
    // and hinge taken off, four planks hanging from a fixed body by hinges: a path.
    let mut deck = hinge_deck(1.0);
    scenes.push(deck.clone());
    deck.0.pop();
    deck.1.pop();
    deck.2.pop();
    scenes.push(deck.clone());
    // A rope from the left anchor to a ball: a second path.
    let mut with_rope = deck.clone();
    with_rope.0.push(
        RigidBody::new(&BodyDesc::dynamic().with_position(Vec3::new(0.0, -1.0, 0.0))).unwrap(),
    );
    with_rope.1.push(Joint::new(Rope::new(1.0).unwrap()));
    with_rope.2.push(JointBodies {
        a: 0,
        b: with_rope.0.len() - 1,
    });
    scenes.push(with_rope.clone());
    // A prismatic joint on a plank: the deck is not closed.
    let mut with_prismatic = with_rope.clone();
    with_prismatic.1.push(Joint::new(PrismaticJoint::new()));
    with_prismatic.2.push(JointBodies {
        a: 2,
        b: with_prismatic.0.len() - 1,
    });
    scenes.push(with_prismatic);
    // A motor on the third hinge (Gauss–Seidel beside the path).
    let mut with_motor = deck.clone();
    with_motor.1[2] = Joint::new(HingeJoint::new().with_motor(Motor::new(1.0, 10.0).unwrap()))
        .with_local_anchors(Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0))
        .unwrap()
        .with_local_axes(Vec3::Z, Vec3::Z)
        .unwrap();
    scenes.push(with_motor);
    // The second plank fixed: two paths.
    let mut pinned = deck.clone();
    pinned.0[2] =
        RigidBody::new(&BodyDesc::fixed().with_position(Vec3::new(1.5, 0.0, 0.0))).unwrap();
    scenes.push(pinned);
    // The joints in another order.
    let mut reordered = with_rope.clone();
    reordered.1.reverse();
    reordered.2.reverse();
    scenes.push(reordered);
    // A chain of ropes hanging from a fixed body.
    let mut chain: Scene = (
        vec![RigidBody::new(&BodyDesc::fixed()).unwrap()],
        Vec::new(),
        Vec::new(),
    );
    for k in 1..=6 {
        let ball = BodyDesc::dynamic().with_position(Vec3::new(0.0, -(k as f32), 0.0));
        chain.0.push(RigidBody::new(&ball).unwrap());
        chain.1.push(Joint::new(Rope::new(1.0).unwrap()));
        chain.2.push(JointBodies { a: k - 1, b: k });
    }
    scenes.push(chain);
    // Two decks side by side with rungs between their planks: a ladder, solved as a graph.
    let mut ladder = deck.clone();
    let offset = ladder.0.len();
    for body in &deck.0 {
        ladder.0.push(body.clone());
    }
    for (joint, pair) in deck.1.iter().zip(&deck.2) {
        ladder.1.push(*joint);
        ladder.2.push(JointBodies {
            a: pair.a + offset,
            b: pair.b + offset,
        });
    }
    for k in [2, 3] {
        ladder.1.push(Joint::new(BallJoint::new()));
        ladder.2.push(JointBodies {
            a: k,
            b: k + offset,
        });
    }
    scenes.push(ladder);
    scenes.push(deck);
    let mut kept = JointSolver::new();
    let (mut graphs, mut kept_paths) = (false, 0);
    for (k, scene) in scenes.iter().enumerate() {
        for again in 0..2 {
            let searches = kept.topology.searches;
            prepare(&mut kept, scene);
            let searched = kept.topology.searches > searches;
            let mut fresh = JointSolver::new();
            prepare(&mut fresh, scene);
            assert_eq!(
                topology(&kept),
                topology(&fresh),
                "scene {k}, prepared {again}"
            );
            graphs |= kept.topology.graph_of.iter().any(Option::is_some);
            let no_graph = kept.topology.graph_of.iter().all(Option::is_none);
            // A changed scene is searched; the same one again is not, unless it has a graph.
            if again == 0 {
                assert!(searched, "scene {k}: changed joints kept the last paths");
            } else if no_graph {
                assert!(!searched, "scene {k}: the same joints were searched again");
                kept_paths += usize::from(!kept.topology.paths.is_empty());
            }
        }
    }
    assert!(graphs, "the scenes have a graph");
    assert!(
        kept_paths >= 5,
        "paths kept without a graph in {kept_paths} scenes"
    );
}

/// A deck's hinge rows are kept into the next step — for the same joints, between the same bodies, with
/// the same inverse masses — and dropped for a path with any of them changed.
#[test]
fn a_path_keeps_its_rows_into_the_next_step_only_unchanged() {
    let (mut bodies, joints, pairs) = hinge_deck(1.0);
    let mut states = vec![JointState::default(); joints.len()];
    let settings = SolverSettings::default();
    let ctx = StepContext::new(1.0 / 60.0, &settings);
    let mut solver = JointSolver::new();
    let mut broken = Vec::new();
    let prepare = |solver: &mut JointSolver,
                   bodies: &[RigidBody],
                   (joints, pairs): (&[Joint], &[JointBodies]),
                   states: &[JointState]| {
        let solver_bodies: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
        let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
        let skipped = solver.prepare(joints, states, pairs, &solver_bodies, &params, &ctx);
        assert_eq!(skipped, 0);
        (solver_bodies, params)
    };
    let deck = (&joints[..], &pairs[..]);
    let kept = |solver: &JointSolver| {
        solver.links[..solver.path_links]
            .iter()
            .filter(|l| l.keeps_last_step_masses())
            .count()
    };
    // A fresh solver keeps nothing; after a step every link is kept.
    let (mut solver_bodies, params) = prepare(&mut solver, &bodies, deck, &states);
    assert_eq!(kept(&solver), 0);
    substeps(&mut solver, &mut solver_bodies, &params, &ctx, |_, _| {});
    solver.project_positions(&mut solver_bodies, &ctx);
    solver.store_impulses(&mut states, &mut broken);
    for (body, (state, params)) in bodies.iter_mut().zip(solver_bodies.iter().zip(&params)) {
        assert!(params.write_back(state, body));
    }
    assert_eq!(solver.kept_rows().len(), 5);
    let before = solver.kept_rows();
    let _ = prepare(&mut solver, &bodies, deck, &states);
    assert_eq!(kept(&solver), 5);
    // The same rows from a snapshot: kept alike.
    let mut restored = JointSolver::new();
    restored.restore_kept_rows(&before);
    let _ = prepare(&mut restored, &bodies, deck, &states);
    assert_eq!(kept(&restored), 5);
    // A plank turned past the carry angle since the build (its inverse inertia too far from the kept
    // one), a heavier plank (other inverse masses), or the joints given in another order (each link of
    // the path another joint's): nothing kept.
    let mut turned = JointSolver::new();
    turned.restore_kept_rows(&before);
    let mut spun = bodies.clone();
    let pose = spun[3].pose();
    let rotation = Quat::from_rotation_x(2.0 * CARRY_ANGLE) * pose.rotation;
    spun[3]
        .set_pose(rebound_math::Pose::new(pose.position, rotation))
        .unwrap();
    let _ = prepare(&mut turned, &spun, deck, &states);
    assert_eq!(kept(&turned), 0);
    let mut heavier = JointSolver::new();
    heavier.restore_kept_rows(&before);
    let mut changed = bodies.clone();
    changed[2].set_mass_properties(
        MassProperties::new(2.0, Vec3::ZERO, Vec3::new(0.1, 0.2, 0.3)).unwrap(),
    );
    let _ = prepare(&mut heavier, &changed, deck, &states);
    assert_eq!(kept(&heavier), 0);
    let mut reordered = JointSolver::new();
    reordered.restore_kept_rows(&before);
    let (joints_back, pairs_back): (Vec<Joint>, Vec<JointBodies>) = joints
        .iter()
        .rev()
        .copied()
        .zip(pairs.iter().rev().copied())
        .unzip();
    let _ = prepare(
        &mut reordered,
        &bodies,
        (&joints_back, &pairs_back),
        &states,
    );
    assert_eq!(kept(&reordered), 0);
}

/// A deck of hinges between two fixed bodies, sagging under gravity: the relax passes of substeps 1 to 3
/// carry the hinges' rows (the planks turn by less than the carry angle a substep), the last relax pass
/// of the step builds them at the final pose, so that the projection finds every link's rows (and their
/// factorisation) made at its pose.
#[test]
fn the_last_relax_pass_builds_the_rows_the_projection_reuses() {
    let (bodies, joints, pairs) = hinge_deck(1.0);
    let states = vec![JointState::default(); joints.len()];
    let settings = SolverSettings::default();
    let ctx = StepContext::new(1.0 / 60.0, &settings);
    let mut solver = JointSolver::new();
    let mut solver_bodies: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
    let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
    let skipped = solver.prepare(&joints, &states, &pairs, &solver_bodies, &params, &ctx);
    assert_eq!((skipped, solver.topology.paths.len()), (0, 1));
    let mut after_relax = Vec::new();
    substeps(
        &mut solver,
        &mut solver_bodies,
        &params,
        &ctx,
        |solver, bodies| {
            after_relax.push(solver.reusable_links(bodies));
        },
    );
    // Carried in the first relax passes (built at the step's first pass, not at their pose), built in the
    // last one.
    assert_eq!(after_relax, [0, 0, 0, 5]);
}

/// A hinge between two dynamic bodies, prepared, with its rows built in `link` at the bodies' pose; the
/// projection's stage, which makes every row's bias its position error.
fn built_hinge() -> (JointSolver, Vec<SolverBody>, Link, Stage) {
    let desc = |x: f32, angle: f32| {
        BodyDesc::dynamic()
            .with_position(Vec3::new(x, 0.2 * x, 0.0))
            .with_rotation(Quat::from_rotation_z(angle))
            .with_mass_properties(
                MassProperties::new(1.5, Vec3::ZERO, Vec3::new(0.2, 0.3, 0.25)).unwrap(),
            )
    };
    let bodies = [desc(0.0, 0.1), desc(1.0, -0.2)].map(|d| RigidBody::new(&d).unwrap());
    let solver_bodies: Vec<SolverBody> = bodies.iter().map(SolverBody::from_body).collect();
    let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
    let joint = Joint::new(HingeJoint::new())
        .with_local_anchors(Vec3::new(0.5, 0.1, 0.0), Vec3::new(-0.5, 0.0, 0.1))
        .unwrap()
        .with_local_axes(Vec3::Z, Vec3::new(0.1, 0.0, 1.0).normalize())
        .unwrap();
    let settings = SolverSettings::default();
    let ctx = StepContext::new(1.0 / 60.0, &settings);
    let mut solver = JointSolver::new();
    let states = [JointState::default()];
    let pairs = [JointBodies { a: 0, b: 1 }];
    assert_eq!(
        solver.prepare(&[joint], &states, &pairs, &solver_bodies, &params, &ctx),
        0
    );
    let stage = Stage::projection(ctx.h);
    let mut link = empty_link();
    let j = &mut solver.joints[0];
    let (a, b) = (&solver_bodies[0], &solver_bodies[1]);
    let _ = rows_at(j, Some((a, b)), &stage, &mut link, false);
    link.built_at(Some(PoseKey::of(a, b)));
    link.built = Some(build_site(j, a, b));
    (solver, solver_bodies, link, stage)
}

#[test]
fn carried_hinge_rows_have_the_errors_of_the_new_pose_to_first_order() {
    let shift = Vec3::new(0.01, -0.02, 0.005);
    let axis = Vec3::new(0.3, 0.5, 0.8).normalize();
    for (turn_a, turn_b) in [(0.0, 0.0), (0.002, -0.004), (-0.009, 0.0095)] {
        let (solver, mut bodies, mut link, stage) = built_hinge();
        let built = link;
        bodies[0].delta_position -= 0.5 * shift;
        bodies[0].delta_rotation = Quat::from_axis_angle(axis, turn_a);
        bodies[1].delta_position += shift;
        bodies[1].delta_rotation = Quat::from_axis_angle(Vec3::new(axis.z, axis.x, axis.y), turn_b);
        let (a, b) = (&bodies[0], &bodies[1]);
        let j = &solver.joints[0];
        assert!(carry(
            j,
            &mut link,
            (a, b),
            &PoseKey::of(a, b),
            &stage,
            CARRY_ANGLE
        ));
        // Jacobians and turned vectors kept, only the targets changed; the rows still count as built at
        // the first pose.
        for (carried, kept) in link.rows.rows().iter().zip(built.rows.rows()) {
            assert_eq!((carried.a, carried.b), (kept.a, kept.b));
        }
        assert!(!link.is_built_at(&PoseKey::of(a, b)));
        let exact = PreparedHinge::direct_errors(&solver.joints[0].pair, a, b);
        // Point rows are linear in the displacements (exact up to rounding: the first case, a translation
        // alone, is held to 1e-6 m); a turn θ of a lever r moves an anchor by r·θ²/2 beyond its
        // linearisation (levers ≤ 0.52 m), and the alignment rows' error is second order in θ likewise.
        let theta = turn_a.abs().max(turn_b.abs());
        let bound = 1e-6 + 0.6 * theta * theta;
        for (row, &(c, _)) in link.rows.rows().iter().zip(&exact) {
            let error = (row.target.bias - c).abs();
            assert!(
                error <= bound,
                "{turn_a} {turn_b}: {} vs {c}",
                row.target.bias
            );
        }
    }
}

/// A pass at the pose the rows were last carried to (the solve pass after a relax pass) takes the carried
/// errors as they are: the targets a second carry would compute, bit for bit, for another stage; at any
/// other pose, nothing.
#[test]
fn a_pass_at_the_pose_carried_to_recomputes_only_the_targets() {
    let (solver, mut bodies, mut link, relax) = built_hinge();
    let j = &solver.joints[0];
    bodies[0].delta_position += Vec3::new(0.003, -0.001, 0.002);
    bodies[1].delta_rotation = Quat::from_rotation_z(0.004);
    let (a, b) = (&bodies[0], &bodies[1]);
    let now = PoseKey::of(a, b);
    assert!(carry(j, &mut link, (a, b), &now, &relax, CARRY_ANGLE));
    let solve = Stage {
        bias: Bias::On,
        h: 1.0 / 240.0,
        inv_h: 240.0,
        joint_softness: JointSettings::default()
            .joint_softness(&StepContext::new(1.0 / 60.0, &SolverSettings::default())),
    };
    let mut carried_again = link;
    assert!(carry(
        j,
        &mut carried_again,
        (a, b),
        &now,
        &solve,
        CARRY_ANGLE
    ));
    assert!(link.recarry(&now, &solve));
    assert_eq!(link, carried_again);
    // Elsewhere it refuses and changes nothing.
    bodies[1].delta_position.y += 1e-4;
    let (a, b) = (&bodies[0], &bodies[1]);
    let kept = link;
    assert!(!link.recarry(&PoseKey::of(a, b), &solve));
    assert_eq!(link, kept);
}

#[test]
fn a_hinge_turned_further_than_the_carry_angle_is_not_carried() {
    let (solver, mut bodies, mut link, stage) = built_hinge();
    let j = &solver.joints[0];
    let built = link;
    let carries = |link: &mut Link, bodies: &[SolverBody], angle: f32| {
        let (a, b) = (&bodies[0], &bodies[1]);
        carry(j, link, (a, b), &PoseKey::of(a, b), &stage, angle)
    };
    bodies[1].delta_rotation = Quat::from_rotation_x(1.2 * CARRY_ANGLE);
    assert!(!carries(&mut link, &bodies, CARRY_ANGLE));
    assert_eq!(link, built, "nothing changed");
    // Nor is any pose with a carry angle of 0, or a link holding no carried rows.
    bodies[1].delta_rotation = Quat::IDENTITY;
    assert!(!carries(&mut link, &bodies, 0.0));
    link.drop_built();
    assert!(!carries(&mut link, &bodies, CARRY_ANGLE));
}
