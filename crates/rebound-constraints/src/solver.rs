//! The joint solver: the stages the world calls, dispatched on the joint kind with a `match` (no trait
//! objects in the hot loop; Box2D's `switch` in `joint.c`).
//!
//! ```text
//! prepare                         once per step: anchors, frames, masses, softness, warm-start impulses
//! for each substep:
//!     integrate velocities        (rebound-dynamics)
//!     apply_forces                SpringModel::Force: the explicit Hooke force as a velocity change
//!     warm_start                  the impulses of the last substep, again
//!     solve(Bias::On)             solve_iterations Gauss–Seidel passes, soft position correction
//!     integrate positions         (rebound-dynamics)
//!     solve(Bias::Off)            relax_iterations passes, no position correction (removes the bias velocity)
//!                                 (joint paths — chains, bridges — are solved as one system in each pass:
//!                                 crate::direct; a pass at the pose of the one before it — a solve pass
//!                                 after a relax pass, the projection — keeps that pass's rows and, if the
//!                                 same rows are in the system, its factorisation; a hinge whose bodies
//!                                 turned less than 0.01 rad since its rows were built this step keeps
//!                                 them and its factorisation, with its errors carried to the pose)
//! project_positions               once: the positions of each joint path, so that its joints end the step closed
//! apply_restitution               once: ropes that snapped taut
//! store_impulses                  impulses back into the JointStates; break check
//! ```
//!
//! Buffers are reused from step to step: once the `Vec` of prepared joints has grown to the scene's joint
//! count, a step allocates nothing.

use crate::coordinate::CoordinateRows;
use crate::direct::{
    BuiltAt, CARRY_ANGLE, InvMass, JointRows, Link, MAX_ROWS, PoseKey, Real, Resume,
    activate_violations, equality_violation, solve_path,
};
use crate::fixed::PreparedFixed;
use crate::hinge::PreparedHinge;
use crate::part::rotation_error;
use crate::prismatic::PreparedPrismatic;
use crate::rod::PreparedRod;
use crate::rope::PreparedRope;
use crate::spring::PreparedSpring;
use crate::tether::{Edge, JointGraph, Tether};
use crate::wheel::PreparedWheel;
use crate::{
    BodyPair, ConstraintError, FixedJoint, Joint, JointBodies, JointKind, JointSettings,
    JointState, ball,
};
use rebound_dynamics::{Bias, BodyParams, Softness, SolverBody, StepContext};
use rebound_math::{Mat3, Vec3};

/// What one solve pass needs besides the bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Stage {
    /// Bias pass or relax pass.
    pub bias: Bias,
    /// Substep length (s).
    pub h: f32,
    /// 1/h (1/s).
    pub inv_h: f32,
    /// Softness of hard parts in the bias pass.
    pub joint_softness: Softness,
}

impl Stage {
    /// The stage of the position projection for substeps of `h` (s): a bias rate of 1 and `inv_h` = 1 make
    /// every row's bias its position error `C` (m or rad), slack ropes included (their speculative bias is
    /// `C·inv_h`).
    fn projection(h: f32) -> Self {
        Self {
            bias: Bias::On,
            h,
            inv_h: 1.0,
            joint_softness: Softness {
                bias_rate: 1.0,
                mass_scale: 1.0,
                impulse_scale: 0.0,
            },
        }
    }
}

/// Newton iterations of the position projection (the rows are re-linearised at the moved poses).
const PROJECTION_ITERATIONS: usize = 4;

/// A path whose worst position error is within this (m, or rad for angular rows) is not projected: 0.1 mm is
/// below what a game shows, and a settled chain or bridge then costs nothing here.
const PROJECTION_TOLERANCE: f32 = 1e-4;

/// Nonlinear Gauss–Seidel sweeps (alternating direction) after the direct projection, at most; they stop once
/// the path is within [`PROJECTION_TOLERANCE`], checked every [`PROJECTION_SWEEP_CHECK`] sweeps.
const PROJECTION_SWEEPS: usize = 16;

/// How many sweeps run between two measurements of the path's worst error.
const PROJECTION_SWEEP_CHECK: usize = 4;

/// How much stiffer than their geometric stiffness `|p|/L` the projection makes pulled ropes and rods against
/// turning when a plain Newton step is rejected ([`Link::stiffen`]). The exact Newton step weighs the
/// Hessian of each link's length by the multiplier of the step it takes, which is larger than the plain step's
/// `p` it is estimated from (about 3× at the SCENES.md chain's whip), and a stiffer metric errs on the safe
/// side: in the limit the links only change length, which for a chain hanging from an anchor is exact. Worst
/// link of that chain over 38 starts with one ball 10 µm off: ×1 0.04–0.56 %, ×3 0.04–0.13 %, ×10 and ×30
/// 0.040–0.041 %.
const PROJECTION_STIFFENING: f32 = 10.0;

/// The fraction of the worst error a full Newton step of the projection must get a path with ropes or rods
/// down to for it to be kept as it is. Near the solution Newton's error shrinks quadratically; a step that
/// does not even quarter it is one whose linearisation is poor (links turning within the step), and the
/// stiffened step ([`PROJECTION_STIFFENING`]) is tried instead. With "kept if no worse", steps that gained a
/// few per cent used up the iterations at the SCENES.md chain's whip (0.19 → 0.19 → 0.18 cm).
const PROJECTION_NEWTON_GAIN: f32 = 0.25;

/// How many times a direct path solve may drop rows that would push, add rows it would violate, and solve
/// again.
const ACTIVE_SET_ROUNDS: usize = 4;

/// A joint kind prepared for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Prepared {
    Spring(PreparedSpring),
    Rope(PreparedRope),
    Rod(PreparedRod),
    Ball,
    Hinge(PreparedHinge),
    Fixed(PreparedFixed),
    Prismatic(PreparedPrismatic),
    Wheel(PreparedWheel),
}

impl Prepared {
    /// Whether the joint's equality rows can join a directly solved path ([`crate::direct`]).
    fn is_direct_capable(&self) -> bool {
        matches!(
            self,
            Self::Rope(_) | Self::Rod(_) | Self::Ball | Self::Hinge(_)
        )
    }

    /// The distance a joint allows between its anchors (m), for tethers: a rope's or rod's length, 0 for the
    /// point joints; `None` for joints that do not bound it.
    fn bounded_length(&self) -> Option<f32> {
        match self {
            Self::Rope(p) => Some(p.max_length()),
            Self::Rod(p) => Some(p.length()),
            Self::Ball | Self::Hinge(_) | Self::Fixed(_) => Some(0.0),
            Self::Spring(_) | Self::Prismatic(_) | Self::Wheel(_) => None,
        }
    }
}

