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
//! apply_restitution               once: ropes that snapped taut
//! store_impulses                  impulses back into the JointStates; break check
//! ```
//!
//! Buffers are reused from step to step: once the `Vec` of prepared joints has grown to the scene's joint
//! count, a step allocates nothing.

use crate::coordinate::CoordinateRows;
use crate::fixed::PreparedFixed;
use crate::hinge::PreparedHinge;
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
}

/// The joint solver. Holds the prepared joints between stages and reuses its buffer from step to step.
///
/// See the crate README for a complete step loop.
#[derive(Debug, Clone)]
pub struct JointSolver {
    settings: JointSettings,
    joints: Vec<PreparedJoint>,
    /// Long-range tethers of chains hanging from fixed bodies (see [`crate::tether`]).
    tethers: Vec<Tether>,
    /// Scratch: the joints as graph edges, and the graph search's buffers.
    edges: Vec<Edge>,
    graph: JointGraph,
    /// The joint softness of the prepared step.
    joint_softness: Softness,
    /// The substep length of the prepared step (s).
    h: f32,
}

impl Default for JointSolver {
    fn default() -> Self {
        Self {
            settings: JointSettings::default(),
            joints: Vec::new(),
            tethers: Vec::new(),
            edges: Vec::new(),
            graph: JointGraph::default(),
            joint_softness: Softness::RIGID,
            h: 0.0,
        }
    }
}

impl JointSolver {
    /// A solver with [`JointSettings::default`].
    #[must_use]
    pub fn new() -> Self {
        Self::default()
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
                JointKind::Hinge(h) => Prepared::Hinge(h.prepare(ctx, &mut state)),
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
            });
        }
        self.analyse_graph(params);
        skipped
    }

    /// The joint graph and its tethers (see [`crate::tether`]).
    fn analyse_graph(&mut self, params: &[BodyParams]) {
        self.tethers.clear();
        if !self.settings.tethers {
            return;
        }
        self.edges.clear();
        self.edges.extend(self.joints.iter().map(|j| Edge {
            pair: j.pair,
            length: j.kind.bounded_length(),
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
            let Some((mut a, mut b)) = j.pair.load(solver_bodies) else {
                continue;
            };
            let (pair, state) = (&j.pair, &j.state);
            match &j.kind {
                Prepared::Spring(p) => p.warm_start(pair, state, &mut a, &mut b),
                Prepared::Rope(p) => p.warm_start(pair, state, &mut a, &mut b),
                Prepared::Rod(p) => p.warm_start(pair, state, &mut a, &mut b),
                Prepared::Ball => ball::warm_start(pair, state, &mut a, &mut b),
                Prepared::Hinge(p) => p.warm_start(pair, state, &mut a, &mut b),
                Prepared::Fixed(_) => PreparedFixed::warm_start(pair, state, &mut a, &mut b),
                Prepared::Prismatic(_) => {
                    PreparedPrismatic::warm_start(pair, state, &mut a, &mut b);
                }
                Prepared::Wheel(_) => PreparedWheel::warm_start(pair, state, &mut a, &mut b),
            }
            j.pair.store(solver_bodies, a, b);
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
    /// [`JointSolver::prepare`], then the tethers.
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
        for _ in 0..iterations {
            for j in &mut self.joints {
                // Springs act in the bias pass only: skip them in the relax pass without touching the bodies.
                if bias == Bias::Off && matches!(j.kind, Prepared::Spring(_)) {
                    continue;
                }
                let Some((mut a, mut b)) = j.pair.load(solver_bodies) else {
                    continue;
                };
                let (pair, state) = (&j.pair, &mut j.state);
                match &mut j.kind {
                    Prepared::Spring(p) => p.solve(pair, state, &mut a, &mut b, &stage),
                    Prepared::Rope(p) => p.solve(pair, state, &mut a, &mut b, &stage),
                    Prepared::Rod(p) => p.solve(pair, state, &mut a, &mut b, &stage),
                    Prepared::Ball => ball::solve(pair, state, &mut a, &mut b, &stage),
                    Prepared::Hinge(p) => p.solve(pair, state, &mut a, &mut b, &stage),
                    Prepared::Fixed(p) => p.solve(pair, state, &mut a, &mut b, &stage),
                    Prepared::Prismatic(p) => p.solve(pair, state, &mut a, &mut b, &stage),
                    Prepared::Wheel(p) => p.solve(pair, state, &mut a, &mut b, &stage),
                }
                j.pair.store(solver_bodies, a, b);
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
