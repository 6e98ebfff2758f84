//! The ball (spherical) joint: two anchor points held together, rotation free. Stages: *prepare*, *warm
//! start*, *solve* and *relax*.

use crate::pair::BodyPair;
use crate::part::{PointPart, block_target};
use crate::path::{JointRows, MAX_ROWS, Row, TargetRule};
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

/// The point rows' world axes and position errors `C`, the components of the anchors' separation `d` (m):
/// the one statement of the rows [`direct_rows`] builds and [`direct_errors`] measures. Each row's target is
/// the component of `block_target(d, …)` along its axis, as the Gauss–Seidel block builds it
/// ([`TargetRule::Block`]).
fn point_rows(d: Vec3) -> [(Vec3, f32); 3] {
    [(Vec3::X, d.x), (Vec3::Y, d.y), (Vec3::Z, d.z)]
}

/// The position errors `C` of [`direct_rows`]' rows and their target rules, in row order, without building
/// the rows: what the position projection measures a path's worst error from after every step it tries.
pub(crate) fn direct_errors(
    pair: &BodyPair,
    a: &SolverBody,
    b: &SolverBody,
) -> [(f32, TargetRule); 3] {
    point_rows(pair.anchors(a, b).d).map(|(_, c)| (c, TargetRule::Block))
}

/// The three point rows (world axes) for the direct solve of a chain ([`crate::path`]) at the current pose:
/// as [`solve`] builds its block.
pub(crate) fn direct_rows(
    pair: &BodyPair,
    a: &SolverBody,
    b: &SolverBody,
    stage: &Stage,
    out: &mut JointRows,
) {
    let anchors = pair.anchors(a, b);
    for (axis, c) in point_rows(anchors.d) {
        let rule = TargetRule::Block;
        let target = rule.target(c, stage);
        out.push(Row::linear(axis, anchors.r_a, anchors.r_b, target), c, rule);
    }
}