/// One prepared joint: its source index, bodies, accumulated impulses and kind.
#[derive(Debug, Clone, Copy, PartialEq)]
struct PreparedJoint {
    source: usize,
    pair: BodyPair,
    state: JointState,
    break_force: f32,
    break_torque: f32,
    kind: Prepared,
    /// The path solved directly ([`crate::direct`]) that the joint's equality rows belong to, as an index
    /// into the solver's `paths`; `None` for a joint solved by Gauss–Seidel alone.
    path: Option<usize>,
    /// The joint's link in the solver's `links` (its index in `path_joints`) when it is on a path.
    link: Option<usize>,
}

/// The rows a [`JointSolver`] keeps from one step to the next — a directly solved path's hinge rows, which
/// the next step carries instead of building them again (see [`crate::direct`]) — as a snapshot holds
/// them. Restored into a solver ([`JointSolver::restore_kept_rows`]) before the next step, they make that
/// step the one the solver they were taken from would have taken, bit for bit.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct KeptRows {
    /// Per link of the paths, in path order: its rows and where they were built (`None`: none kept).
    links: Vec<Option<(JointRows, BuiltAt)>>,
}

impl KeptRows {
    /// The number of links whose rows are kept.
    #[must_use]
    pub fn len(&self) -> usize {
        self.links.iter().flatten().count()
    }

    /// Whether no rows are kept.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether every number is finite (impulse bounds may be infinite, never NaN) and every row count in
    /// range: what a solver restoring them trusts. A snapshot that was deserialised is checked with it.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        self.links.iter().flatten().all(|(rows, built)| {
            let (a, b) = built.frames;
            rows.is_valid() && a.is_finite() && b.is_finite() && built.relative.is_finite()
        })
    }
}

/// The joint solver. Holds the prepared joints between stages and reuses its buffer from step to step.
///
/// See the crate README for a complete step loop.
#[derive(Debug, Clone)]
pub struct JointSolver {
    settings: JointSettings,
    joints: Vec<PreparedJoint>,
    /// The joints a Gauss–Seidel pass visits (indices into `joints`, in order): those on no direct path, and
    /// hinges on one that have limit, motor or spring rows. A rope chain or a bridge solved directly has none.
    iterated: Vec<usize>,
    /// Long-range tethers of chains hanging from fixed bodies (see [`crate::tether`]).
    tethers: Vec<Tether>,
    /// Scratch: the joints as graph edges, and the graph search's buffers.
    edges: Vec<Edge>,
    graph: JointGraph,
    /// Paths of joints solved directly ([`crate::direct`]), as ranges into `path_joints` (joint indices in
    /// path order).
    paths: Vec<core::ops::Range<usize>>,
    path_joints: Vec<usize>,
    /// Scratch of the path search: per body, its number of direct-capable joints and the first two of them;
    /// per joint, whether a path has taken it.
    degree: Vec<u32>,
    incident: Vec<[usize; 2]>,
    visited: Vec<bool>,
    /// The links of the direct solve, one per entry of `path_joints` (a path's links are the slice of its
    /// range), kept from pass to pass: a pass at the pose a link's rows were built at reuses them, and their
    /// factorisation if the rows in the system are also the same (see [`crate::direct`]).
    links: Vec<Link>,
    /// How many of `links` belong to the paths of the last prepared step (or of the restored [`KeptRows`]).
    path_links: usize,
    solution: Vec<[Real; MAX_ROWS]>,
    /// Scratch of the position projection: the path's bodies before a Newton step, and a link to measure
    /// errors with.
    saved: Vec<(usize, SolverBody)>,
    probe: Vec<Link>,
    /// The joint softness of the prepared step.
    joint_softness: Softness,
    /// The substep length of the prepared step (s).
    h: f32,
    /// How far (rad) the bodies of a hinge on a path may turn before a velocity pass builds its rows again
    /// instead of carrying them ([`Link::carry`]); 0 builds them at every new pose.
    carry_angle: f32,
    /// Relax passes since [`JointSolver::prepare`]: the last one of a step (the `substep_count`-th) builds
    /// every path's rows at the final pose, where the position projection starts.
    relax_passes: u32,
    /// Per path, whether it is *closed*: all of its joints' rows are in the direct solve (no hinge limit,
    /// motor or spring) and no other joint or tether acts on its dynamic bodies. Only the last relax pass of
    /// a step solves a closed path (see [`JointSolver::solve`]).
    closed: Vec<bool>,
    /// Scratch of [`JointSolver::find_closed_paths`]: per body, the joints and tethers acting on it.
    touches: Vec<u32>,
}

impl Default for JointSolver {
    fn default() -> Self {
        Self {
            settings: JointSettings::default(),
            joints: Vec::new(),
            iterated: Vec::new(),
            tethers: Vec::new(),
            edges: Vec::new(),
            graph: JointGraph::default(),
            paths: Vec::new(),
            path_joints: Vec::new(),
            degree: Vec::new(),
            incident: Vec::new(),
            visited: Vec::new(),
            links: Vec::new(),
            path_links: 0,
            solution: Vec::new(),
            saved: Vec::new(),
            probe: Vec::new(),
            joint_softness: Softness::RIGID,
            h: 0.0,
            carry_angle: CARRY_ANGLE,
            relax_passes: 0,
            closed: Vec::new(),
            touches: Vec::new(),
        }
    }
}

impl JointSolver {
    /// A solver with [`JointSettings::default`].
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The rows this solver keeps for the next step ([`KeptRows`]), for a snapshot.
    #[must_use]
    pub fn kept_rows(&self) -> KeptRows {
        let links = self.links.get(..self.path_links).unwrap_or_default();
        KeptRows {
            links: links
                .iter()
                .map(|link| link.built.map(|built| (link.rows, built)))
                .collect(),
        }
    }

    /// Replaces the rows kept for the next step with `kept` (taken by [`JointSolver::kept_rows`]); rows kept
    /// for joints or bodies other than the next step's are dropped by it. Check a deserialised value with
    /// [`KeptRows::is_valid`] first.
    pub fn restore_kept_rows(&mut self, kept: &KeptRows) {
        resize_links(&mut self.links, kept.links.len());
        for (k, link) in self.links.iter_mut().enumerate() {
            link.drop_built();
            if let Some(&Some((rows, built))) = kept.links.get(k) {
                link.rows = rows;
                link.built = Some(built);
            }
        }
        self.path_links = kept.links.len();
    }

