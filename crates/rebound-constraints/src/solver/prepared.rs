//! A joint prepared for the substeps ([`PreparedJoint`]: its bodies, impulses and kind-specific prepared
//! data, [`Prepared`]), and what the stages need to know of each kind in one place: which kinds a path
//! solves directly, the impulses their direct rows carry, the reaction a joint reports at *store impulses*.

use crate::coordinate::CoordinateRows;
use crate::fixed::PreparedFixed;
use crate::hinge::PreparedHinge;
use crate::pair::BodyPair;
use crate::path::MAX_ROWS;
use crate::prismatic::PreparedPrismatic;
use crate::rod::PreparedRod;
use crate::rope::PreparedRope;
use crate::spring::PreparedSpring;
use crate::state::JointState;
use crate::wheel::PreparedWheel;

/// A joint kind prepared for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum Prepared {
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
    /// Whether the joint's equality rows can join a directly solved path ([`crate::path`]).
    pub(super) fn is_direct_capable(&self) -> bool {
        matches!(
            self,
            Self::Rope(_) | Self::Rod(_) | Self::Ball | Self::Hinge(_)
        )
    }

    /// Whether all of the joint's rows are in the direct solve when it is on a path: a rope's, a rod's, a
    /// ball joint's, a hinge's without limit, motor or spring.
    pub(super) fn is_solved_directly_whole(&self) -> bool {
        match self {
            Self::Rope(_) | Self::Rod(_) | Self::Ball => true,
            Self::Hinge(hinge) => hinge.has_no_coordinate_rows(),
            _ => false,
        }
    }

    /// The distance a joint allows between its anchors (m), for tethers: a rope's or rod's length, 0 for the
    /// point joints; `None` for joints that do not bound it.
    pub(super) fn bounded_length(&self) -> Option<f32> {
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
pub(super) struct PreparedJoint {
    pub(super) source: usize,
    pub(super) pair: BodyPair,
    pub(super) state: JointState,
    pub(super) break_force: f32,
    pub(super) break_torque: f32,
    pub(super) kind: Prepared,
    /// The path solved directly ([`crate::path`]) that the joint's equality rows belong to, as an index
    /// into the solver's `paths`; `None` for a joint solved by Gauss–Seidel alone.
    pub(super) path: Option<usize>,
    /// The joint's link in the solver's `links` (its index in `path_joints`) when it is on a path.
    pub(super) link: Option<usize>,
}

/// The one impulse field a distance-type or ball joint uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Keep {
    Axial,
    Upper,
    Linear,
}

/// Zeroes every impulse field but `keep` (so a joint whose kind changed is not warm-started with another
/// kind's impulses).
pub(super) fn keep_only(state: &mut JointState, keep: Keep) {
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
pub(super) fn reaction_impulses(kind: &Prepared, s: &JointState) -> (f32, f32) {
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

/// The accumulated impulses of joint `j`'s direct rows, in row order (0 for a joint without direct rows).
pub(super) fn state_lambda(j: &PreparedJoint) -> [f32; MAX_ROWS] {
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
