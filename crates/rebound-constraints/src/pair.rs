//! The two bodies of a prepared joint as the solver sees them (stage *prepare* builds it, every later stage
//! reads it): indices into the solver arrays, inverse masses and world inverse inertias at the start of the
//! step, and the joint's anchors and frames at the start of the step.
//!
//! Why start-of-step values plus deltas: a constraint measures its current error from the solver bodies'
//! displacement since the step began (`Δp`, `Δq`), as the contact kernel does (Box2D v3's `deltaCenter`), so
//! large world coordinates never enter the error:
//!
//! ```text
//! r_a = Δq_a·r_a⁰                       current anchor of A, relative to A's centre of mass (m)
//! d   = (c_b⁰ − c_a⁰) + Δp_b − Δp_a + r_b − r_a      current separation of the anchors, A → B (m)
//! F_a = Δq_a·F_a⁰                       current joint frame of A (world orientation)
//! ```

use rebound_dynamics::{BodyParams, SolverBody};
use rebound_math::{Mat3, Quat, Vec3, rotate};

/// Below this separation (m) a distance direction is taken from the last valid one instead of `d/|d|`.
pub const MIN_AXIS_LENGTH: f32 = 1e-6;

/// The prepared pair of bodies of one joint: 176 bytes, read by every part in every iteration. The default
/// is a pair of body 0 with itself, all zero, identity frames: a placeholder, never solved.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BodyPair {
    /// Index of body A in the solver arrays.
    pub index_a: usize,
    /// Index of body B in the solver arrays.
    pub index_b: usize,
    /// Inverse mass of A (1/kg); 0 for a fixed or kinematic body.
    pub inv_mass_a: f32,
    /// Inverse mass of B (1/kg).
    pub inv_mass_b: f32,
    /// World inverse inertia of A at the start of the step (1/(kg·m²)).
    pub inv_inertia_a: Mat3,
    /// World inverse inertia of B at the start of the step (1/(kg·m²)).
    pub inv_inertia_b: Mat3,
    /// Anchor on A relative to A's centre of mass, world axes, at the start of the step (m).
    pub anchor_a: Vec3,
    /// Anchor on B relative to B's centre of mass, world axes, at the start of the step (m).
    pub anchor_b: Vec3,
    /// World orientation of A's joint frame at the start of the step.
    pub basis_a: Quat,
    /// World orientation of B's joint frame at the start of the step.
    pub basis_b: Quat,
    /// `c_b⁰ − c_a⁰`: centre of mass of B minus that of A at the start of the step (m).
    pub delta_center: Vec3,
}

/// The current anchors and their separation, computed from the solver bodies' deltas.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Anchors {
    /// Current anchor on A, relative to A's centre of mass, world axes (m).
    pub r_a: Vec3,
    /// Current anchor on B, relative to B's centre of mass, world axes (m).
    pub r_b: Vec3,
    /// Current separation `p_b − p_a` of the anchor points (m).
    pub d: Vec3,
}

/// A distance between the anchors: the current anchors, the unit direction A → B and the length.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Distance {
    /// The current anchors.
    pub anchors: Anchors,
    /// Unit direction from anchor A to anchor B; the fallback when the anchors (nearly) coincide.
    pub axis: Vec3,
    /// `|d|` (m).
    pub length: f32,
}

impl BodyPair {
    /// The pair for bodies `index_a`, `index_b` with their step constants, a joint anchored at `local_anchor_*`
    /// (body frame, relative to the body origin, m) with frames `local_basis_*` (body frame).
    #[must_use]
    pub fn new(
        index_a: usize,
        index_b: usize,
        params_a: &BodyParams,
        params_b: &BodyParams,
        local_anchors: (Vec3, Vec3),
        local_bases: (Quat, Quat),
    ) -> Self {
        let mut pair = Self::default();
        let params = (params_a, params_b);
        pair.reset(index_a, index_b, params, local_anchors, local_bases);
        pair
    }

    /// [`BodyPair::new`] written over `self`: the joint solver's prepare writes each pair into its slot in
    /// place (a returned pair would be copied in).
    pub(crate) fn reset(
        &mut self,
        index_a: usize,
        index_b: usize,
        (params_a, params_b): (&BodyParams, &BodyParams),
        local_anchors: (Vec3, Vec3),
        local_bases: (Quat, Quat),
    ) {
        let anchor =
            |p: &BodyParams, local: Vec3| rotate(p.rotation, local - p.local_center_of_mass);
        *self = Self {
            index_a,
            index_b,
            inv_mass_a: params_a.inv_mass,
            inv_mass_b: params_b.inv_mass,
            inv_inertia_a: params_a.inv_inertia_world,
            inv_inertia_b: params_b.inv_inertia_world,
            anchor_a: anchor(params_a, local_anchors.0),
            anchor_b: anchor(params_b, local_anchors.1),
            basis_a: (params_a.rotation * local_bases.0).normalize(),
            basis_b: (params_b.rotation * local_bases.1).normalize(),
            delta_center: params_b.center_of_mass - params_a.center_of_mass,
        };
    }

