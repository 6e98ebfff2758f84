//! Stage *prepare* (once per step): each joint's anchors, frames, masses and softness, the paths solved
//! directly and the links kept from the last step, the joints Gauss–Seidel visits, the tethers and which
//! paths are closed.

use super::dispatch::{JointRecord, PreparedJoint};
use super::joint_solver::JointSolver;
use crate::joint::{Joint, JointBodies};
use crate::part::rotation_error;
use crate::path::resize_links;
use crate::path::tether::{Edge, starts_a_tether};
use crate::path::topology::{JointShape, Topology};
use crate::state::JointState;
use core::sync::atomic::{AtomicBool, Ordering};
use rebound_dynamics::{BodyParams, SolverBody, StepContext};
use rebound_math::{Mat3, Vec3, par};

/// Joints per task of the preparation over the pool (a joint prepares in about a microsecond).
const JOINTS_PER_PREPARE_TASK: usize = 16;

/// One joint's preparation into its slot `j`: its bodies' pair, its state (warm start) and its kind's
/// anchors, frames, masses and softness.
#[inline(always)]
fn prepare_joint(
    j: &mut PreparedJoint,
    source: usize,
    joint: &Joint,
    state: &JointState,
    jb: JointBodies,
    solver_bodies: &[SolverBody],
    params: &[BodyParams],
    ctx: &StepContext,
) {
    // Each field written in its slot: the pair and the kind are made where they are kept.
    j.source = source;
    j.pair.reset(
        jb.a,
        jb.b,
        (&params[jb.a], &params[jb.b]),
        (joint.local_anchor_a(), joint.local_anchor_b()),
        (joint.local_basis_a(), joint.local_basis_b()),
    );
    j.state = if ctx.warm_starting {
        JointState {
            broken: false,
            ..*state
        }
    } else {
        JointState::default()
    };
    let bodies = (&solver_bodies[jb.a], &solver_bodies[jb.b]);
    j.kind
        .prepare(joint.kind(), &j.pair, bodies, ctx, &mut j.state);
    j.path = None;
}

impl JointSolver {
    /// Stage *prepare*: reads `joints[i]`, its state `states[i]` and its bodies `bodies[i]` (indices into
    /// `solver_bodies` and `params`, which hold the bodies' start-of-step state), and computes anchors, frames,
    /// masses and softness. Warm-start impulses come from the states if `ctx.warm_starting`, else zero.
    ///
    /// Returns how many joints were skipped and will not be solved: broken ones, ones without a state or body
    /// pair (slices shorter than `joints`), and ones whose body indices are equal or out of range. Never panics.
    pub fn prepare(
        &mut self,
        joints: &[Joint],
        states: &[JointState],
        bodies: &[JointBodies],
        solver_bodies: &[SolverBody],
        params: &[BodyParams],
        ctx: &StepContext,
    ) -> usize {
        let joint = |i: usize| Some((joints.get(i)?, states.get(i)?, *bodies.get(i)?));
        self.prepare_from(joints.len(), joint, solver_bodies, params, ctx)
    }

