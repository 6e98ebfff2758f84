//! The ball (spherical) joint: two anchor points held together, rotation free. Stages: *prepare*, *warm
//! start*, *solve* and *relax*.

use crate::pair::BodyPair;
use crate::part::{PointPart, block_target};
use crate::path::{JointRows, MAX_ROWS, TargetRule};
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::SolverBody;
use rebound_math::Vec3;

/// A ball joint. It has no parameters: the anchors of the [`crate::Joint`] are the
/// pivot.
///
/// ```text
/// C = d = p_b − p_a = 0                                 (m, 3 rows)
/// Ċ = v_b + ω_b × r_b − v_a − ω_a × r_a,   J = [ −1   [r_a]×   1   −[r_b]× ]
/// K = (1/m_a + 1/m_b)·1 − [r_a]×·I_a⁻¹·[r_a]× − [r_b]×·I_b⁻¹·[r_b]×,    M_eff = K⁻¹
/// ```
///
/// Softness: the joint softness of [`crate::JointSettings`] in the bias pass, none in the relax pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BallJoint;

impl BallJoint {
    /// A ball joint.
    #[must_use]
    pub const fn new() -> Self {
        Self
    }
}

pub(crate) fn warm_start(
    pair: &BodyPair,
    state: &JointState,
    a: &mut SolverBody,
    b: &mut SolverBody,
) {
    let anchors = pair.anchors(a, b);
    PointPart::apply_at(pair, anchors.r_a, anchors.r_b, a, b, state.linear_impulse);
}

pub(crate) fn solve(
    pair: &BodyPair,
    state: &mut JointState,
    a: &mut SolverBody,
    b: &mut SolverBody,
    stage: &Stage,
) {
    let anchors = pair.anchors(a, b);
    let part = PointPart::new(pair, anchors.r_a, anchors.r_b);
    let target = block_target(anchors.d, stage.bias, stage.joint_softness);
    part.solve(pair, a, b, target, &mut state.linear_impulse);
}

/// The accumulated impulses of [`direct_rows`]' rows, in row order (the point block's, along x, y, z).
#[inline]
pub(crate) fn direct_impulses(state: &JointState) -> [f32; MAX_ROWS] {
    let l = state.linear_impulse;
    [l.x, l.y, l.z, 0.0, 0.0]
}

/// Writes the impulses a direct solve gave [`direct_rows`]' rows back into `state`.
#[inline]
pub(crate) fn store_direct_impulses(state: &mut JointState, lambda: [f32; MAX_ROWS]) {
    state.linear_impulse = Vec3::new(lambda[0], lambda[1], lambda[2]);
}

/// The position errors `C` of [`direct_rows`]' rows and their target rules, in row order, without building
/// the rows: what the position projection measures a path's worst error from after every step it tries.
pub(crate) fn direct_errors(
    pair: &BodyPair,
    a: &SolverBody,
    b: &SolverBody,
) -> [(f32, TargetRule); 3] {
    PointPart::errors(pair.anchors(a, b).d)
}

/// The three point rows (world axes) for the direct solve of a chain ([`crate::path`]) at the current pose:
/// [`PointPart::push_rows`] at the anchors [`solve`] builds its block at.
pub(crate) fn direct_rows(
    pair: &BodyPair,
    a: &SolverBody,
    b: &SolverBody,
    stage: &Stage,
    out: &mut JointRows,
) {
    let anchors = pair.anchors(a, b);
    PointPart::push_rows(anchors.r_a, anchors.r_b, anchors.d, stage, out);
}
