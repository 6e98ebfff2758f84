//! The one dispatch over the joint kinds, a `match` per stage (Box2D's `joint.c`): a joint prepared for
//! the substeps ([`PreparedJoint`]: its bodies, impulses and kind-specific prepared data, [`Prepared`]),
//! and for each stage what each kind does — *prepare*, *apply forces*, *warm start*, *solve* and *relax*,
//! the rows it gives a directly solved path and the impulses they carry, *project positions*,
//! *restitution* and the reaction reported at *store impulses*. The stages themselves (`prepare`,
//! `passes`, `path_pass`, `project`) name no joint kind.

use crate::ball::{self, PreparedBall};
use crate::coordinate::{Coordinate, CoordinateRows};
use crate::fixed::{FixedJoint, PreparedFixed};
use crate::hinge::PreparedHinge;
use crate::joint::JointKind;
use crate::pair::BodyPair;
use crate::path::MAX_ROWS;
use crate::path::{JointRows, equality_violation};
use crate::prismatic::PreparedPrismatic;
use crate::rod::PreparedRod;
use crate::rope::PreparedRope;
use crate::six_dof::PreparedSixDof;
use crate::spring::PreparedSpring;
use crate::stage::Stage;
use crate::state::JointState;
use crate::wheel::PreparedWheel;
use rebound_dynamics::{SolverBody, StepContext};
use rebound_math::{Vec3, real};

/// A joint kind prepared for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Prepared {
    Spring(PreparedSpring),
    Rope(PreparedRope),
    Rod(PreparedRod),
    Ball,
    /// A ball joint with swing–twist limits or an orientation motor.
    LimitedBall(PreparedBall),
    Hinge(PreparedHinge),
    Fixed(PreparedFixed),
    Prismatic(PreparedPrismatic),
    Wheel(PreparedWheel),
    SixDof(PreparedSixDof),
}

impl Prepared {
    /// Stage *prepare* of `kind` between the bodies `sa`, `sb` of `pair`: the kind's prepared data, written
    /// over `self` (what the slot held the step before: a spring reuses its oscillator step when it was made
    /// for the same numbers), with the impulses in `state` it does not use zeroed (so a joint whose kind
    /// changed is not warm-started with another kind's impulses). Each arm writes its variant in place: a
    /// variant built and then copied costs a copy of the largest kind's size.
    pub(super) fn prepare(
        &mut self,
        kind: &JointKind,
        pair: &BodyPair,
        (sa, sb): (&SolverBody, &SolverBody),
        ctx: &StepContext,
        state: &mut JointState,
    ) {
        match kind {
            JointKind::Spring(s) => {
                keep_only(state, Keep::Axial);
                state.axial_impulse = 0.0;
                let last = match self {
                    Self::Spring(last) => Some(*last),
                    _ => None,
                };
                *self = Self::Spring(s.prepare(pair, (sa, sb), ctx.h, last.as_ref()));
            }
            JointKind::Rope(r) => {
                keep_only(state, Keep::Upper);
                *self = Self::Rope(r.prepare(pair, sa, sb));
            }
            JointKind::Rod(r) => {
                keep_only(state, Keep::Axial);
                *self = Self::Rod(r.prepare(pair, sa, sb));
            }
            JointKind::Ball(ball) if !ball.is_free() => {
                *self = Self::LimitedBall(ball.prepare(pair, (sa, sb), ctx, state));
            }
            JointKind::Ball(_) => {
                keep_only(state, Keep::Linear);
                *self = Self::Ball;
            }
            JointKind::Hinge(h) => *self = Self::Hinge(h.prepare(pair, state)),
            JointKind::Fixed(_) => *self = Self::Fixed(FixedJoint::prepare(pair, state)),
            JointKind::Prismatic(p) => *self = Self::Prismatic(p.prepare(pair, state)),
            JointKind::Wheel(w) => *self = Self::Wheel(w.prepare(state)),
            JointKind::SixDof(j) => *self = Self::SixDof(j.prepare(pair, ctx, state)),
        }
    }

