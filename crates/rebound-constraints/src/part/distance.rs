//! The distance row: the distance `|d|` between two anchors held to a length `L` by one [`AxisPart`] row
//! along `n = d/|d|` — a rod's (`|d| = L`), a rope's and a long-range tether's (`|d| ≤ L`).
//!
//! ```text
//! C = |d| − L                                          (m)
//! exactly:   C = 0, an equality row, λ free                              (rod)
//! at most:   C ≤ 0, an upper limit (speculative while slack), λ ≤ 0      (rope, tether)
//! ```
//!
//! The error, the target rule and the impulse bounds are stated here once: the Gauss–Seidel solve
//! ([`DistanceRow::solve`]) and the direct solve of a path ([`DistanceRow::push`]) read them.

use super::AxisPart;
use crate::pair::{BodyPair, Distance};
use crate::path::{JointRows, TargetRule};
use crate::stage::Stage;
use rebound_dynamics::SolverBody;
use rebound_math::Vec3;

/// How a distance row bounds the distance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Bound {
    /// `|d| = L` (a rod): an equality, pushing and pulling.
    Exactly,
    /// `|d| ≤ L` (a rope, a tether): an upper limit, pulling only.
    AtMost,
}

impl Bound {
    /// How the row's target follows from its error.
    #[inline(always)]
    fn rule(self) -> TargetRule {
        match self {
            Self::Exactly => TargetRule::Equality,
            Self::AtMost => TargetRule::UpperLimit,
        }
    }

    /// The bounds `[lower, upper]` of the row's impulse (N·s).
    #[inline(always)]
    fn impulse_range(self) -> (f32, f32) {
        match self {
            Self::Exactly => (f32::NEG_INFINITY, f32::INFINITY),
            Self::AtMost => (f32::NEG_INFINITY, 0.0),
        }
    }
}

/// A distance row measured at the bodies' current pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct DistanceRow {
    /// The current anchors, direction and distance.
    pub dist: Distance,
    /// `C = |d| − L` (m).
    error: f32,
    bound: Bound,
    /// Whether both anchors are the bodies' centres of mass ([`BodyPair::is_between_centres`]).
    between_centres: bool,
}

impl DistanceRow {
    /// The row holding the anchors of `pair` to `length` (m) as `bound` says, at the pose of `a`, `b`; the
    /// direction is `fallback_axis` when the anchors (nearly) coincide. Always inlined, as
    /// [`BodyPair::distance`].
    #[inline(always)]
    pub(crate) fn measure(
        pair: &BodyPair,
        bodies: (&SolverBody, &SolverBody),
        fallback_axis: Vec3,
        length: f32,
        bound: Bound,
    ) -> Self {
        let between_centres = pair.is_between_centres();
        Self::measure_known(
            pair,
            bodies,
            fallback_axis,
            length,
            (bound, between_centres),
        )
    }

    /// [`DistanceRow::measure`] of a pair whose [`BodyPair::is_between_centres`] is known (`between_centres`,
    /// kept from prepare by a rope or a rod).
    #[inline(always)]
    pub(crate) fn measure_known(
        pair: &BodyPair,
        (a, b): (&SolverBody, &SolverBody),
        fallback_axis: Vec3,
        length: f32,
        (bound, between_centres): (Bound, bool),
    ) -> Self {
        let dist = pair.distance_known(a, b, fallback_axis, between_centres);
        Self {
            error: dist.length - length,
            dist,
            bound,
            between_centres,
        }
    }

    /// The unit direction A → B (the next fallback direction).
    #[inline]
    pub(crate) fn axis(&self) -> Vec3 {
        self.dist.axis
    }

    /// One Gauss–Seidel iteration of the row in a pass of `stage`, accumulating into `accumulated` (N·s);
    /// returns the applied increment.
    #[inline]
    pub(crate) fn solve(
        &self,
        pair: &BodyPair,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
        accumulated: &mut f32,
    ) -> f32 {
        let target = self.bound.rule().target(self.error, stage);
        let (lower, upper) = self.bound.impulse_range();
        AxisPart::along(pair, &self.dist).solve(pair, a, b, target, accumulated, lower, upper)
    }