    /// [`JointSolver::prepare`] of `count` joints read where they are kept: `joint(i)` gives joint `i`, its
    /// state and its bodies (`None`: skipped), so that a world copies each joint's state once into the
    /// solver (and once back, [`JointSolver::store_impulses_to`]).
    pub fn prepare_from<'j>(
        &mut self,
        count: usize,
        joint: impl Fn(usize) -> Option<(&'j Joint, &'j JointState, JointBodies)> + Sync,
        solver_bodies: &[SolverBody],
        params: &[BodyParams],
        ctx: &StepContext,
    ) -> usize {
        self.records.clear();
        self.relax_passes = 0;
        self.joint_softness = self.settings.joint_softness(ctx);
        self.h = ctx.h;
        let body_count = solver_bodies.len().min(params.len());
        let (mut coordinate_springs, mut restitution) = (false, false);
        let mut skipped = 0;
        // On a pool, every joint alone over the pool while none is skipped (each then has its own slot).
        let pooled = if par::is_parallel() && count >= 2 * JOINTS_PER_PREPARE_TASK {
            self.prepare_on_pool(count, &joint, solver_bodies, params, ctx)
        } else {
            None
        };
        if let Some(flags) = pooled {
            (coordinate_springs, restitution) = flags;
        } else {
            for source in 0..count {
                let Some((joint, state, jb)) = joint(source) else {
                    skipped += 1;
                    continue;
                };
                if state.broken || jb.a >= body_count || jb.b >= body_count || jb.a == jb.b {
                    skipped += 1;
                    continue;
                }
                let prepared = self.records.len();
                if prepared == self.joints.len() {
                    self.joints.push(PreparedJoint::unprepared());
                }
                let Some(j) = self.joints.get_mut(prepared) else {
                    continue;
                };
                prepare_joint(j, source, joint, state, jb, solver_bodies, params, ctx);
                coordinate_springs |= j.kind.has_coordinate_spring();
                restitution |= j.kind.has_restitution();
                self.records.push(JointRecord {
                    break_force: joint.break_force(),
                    break_torque: joint.break_torque(),
                    tether: None,
                });
            }
        }
        self.joints.truncate(self.records.len());
        self.coordinate_springs = coordinate_springs;
        self.restitution = restitution;
        // The paths first: the graph search leaves out the tethers they make redundant.
        self.find_paths(body_count);
        // One link per path member. A path whose links all hold carried rows of the last step for the same
        // joint, bodies and inverse masses keeps them ([`Link::new_step`]; see `crate::path`, "Rows carried
        // through the step"); any other path starts from nothing.
        resize_links(&mut self.links, self.topology.path_joints.len());
        self.path_links = self.topology.path_joints.len();
        for range in &self.topology.paths {
            let keeps = |k: usize| {
                let (Some(j), Some(link)) = (
                    self.topology
                        .path_joints
                        .get(k)
                        .and_then(|&index| self.joints.get(index)),
                    self.links.get(k),
                ) else {
                    return false;
                };
                // Turned by less than the carry angle since the build, so that the inverse inertias the
                // rows keep until the last relax pass are those of a rotation at most that far off.
                let limit = self.carry_angle * self.carry_angle;
                link.built.is_some_and(|built| {
                    built.owner == (j.source, j.pair.index_a, j.pair.index_b)
                        && link.rows.mass_a.mass.to_bits() == j.pair.inv_mass_a.to_bits()
                        && link.rows.mass_b.mass.to_bits() == j.pair.inv_mass_b.to_bits()
                        && rotation_error(built.frames.0, j.pair.basis_a).length_squared() <= limit
                        && rotation_error(built.frames.1, j.pair.basis_b).length_squared() <= limit
                })
            };
            let keep = range.clone().all(keeps);
            for link in self.links.get_mut(range.clone()).into_iter().flatten() {
                if keep {
                    link.new_step();
                } else {
                    link.drop_built();
                }
            }
        }
        for link in self.links.iter_mut().skip(self.topology.path_joints.len()) {
            link.drop_built();
        }
        self.link_paths();
        self.list_iterated();
        self.analyse_graph(params);
        self.find_closed_paths(body_count);
        self.pool.plan(&self.joints, body_count);
        skipped
    }

    /// The paths and graphs solved directly ([`Topology::find_paths_and_graphs`]), each joint on one told
    /// its path (or graph).
    fn find_paths(&mut self, body_count: usize) {
        let Self {
            settings,
            joints,
            topology,
            ..
        } = self;
        // No joint that can join a path, no path and no graph: nothing to search (a world of contacts or of
        // springs alone walks no per-body array).
        if !settings.direct_chains || !joints.iter().any(|j| j.kind.is_direct_capable()) {
            topology.clear();
            return;
        }
        let joints_ref = &*joints;
        // The same joints between the same bodies as in the last step: the same paths (a deck or a chain
        // keeps its joints from step to step), not searched again.
        let shapes = joints_ref.iter().map(|j| {
            JointShape::new(
                &j.pair,
                j.kind.is_direct_capable(),
                j.kind.direct_row_count(),
                j.kind.is_solved_directly_whole(),
            )
        });
        if !topology.keeps(body_count, shapes) {
            topology.find_paths_and_graphs(
                body_count,
                joints_ref.len(),
                |i| &joints_ref[i].pair,
                |i| joints_ref[i].kind.is_direct_capable(),
                |i| joints_ref[i].kind.direct_row_count(),
            );
        }
        for (path, range) in topology.paths.iter().enumerate() {
            for &index in &topology.path_joints[range.clone()] {
                joints[index].path = Some(path);
            }
        }
    }

    /// Links each path's consecutive members through the body they share (which side of each it is), and
    /// leaves its last member unlinked: the shape every pass of the step solves ([`Link::shared_with_next`]),
    /// set once here rather than before each solve.
    fn link_paths(&mut self) {
        let Self {
            joints,
            topology,
            links,
            ..
        } = self;
        for (path, range) in topology.paths.iter().enumerate() {
            let graph = topology.graph_of.get(path).copied().flatten().is_some();
            let (Some(members), Some(links)) = (
                topology.path_joints.get(range.clone()),
                links.get_mut(range.clone()),
            ) else {
                continue;
            };
            for (slot, link) in links.iter_mut().enumerate() {
                // A graph's links are coupled through its `DirectGraph`, not one to the next.
                link.shared_with_next = if graph {
                    None
                } else {
                    Topology::shared_with_next(members, slot, |i| &joints[i].pair)
                };
            }
        }
    }

    /// Marks each path closed or not ([`Topology::find_closed`]): a joint's rows are all in the direct solve
    /// if it is a rope, a rod, a ball joint or a hinge without limit, motor or spring.
    fn find_closed_paths(&mut self, body_count: usize) {
        let Self {
            joints,
            tethers,
            topology,
            ..
        } = self;
        // No path, nothing closed: the count of joints per body is not needed.
        if topology.paths.is_empty() {
            topology.closed.clear();
            return;
        }
        topology.find_closed(
            body_count,
            joints.len(),
            |i| &joints[i].pair,
            tethers.iter().map(|t| &t.pair),
            |i| joints[i].kind.is_solved_directly_whole(),
        );
    }

    /// The joints a Gauss–Seidel pass visits: all but the springs (whose substep is *apply forces* alone)
    /// and the ones whose rows a path solves entirely (a hinge on a path with coordinate rows — limit, motor,
    /// spring — keeps them in the pass).
    pub(super) fn list_iterated(&mut self) {
        self.iterated.clear();
        self.iterated.extend(
            self.joints
                .iter()
                .enumerate()
                .filter(|(_, j)| j.kind.is_iterated(j.path.is_some()))
                .map(|(index, _)| index),
        );
    }

    /// The joint graph and its tethers (see [`crate::path::tether`]).
    pub(super) fn analyse_graph(&mut self, params: &[BodyParams]) {
        self.tethers.clear();
        // No joint, no tether: the search would walk every body for nothing.
        if !self.settings.tethers || self.joints.is_empty() {
            return;
        }
        // Every joint on one directly solved path (a rope chain, a bridge): each body's way to a fixed body
        // runs along that path alone, so the search would make no tether (see `crate::path::tether`).
        if self.topology.paths.len() == 1 && self.topology.path_joints.len() == self.joints.len() {
            return;
        }
        // No joint that can start a tether (a field of springs, bodies joined to moving bodies only): the
        // search would make none.
        let starts = |j: &PreparedJoint| {
            starts_a_tether(
                j.kind.bounded_length(),
                (j.pair.inv_mass_a, j.pair.inv_mass_b),
            )
        };
        if !self.joints.iter().any(starts) {
            return;
        }
        self.edges.clear();
        self.edges.extend(self.joints.iter().map(|j| Edge {
            index_a: j.pair.index_a,
            index_b: j.pair.index_b,
            inv_mass_a: j.pair.inv_mass_a,
            inv_mass_b: j.pair.inv_mass_b,
            anchor_a: j.pair.anchor_a,
            anchor_b: j.pair.anchor_b,
            length: j.kind.bounded_length(),
            path: j.path,
        }));
        self.graph.analyse(&self.edges, params.len());
        let body = |i: usize| {
            params.get(i).map_or((0.0, Mat3::ZERO, Vec3::ZERO), |p| {
                (p.inv_mass, p.inv_inertia_world, p.center_of_mass)
            })
        };
        self.tethers.extend(self.graph.tethers(body));
        for (k, t) in self.tethers.iter_mut().enumerate() {
            if let (Some(j), Some(record)) =
                (self.joints.get(t.joint), self.records.get_mut(t.joint))
            {
                t.impulse = j.state.tether_impulse;
                record.tether = Some(k);
            } else {
                t.impulse = 0.0;
            }
        }
    }
}