    /// Stage *apply forces*: a distance spring's impulse over the substep `h` (s) on its bodies, recorded in
    /// `state` (see [`crate::spring`]); nothing for every other joint (the springs of joint coordinates:
    /// [`Prepared::apply_coordinate_spring`]).
    #[inline]
    pub(super) fn apply_forces(
        &self,
        pair: &BodyPair,
        state: &mut JointState,
        solver_bodies: &mut [SolverBody],
        h: f32,
    ) {
        let Self::Spring(spring) = self else {
            return;
        };
        // The bodies in place: the spring changes velocities only (`prepare` never keeps a joint whose two
        // bodies are one).
        let Some([a, b]) = pair.bodies_mut(solver_bodies) else {
            return;
        };
        state.axial_impulse = spring.apply_forces(pair, a, b, h);
    }

    /// Whether the joint is a hinge or prismatic joint with a spring, or a wheel (its suspension): what
    /// [`Prepared::apply_coordinate_spring`] acts on.
    #[inline]
    pub(super) fn has_coordinate_spring(&self) -> bool {
        match self {
            Self::Hinge(p) => p.has_spring(),
            Self::Prismatic(p) => p.has_spring(),
            Self::Wheel(p) => p.has_spring(),
            _ => false,
        }
    }

    /// Stage *apply forces* of a hinge's, prismatic joint's or wheel's spring over the substep `h` (s)
    /// ([`crate::coordinate`]); nothing for every other joint.
    pub(super) fn apply_coordinate_spring(
        &self,
        pair: &BodyPair,
        state: &mut JointState,
        solver_bodies: &mut [SolverBody],
        h: f32,
    ) {
        if !self.has_coordinate_spring() {
            return;
        }
        let Some([a, b]) = pair.bodies_mut(solver_bodies) else {
            return;
        };
        let bodies = (a, b);
        match self {
            Self::Hinge(p) => p.apply_spring(pair, state, bodies, h),
            Self::Prismatic(p) => p.apply_spring(pair, state, bodies, h),
            Self::Wheel(p) => p.apply_spring(pair, state, bodies, h),
            _ => {}
        }
    }

    /// Stage *warm start*: the impulses of the last substep in `state`, again, along the current directions.
    #[inline]
    pub(super) fn warm_start(
        &self,
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        match self {
            Self::Spring(_) => {}
            Self::Rope(p) => p.warm_start(pair, state, a, b),
            Self::Rod(p) => p.warm_start(pair, state, a, b),
            Self::Ball => ball::warm_start(pair, state, a, b),
            Self::LimitedBall(p) => p.warm_start(pair, state, a, b),
            Self::Hinge(p) => p.warm_start(pair, state, a, b),
            Self::Fixed(_) => PreparedFixed::warm_start(pair, state, a, b),
            Self::Prismatic(_) => PreparedPrismatic::warm_start(pair, state, a, b),
            Self::Wheel(_) => PreparedWheel::warm_start(pair, state, a, b),
            Self::SixDof(p) => p.warm_start(pair, state, a, b),
        }
    }

    /// Whether the joint acts in no pass but *apply forces* (a spring: its warm start and its visits in
    /// *solve* and *relax* do nothing).
    #[inline]
    pub(super) fn acts_in_no_pass(&self) -> bool {
        matches!(self, Self::Spring(_))
    }

    /// Whether a Gauss–Seidel pass visits the joint: a joint on no path but a spring (which acts in *apply
    /// forces* alone), and a hinge on one for its motor and the limits the path does not solve, if it has any
    /// (the path solves the rest; its spring acts in *apply forces*).
    pub(super) fn is_iterated(&self, on_path: bool) -> bool {
        match self {
            Self::Spring(_) => false,
            Self::Hinge(hinge) => !on_path || !hinge.is_solved_directly_whole(),
            Self::LimitedBall(ball) => !on_path || ball.is_iterated_on_path(),
            _ => !on_path,
        }
    }

