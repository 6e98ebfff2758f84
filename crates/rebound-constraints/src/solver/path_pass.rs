//! One direct pass over a path (every solve and relax pass, and the projection's Newton steps): each
//! member's rows at the current pose — kept, carried or built by its joint — handed to the path solver
//! ([`crate::path`]), its active-set rounds, and the impulses written back to the joints.

use super::dispatch::{PreparedJoint, state_lambda};
use super::joint_solver::JointSolver;
use crate::path::topology::Topology;
use crate::path::{
    BuiltAt, DirectGraph, InvMass, Link, MAX_ROWS, PoseKey, Real, Resume, activate_violations,
    resize_links, solve_path,
};
use crate::stage::Stage;
use rebound_dynamics::SolverBody;
use rebound_math::par;

/// How many times a direct path solve may drop rows that would push, add rows it would violate, and solve
/// again.
pub(super) const ACTIVE_SET_ROUNDS: usize = 4;

impl JointSolver {
    /// One direct pass over path `path` ([`crate::path`]): the rows of its joints at the current pose, the
    /// exact solve of their coupled system, the soft update of each row.
    ///
    /// A link whose bodies are where they were when its rows were built — the bits of their displacements
    /// and rotations ([`PoseKey`]) unchanged, as from a relax pass to the next substep's solve pass, where
    /// only velocities change — keeps its rows and recomputes only their targets for this pass's stage; the
    /// others are built again. The solve keeps each link's factorisation while that link and its neighbours
    /// have the rows, and the rows in the system, it was made for ([`solve_path`]). Both give the bits a
    /// rebuild would.
    pub(super) fn solve_path(
        &mut self,
        path: usize,
        solver_bodies: &mut [SolverBody],
        stage: &Stage,
        carry_angle: f32,
    ) {
        let Some(range) = self.topology.paths.get(path).cloned() else {
            return;
        };
        let Self {
            joints,
            topology,
            links,
            solution,
            ..
        } = self;
        // `prepare` sized the links to the path members; a solver never prepared has no paths.
        let graph = topology.graph(path);
        let Topology {
            path_joints,
            graphs,
            ..
        } = topology;
        let graph = graph.and_then(|g| graphs.get_mut(g));
        resize_links(links, path_joints.len());
        let (Some(members), Some(links)) = (path_joints.get(range.clone()), links.get_mut(range))
        else {
            return;
        };
        let carry_angle = if graph.is_some() { 0.0 } else { carry_angle };
        if !rows_on_pool(joints, members, links, solver_bodies, (stage, carry_angle)) {
            for (link, &index) in links.iter_mut().zip(members) {
                let j = &mut joints[index];
                // The bodies in place serve the rows and the activation.
                match j.pair.bodies_mut(solver_bodies) {
                    Some([a, b]) => {
                        link_rows(j, Some((&*a, &*b)), stage, link, carry_angle);
                        link.activate(a, b);
                    }
                    None => link_rows(j, None, stage, link, carry_angle),
                }
            }
        }
        solve_links(joints, members, links, solution, solver_bodies, graph);
        for ((link, x), &index) in links.iter_mut().zip(solution.iter()).zip(members) {
            let j = &mut joints[index];
            let Some([a, b]) = j.pair.bodies_mut(solver_bodies) else {
                continue;
            };
            link.apply_solution(x, a, b);
            j.kind.store_direct_impulses(&mut j.state, link.lambda);
        }
    }

    /// Drops the rows and factorisations kept between passes, so that the next pass builds everything again
    /// (what a pass did before they were kept).
    #[cfg(test)]
    pub(super) fn forget_rows(&mut self) {
        for link in &mut self.links {
            link.forget();
        }
    }

    /// How many links of the paths have rows built at the bodies' current pose (the next pass reuses them).
    #[cfg(test)]
    pub(super) fn reusable_links(&self, solver_bodies: &[SolverBody]) -> usize {
        self.topology
            .path_joints
            .iter()
            .zip(&self.links)
            .filter(|&(&index, link)| {
                let pose = self.joints[index]
                    .pair
                    .load(solver_bodies)
                    .map(|(a, b)| PoseKey::of(&a, &b));
                pose.is_some_and(|pose| link.is_built_at(&pose))
            })
            .count()
    }
}

/// Paths of at least this many links build their rows over the pool ([`rows_on_pool`]).
const ROWS_ON_POOL_MIN_LINKS: usize = 64;

