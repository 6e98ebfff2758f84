//! Stage *project positions* (once, after the substeps): the Newton steps that move each directly solved
//! path's bodies so that its joints hold exactly, the stiffened and shortened steps tried when a full one
//! does not help, and the Gauss–Seidel sweeps after them.

use super::dispatch::PreparedJoint;
use super::joint_solver::JointSolver;
use super::path_pass::{direct_rows, link_rows, solve_links};
use super::projection_velocity::apply_turning_rows;
use crate::path::topology::Topology;
use crate::path::{DirectGraph, Link, MAX_ROWS, Real, link_at, project_rows, resize_links};
use crate::stage::Stage;
use rebound_dynamics::{SolverBody, StepContext};

/// Newton iterations of the position projection (the rows are re-linearised at the moved poses).
pub(super) const PROJECTION_ITERATIONS: usize = 4;

/// A path whose worst position error is within this (m, or rad for angular rows) is not projected: 0.1 mm is
/// below what a game shows, and a settled chain or bridge then costs nothing here.
pub(super) const PROJECTION_TOLERANCE: f32 = 1e-4;

/// [`PROJECTION_TOLERANCE`] for a joint graph (m, or rad): a tenth of it. A path's errors do not add up, a
/// loop's do — twenty rods each 0.1 mm long change a 5 m loop's length by 0.04 % — and the graphs solved
/// directly are small (at most [`crate::path`]'s `MAX_GRAPH_JOINTS` joints), so the tighter bound costs a
/// Newton step or two where it is not met.
pub(super) const GRAPH_PROJECTION_TOLERANCE: f32 = 1e-5;

/// Nonlinear Gauss–Seidel sweeps (alternating direction) after the direct projection, at most; they stop once
/// the path is within [`PROJECTION_TOLERANCE`], checked every [`PROJECTION_SWEEP_CHECK`] sweeps.
pub(super) const PROJECTION_SWEEPS: usize = 16;

/// How many sweeps run between two measurements of the path's worst error.
pub(super) const PROJECTION_SWEEP_CHECK: usize = 4;

/// How much stiffer than their geometric stiffness `|p|/L` the projection makes pulled ropes and rods against
/// turning when a plain Newton step is rejected ([`Link::stiffen`]). The exact Newton step weighs the
/// Hessian of each link's length by the multiplier of the step it takes, which is larger than the plain step's
/// `p` it is estimated from (several times larger at a whipping chain's tip), and a stiffer metric errs on
/// the safe side: in the limit the links only change length, which for a chain hanging from an anchor is
/// exact.
pub(super) const PROJECTION_STIFFENING: f32 = 10.0;

/// The fraction of the worst error a full Newton step of the projection must get a path with ropes or rods
/// down to for it to be kept as it is. Near the solution Newton's error shrinks quadratically; a step that
/// does not even quarter it is one whose linearisation is poor (links turning within the step), and the
/// stiffened step ([`PROJECTION_STIFFENING`]) is tried instead: steps kept for gaining a few per cent would
/// use up the iterations.
pub(super) const PROJECTION_NEWTON_GAIN: f32 = 0.25;