    /// Stages *solve* and *relax*, one Gauss–Seidel visit of the joint's rows (of a hinge `on_path`, only its
    /// limit and motor rows).
    #[inline]
    pub(super) fn solve(
        &mut self,
        pair: &BodyPair,
        state: &mut JointState,
        (a, b): (&mut SolverBody, &mut SolverBody),
        stage: &Stage,
        on_path: bool,
    ) {
        match self {
            Self::Spring(_) => {}
            Self::Rope(p) => p.solve(pair, state, (a, b), stage),
            Self::Rod(p) => p.solve(pair, state, (a, b), stage),
            Self::Ball => ball::solve(pair, state, a, b, stage),
            Self::LimitedBall(p) => p.solve(pair, state, a, b, stage, on_path),
            Self::Hinge(p) if on_path => p.solve_coordinate(pair, state, a, b, stage),
            Self::Hinge(p) => p.solve(pair, state, a, b, stage),
            Self::Fixed(p) => p.solve(pair, state, a, b, stage),
            Self::Prismatic(p) => p.solve(pair, state, a, b, stage),
            Self::Wheel(p) => p.solve(pair, state, a, b, stage),
            Self::SixDof(p) => p.solve(pair, state, a, b, stage),
        }
    }

    /// The joint's rows for a direct pass of `stage` at its bodies' pose `a`, `b`, pushed into `rows`;
    /// `false` for a kind without direct rows.
    #[inline(always)]
    pub(super) fn direct_rows(
        &mut self,
        pair: &BodyPair,
        (a, b): (&SolverBody, &SolverBody),
        stage: &Stage,
        rows: &mut JointRows,
    ) -> bool {
        match self {
            Self::Rope(p) => p.direct_row(pair, (a, b), stage, rows),
            Self::Rod(p) => p.direct_row(pair, (a, b), stage, rows),
            Self::Ball => ball::direct_rows(pair, a, b, stage, rows),
            Self::LimitedBall(p) => p.direct_rows(pair, a, b, stage, rows),
            Self::Hinge(p) => p.direct_rows(pair, a, b, stage, rows),
            Self::Fixed(_) => PreparedFixed::direct_rows(pair, a, b, stage, rows),
            _ => return false,
        }
        true
    }

    /// Whether a path carries the joint's rows from pose to pose instead of building them again (a hinge's:
    /// their Jacobians depend on the bodies' rotations alone, see [`crate::path`]).
    #[inline]
    pub(super) fn carries_rows(&self) -> bool {
        matches!(self, Self::Hinge(_))
    }

    /// Writes the impulses `lambda` of the joint's direct rows, in row order, into `state` (and notes a
    /// rope's, for its restitution).
    #[inline]
    pub(super) fn store_direct_impulses(
        &mut self,
        state: &mut JointState,
        lambda: [f32; MAX_ROWS],
    ) {
        match self {
            Self::Rope(p) => p.store_direct_impulses(state, lambda),
            Self::Rod(_) => PreparedRod::store_direct_impulses(state, lambda),
            Self::Ball => ball::store_direct_impulses(state, lambda),
            Self::LimitedBall(p) => p.store_direct_impulses(state, lambda),
            Self::Hinge(p) => p.store_direct_impulses(state, lambda),
            Self::Fixed(_) => PreparedFixed::store_direct_impulses(state, lambda),
            _ => {}
        }
    }