    /// The row for the direct solve of a path in a pass of `stage`, pushed into `out` with its error and
    /// rule ([`AxisPart::push_row`]). Inlined into the path pass, which builds a rope's row at every new pose.
    #[inline(always)]
    pub(crate) fn push(&self, stage: &Stage, out: &mut JointRows) {
        let rule = self.bound.rule();
        let target = rule.target(self.error, stage);
        AxisPart::push_row(
            self.between_centres,
            &self.dist,
            target,
            self.bound.impulse_range(),
            (self.error, rule),
            out,
        );
    }
}

/// A distance row as a joint keeps it through a step (a rope's, a rod's): its length, whether both anchors
/// are the centres of mass (known at prepare), and its last direction — the fallback when the anchors
/// coincide. The stages of both kinds' row are written here once; each kind names its [`Bound`] where it
/// calls them (a constant there, so the row's rule and impulse bounds are too).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct DistanceLink {
    /// `L` (m).
    length: f32,
    /// [`BodyPair::is_between_centres`] of the joint's pair, which every pass of the step asks.
    between_centres: bool,
    fallback_axis: Vec3,
}

impl DistanceLink {
    /// Stage *prepare*: the link holding the anchors of `pair` to `length` (m), and the distance at the pose
    /// of `a`, `b` (its direction the first fallback).
    #[inline]
    pub(crate) fn prepare(
        pair: &BodyPair,
        (a, b): (&SolverBody, &SolverBody),
        length: f32,
    ) -> (Self, Distance) {
        let between_centres = pair.is_between_centres();
        let dist = pair.distance_known(a, b, Vec3::X, between_centres);
        let link = Self {
            length,
            between_centres,
            fallback_axis: dist.axis,
        };
        (link, dist)
    }

    /// `L` (m).
    #[inline]
    pub(crate) fn length(&self) -> f32 {
        self.length
    }

    /// The current anchors, direction and distance ([`BodyPair::distance`]).
    #[inline(always)]
    pub(crate) fn distance(&self, pair: &BodyPair, a: &SolverBody, b: &SolverBody) -> Distance {
        pair.distance_known(a, b, self.fallback_axis, self.between_centres)
    }

    /// Stage *warm start*: `impulse` (N·s) along the current direction on both bodies.
    #[inline]
    pub(crate) fn warm_start(
        &self,
        pair: &BodyPair,
        a: &mut SolverBody,
        b: &mut SolverBody,
        impulse: f32,
    ) {
        let dist = self.distance(pair, a, b);
        AxisPart::along(pair, &dist).apply(pair, a, b, impulse);
    }

    /// The row bounding the distance as `bound` says at the current pose, its direction kept as the next
    /// fallback.
    #[inline(always)]
    pub(crate) fn measure(
        &mut self,
        pair: &BodyPair,
        bodies: (&SolverBody, &SolverBody),
        bound: Bound,
    ) -> DistanceRow {
        let row = DistanceRow::measure_known(
            pair,
            bodies,
            self.fallback_axis,
            self.length,
            (bound, self.between_centres),
        );
        self.fallback_axis = row.axis();
        row
    }

    /// Stages *solve* and *relax*: one Gauss–Seidel iteration of the row (`bound`), accumulating into
    /// `accumulated` (N·s).
    #[inline(always)]
    pub(crate) fn solve(
        &mut self,
        pair: &BodyPair,
        (a, b): (&mut SolverBody, &mut SolverBody),
        (stage, bound): (&Stage, Bound),
        accumulated: &mut f32,
    ) {
        let row = self.measure(pair, (&*a, &*b), bound);
        row.solve(pair, a, b, stage, accumulated);
    }

    /// The row (`bound`) for the direct solve of a path ([`crate::path`]) at the current pose, pushed into
    /// `out` with its position error for the passes that reuse it ([`DistanceRow::push`]).
    #[inline(always)]
    pub(crate) fn direct_row(
        &mut self,
        pair: &BodyPair,
        bodies: (&SolverBody, &SolverBody),
        (stage, bound): (&Stage, Bound),
        out: &mut JointRows,
    ) {
        self.measure(pair, bodies, bound).push(stage, out);
    }
}