    /// A solver with `settings`.
    ///
    /// # Errors
    /// Invalid settings (see [`JointSettings::validated`]).
    pub fn with_settings(settings: JointSettings) -> Result<Self, ConstraintError> {
        Ok(Self {
            settings: settings.validated()?,
            ..Self::default()
        })
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &JointSettings {
        &self.settings
    }

    /// Replaces the settings (taking effect at the next [`JointSolver::prepare`]); nothing changes on error.
    ///
    /// # Errors
    /// Invalid settings.
    pub fn set_settings(&mut self, settings: JointSettings) -> Result<(), ConstraintError> {
        self.settings = settings.validated()?;
        Ok(())
    }

    /// The number of prepared joints.
    #[must_use]
    pub fn len(&self) -> usize {
        self.joints.len()
    }

    /// Whether no joint is prepared.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty()
    }

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
        self.joints.clear();
        self.relax_passes = 0;
        self.joint_softness = self.settings.joint_softness(ctx);
        self.h = ctx.h;
        let body_count = solver_bodies.len().min(params.len());
        let mut skipped = 0;
        for (source, joint) in joints.iter().enumerate() {
            let (Some(state), Some(jb)) = (states.get(source), bodies.get(source)) else {
                skipped += 1;
                continue;
            };
            if state.broken || jb.a >= body_count || jb.b >= body_count || jb.a == jb.b {
                skipped += 1;
                continue;
            }
            let pair = BodyPair::new(
                jb.a,
                jb.b,
                &params[jb.a],
                &params[jb.b],
                (joint.local_anchor_a(), joint.local_anchor_b()),
                (joint.local_basis_a(), joint.local_basis_b()),
            );
            let (sa, sb) = (&solver_bodies[jb.a], &solver_bodies[jb.b]);
            let mut state = if ctx.warm_starting {
                JointState {
                    broken: false,
                    ..*state
                }
            } else {
                JointState::default()
            };
            let kind = match joint.kind() {
                JointKind::Spring(s) => {
                    keep_only(&mut state, Keep::Axial);
                    let prepared = s.prepare(&pair, sa, sb, ctx);
                    if !prepared.is_soft() {
                        state.axial_impulse = 0.0;
                    }
                    Prepared::Spring(prepared)
                }
                JointKind::Rope(r) => {
                    keep_only(&mut state, Keep::Upper);
                    Prepared::Rope(r.prepare(&pair, sa, sb))
                }
                JointKind::Rod(r) => {
                    keep_only(&mut state, Keep::Axial);
                    Prepared::Rod(r.prepare(&pair, sa, sb))
                }
                JointKind::Ball(_) => {
                    keep_only(&mut state, Keep::Linear);
                    Prepared::Ball
                }
                JointKind::Hinge(h) => Prepared::Hinge(h.prepare(&pair, ctx, &mut state)),
                JointKind::Fixed(_) => Prepared::Fixed(FixedJoint::prepare(&pair, &mut state)),
                JointKind::Prismatic(p) => Prepared::Prismatic(p.prepare(&pair, ctx, &mut state)),
                JointKind::Wheel(w) => Prepared::Wheel(w.prepare(ctx, &mut state)),
            };
            self.joints.push(PreparedJoint {
                source,
                pair,
                state,
                break_force: joint.break_force(),
                break_torque: joint.break_torque(),
                kind,
                path: None,
                link: None,
            });
        }
        // The paths first: the graph search leaves out the tethers they make redundant.
        self.find_paths(body_count);
        // One link per path member. A path whose links all hold carried rows of the last step for the same
        // joint, bodies and inverse masses keeps them ([`Link::new_step`]; see `crate::direct`, "Rows carried
        // through the step"); any other path starts from nothing.
        resize_links(&mut self.links, self.path_joints.len());
        self.path_links = self.path_joints.len();
        for range in &self.paths {
            let keeps = |k: usize| {
                let (Some(j), Some(link)) = (
                    self.path_joints
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
        for link in self.links.iter_mut().skip(self.path_joints.len()) {
            link.drop_built();
        }
        self.link_paths();
        self.list_iterated();
        self.analyse_graph(params);
        self.find_closed_paths(body_count);
        skipped
    }

    /// Marks each path closed or not ([`JointSolver::closed`]): a path is closed when every member's rows are
    /// all in the direct solve (ropes, rods, ball joints, hinges without limit, motor or spring) and each of its
    /// dynamic bodies is acted on by the path's joints alone — no other joint, no tether. Fixed and kinematic
    /// bodies (zero inverse mass and inertia) take no impulse and may be shared.
    fn find_closed_paths(&mut self, body_count: usize) {
        let Self {
            joints,
            tethers,
            paths,
            path_joints,
            closed,
            touches,
            ..
        } = self;
        touches.clear();
        touches.resize(body_count, 0);
        let pairs = joints
            .iter()
            .map(|j| &j.pair)
            .chain(tethers.iter().map(|t| &t.pair));
        for pair in pairs {
            for body in dynamic_bodies(pair).into_iter().flatten() {
                if let Some(count) = touches.get_mut(body) {
                    *count += 1;
                }
            }
        }
        closed.clear();
        closed.extend(paths.iter().map(|range| {
            let members = path_joints.get(range.clone()).unwrap_or_default();
            let whole = members.iter().all(|&index| match &joints[index].kind {
                Prepared::Rope(_) | Prepared::Rod(_) | Prepared::Ball => true,
                Prepared::Hinge(hinge) => hinge.has_no_coordinate_rows(),
                _ => false,
            });
            // Each dynamic body of the path: as many joints and tethers act on it as path joints do.
            count_dynamic_bodies(touches, joints, members, false);
            let alone = members.iter().all(|&index| {
                dynamic_bodies(&joints[index].pair)
                    .into_iter()
                    .flatten()
                    .all(|body| touches.get(body) == Some(&0))
            });
            count_dynamic_bodies(touches, joints, members, true);
            whole && alone
        }));
    }

    /// The paths solved directly: maximal sequences of direct-capable joints (rope, rod, ball, hinge) through
    /// dynamic bodies that belong to exactly two such joints. A path ends at a fixed body, a free end or a
    /// branching body; joints on a closed loop stay with Gauss–Seidel.
    fn find_paths(&mut self, body_count: usize) {
        self.paths.clear();
        self.path_joints.clear();
        if !self.settings.direct_chains {
            return;
        }
        self.degree.clear();
        self.degree.resize(body_count, 0);
        self.incident.clear();
        self.incident.resize(body_count, [usize::MAX; 2]);
        for (index, joint) in self.joints.iter().enumerate() {
            if !joint.kind.is_direct_capable() {
                continue;
            }
            for body in dynamic_bodies(&joint.pair).into_iter().flatten() {
                let (Some(degree), Some(incident)) =
                    (self.degree.get_mut(body), self.incident.get_mut(body))
                else {
                    continue;
                };
                if let Some(slot) = incident.get_mut(*degree as usize) {
                    *slot = index;
                }
                *degree += 1;
            }
        }
        let inner = |degree: &[u32], body: Option<usize>| {
            body.is_some_and(|b| degree.get(b).copied() == Some(2))
        };
        self.visited.clear();
        self.visited.resize(self.joints.len(), false);
        for start in 0..self.joints.len() {
            if self.visited[start] || !self.joints[start].kind.is_direct_capable() {
                continue;
            }
            let [body_a, body_b] = dynamic_bodies(&self.joints[start].pair);
            // Walk away from an end of the path; a joint with inner bodies on both sides is not an end.
            let mut toward = if !inner(&self.degree, body_a) {
                body_b
            } else if !inner(&self.degree, body_b) {
                body_a
            } else {
                continue;
            };
            let first = self.path_joints.len();
            let mut current = start;
            loop {
                self.visited[current] = true;
                self.path_joints.push(current);
                let Some(body) = toward.filter(|&b| inner(&self.degree, Some(b))) else {
                    break;
                };
                let [j0, j1] = self.incident[body];
                let next = if j0 == current { j1 } else { j0 };
                let Some(next_joint) = self.joints.get(next) else {
                    break;
                };
                let pair = next_joint.pair;
                let other = if pair.index_a == body {
                    pair.index_b
                } else {
                    pair.index_a
                };
                // Two joints between the same two bodies share both: not a path link.
                let here = self.joints[current].pair;
                if self.visited[next] || other == here.index_a || other == here.index_b {
                    break;
                }
                toward = dynamic_bodies(&pair)
                    .into_iter()
                    .flatten()
                    .find(|&b| b == other);
                current = next;
            }
            self.paths.push(first..self.path_joints.len());
        }
        for (path, range) in self.paths.iter().enumerate() {
            for (link, &index) in range.clone().zip(&self.path_joints[range.clone()]) {
                self.joints[index].path = Some(path);
                self.joints[index].link = Some(link);
            }
        }
    }

    /// Links each path's consecutive members through the body they share (which side of each it is), and
    /// leaves its last member unlinked: the shape every pass of the step solves ([`Link::shared_with_next`]),
    /// set once here rather than before each solve.
    fn link_paths(&mut self) {
        let Self {
            joints,
            paths,
            path_joints,
            links,
            ..
        } = self;
        for range in paths.iter() {
            let (Some(members), Some(links)) =
                (path_joints.get(range.clone()), links.get_mut(range.clone()))
            else {
                continue;
            };
            for (slot, link) in links.iter_mut().enumerate() {
                link.shared_with_next = members.get(slot + 1).map(|&next| {
                    let (this, next) = (&joints[members[slot]].pair, &joints[next].pair);
                    let shared = if this.index_a == next.index_a || this.index_a == next.index_b {
                        this.index_a
                    } else {
                        this.index_b
                    };
                    (this.index_b == shared, next.index_b == shared)
                });
            }
        }
    }

    /// The joints a Gauss–Seidel pass visits: all but the ones whose rows a path solves entirely (a hinge on a
    /// path with coordinate rows — limit, motor, spring — keeps them in the pass).
    fn list_iterated(&mut self) {
        self.iterated.clear();
        self.iterated.extend(
            self.joints
                .iter()
                .enumerate()
                .filter(|(_, j)| match &j.kind {
                    // A hinge on a path is visited for its limit, motor and spring rows, if it has any.
                    Prepared::Hinge(hinge) => j.path.is_none() || !hinge.has_no_coordinate_rows(),
                    _ => j.path.is_none(),
                })
                .map(|(index, _)| index),
        );
    }

    /// The joint graph and its tethers (see [`crate::tether`]).
    fn analyse_graph(&mut self, params: &[BodyParams]) {
        self.tethers.clear();
        if !self.settings.tethers {
            return;
        }
        // Every joint on one directly solved path (a rope chain, a bridge): each body's way to a fixed body
        // runs along that path alone, so the search would make no tether (see `crate::tether`).
        if self.paths.len() == 1 && self.path_joints.len() == self.joints.len() {
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
        for t in &mut self.tethers {
            t.impulse = self
                .joints
                .get(t.joint)
                .map_or(0.0, |j| j.state.tether_impulse);
        }
    }

    /// Stage *apply forces* (every substep, right after integrate velocities): the explicit Hooke force of
    /// each [`crate::SpringModel::Force`] spring, `Δv = f·h·n/m` on both bodies (course items 1–2).
    pub fn apply_forces(&self, solver_bodies: &mut [SolverBody], ctx: &StepContext) {
        for j in &self.joints {
            let Prepared::Spring(spring) = &j.kind else {
                continue;
            };
            if spring.is_soft() {
                continue;
            }
            let Some((mut a, mut b)) = j.pair.load(solver_bodies) else {
                continue;
            };
            spring.apply_forces(&j.pair, &mut a, &mut b, ctx.h);
            j.pair.store(solver_bodies, a, b);
        }
    }

    /// Stage *warm start* (every substep): applies the impulses accumulated in the last substep again, along
    /// the current directions.
    pub fn warm_start(&self, solver_bodies: &mut [SolverBody]) {
        for j in &self.joints {
            // The bodies in place: a warm start changes velocities only (`prepare` never keeps a joint whose
            // two bodies are one).
            let Some([a, b]) = j.pair.bodies_mut(solver_bodies) else {
                continue;
            };
            let (pair, state) = (&j.pair, &j.state);
            // A rope or rod on a path whose link has its row built at this pose (the pose of the last relax
            // pass: every substep but the first) applies the impulse along that row: the Jacobian and the
            // turned vectors the warm start would compute again, so the same bits without the distance.
            let built = match j.kind {
                Prepared::Rope(_) | Prepared::Rod(_) => j
                    .link
                    .and_then(|k| self.links.get(k))
                    .filter(|link| link.is_built_at(&PoseKey::of(a, b))),
                _ => None,
            };
            if let Some(link) = built {
                link.warm_start_row(a, b, state_lambda(j)[0]);
                continue;
            }
            match &j.kind {
                Prepared::Spring(p) => p.warm_start(pair, state, a, b),
                Prepared::Rope(p) => p.warm_start(pair, state, a, b),
                Prepared::Rod(p) => p.warm_start(pair, state, a, b),
                Prepared::Ball => ball::warm_start(pair, state, a, b),
                Prepared::Hinge(p) => p.warm_start(pair, state, a, b),
                Prepared::Fixed(_) => PreparedFixed::warm_start(pair, state, a, b),
                Prepared::Prismatic(_) => PreparedPrismatic::warm_start(pair, state, a, b),
                Prepared::Wheel(_) => PreparedWheel::warm_start(pair, state, a, b),
            }
        }
        for t in &self.tethers {
            let Some((mut a, mut b)) = t.pair.load(solver_bodies) else {
                continue;
            };
            t.warm_start(&mut a, &mut b);
            t.pair.store(solver_bodies, a, b);
        }
    }

    /// Stages *solve* (`Bias::On`: [`JointSettings::solve_iterations`] Gauss–Seidel passes with soft position
    /// correction) and *relax* (`Bias::Off`: [`JointSettings::relax_iterations`] passes on velocities only;
    /// soft springs are left alone, see [`crate::spring`]). Each pass visits the joints in the order given to
    /// [`JointSolver::prepare`] (all but those a direct path solves entirely), then the paths, then the
    /// tethers.
    ///
    /// A *closed* path (every row of its joints in the direct solve, no other joint or tether on its bodies)
    /// is relaxed in the last substep only. The relax pass of an inner substep leaves the velocities at the
    /// pose where the next substep's solve pass starts, and that pass solves the same rows of the same path
    /// exactly: for rigid rows its result does not depend on the velocity along the rows at all (a
    /// projection: `P·(P·v + g·h) = P·(v + g·h)`), and the soft step keeps `1 − mass_scale` of it (about a
    /// tenth at the default joint softness). The last relax pass stays: it takes the bias velocity out of
    /// the step's final velocities, and builds the rows the position projection starts from. On the SCENES.md
    /// bridge and chain this is a third of the direct solves (instructions −9 % and −12 %) with joint gaps
    /// and stretch no worse (`docs/physics.md`, "Relaxing a closed path"). A path with other rows on its
    /// bodies is relaxed every substep: a hinge limit solved by Gauss–Seidel before the path's exact solve
    /// was pushed past by up to 1.5° without the path's relax (`tests/hinge.rs`).
    pub fn solve(&mut self, solver_bodies: &mut [SolverBody], ctx: &StepContext, bias: Bias) {
        let stage = Stage {
            bias,
            h: ctx.h,
            inv_h: ctx.inv_h,
            joint_softness: self.joint_softness,
        };
        let iterations = match bias {
            Bias::On => self.settings.solve_iterations,
            Bias::Off => self.settings.relax_iterations,
        };
        // The last relax pass of the step builds the paths' rows at the final pose instead of carrying them:
        // the position projection ([`JointSolver::project_positions`]) starts at that pose and then reuses
        // the rows and, for paths whose rows all stay in the system (hinges, ball joints, taut ropes), their
        // factorisation — one factorisation of every such path a step fewer than building them there.
        let mut carry_angle = self.carry_angle;
        let mut last_relax = false;
        if bias == Bias::Off {
            self.relax_passes += 1;
            if self.relax_passes >= ctx.substep_count {
                last_relax = true;
                carry_angle = 0.0;
                // Every link is built again at the final pose, and with this step's inverse inertias.
                for link in &mut self.links {
                    link.end_last_step();
                }
            }
        }
        for _ in 0..iterations {
            // Joints on a direct path are solved below, all but a hinge's limit, motor and spring rows (they
            // are not in `iterated`).
            for &index in &self.iterated {
                let Some(j) = self.joints.get_mut(index) else {
                    continue;
                };
                // Springs act in the bias pass only: skip them in the relax pass without touching the bodies.
                if bias == Bias::Off && matches!(j.kind, Prepared::Spring(_)) {
                    continue;
                }
                // The bodies in place (a pass changes velocities only).
                let Some([a, b]) = j.pair.bodies_mut(solver_bodies) else {
                    continue;
                };
                let (pair, state) = (&j.pair, &mut j.state);
                match &mut j.kind {
                    Prepared::Spring(p) => p.solve(pair, state, a, b, &stage),
                    Prepared::Rope(p) => p.solve(pair, state, a, b, &stage),
                    Prepared::Rod(p) => p.solve(pair, state, a, b, &stage),
                    Prepared::Ball => ball::solve(pair, state, a, b, &stage),
                    Prepared::Hinge(p) if j.path.is_some() => {
                        p.solve_coordinate(pair, state, a, b, &stage);
                    }
                    Prepared::Hinge(p) => p.solve(pair, state, a, b, &stage),
                    Prepared::Fixed(p) => p.solve(pair, state, a, b, &stage),
                    Prepared::Prismatic(p) => p.solve(pair, state, a, b, &stage),
                    Prepared::Wheel(p) => p.solve(pair, state, a, b, &stage),
                }
            }
            for path in 0..self.paths.len() {
                // A closed path is relaxed in the step's last substep only: see the method docs.
                if bias == Bias::Off && !last_relax && self.closed.get(path) == Some(&true) {
                    continue;
                }
                self.solve_path(path, solver_bodies, &stage, carry_angle);
            }
            for t in &mut self.tethers {
                let Some((mut a, mut b)) = t.pair.load(solver_bodies) else {
                    continue;
                };
                t.solve(&mut a, &mut b, &stage);
                t.pair.store(solver_bodies, a, b);
            }
        }
    }

    /// Stage *project positions* (once, after the substeps): moves the bodies of every directly solved path
    /// so that its joints hold exactly — stretched ropes back to their length, hinge and ball anchors together
    /// — by solving `K·x = C` for the position errors `C` of all the path's rows at once and displacing the
    /// bodies by `−M⁻¹·Jᵀ·x` (Box2D v2's position pass, solved exactly for the path). Velocities are left
    /// alone, so this adds no energy. Why it is needed: the velocity passes keep `Ċ = 0` only to first order;
    /// a link that turns fast (the whip of a falling chain turns links by 90° within a step) drifts by
    /// `(v·h)²/(2L)` in each substep, far more than the soft correction takes back.
    pub fn project_positions(&mut self, solver_bodies: &mut [SolverBody], ctx: &StepContext) {
        let stage = Stage::projection(ctx.h);
        for path in 0..self.paths.len() {
            let Some(range) = self.paths.get(path).cloned() else {
                continue;
            };
            let Self {
                joints,
                path_joints,
                links,
                solution,
                saved,
                probe,
                ..
            } = self;
            resize_links(links, path_joints.len());
            let (Some(members), Some(links)) =
                (path_joints.get(range.clone()), links.get_mut(range))
            else {
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
                .any(|&index| matches!(joints[index].kind, Prepared::Rope(_) | Prepared::Rod(_)))
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
                    link.make_positional(PROJECTION_TOLERANCE);
                }
                known = Some(before);
                if before <= PROJECTION_TOLERANCE {
                    break;
                }
                solve_links(joints, members, links, solution, solver_bodies);
                save_bodies(joints, members, solver_bodies, saved);
                let probe = link_at(probe, 0);
                // A Newton step can overshoot where the linearisation is poor: a light body between two
                // nearly aligned, pulled links is moved far sideways (by about `p·θ/m` for a position
                // impulse `p` through links turned by `θ`), which lengthens both links by the square of
                // that (at the SCENES.md chain's whip a step meant to close 0.36 cm moved bodies 10 cm and
                // left 7.4 cm). If the full step does not get the worst error down to `gain` of it, the
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
                    Some(after) if after <= PROJECTION_TOLERANCE => {
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
            if before <= PROJECTION_TOLERANCE {
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
                        crate::direct::project_rows(&probe.rows, a, b);
                    }
                }
                if (sweep + 1) % PROJECTION_SWEEP_CHECK == 0 || sweep + 1 == PROJECTION_SWEEPS {
                    let after = worst(joints, solver_bodies, probe);
                    if after > before {
                        restore_bodies(saved, solver_bodies);
                        break;
                    }
                    if after <= PROJECTION_TOLERANCE {
                        break;
                    }
                }
            }
        }
    }

    /// One direct pass over path `path` ([`crate::direct`]): the rows of its joints at the current pose, the
    /// exact solve of their coupled system, the soft update of each row.
    ///
    /// A link whose bodies are where they were when its rows were built — the bits of their displacements
    /// and rotations ([`PoseKey`]) unchanged, as from a relax pass to the next substep's solve pass, where
    /// only velocities change — keeps its rows and recomputes only their targets for this pass's stage; the
    /// others are built again. The solve keeps each link's factorisation while that link and its neighbours
    /// have the rows, and the rows in the system, it was made for ([`solve_path`]). Both give the bits a
    /// rebuild would.
    fn solve_path(
        &mut self,
        path: usize,
        solver_bodies: &mut [SolverBody],
        stage: &Stage,
        carry_angle: f32,
    ) {
        let Some(range) = self.paths.get(path).cloned() else {
            return;
        };
        let Self {
            joints,
            path_joints,
            links,
            solution,
            ..
        } = self;
        // `prepare` sized the links to the path members; a solver never prepared has no paths.
        resize_links(links, path_joints.len());
        let (Some(members), Some(links)) = (path_joints.get(range.clone()), links.get_mut(range))
        else {
            return;
        };
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
        solve_links(joints, members, links, solution, solver_bodies);
        for ((link, x), &index) in links.iter_mut().zip(solution.iter()).zip(members) {
            let j = &mut joints[index];
            let Some([a, b]) = j.pair.bodies_mut(solver_bodies) else {
                continue;
            };
            link.apply_solution(x, a, b);
            let (lambda, s) = (link.lambda, &mut j.state);
            match &mut j.kind {
                Prepared::Rope(p) => {
                    s.upper_impulse = lambda[0];
                    p.note_impulse(lambda[0]);
                }
                Prepared::Rod(_) => s.axial_impulse = lambda[0],
                Prepared::Ball => s.linear_impulse = Vec3::new(lambda[0], lambda[1], lambda[2]),
                Prepared::Hinge(_) => {
                    s.linear_impulse = Vec3::new(lambda[0], lambda[1], lambda[2]);
                    s.angular_impulse.x = lambda[3];
                    s.angular_impulse.y = lambda[4];
                }
                _ => {}
            }
        }
    }

    /// Drops the rows and factorisations kept between passes, so that the next pass builds everything again
    /// (what a pass did before they were kept).
    #[cfg(test)]
    fn forget_rows(&mut self) {
        for link in &mut self.links {
            link.forget();
        }
    }

    /// How many links of the paths have rows built at the bodies' current pose (the next pass reuses them).
    #[cfg(test)]
    fn reusable_links(&self, solver_bodies: &[SolverBody]) -> usize {
        self.path_joints
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

    /// Stage *restitution* (once, after the substeps): a rope with restitution `e` that snapped taut during
    /// the step while its anchors separated faster than `ctx.restitution_threshold` gets `Ċ = −e·Ċ⁻`.
    pub fn apply_restitution(&mut self, solver_bodies: &mut [SolverBody], ctx: &StepContext) {
        for j in &mut self.joints {
            let Prepared::Rope(rope) = &j.kind else {
                continue;
            };
            let Some((mut a, mut b)) = j.pair.load(solver_bodies) else {
                continue;
            };
            rope.apply_restitution(&j.pair, &mut j.state, &mut a, &mut b, ctx);
            j.pair.store(solver_bodies, a, b);
        }
    }

    /// Stage *store impulses*: writes each prepared joint's impulses and reaction force and torque (N, N·m)
    /// into `states` (the slice given to [`JointSolver::prepare`]) for warm starting the next step. A joint
    /// whose reaction exceeds its break force or torque is marked broken and its index pushed into `broken`
    /// (which is not cleared first).
    pub fn store_impulses(&self, states: &mut [JointState], broken: &mut Vec<usize>) {
        let inv_h = if self.h > 0.0 { 1.0 / self.h } else { 0.0 };
        for j in &self.joints {
            let Some(out) = states.get_mut(j.source) else {
                continue;
            };
            let (linear, angular) = reaction_impulses(&j.kind, &j.state);
            *out = JointState {
                reaction_force: linear * inv_h,
                reaction_torque: angular * inv_h,
                tether_impulse: 0.0,
                broken: false,
                ..j.state
            };
            if out.reaction_force > j.break_force || out.reaction_torque > j.break_torque {
                out.broken = true;
                broken.push(j.source);
            }
        }
        for t in &self.tethers {
            if let Some(out) = self
                .joints
                .get(t.joint)
                .and_then(|j| states.get_mut(j.source))
            {
                out.tether_impulse = t.impulse;
            }
        }
    }
}

/// The one impulse field a distance-type or ball joint uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Keep {
    Axial,
    Upper,
    Linear,
}

/// Zeroes every impulse field but `keep` (so a joint whose kind changed is not warm-started with another
/// kind's impulses).
fn keep_only(state: &mut JointState, keep: Keep) {
    let kept = *state;
    *state = JointState {
        tether_impulse: kept.tether_impulse,
        ..JointState::default()
    };
    match keep {
        Keep::Axial => state.axial_impulse = kept.axial_impulse,
        Keep::Upper => state.upper_impulse = kept.upper_impulse,
        Keep::Linear => state.linear_impulse = kept.linear_impulse,
    }
}

/// The magnitudes of the linear (N·s) and angular (N·m·s) impulses a joint carried in the last substep. Rows
/// of one joint act along orthogonal directions, so the magnitudes add in quadrature.
fn reaction_impulses(kind: &Prepared, s: &JointState) -> (f32, f32) {
    let along = CoordinateRows::accumulated(s);
    let hypot3 = |x: f32, y: f32, z: f32| (x * x + y * y + z * z).sqrt();
    match kind {
        Prepared::Spring(_) | Prepared::Rod(_) => (s.axial_impulse.abs(), 0.0),
        Prepared::Rope(_) => (s.upper_impulse.abs(), 0.0),
        Prepared::Ball => (s.linear_impulse.length(), 0.0),
        Prepared::Hinge(_) => (
            s.linear_impulse.length(),
            hypot3(s.angular_impulse.x, s.angular_impulse.y, along),
        ),
        Prepared::Fixed(_) => (s.linear_impulse.length(), s.angular_impulse.length()),
        Prepared::Prismatic(_) => (
            hypot3(s.linear_impulse.x, s.linear_impulse.y, along),
            s.angular_impulse.length(),
        ),
        Prepared::Wheel(_) => (
            hypot3(
                s.linear_impulse.x,
                s.linear_impulse.y,
                s.axial_impulse + s.lower_impulse + s.upper_impulse,
            ),
            hypot3(s.angular_impulse.x, s.angular_impulse.y, s.motor_impulse),
        ),
    }
}

/// The joint's bodies that the solver moves (dynamic: a non-zero inverse mass or inertia); `None` for a
/// fixed or kinematic side, which couples nothing.
fn dynamic_bodies(pair: &BodyPair) -> [Option<usize>; 2] {
    let moves = |inv_mass: f32, inv_inertia: &Mat3| inv_mass > 0.0 || *inv_inertia != Mat3::ZERO;
    [
        moves(pair.inv_mass_a, &pair.inv_inertia_a).then_some(pair.index_a),
        moves(pair.inv_mass_b, &pair.inv_inertia_b).then_some(pair.index_b),
    ]
}

/// The rows of joint `j` for a direct pass at its bodies' current pose, written into `rows` (after a reset
/// to the joint's bodies), and its accumulated impulses in row order (no rows for a body pair out of range,
/// which the world never hands over).
fn direct_rows(
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
/// body by one inverse inertia until the last relax pass builds every link again, see `crate::direct`).
fn rows_at(
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
    match &mut j.kind {
        Prepared::Rope(p) => p.direct_row(&j.pair, a, b, stage, rows),
        Prepared::Rod(p) => p.direct_row(&j.pair, a, b, stage, rows),
        Prepared::Ball => ball::direct_rows(&j.pair, a, b, stage, rows),
        Prepared::Hinge(_) => PreparedHinge::direct_rows(&j.pair, a, b, stage, rows),
        _ => return [0.0; MAX_ROWS],
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
fn link_rows(
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
    if let (Prepared::Hinge(_), Some((a, b)), Some(now)) = (&j.kind, bodies, &pose) {
        if carry_angle > 0.0
            && (link.recarry(now, stage) || carry(j, link, (a, b), now, stage, carry_angle))
        {
            link.lambda = state_lambda(j);
            return;
        }
        // Built again: carried from here, in this step or the next; with the kept rows' inverse masses on a
        // path kept from the last step.
        let keep_masses = link.from_last_step;
        link.lambda = rows_at(j, bodies, stage, link, keep_masses);
        link.built_at(pose);
        link.built = Some(build_site(j, a, b));
        return;
    }
    link.lambda = rows_at(j, bodies, stage, link, false);
    link.built_at(pose);
}

/// Adds (`add`) or takes off one count per joint of `members` from each of its dynamic bodies in `touches`.
fn count_dynamic_bodies(
    touches: &mut [u32],
    joints: &[PreparedJoint],
    members: &[usize],
    add: bool,
) {
    for &index in members {
        for body in dynamic_bodies(&joints[index].pair).into_iter().flatten() {
            if let Some(count) = touches.get_mut(body) {
                *count = if add {
                    *count + 1
                } else {
                    count.wrapping_sub(1)
                };
            }
        }
    }
}

/// Where joint `j`'s rows are when its bodies are at `a`, `b`, in world terms ([`BuiltAt`]).
fn build_site(j: &PreparedJoint, a: &SolverBody, b: &SolverBody) -> BuiltAt {
    BuiltAt {
        frames: j.pair.frames(a, b),
        relative: j.pair.delta_center + (b.delta_position - a.delta_position),
        owner: (j.source, j.pair.index_a, j.pair.index_b),
    }
}

/// [`Link::carry`] of joint `j`'s rows in `link` to its bodies' pose `a`, `b` (`now`, its key).
#[inline(never)]
fn carry(
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

/// The accumulated impulses of joint `j`'s direct rows, in row order (0 for a joint without direct rows).
fn state_lambda(j: &PreparedJoint) -> [f32; MAX_ROWS] {
    let s = &j.state;
    let (l, w) = (s.linear_impulse, s.angular_impulse);
    match &j.kind {
        Prepared::Rope(_) => [s.upper_impulse, 0.0, 0.0, 0.0, 0.0],
        Prepared::Rod(_) => [s.axial_impulse, 0.0, 0.0, 0.0, 0.0],
        Prepared::Ball => [l.x, l.y, l.z, 0.0, 0.0],
        Prepared::Hinge(_) => [l.x, l.y, l.z, w.x, w.y],
        _ => [0.0; MAX_ROWS],
    }
}

/// An empty link (no rows, no bodies), to grow a buffer of links with.
fn empty_link() -> Link {
    let zero = InvMass {
        mass: 0.0,
        inertia: Mat3::ZERO,
    };
    Link::new(JointRows::new(zero, zero), [0.0; MAX_ROWS])
}

/// Grows `links` to at least `len` links (it never shrinks: the buffer keeps the longest it has been, so
/// that a step allocates nothing once it has).
fn resize_links(links: &mut Vec<Link>, len: usize) {
    if links.len() < len {
        links.resize(len, empty_link());
    }
}

/// Link `k` of a pass, reused from earlier passes (the buffer grows to the longest path once).
fn link_at(links: &mut Vec<Link>, k: usize) -> &mut Link {
    resize_links(links, k + 1);
    &mut links[k]
}

/// The worst position error of joint `j`'s rows at the bodies' current pose (see `JointRows::violation`),
/// built in `scratch` — or, for a ball joint or hinge, whose rows are all equalities, measured from the rows'
/// errors alone ([`equality_violation`]): the same value without building the Jacobians.
fn violation(
    j: &mut PreparedJoint,
    solver_bodies: &[SolverBody],
    stage: &Stage,
    scratch: &mut Link,
) -> f32 {
    if let Some((a, b)) = j.pair.bodies(solver_bodies) {
        match j.kind {
            Prepared::Ball => {
                return equality_violation(&ball::direct_errors(&j.pair, a, b), stage);
            }
            Prepared::Hinge(_) => {
                return equality_violation(&PreparedHinge::direct_errors(&j.pair, a, b), stage);
            }
            _ => {}
        }
    }
    let _ = direct_rows(j, solver_bodies, stage, scratch);
    scratch.rows.violation()
}

/// The worst position error of the path's joints at the bodies' current pose.
fn path_worst(
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
/// `solution`, the solver bodies and their saved pose, the probe link and the projection's stage.
struct NewtonStep<'a> {
    joints: &'a mut [PreparedJoint],
    members: &'a [usize],
    links: &'a mut [Link],
    solution: &'a mut Vec<[Real; MAX_ROWS]>,
    solver_bodies: &'a mut [SolverBody],
    saved: &'a [(usize, SolverBody)],
    probe: &'a mut Link,
    stage: &'a Stage,
}

impl NewtonStep<'_> {
    /// Applies `first` times the step `solution` to the path's bodies (saved in `saved`), then half of that,
    /// and so on (up to `sizes` sizes), until the path's worst error is no larger than `target`; returns the
    /// worst error of the step kept, or `None` with the bodies restored if no size was good enough.
    fn try_scaled(&mut self, target: f32, first: Real, sizes: usize) -> Option<f32> {
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
                return Some(after);
            }
            restore_bodies(self.saved, self.solver_bodies);
            scale *= 0.5;
        }
        None
    }

    /// Stiffens the path's pulled ropes and rods ([`stiffen`]) and, if any was, solves the step again; whether
    /// it was.
    fn stiffen_and_solve(&mut self) -> bool {
        let stiffened = stiffen(self.joints, self.members, self.links, self.solution);
        if stiffened {
            solve_links(
                self.joints,
                self.members,
                self.links,
                self.solution,
                self.solver_bodies,
            );
        }
        stiffened
    }
}

/// Stiffens the path's pulled rope and rod links against turning for another Newton step of the projection
/// ([`Link::stiffen`]), each with [`PROJECTION_STIFFENING`] times the geometric stiffness `|p|/L` of its
/// position impulse `p` in `solution` (the rejected plain step) and its length `L`. Returns whether any link
/// was stiffened (none on a path without ropes and rods, or whose ropes all are slack).
fn stiffen(
    joints: &[PreparedJoint],
    members: &[usize],
    links: &mut [Link],
    solution: &[[Real; MAX_ROWS]],
) -> bool {
    let mut any = false;
    for ((link, x), &index) in links.iter_mut().zip(solution).zip(members) {
        let length = match &joints[index].kind {
            Prepared::Rope(p) => p.max_length(),
            Prepared::Rod(p) => p.length(),
            _ => continue,
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
fn save_bodies(
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
fn restore_bodies(saved: &[(usize, SolverBody)], solver_bodies: &mut [SolverBody]) {
    for &(index, body) in saved.iter().rev() {
        if let Some(slot) = solver_bodies.get_mut(index) {
            *slot = body;
        }
    }
}

/// Solves the path (with the active-set rounds that drop rows which would push) into `solution`; its links
/// are linked through their shared bodies ([`JointSolver::prepare`], `link_paths`).
fn solve_links(
    joints: &[PreparedJoint],
    members: &[usize],
    links: &mut [Link],
    solution: &mut Vec<[Real; MAX_ROWS]>,
    solver_bodies: &mut [SolverBody],
) {
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

#[cfg(test)]
mod tests {
    #![allow(
        clippy::unwrap_used,
        reason = "the scene is built from known-valid inputs; a failure is a test failure"
    )]

    use super::*;
    use crate::{BallJoint, FixedJoint, HingeJoint, Rope};
    use rebound_dynamics::integrate::{integrate_positions, integrate_velocities};
    use rebound_dynamics::{BodyDesc, MassProperties, RigidBody, SolverSettings};
    use rebound_math::Quat;

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
        // The first hinge's limits never bind, but they keep the deck from being a closed path (one relaxed
        // in the last substep only), so that its rows are reused in every substep.
        let limited = Joint::new(HingeJoint::new().with_limits(-3.0, 3.0).unwrap())
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
            let mut solver_bodies: Vec<SolverBody> =
                bodies.iter().map(SolverBody::from_body).collect();
            let params: Vec<BodyParams> = bodies.iter().map(BodyParams::from_body).collect();
            let skipped = solver.prepare(&joints, &states, &pairs, &solver_bodies, &params, &ctx);
            assert_eq!((skipped, solver.paths.len()), (0, 2));
            assert_eq!(
                solver.closed,
                [false, true],
                "the deck has a limit, the chain is closed"
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
            for (body, (state, params)) in bodies.iter_mut().zip(solver_bodies.iter().zip(&params))
            {
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
            solver.closed
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
        // A fixed joint (not solved directly) on the second plank: the deck is still a path, not a closed one.
        joints.push(Joint::new(FixedJoint::new()));
        pairs.push(JointBodies {
            a: 2,
            b: bodies.len() - 1,
        });
        assert_eq!(closed(&bodies, &joints, &pairs), [false, false]);
        // A limit on one hinge: its rows are solved by Gauss–Seidel beside the path's.
        let (bodies, mut joints, pairs) = hinge_deck(1.0);
        joints[2] = Joint::new(HingeJoint::new().with_limits(-1.0, 1.0).unwrap())
            .with_local_anchors(Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0))
            .unwrap()
            .with_local_axes(Vec3::Z, Vec3::Z)
            .unwrap();
        assert_eq!(closed(&bodies, &joints, &pairs), [false]);
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
                .filter(|l| l.from_last_step)
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
        assert_eq!((skipped, solver.paths.len()), (0, 1));
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
            bodies[1].delta_rotation =
                Quat::from_axis_angle(Vec3::new(axis.z, axis.x, axis.y), turn_b);
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
}
