//! What a link's rows were built from: the pose key that says whether a pass may keep them as they are
//! ([`PoseKey`]) and where, in world terms, they were built ([`BuiltAt`]), from which a later pass of the
//! step (or the next step) carries them. Read at every solve and relax pass and by the projection.

use rebound_dynamics::SolverBody;
use rebound_math::{Quat, Vec3};

/// The bits of what a link's rows are built from that changes within a step: both bodies' displacement and
/// rotation since the step began (`SolverBody::delta_position`, `delta_rotation`; the anchors, distance and
/// frames of [`crate::BodyPair`] read nothing else of the bodies). Equal keys mean the rows would be built
/// again bit for bit; any difference, even of a zero's sign, means they are built again.
#[derive(Debug, Clone, Copy, Eq)]
pub(crate) struct PoseKey([u32; 14]);

/// Word by word, inline: the derived comparison of the 56 bytes calls the C library's `memcmp`, and a path
/// compares a key per link and pass.
impl PartialEq for PoseKey {
    #[inline]
    fn eq(&self, other: &Self) -> bool {
        self.0.iter().zip(&other.0).all(|(a, b)| a == b)
    }
}

impl PoseKey {
    /// The key of bodies `a` and `b`'s current pose.
    #[inline]
    pub fn of(a: &SolverBody, b: &SolverBody) -> Self {
        let mut key = [0; 14];
        let fields = [
            a.delta_position.x,
            a.delta_position.y,
            a.delta_position.z,
            a.delta_rotation.x,
            a.delta_rotation.y,
            a.delta_rotation.z,
            a.delta_rotation.w,
            b.delta_position.x,
            b.delta_position.y,
            b.delta_position.z,
            b.delta_rotation.x,
            b.delta_rotation.y,
            b.delta_rotation.z,
            b.delta_rotation.w,
        ];
        for (key, field) in key.iter_mut().zip(fields) {
            *key = field.to_bits();
        }
        Self(key)
    }
}

/// How far (rad) either body of a hinge on a path may turn within a step before a velocity pass builds the
/// hinge's rows again instead of carrying them ([`Link::carry`]). The Jacobians of a hinge's rows depend on
/// the bodies' rotations alone, and a row turned by `θ` acts up to `θ` off its direction. At 0.01 rad a
/// bridge's joint gaps are those of building the rows at every pass; a few times more lets them grow
/// (`docs/physics.md`).
pub(crate) const CARRY_ANGLE: f32 = 0.01;

/// Where a link's rows were built, in world terms, and for which joint: what carries them to a later pose of
/// the same step or of a later one ([`Link::carry`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct BuiltAt {
    /// Both bodies' joint frames (world orientation) at the build.
    pub frames: (Quat, Quat),
    /// `c_b − c_a`, the vector between the bodies' centres of mass at the build (m, world).
    pub relative: Vec3,
    /// The joint (its index in the slice given to [`crate::JointSolver::prepare`]) and its bodies' solver
    /// indices: rows are kept into a step only for the same joint between the same bodies.
    pub owner: (usize, usize, usize),
}