impl JointSolver {
    /// Stage *project positions* (once, after the substeps): moves the bodies of every directly solved path
    /// so that its joints hold exactly — stretched ropes back to their length, hinge and ball anchors together
    /// — by solving `K·x = C` for the position errors `C` of all the path's rows at once and displacing the
    /// bodies by `−M⁻¹·Jᵀ·x` (Box2D v2's position pass, solved exactly for the path). Velocities are left
    /// alone, so this adds no energy. Why it is needed: the velocity passes keep `Ċ = 0` only to first order;
    /// a link that turns fast (the whip of a falling chain turns links by 90° within a step) drifts by
    /// `(v·h)²/(2L)` in each substep, far more than the soft correction takes back.
    pub fn project_positions(&mut self, solver_bodies: &mut [SolverBody], ctx: &StepContext) {
        let stage = Stage::projection(ctx.h);
        self.position_impulses.clear();
        self.position_impulses
            .resize(self.topology.path_joints.len(), 0.0);
        for path in 0..self.topology.paths.len() {
            let Some(range) = self.topology.paths.get(path).cloned() else {
                continue;
            };
            let Self {
                joints,
                topology,
                links,
                solution,
                saved,
                probe,
                position_impulses,
                ..
            } = self;
            let graph = topology.graph(path);
            let Topology {
                path_joints,
                graphs,
                ..
            } = topology;
            let mut graph = graph.and_then(|g| graphs.get_mut(g));
            let tolerance = if graph.is_some() {
                GRAPH_PROJECTION_TOLERANCE
            } else {
                PROJECTION_TOLERANCE
            };
            resize_links(links, path_joints.len());
            let (Some(members), Some(links), Some(impulses)) = (
                path_joints.get(range.clone()),
                links.get_mut(range.clone()),
                position_impulses.get_mut(range),
            ) else {
                continue;
            };
            let worst =
                |joints: &mut [PreparedJoint], solver_bodies: &[SolverBody], probe: &mut Link| {
                    path_worst(joints, members, solver_bodies, &stage, probe)
                };
            // The worst error at the bodies' current pose, once measured: the Newton loop always ends at a
            // pose it measured (the one it stopped at, the last step it accepted, or the one it restored), so
            // the sweeps below need not build every joint's rows again to know it.
            let mut known = None;
            // Only a path with ropes or rods can be stiffened: the others keep any full step that helps.
            let gain = if members
                .iter()
                .any(|&index| joints[index].kind.link_length().is_some())
            {
                PROJECTION_NEWTON_GAIN
            } else {
                1.0
            };
            for _ in 0..PROJECTION_ITERATIONS {
                let mut before = 0.0f32;
                // The first iteration is at the pose of the last relax pass: its rows (retargeted) and, if
                // the same rows are in the system, its factorisation serve again.
                for (link, &index) in links.iter_mut().zip(members) {
                    let bodies = joints[index].pair.bodies(solver_bodies);
                    link_rows(&mut joints[index], bodies, &stage, link, 0.0);
                    before = before.max(link.rows.violation());
                    link.make_positional(tolerance);
                }
                known = Some(before);
                if before <= tolerance {
                    break;
                }
                solve_links(
                    joints,
                    members,
                    links,
                    solution,
                    solver_bodies,
                    graph.as_deref_mut(),
                );
                save_bodies(joints, members, solver_bodies, saved);
                let probe = link_at(probe, 0);
                // A Newton step can overshoot where the linearisation is poor: a light body between two
                // nearly aligned, pulled links is moved far sideways (by about `p·θ/m` for a position
                // impulse `p` through links turned by `θ`), which lengthens both links by the square of
                // that, far more than the step was meant to close. If the full step does not get the worst error down to `gain` of it, the
                // path's ropes and rods are stiffened against turning (`stiffen`) and the step solved again,
                // kept if it makes things no worse; if that fails too, or nothing can be stiffened, half of
                // the last step is tried, then a quarter. If even that fails, the next iteration would start
                // from the same pose: stop.
                let mut step = NewtonStep {
                    joints: &mut *joints,
                    members,
                    links: &mut *links,
                    solution: &mut *solution,
                    solver_bodies: &mut *solver_bodies,
                    saved,
                    probe,
                    stage: &stage,
                    impulses: &mut *impulses,
                    graph: graph.as_deref_mut(),
                };
                let mut after = step.try_scaled(before * gain, 1.0, 1);
                if after.is_none() && step.stiffen_and_solve() {
                    after = step.try_scaled(before, 1.0, 1);
                }
                if after.is_none() {
                    after = step.try_scaled(before, 0.5, 2);
                }
                match after {
                    // Within tolerance: the next iteration would build every row only to measure the error
                    // the step just measured.
                    Some(after) if after <= tolerance => {
                        known = Some(after);
                        break;
                    }
                    Some(after) => known = Some(after),
                    None => break,
                }
            }
            // Nonlinear Gauss–Seidel sweeps, alternating direction, take back what the linearisation missed —
            // kept only where they do not make the path's worst error larger.
            let probe = link_at(probe, 0);
            let before = match known {
                Some(before) => before,
                None => worst(joints, solver_bodies, probe),
            };
            if before <= tolerance {
                continue;
            }
            save_bodies(joints, members, solver_bodies, saved);
            for sweep in 0..PROJECTION_SWEEPS {
                for k in 0..members.len() {
                    let index = members[if sweep % 2 == 0 {
                        k
                    } else {
                        members.len() - 1 - k
                    }];
                    let j = &mut joints[index];
                    let _ = direct_rows(j, solver_bodies, &stage, probe);
                    if let Some([a, b]) = j.pair.bodies_mut(solver_bodies) {
                        project_rows(&probe.rows, a, b);
                    }
                }
                if (sweep + 1) % PROJECTION_SWEEP_CHECK == 0 || sweep + 1 == PROJECTION_SWEEPS {
                    let after = worst(joints, solver_bodies, probe);
                    if after > before {
                        restore_bodies(saved, solver_bodies);
                        break;
                    }
                    if after <= tolerance {
                        break;
                    }
                }
            }
        }
        // The velocities of bodies moved along turning rows (`projection_velocity.rs`): without them, each
        // projection takes the centripetal work of its shortening out of a swinging rope.
        apply_turning_rows(
            &self.joints,
            &self.topology.path_joints,
            &self.position_impulses,
            solver_bodies,
        );
    }
}

