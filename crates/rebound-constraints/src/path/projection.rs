//! The position projection's part of the path solver (stage *project positions*, once after the
//! substeps): links turned into `K·x = C` systems ([`Link::make_positional`]), pulled ropes stiffened against
//! turning ([`Link::stiffen`]), and the one-joint Gauss–Seidel projection ([`project_rows`]) that follows
//! the direct one.

use super::link::{Link, Mode};
use super::row::{JointRows, MAX_ROWS, Real, TargetRule, row_violation};
use crate::part::{AxisPart, RowTarget};
use rebound_dynamics::SolverBody;

impl Link {
    /// Turns a link whose rows' biases are their position errors into a link of the position projection, in
    /// place (the rows stay reusable: [`Link::reuse`] recomputes the targets and starts a velocity pass).
    /// Equality rows take part; a rope only if it is stretched or within `taut` (m) of its length (`C >
    /// −taut`). A slack rope gets the target "no longer than now"; one further from its length joins through
    /// the active-set rounds ([`activate_violations`]) if moving its neighbours would lengthen it: it may then
    /// pull, but the linear step never spends its slack (which a curved chain's linearisation would
    /// overshoot). Ropes at their length join at once because the rounds add only the ropes next to those in
    /// the system: along a straight run of ropes at their length (a falling chain) they crept a few links per
    /// round, and the step stretched the first rope left out by as much as it closed elsewhere.
    pub fn make_positional(&mut self, taut: f32) {
        let mut active = [false; MAX_ROWS];
        for (row, active) in self
            .rows
            .rows
            .iter_mut()
            .zip(&mut active)
            .take(self.rows.count)
        {
            let c = row.target.bias;
            *active = if row.upper == 0.0 {
                c > -taut
            } else if row.lower == 0.0 {
                c < taut
            } else {
                true
            };
            if (row.upper == 0.0 && c < 0.0) || (row.lower == 0.0 && c > 0.0) {
                row.target.bias = 0.0;
            }
        }
        self.lambda = [0.0; MAX_ROWS];
        self.mode = Mode::Position;
        self.active = active;
        self.compliance = [0.0; MAX_ROWS];
    }

    /// Stiffens a projection link of one pulled rope or rod row against turning, with `stiffness` (kg): two
    /// linear rows across its axis, between the bodies' centres, with target 0 and compliance `1/stiffness`.
    /// Solved with them, the projection minimises `½·ΔᵀMΔ + ½·stiffness·|Δ⊥|²` (`Δ⊥` the bodies' relative
    /// displacement across the link) instead of `½·ΔᵀMΔ`, subject to the linearised rows: with `stiffness =
    /// |p|/L` (`p` the link's position impulse, `L` its length) that is the Newton step of the projection
    /// with the Hessian of the link's length, `(I − u·uᵀ)/L`, weighted by its multiplier (the geometric
    /// stiffness), which the plain step leaves out. Returns whether the rows were added (a link of one row
    /// and a positive, finite stiffness only). The rows and factorisation are dropped for the next pass.
    pub fn stiffen(&mut self, stiffness: f32) -> bool {
        if self.mode != Mode::Position
            || self.rows.count != 1
            || !(stiffness > 0.0 && stiffness.is_finite())
        {
            return false;
        }
        let row = self.rows.rows[0];
        let (across, other) = row.b.linear.any_orthonormal_pair();
        let target = RowTarget {
            bias: 0.0,
            softness: row.target.softness,
        };
        for axis in [across, other] {
            self.rows.push(
                AxisPart::row_between_centres(axis, target),
                0.0,
                TargetRule::Equality,
            );
        }
        for k in 1..self.rows.count {
            self.active[k] = true;
            self.lambda[k] = 0.0;
            self.compliance[k] = 1.0 / Real::from(stiffness);
        }
        self.forget();
        true
    }
}

/// One nonlinear Gauss–Seidel projection of one joint's rows (Box2D v2's position solver): each row whose
/// position error `C` (its bias) is violated moves the two bodies by `−M⁻¹·Jᵀ·C/K` — exactly onto the row to
/// first order, never past it, so repeated sweeps cannot diverge. Used after the direct projection to take
/// back what its linearisation missed.
pub(crate) fn project_rows(rows: &JointRows, a: &mut SolverBody, b: &mut SolverBody) {
    for (k, row) in rows.rows().iter().enumerate() {
        let c = row.target.bias;
        let violated = row_violation(c, row.lower, row.upper) > 0.0;
        let mass = rows.self_coupling(k);
        if !violated || mass <= 0.0 {
            continue;
        }
        rows.displace(k, a, b, -c / mass);
    }
}