    /// Copies the two solver bodies out, or `None` when an index is out of range.
    #[inline]
    #[must_use]
    pub fn load(&self, bodies: &[SolverBody]) -> Option<(SolverBody, SolverBody)> {
        Some((*bodies.get(self.index_a)?, *bodies.get(self.index_b)?))
    }

    /// The two solver bodies in place, or `None` when an index is out of range.
    #[inline]
    #[must_use]
    pub fn bodies<'a>(&self, bodies: &'a [SolverBody]) -> Option<(&'a SolverBody, &'a SolverBody)> {
        Some((bodies.get(self.index_a)?, bodies.get(self.index_b)?))
    }

    /// The two solver bodies in place for changing, or `None` when an index is out of range or both are the
    /// same body. A pass that changes only velocities reads and writes them where they are instead of copying
    /// both bodies out and back ([`BodyPair::load`], [`BodyPair::store`]): the same operations on the same
    /// values.
    #[inline]
    #[must_use]
    pub fn bodies_mut<'a>(&self, bodies: &'a mut [SolverBody]) -> Option<[&'a mut SolverBody; 2]> {
        bodies.get_disjoint_mut([self.index_a, self.index_b]).ok()
    }

    /// Writes the two solver bodies back (indices checked as in [`BodyPair::load`]).
    #[inline]
    pub fn store(&self, bodies: &mut [SolverBody], a: SolverBody, b: SolverBody) {
        if let Some(slot) = bodies.get_mut(self.index_a) {
            *slot = a;
        }
        if let Some(slot) = bodies.get_mut(self.index_b) {
            *slot = b;
        }
    }

    /// The current anchors and their separation.
    #[inline]
    #[must_use]
    pub fn anchors(&self, a: &SolverBody, b: &SolverBody) -> Anchors {
        let r_a = rotate(a.delta_rotation, self.anchor_a);
        let r_b = rotate(b.delta_rotation, self.anchor_b);
        let d = self.delta_center + (b.delta_position - a.delta_position) + (r_b - r_a);
        Anchors { r_a, r_b, d }
    }

    /// The current anchors, the unit direction A → B and the distance. When the anchors are closer than
    /// [`MIN_AXIS_LENGTH`] the direction is `fallback_axis` (no NaN for coinciding anchors). Always inlined:
    /// ropes and rods measure it for every rebuilt row, and a call returns the 40-byte result through memory.
    #[inline(always)]
    #[must_use]
    pub fn distance(&self, a: &SolverBody, b: &SolverBody, fallback_axis: Vec3) -> Distance {
        self.distance_known(a, b, fallback_axis, self.is_between_centres())
    }

    /// [`BodyPair::distance`] of a pair whose [`BodyPair::is_between_centres`] is known (`between_centres`,
    /// kept from prepare by a joint that measures its distance in every pass).
    #[inline(always)]
    #[must_use]
    pub(crate) fn distance_known(
        &self,
        a: &SolverBody,
        b: &SolverBody,
        fallback_axis: Vec3,
        between_centres: bool,
    ) -> Distance {
        let anchors = if between_centres {
            // No lever arm to turn, and `r_b − r_a` would add zeros.
            Anchors {
                r_a: Vec3::ZERO,
                r_b: Vec3::ZERO,
                d: self.delta_center + (b.delta_position - a.delta_position),
            }
        } else {
            self.anchors(a, b)
        };
        let length = anchors.d.length();
        let axis = if length > MIN_AXIS_LENGTH {
            anchors.d / length
        } else {
            fallback_axis
        };
        Distance {
            anchors,
            axis,
            length,
        }
    }

    /// Whether both anchors are the bodies' centres of mass (a rope between the centres of two balls): the
    /// anchors then never turn and a distance row has no angular parts.
    #[inline]
    #[must_use]
    pub fn is_between_centres(&self) -> bool {
        self.anchor_a == Vec3::ZERO && self.anchor_b == Vec3::ZERO
    }

    /// The current world orientations of the joint frames of A and B.
    #[inline]
    #[must_use]
    pub fn frames(&self, a: &SolverBody, b: &SolverBody) -> (Quat, Quat) {
        (
            a.delta_rotation * self.basis_a,
            b.delta_rotation * self.basis_b,
        )
    }
}

/// The joint's bodies that the solver moves (dynamic: a non-zero inverse mass or inertia); `None` for a
/// fixed or kinematic side, which couples nothing.
pub(crate) fn dynamic_bodies(pair: &BodyPair) -> [Option<usize>; 2] {
    let moves = |inv_mass: f32, inv_inertia: &Mat3| inv_mass > 0.0 || *inv_inertia != Mat3::ZERO;
    [
        moves(pair.inv_mass_a, &pair.inv_inertia_a).then_some(pair.index_a),
        moves(pair.inv_mass_b, &pair.inv_inertia_b).then_some(pair.index_b),
    ]
}