/// The worst position error of joint `j`'s rows at the bodies' current pose (see `JointRows::violation`),
/// built in `scratch` — or, for a ball joint or hinge, whose rows are all equalities, measured from the rows'
/// errors alone ([`equality_violation`]): the same value without building the Jacobians.
pub(super) fn violation(
    j: &mut PreparedJoint,
    solver_bodies: &[SolverBody],
    stage: &Stage,
    scratch: &mut Link,
) -> f32 {
    if let Some(bodies) = j.pair.bodies(solver_bodies)
        && let Some(worst) = j.kind.equality_violation(&j.pair, bodies, stage)
    {
        return worst;
    }
    let _ = direct_rows(j, solver_bodies, stage, scratch);
    scratch.rows.violation()
}

/// The worst position error of the path's joints at the bodies' current pose.
pub(super) fn path_worst(
    joints: &mut [PreparedJoint],
    members: &[usize],
    solver_bodies: &[SolverBody],
    stage: &Stage,
    probe: &mut Link,
) -> f32 {
    members
        .iter()
        .map(|&index| violation(&mut joints[index], solver_bodies, stage, probe))
        .fold(0.0f32, f32::max)
}

/// What a Newton step of the position projection reads and moves: one path's joints, links and solved step
/// `solution`, the solver bodies and their saved pose, the probe link, the projection's stage and the
/// path's graph if it is one.
pub(super) struct NewtonStep<'a> {
    pub(super) joints: &'a mut [PreparedJoint],
    pub(super) members: &'a [usize],
    pub(super) links: &'a mut [Link],
    pub(super) solution: &'a mut Vec<[Real; MAX_ROWS]>,
    pub(super) solver_bodies: &'a mut [SolverBody],
    pub(super) saved: &'a [(usize, SolverBody)],
    pub(super) probe: &'a mut Link,
    pub(super) stage: &'a Stage,
    /// Per link, the position impulse of its rope or rod row summed over the accepted steps.
    pub(super) impulses: &'a mut [f32],
    /// The path's graph, if it is one ([`DirectGraph`]).
    pub(super) graph: Option<&'a mut DirectGraph>,
}