/// The first step of a direct pass over a long path on the pool: every link's rows at its bodies' pose
/// ([`link_rows`]) at once, then each link's activation in path order. A link's rows read only its bodies'
/// pose (displacements and rotations) and write the link and its joint; the activation reads and changes
/// only velocities: so the rows may be built all before the activations, and the pass computes the bits of
/// the joint-by-joint loop. Taken when the pool has more than one thread, the path is at least
/// [`ROWS_ON_POOL_MIN_LINKS`] long and its joints are consecutive prepared joints in path order (as a chain
/// or a deck built link after link is); returns whether it ran.
fn rows_on_pool(
    joints: &mut [PreparedJoint],
    members: &[usize],
    links: &mut [Link],
    solver_bodies: &mut [SolverBody],
    (stage, carry_angle): (&Stage, f32),
) -> bool {
    if !par::is_parallel() || links.len() < ROWS_ON_POOL_MIN_LINKS {
        return false;
    }
    let Some(&first) = members.first() else {
        return false;
    };
    let consecutive = members.iter().zip(first..).all(|(&m, k)| m == k);
    let Some(path_joints) = joints.get_mut(first..first + members.len()) else {
        return false;
    };
    if !consecutive || path_joints.len() != links.len() {
        return false;
    }
    let bodies: &[SolverBody] = solver_bodies;
    // Two tasks: a rope's rows cost less than handing out more.
    let half = links.len().div_ceil(2);
    par::for_each_zip_both_mut(links, path_joints, half, |link, j| {
        // As `bodies_mut` in the loop: no rows for a joint whose two bodies are one.
        let pair = (j.pair.index_a != j.pair.index_b)
            .then(|| j.pair.bodies(bodies))
            .flatten();
        link_rows(j, pair, stage, link, carry_angle);
    });
    for (link, &index) in links.iter_mut().zip(members) {
        if let Some([a, b]) = joints[index].pair.bodies_mut(solver_bodies) {
            link.activate(a, b);
        }
    }
    true
}

/// The rows of joint `j` for a direct pass at its bodies' current pose, written into `rows` (after a reset
/// to the joint's bodies), and its accumulated impulses in row order (no rows for a body pair out of range,
/// which the world never hands over).
pub(super) fn direct_rows(
    j: &mut PreparedJoint,
    solver_bodies: &[SolverBody],
    stage: &Stage,
    link: &mut Link,
) -> [f32; MAX_ROWS] {
    let bodies = j.pair.bodies(solver_bodies);
    rows_at(j, bodies, stage, link, false)
}

/// [`direct_rows`] with the joint's bodies already loaded (`None`: no rows), with the joint's inverse masses
/// or, if `keep_masses`, those the link has (a link of a path kept from the last step: `K` must turn each
/// body by one inverse inertia until the last relax pass builds every link again, see `crate::path`).
// Inlined into the pass loops (as `link_rows`): they run once per link and pass, and a rope's rows cost
// less to build than the calls.
#[inline(always)]
pub(super) fn rows_at(
    j: &mut PreparedJoint,
    bodies: Option<(&SolverBody, &SolverBody)>,
    stage: &Stage,
    link: &mut Link,
    keep_masses: bool,
) -> [f32; MAX_ROWS] {
    let mass = |inv_mass, inertia| InvMass {
        mass: inv_mass,
        inertia,
    };
    if keep_masses {
        link.clear();
    } else {
        link.reset(
            mass(j.pair.inv_mass_a, j.pair.inv_inertia_a),
            mass(j.pair.inv_mass_b, j.pair.inv_inertia_b),
        );
    }
    let rows = &mut link.rows;
    let Some((a, b)) = bodies else {
        return [0.0; MAX_ROWS];
    };
    if !j.kind.direct_rows(&j.pair, (a, b), stage, rows) {
        return [0.0; MAX_ROWS];
    }
    state_lambda(j)
}

/// The rows of joint `j` in `link` for a pass of `stage` at its bodies' current pose, and its accumulated
/// impulses: the rows already there if they were built at this very pose ([`PoseKey`]: the same bits of
/// both bodies' displacements and rotations) — only their targets recomputed for `stage`
/// ([`Link::reuse`]); a hinge's rows built earlier in the step (or kept from the last) if neither body has
/// turned by more than `carry_angle` (rad) since — their errors carried to this pose ([`Link::carry`]); else
/// built again
/// ([`rows_at`]). `bodies` are the joint's bodies (`None`: no rows). The position projection passes
/// `carry_angle` = 0: its Newton steps need the Jacobians of the pose.
#[inline(always)]
pub(super) fn link_rows(
    j: &mut PreparedJoint,
    bodies: Option<(&SolverBody, &SolverBody)>,
    stage: &Stage,
    link: &mut Link,
    carry_angle: f32,
) {
    let pose = bodies.map(|(a, b)| PoseKey::of(a, b));
    if pose.as_ref().is_some_and(|pose| link.is_built_at(pose)) {
        link.reuse(stage);
        link.lambda = state_lambda(j);
        return;
    }
    if let (true, Some((a, b)), Some(now)) = (j.kind.carries_rows(), bodies, &pose) {
        if carry_angle > 0.0
            && (link.recarry(now, stage) || carry(j, link, (a, b), now, stage, carry_angle))
        {
            link.lambda = state_lambda(j);
            return;
        }
        // Built again: carried from here, in this step or the next; with the kept rows' inverse masses on a
        // path kept from the last step.
        let keep_masses = link.keeps_last_step_masses();
        link.lambda = rows_at(j, bodies, stage, link, keep_masses);
        link.built_at(pose);
        link.built = Some(build_site(j, a, b));
        return;
    }
    link.lambda = rows_at(j, bodies, stage, link, false);
    link.built_at(pose);
}

