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