impl NewtonStep<'_> {
    /// Applies `first` times the step `solution` to the path's bodies (saved in `saved`), then half of that,
    /// and so on (up to `sizes` sizes), until the path's worst error is no larger than `target`; returns the
    /// worst error of the step kept, or `None` with the bodies restored if no size was good enough.
    pub(super) fn try_scaled(&mut self, target: f32, first: Real, sizes: usize) -> Option<f32> {
        let mut scale = first;
        for _ in 0..sizes {
            for ((link, x), &index) in self.links.iter_mut().zip(&*self.solution).zip(self.members)
            {
                if let Some([a, b]) = self.joints[index].pair.bodies_mut(self.solver_bodies) {
                    link.apply_solution(&x.map(|v| v * scale), a, b);
                }
            }
            let after = path_worst(
                self.joints,
                self.members,
                self.solver_bodies,
                self.stage,
                self.probe,
            );
            if after <= target {
                self.add_distance_impulses(scale);
                return Some(after);
            }
            restore_bodies(self.saved, self.solver_bodies);
            scale *= 0.5;
        }
        None
    }

    /// Adds `scale` times the solution's position impulse of each rope's and rod's distance row (its first,
    /// while active; what `Link::apply_solution` displaced the bodies by) to `impulses`.
    fn add_distance_impulses(&mut self, scale: Real) {
        for ((link, x), (&index, total)) in self
            .links
            .iter()
            .zip(&*self.solution)
            .zip(self.members.iter().zip(self.impulses.iter_mut()))
        {
            if !link.active[0] || self.joints[index].kind.link_length().is_none() {
                continue;
            }
            let row = &link.rows.rows[0];
            *total += crate::part::clamp_impulse(-((x[0] * scale) as f32), row.lower, row.upper);
        }
    }

    /// Stiffens the path's pulled ropes and rods ([`stiffen`]) and, if any was, solves the step again; whether
    /// it was.
    pub(super) fn stiffen_and_solve(&mut self) -> bool {
        let stiffened = stiffen(self.joints, self.members, self.links, self.solution);
        if stiffened {
            solve_links(
                self.joints,
                self.members,
                self.links,
                self.solution,
                self.solver_bodies,
                self.graph.as_deref_mut(),
            );
        }
        stiffened
    }
}

/// Stiffens the path's pulled rope and rod links against turning for another Newton step of the projection
/// ([`Link::stiffen`]), each with [`PROJECTION_STIFFENING`] times the geometric stiffness `|p|/L` of its
/// position impulse `p` in `solution` (the rejected plain step) and its length `L`. Returns whether any link
/// was stiffened (none on a path without ropes and rods, or whose ropes all are slack).
pub(super) fn stiffen(
    joints: &[PreparedJoint],
    members: &[usize],
    links: &mut [Link],
    solution: &[[Real; MAX_ROWS]],
) -> bool {
    let mut any = false;
    for ((link, x), &index) in links.iter_mut().zip(solution).zip(members) {
        let Some(length) = joints[index].kind.link_length() else {
            continue;
        };
        if !link.active[0] {
            continue;
        }
        let row = &link.rows.rows[0];
        let p = crate::part::clamp_impulse(-(x[0] as f32), row.lower, row.upper).abs();
        any |= link.stiffen(PROJECTION_STIFFENING * p / length);
    }
    any
}

/// Saves the bodies of the path's joints, so that a projection step that makes things worse can be undone.
pub(super) fn save_bodies(
    joints: &[PreparedJoint],
    members: &[usize],
    solver_bodies: &[SolverBody],
    saved: &mut Vec<(usize, SolverBody)>,
) {
    saved.clear();
    for &index in members {
        let pair = &joints[index].pair;
        if let Some((a, b)) = pair.load(solver_bodies) {
            saved.push((pair.index_a, a));
            saved.push((pair.index_b, b));
        }
    }
}

/// Undoes what happened to the bodies since [`save_bodies`] (in reverse, so a body saved twice gets its first
/// copy, which is the same).
pub(super) fn restore_bodies(saved: &[(usize, SolverBody)], solver_bodies: &mut [SolverBody]) {
    for &(index, body) in saved.iter().rev() {
        if let Some(slot) = solver_bodies.get_mut(index) {
            *slot = body;
        }
    }
}