    /// The worst position error of the joint's direct rows at the pose `a`, `b` measured from the rows'
    /// errors alone, for a ball joint, a hinge or a fixed joint: the value [`JointRows::violation`] of the
    /// built rows gives, without building the Jacobians. `None` for the other kinds, whose rows are built to
    /// be measured.
    pub(super) fn equality_violation(
        &self,
        pair: &BodyPair,
        (a, b): (&SolverBody, &SolverBody),
        stage: &Stage,
    ) -> Option<f32> {
        match self {
            Self::Ball => Some(equality_violation(&ball::direct_errors(pair, a, b), stage)),
            Self::LimitedBall(p) => Some(p.direct_violation(pair, a, b, stage)),
            Self::Hinge(p) => Some(p.direct_violation(pair, a, b, stage)),
            Self::Fixed(_) => Some(equality_violation(
                &PreparedFixed::direct_errors(pair, a, b),
                stage,
            )),
            _ => None,
        }
    }

    /// The length (m) of a rope or rod, whose one direct row the projection may stiffen against turning;
    /// `None` for the other kinds.
    pub(super) fn link_length(&self) -> Option<f32> {
        match self {
            Self::Rope(p) => Some(p.max_length()),
            Self::Rod(p) => Some(p.length()),
            _ => None,
        }
    }

    /// Whether the joint may act in stage *restitution* ([`Prepared::apply_restitution`]): a rope with a
    /// coefficient of restitution, a ball joint with limits.
    pub(super) fn has_restitution(&self) -> bool {
        match self {
            Self::Rope(p) => p.has_restitution(),
            Self::LimitedBall(_) => true,
            _ => false,
        }
    }

    /// Stage *restitution*: a rope that snapped taut during the step bounces back; nothing for the others.
    pub(super) fn apply_restitution(
        &self,
        pair: &BodyPair,
        state: &mut JointState,
        solver_bodies: &mut [SolverBody],
        ctx: &StepContext,
    ) {
        if !matches!(self, Self::Rope(_) | Self::LimitedBall(_)) {
            return;
        }
        let Some((mut a, mut b)) = pair.load(solver_bodies) else {
            return;
        };
        match self {
            Self::Rope(rope) => rope.apply_restitution(pair, state, &mut a, &mut b, ctx),
            Self::LimitedBall(ball) => ball.apply_restitution(pair, state, &mut a, &mut b, ctx),
            _ => {}
        }
        pair.store(solver_bodies, a, b);
    }

    /// Whether the joint's equality rows can join a directly solved path ([`crate::path`]).
    pub(super) fn is_direct_capable(&self) -> bool {
        matches!(
            self,
            Self::Rope(_)
                | Self::Rod(_)
                | Self::Ball
                | Self::LimitedBall(_)
                | Self::Hinge(_)
                | Self::Fixed(_)
        )
    }

    /// How many rows the joint gives the direct solve ([`Prepared::direct_rows`]): 1 for a rope or rod, 3 for a
    /// ball joint (its point rows; a limited one's are its point rows and at most 2 limit rows), 5 for a hinge
    /// (point and alignment rows) and 6 with its limit row, 6 for a fixed joint, 0 for the others.
    pub(super) fn direct_row_count(&self) -> usize {
        match self {
            Self::Rope(_) | Self::Rod(_) => 1,
            Self::Ball | Self::LimitedBall(_) => 3,
            Self::Hinge(hinge) => hinge.direct_row_count(),
            Self::Fixed(_) => 6,
            _ => 0,
        }
    }

    /// Whether all of the joint's rows are in the direct solve when it is on a path: a rope's, a rod's, a
    /// ball joint's, a fixed joint's, a hinge's without motor whose limits (if any) are in the direct solve.
    pub(super) fn is_solved_directly_whole(&self) -> bool {
        match self {
            Self::Rope(_) | Self::Rod(_) | Self::Ball | Self::Fixed(_) => true,
            Self::Hinge(hinge) => hinge.is_solved_directly_whole(),
            _ => false,
        }
    }

    /// The distance a joint allows between its anchors (m), for tethers: a rope's or rod's length, 0 for the
    /// point joints; `None` for joints that do not bound it.
    pub(super) fn bounded_length(&self) -> Option<f32> {
        match self {
            Self::Rope(p) => Some(p.max_length()),
            Self::Rod(p) => Some(p.length()),
            Self::Ball | Self::LimitedBall(_) | Self::Hinge(_) | Self::Fixed(_) => Some(0.0),
            Self::Spring(_) | Self::Prismatic(_) | Self::Wheel(_) | Self::SixDof(_) => None,
        }
    }
}