/// Where joint `j`'s rows are when its bodies are at `a`, `b`, in world terms ([`BuiltAt`]).
pub(super) fn build_site(j: &PreparedJoint, a: &SolverBody, b: &SolverBody) -> BuiltAt {
    BuiltAt {
        frames: j.pair.frames(a, b),
        relative: j.pair.delta_center + (b.delta_position - a.delta_position),
        owner: (j.source, j.pair.index_a, j.pair.index_b),
    }
}

/// [`Link::carry`] of joint `j`'s rows in `link` to its bodies' pose `a`, `b` (`now`, its key).
#[inline(never)]
pub(super) fn carry(
    j: &PreparedJoint,
    link: &mut Link,
    (a, b): (&SolverBody, &SolverBody),
    now: &PoseKey,
    stage: &Stage,
    max_angle: f32,
) -> bool {
    let site = build_site(j, a, b);
    link.carry(site.frames, site.relative, now, stage, max_angle)
}

/// Solves the path (with the active-set rounds that drop rows which would push) into `solution`; its links
/// are linked through their shared bodies ([`JointSolver::prepare`], `link_paths`) — or, for a graph
/// (`graph`), through its [`DirectGraph`].
pub(super) fn solve_links(
    joints: &[PreparedJoint],
    members: &[usize],
    links: &mut [Link],
    solution: &mut Vec<[Real; MAX_ROWS]>,
    solver_bodies: &mut [SolverBody],
    graph: Option<&mut DirectGraph>,
) {
    if let Some(graph) = graph {
        solve_graph(graph, joints, members, links, solution, solver_bodies);
        return;
    }
    // Active set: a rope the solution would make push is released, a rope left out that the solution would
    // stretch is added, and the system solved again; the last round's solution is the one applied.
    // A round after the first sweeps again only from the link before the first one it changed ([`Resume`]).
    let mut resume = Resume::default();
    for round in 0..ACTIVE_SET_ROUNDS {
        let solved = solve_path(
            links,
            |slot| joints[members[slot]].pair.bodies(solver_bodies),
            solution,
            &mut resume,
        );
        if round + 1 == ACTIVE_SET_ROUNDS {
            break;
        }
        // Each step below sweeps every link: skipped when the solve saw nothing for it to do.
        let activated = if solved.left_out {
            activate_violations(links, solution, |slot| {
                joints[members[slot]].pair.bodies(solver_bodies)
            })
        } else {
            None
        };
        let mut changed = activated.is_some();
        if let Some(slot) = activated {
            resume.changed(slot);
        }
        if !solved.released {
            if !changed {
                break;
            }
            continue;
        }
        for (slot, ((link, x), &index)) in links
            .iter_mut()
            .zip(solution.iter())
            .zip(members)
            .enumerate()
        {
            if !link.would_deactivate(x) {
                continue;
            }
            if let Some([a, b]) = joints[index].pair.bodies_mut(solver_bodies)
                && link.deactivate_violations(x, a, b)
            {
                resume.changed(slot);
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
}

/// [`solve_links`] for a graph: its solve ([`DirectGraph::solve`]) with the active-set rounds of a path —
/// rows left out that the solution would violate added, rows it would make push released (a released row
/// changes its bodies' velocities), and the system solved again.
// Kept out of line: `solve_links` runs for every path of every pass, and a path's sweep should not carry it.
#[inline(never)]
fn solve_graph(
    graph: &mut DirectGraph,
    joints: &[PreparedJoint],
    members: &[usize],
    links: &mut [Link],
    solution: &mut Vec<[Real; MAX_ROWS]>,
    solver_bodies: &mut [SolverBody],
) {
    for round in 0..ACTIVE_SET_ROUNDS {
        let solved = graph.solve(
            links,
            |slot| joints[members[slot]].pair.bodies(solver_bodies),
            solution,
        );
        if round + 1 == ACTIVE_SET_ROUNDS {
            break;
        }
        let mut changed = solved.left_out
            && graph.activate_violations(links, solution, |slot| {
                joints[members[slot]].pair.bodies(solver_bodies)
            });
        if solved.released {
            for ((link, x), &index) in links.iter_mut().zip(solution.iter()).zip(members) {
                if !link.would_deactivate(x) {
                    continue;
                }
                if let Some([a, b]) = joints[index].pair.bodies_mut(solver_bodies) {
                    changed |= link.deactivate_violations(x, a, b);
                }
            }
        }
        if !changed {
            break;
        }
    }
}
