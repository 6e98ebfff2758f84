//! The fixed (weld) joint: the anchors held together and the joint frames kept in the same orientation, so the
//! two bodies move as one. Stages: *prepare*, *warm start*, *solve* and *relax*.

use crate::ball;
use crate::pair::BodyPair;
use crate::part::RotationPart;
use crate::stage::Stage;
use crate::state::JointState;
use rebound_dynamics::SolverBody;

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
/// last.
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
