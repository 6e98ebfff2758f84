//! An angular row about a pivot (a ball joint's limits): the relative rotation about a unit axis, its impulse
//! applied together with the point impulse that keeps the anchors' relative velocity unchanged, so that the
//! row acts on the bodies turning about the pivot rather than about their centres of mass, and a later
//! solve of the point rows (Gauss–Seidel or a path's direct solve) does not take it back.
//!
//! For the angular impulse `λ` about `n` (`+` on B, `−` on A) the anchors' relative velocity changes by
//!
//! ```text
//! u·λ,   u = (I_b⁻¹·n) × r_b + (I_a⁻¹·n) × r_a
//! ```
//!
//! and the point impulse `P = −K_p⁻¹·u·λ` (`K_p` the point block's) cancels it. The row's effective mass is
//! that of the angular direction on the manifold where the point rows hold (a Schur complement):
//!
//! ```text
//! Ċ = n·(ω_b − ω_a),   K = n·(I_a⁻¹ + I_b⁻¹)·n − u·K_p⁻¹·u
//! ```
//!
//! For a rod of length `L` hung at its end, `K = 1/I_pivot` instead of `1/I_centre`: stopping it at a limit
//! stops it, where the plain angular row left 3/4 of the rotation for the point rows to turn back.

use super::{AnglePart, PointPart, Row, RowTarget, inverse_or_zero};
use crate::pair::BodyPair;
use crate::path::{Row as DirectRow, Side};
use rebound_dynamics::SolverBody;
use rebound_math::Vec3;

/// An angular row coupled to a pivot (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PivotAnglePart {
    angle: AnglePart,
    /// The point impulse per unit of the row's impulse (N·s per N·m·s).
    point_impulse: Vec3,
    r_a: Vec3,
    r_b: Vec3,
    effective_mass: f32,
}

impl PivotAnglePart {
    /// The row about the unit world `axis` at the pivot of `point`.
    #[inline]
    #[must_use]
    pub fn new(pair: &BodyPair, point: &PointPart, axis: Vec3) -> Self {
        let (r_a, r_b) = point.levers();
        let (w_a, w_b) = (pair.inv_inertia_a * axis, pair.inv_inertia_b * axis);
        let u = w_b.cross(r_b) + w_a.cross(r_a);
        let point_impulse = -(point.effective_mass() * u);
        let k = axis.dot(w_a + w_b) + u.dot(point_impulse);
        Self {
            angle: AnglePart::new(pair, axis),
            point_impulse,
            r_a,
            r_b,
            effective_mass: inverse_or_zero(k.max(0.0)),
        }
    }
}

impl PivotAnglePart {
    /// The point impulse (N·s, world, `+` at B's anchor) the row applies per unit of its impulse.
    #[inline]
    #[must_use]
    pub fn point_impulse(&self) -> Vec3 {
        self.point_impulse
    }

    /// The row about the unit world `axis` (the one given to [`PivotAnglePart::new`]) for the direct solve
    /// of a joint's rows together with its point rows ([`crate::path`]): `J = J_angle + Pᵀ·J_point`, the
    /// angle row with the point rows weighted by the point impulse `P` per unit impulse,
    ///
    /// ```text
    /// J = [ −Pᵀ   −(n + r_a × P)ᵀ   Pᵀ   (n + r_b × P)ᵀ ]
    /// ```
    ///
    /// so that its impulse `Jᵀ·λ` is the one [`Row::apply_impulse`] applies, and an accumulated impulse
    /// means the same to a warm start whichever solve made it. Where the point rows hold (`Ċ_point = 0`) it
    /// measures `Ċ = n·(ω_b − ω_a)`; its `K` entry is the row's effective mass's inverse and its coupling
    /// with the point rows is `u + K_p·P = 0`.
    #[inline]
    pub(crate) fn direct_row(&self, axis: Vec3, target: RowTarget) -> DirectRow {
        let p = self.point_impulse;
        let sides = [
            Side {
                linear: -p,
                angular: -(axis + self.r_a.cross(p)),
            },
            Side {
                linear: p,
                angular: axis + self.r_b.cross(p),
            },
        ];
        DirectRow::new(sides, target)
    }
}

impl Row for PivotAnglePart {
    #[inline]
    fn effective_mass(&self) -> f32 {
        self.effective_mass
    }
    #[inline]
    fn velocity(&self, a: &SolverBody, b: &SolverBody) -> f32 {
        self.angle.velocity(a, b)
    }
    #[inline]
    fn apply_impulse(&self, pair: &BodyPair, a: &mut SolverBody, b: &mut SolverBody, impulse: f32) {
        if impulse == 0.0 {
            return;
        }
        self.angle.apply(a, b, impulse);
        PointPart::apply_at(pair, self.r_a, self.r_b, a, b, self.point_impulse * impulse);
    }
}