impl JointSolver {
    /// The joint loop of [`JointSolver::prepare_from`] over the pool: joint `i` into slot `i`, which is
    /// where the one-thread loop puts it when no joint is skipped. Returns whether some joint has a
    /// coordinate spring and whether some has restitution; `None` when some joint is skipped (the one-thread
    /// loop then prepares them all again, into the slots it chooses).
    fn prepare_on_pool<'j>(
        &mut self,
        count: usize,
        joint: &(impl Fn(usize) -> Option<(&'j Joint, &'j JointState, JointBodies)> + Sync),
        solver_bodies: &[SolverBody],
        params: &[BodyParams],
        ctx: &StepContext,
    ) -> Option<(bool, bool)> {
        let body_count = solver_bodies.len().min(params.len());
        self.joints.resize(count, PreparedJoint::unprepared());
        let whole = AtomicBool::new(true);
        par::for_each_mut(
            &mut self.joints,
            JOINTS_PER_PREPARE_TASK,
            |source, j| match joint(source) {
                Some((joint, state, jb))
                    if !(state.broken
                        || jb.a >= body_count
                        || jb.b >= body_count
                        || jb.a == jb.b) =>
                {
                    prepare_joint(j, source, joint, state, jb, solver_bodies, params, ctx);
                }
                _ => whole.store(false, Ordering::Relaxed),
            },
        );
        if !whole.into_inner() {
            return None;
        }
        let (mut coordinate_springs, mut restitution) = (false, false);
        for j in &self.joints {
            coordinate_springs |= j.kind.has_coordinate_spring();
            restitution |= j.kind.has_restitution();
        }
        for source in 0..count {
            if let Some((joint, _, _)) = joint(source) {
                self.records.push(JointRecord {
                    break_force: joint.break_force(),
                    break_torque: joint.break_torque(),
                    tether: None,
                });
            }
        }
        Some((coordinate_springs, restitution))
    }
}
