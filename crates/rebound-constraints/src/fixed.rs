//! The fixed (weld) joint: the anchors held together and the joint frames kept in the same orientation, so the
//! two bodies move as one. Stages: *prepare*, *warm start*, *solve* and *relax*.

use crate::ball;
use crate::pair::BodyPair;
use crate::part::{AnglePart, RotationPart, rotation_error};
use crate::path::{JointRows, MAX_ROWS, TargetRule};
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::SolverBody;
use rebound_math::{Quat, Vec3};

/// A fixed joint. It has no parameters of its own.
///
/// ```text
/// point:    C = d = 0 (3 rows)                          see crate::part::PointPart
/// rotation: C = 2·sign(w)·xyz of F_b·F_a⁻¹ = 0 (3 rows)   Ċ = ω_b − ω_a,  K = I_a⁻¹ + I_b⁻¹   (crate::part::RotationPart)
/// ```
///
/// The relative pose to keep is given by the anchors and the joint frames ([`crate::Joint::local_basis_a`],
/// [`crate::Joint::local_basis_b`]): [`crate::Joint::from_world`] with the bodies' current poses welds them
/// where they are. Softness: the joint softness in the bias pass, none in the relax pass. Rotation first, point
/// last. On a directly solved path or graph (see [`crate::JointSettings::direct_chains`]) its six rows are
/// solved there together.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct FixedJoint;

impl FixedJoint {
    /// A fixed joint.
    #[must_use]
    pub const fn new() -> Self {
        Self
    }

    pub(crate) fn prepare(pair: &BodyPair, state: &mut JointState) -> PreparedFixed {
        state.axial_impulse = 0.0;
        state.motor_impulse = 0.0;
        state.lower_impulse = 0.0;
        state.upper_impulse = 0.0;
        PreparedFixed {
            rotation: RotationPart::new(pair),
        }
    }
}

/// A fixed joint ready for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedFixed {
    rotation: RotationPart,
}

impl PreparedFixed {
    pub(crate) fn warm_start(
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        RotationPart::apply(pair, a, b, state.angular_impulse);
        ball::warm_start(pair, state, a, b);
    }

    pub(crate) fn solve(
        &self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        let frames = pair.frames(a, b);
        self.rotation
            .solve_frames(pair, frames, a, b, stage, &mut state.angular_impulse);
        ball::solve(pair, state, a, b, stage);
    }
}

impl PreparedFixed {
    /// The three point rows and the three rotation rows (about the world axes, `J = [0 −êₖ 0 êₖ]`, `C` the
    /// rotation error's component `k`: [`RotationPart`]'s block as rows) for the direct solve of a path or
    /// graph ([`crate::path`]) at the current pose.
    pub(crate) fn direct_rows(
        pair: &BodyPair,
        a: &SolverBody,
        b: &SolverBody,
        stage: &Stage,
        out: &mut JointRows,
    ) {
        ball::direct_rows(pair, a, b, stage, out);
        for (axis, (c, rule)) in [Vec3::X, Vec3::Y, Vec3::Z]
            .into_iter()
            .zip(rotation_errors(pair.frames(a, b)))
        {
            out.push(AnglePart::row(axis, rule.target(c, stage)), c, rule);
        }
    }

    /// The accumulated impulses of [`PreparedFixed::direct_rows`]' rows, in row order: the point block's,
    /// then the rotation block's (N·m·s, world axes).
    #[inline]
    pub(crate) fn direct_impulses(state: &JointState) -> [f32; MAX_ROWS] {
        let (l, w) = (state.linear_impulse, state.angular_impulse);
        [l.x, l.y, l.z, w.x, w.y, w.z]
    }

    /// Writes the impulses a direct solve gave [`PreparedFixed::direct_rows`]' rows back into `state`.
    #[inline]
    pub(crate) fn store_direct_impulses(state: &mut JointState, lambda: [f32; MAX_ROWS]) {
        ball::store_direct_impulses(state, lambda);
        state.angular_impulse = Vec3::new(lambda[3], lambda[4], lambda[5]);
    }

    /// The position errors `C` of [`PreparedFixed::direct_rows`]' rows and their target rules, in row order,
    /// without building the rows (what the position projection measures a path's worst error from).
    pub(crate) fn direct_errors(
        pair: &BodyPair,
        a: &SolverBody,
        b: &SolverBody,
    ) -> [(f32, TargetRule); MAX_ROWS] {
        let [x, y, z] = ball::direct_errors(pair, a, b);
        let [p, q, r] = rotation_errors(pair.frames(a, b));
        [x, y, z, p, q, r]
    }
}

/// The rotation rows' errors (rad, world axes: the components of [`rotation_error`] between the joint frames
/// `(F_a, F_b)`) and their target rule, an equality.
#[inline]
fn rotation_errors((frame_a, frame_b): (Quat, Quat)) -> [(f32, TargetRule); 3] {
    rotation_error(frame_a, frame_b)
        .to_array()
        .map(|c| (c, TargetRule::Equality))
}