/// One prepared joint as the passes read it: its source index, bodies, accumulated impulses, kind and path.
/// What only *prepare* and *store impulses* read is beside it, in a [`JointRecord`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct PreparedJoint {
    pub(super) source: usize,
    pub(super) pair: BodyPair,
    pub(super) state: JointState,
    pub(super) kind: Prepared,
    /// The path solved directly ([`crate::path`]) that the joint's equality rows belong to, as an index
    /// into the solver's `paths`; `None` for a joint solved by Gauss–Seidel alone.
    pub(super) path: Option<usize>,
}

impl PreparedJoint {
    /// A slot of the solver's buffer before its first *prepare* writes it (the buffer keeps its slots from
    /// step to step, and *prepare* writes each joint's fields into its slot in place).
    pub(super) fn unprepared() -> Self {
        Self {
            source: 0,
            pair: BodyPair::default(),
            state: JointState::default(),
            kind: Prepared::Ball,
            path: None,
        }
    }
}

/// The part of a prepared joint that the substeps never read: its break limits, checked at *store
/// impulses*, and the tether whose impulse it keeps for the next step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct JointRecord {
    /// Break force (N) and torque (N·m).
    pub(super) break_force: f32,
    pub(super) break_torque: f32,
    /// The tether (an index into the solver's `tethers`) whose impulse the joint keeps for the next step.
    pub(super) tether: Option<usize>,
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
    *state = kept.tether_only();
    match keep {
        Keep::Axial => state.axial_impulse = kept.axial_impulse,
        Keep::Upper => state.upper_impulse = kept.upper_impulse,
        Keep::Linear => state.linear_impulse = kept.linear_impulse,
    }
}

/// The magnitudes of the linear (N·s) and angular (N·m·s) impulses a joint carried in the last substep. Rows
/// of one joint act along orthogonal directions, so the magnitudes add in quadrature.
pub(super) fn reaction_impulses(kind: &Prepared, s: &JointState) -> (f32, f32) {
    let along = CoordinateRows::accumulated(s);
    let hypot3 = |x: f32, y: f32, z: f32| (x * x + y * y + z * z).sqrt();
    match kind {
        Prepared::Spring(_) | Prepared::Rod(_) => (s.axial_impulse.abs(), 0.0),
        Prepared::Rope(_) => (s.upper_impulse.abs(), 0.0),
        Prepared::Ball => (s.linear_impulse.length(), 0.0),
        Prepared::LimitedBall(_) => (
            s.linear_impulse.length(),
            real::hypot(
                s.angular_impulse.length(),
                real::hypot(s.axial_impulse, s.lower_impulse + s.upper_impulse),
            ),
        ),
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
        Prepared::SixDof(p) => {
            let d = p.drive_impulses();
            (
                (s.linear_impulse + Vec3::new(d[0], d[1], d[2])).length(),
                (s.angular_impulse + Vec3::new(d[3], d[4], d[5])).length(),
            )
        }
    }
}

/// The accumulated impulses of joint `j`'s direct rows, in row order (0 for a joint without direct rows).
#[inline]
pub(super) fn state_lambda(j: &PreparedJoint) -> [f32; MAX_ROWS] {
    let s = &j.state;
    match &j.kind {
        Prepared::Rope(_) => PreparedRope::direct_impulses(s),
        Prepared::Rod(_) => PreparedRod::direct_impulses(s),
        Prepared::Ball => ball::direct_impulses(s),
        Prepared::LimitedBall(p) => p.direct_impulses(s),
        Prepared::Hinge(p) => p.direct_impulses(s),
        Prepared::Fixed(_) => PreparedFixed::direct_impulses(s),
        _ => [0.0; MAX_ROWS],
    }
}
