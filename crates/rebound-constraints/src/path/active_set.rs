//! The active set of a path solve (every solve and relax pass and the projection): which rows bounded at 0
//! (ropes, limits) take part in the system ([`Link::activate`]), and the rounds after a solve that release
//! rows that would push and add rows left out that would be violated ([`activate_violations`]).

use super::link::{Link, Mode};
use super::row::{MAX_ROWS, Real, Row};
use crate::part::clamp_impulse;
use rebound_dynamics::SolverBody;

impl Link {
    /// Step 1 of a pass: decides which rows take part and releases the others' impulses. A row bounded at 0
    /// on one side (a rope, a limit) takes part if, without its own impulse, the bodies would violate it this
    /// substep (`Ċ + bias` on the wrong side); equality rows always take part.
    pub fn activate(&mut self, a: &mut SolverBody, b: &mut SolverBody) {
        // A one-row link bounded at 0 (a rope, a rod's limit): the loop below for its one row, with the
        // coupling stored when it was pushed.
        if self.rows.count == 1
            && let Some(coupling) = self.rows.bounded_couplings[0]
        {
            let row = &self.rows.rows[0];
            let lambda = self.lambda[0];
            let own = coupling * lambda;
            let free = row.velocity(a, b) - own + row.target.bias;
            let active = if row.upper == 0.0 {
                free > 0.0
            } else {
                free < 0.0
            };
            self.active[0] = active;
            if !active {
                self.rows.apply_first(a, b, -lambda);
                self.lambda[0] = 0.0;
            }
            return;
        }
        // Equality rows only (a hinge's, a ball joint's): all take part, whatever the velocities.
        if !self.rows.may_release {
            for (k, active) in self.active.iter_mut().enumerate() {
                *active = k < self.rows.count;
            }
            return;
        }
        let rows = &self.rows;
        for (i, ((row, lambda), active)) in rows
            .rows()
            .iter()
            .zip(&mut self.lambda)
            .zip(&mut self.active)
            .enumerate()
        {
            let (upper, lower) = (row.upper == 0.0, row.lower == 0.0);
            // An equality row takes part whatever its state: no need for its free velocity.
            if !upper && !lower {
                *active = true;
                continue;
            }
            let own = rows.self_coupling(i) * *lambda;
            let free = row.velocity(a, b) - own + row.target.bias;
            *active = if upper { free > 0.0 } else { free < 0.0 };
            if !*active {
                rows.apply(i, a, b, -*lambda);
                *lambda = 0.0;
            }
        }
    }

    /// Active-set step: deactivates (and releases) every active row whose update from `x` would cross a bound
    /// of 0 — a rope that would push; returns whether any did, so that the system is solved again without
    /// them.
    pub fn deactivate_violations(
        &mut self,
        x: &[Real; MAX_ROWS],
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) -> bool {
        let rows = &self.rows;
        let mut any = false;
        for (i, (((row, &x), lambda), active)) in rows
            .rows()
            .iter()
            .zip(x)
            .zip(&mut self.lambda)
            .zip(&mut self.active)
            .enumerate()
        {
            if *active && crosses_zero(row, *lambda, x) {
                *active = false;
                rows.apply(i, a, b, -*lambda);
                *lambda = 0.0;
                any = true;
            }
        }
        any
    }

    /// Whether [`Link::deactivate_violations`] would deactivate a row for the solution `x` (checked without
    /// the bodies, which only a row released needs).
    pub fn would_deactivate(&self, x: &[Real; MAX_ROWS]) -> bool {
        self.rows.may_release
            && self
                .rows
                .rows()
                .iter()
                .zip(x)
                .zip(&self.lambda)
                .zip(&self.active)
                .any(|(((row, &x), &lambda), &active)| active && crosses_zero(row, lambda, x))
    }

    /// What active row `k` would get from its solution `x`: the clamped soft update of its impulse, as an
    /// increment (velocity pass) or as the position impulse itself (projection, where `lambda` is 0).
    pub(super) fn increment(&self, k: usize, x: Real) -> f32 {
        let row = &self.rows.rows[k];
        let new = clamp_impulse(self.lambda[k] - x as f32, row.lower, row.upper);
        new - self.lambda[k]
    }

    /// The change of row `row`'s `Ċ` (or `C`) that the increments of this link's active rows, solved as `x`,
    /// make: through both bodies (`shared` = `None`, `row` is one of this link's rows), or through the one
    /// body `row`'s link shares with this link, given as (`row` acts on it as its body B, this link does).
    pub(super) fn effect_on(
        &self,
        row: &Row,
        shared: Option<(bool, bool)>,
        x: &[Real; MAX_ROWS],
    ) -> f32 {
        let mut change = 0.0;
        for ((k, other), _) in self
            .rows
            .rows()
            .iter()
            .enumerate()
            .zip(&self.active)
            .filter(|(_, active)| **active)
        {
            let [ta, tb] = self.rows.turned(k);
            let coupling = match shared {
                None => {
                    row.a.coupling_turned(&self.rows.mass_a, &other.a, ta)
                        + row.b.coupling_turned(&self.rows.mass_b, &other.b, tb)
                }
                Some((row_b, own_b)) => {
                    let side = if row_b { &row.b } else { &row.a };
                    let (other, mass, turned) = if own_b {
                        (&other.b, &self.rows.mass_b, tb)
                    } else {
                        (&other.a, &self.rows.mass_a, ta)
                    };
                    side.coupling_turned(mass, other, turned)
                }
            };
            change += coupling * self.increment(k, x[k]);
        }
        change
    }
}

/// Whether the update `λ − x` of a row bounded at 0 (a rope, a limit) would cross that bound — a rope that
/// would push; never for a row without a bound at 0.
#[inline]
pub(super) fn crosses_zero(row: &Row, lambda: f32, x: Real) -> bool {
    let new = lambda - x as f32;
    (row.upper == 0.0 && new > 0.0) || (row.lower == 0.0 && new < 0.0)
}

/// Active-set step for the rows left out: activates every one-sided row (a rope) that is not in the system
/// but that the solution `solution` of the rows around it would violate — a slack rope whose neighbours would
/// pull its bodies apart past its length, or a taut rope that was closing before the solve and would no
/// longer be. Returns the first link that had a row activated (`None`: none), so that the system is solved
/// again with them — from the link before it on ([`Resume`]). Without this step a rope left out at the start
/// of a pass is pulled past its length by the solve of its neighbours (a chain whipping round would stretch
/// its links by a large fraction within a substep).
pub(crate) fn activate_violations<'b>(
    links: &mut [Link],
    solution: &[[Real; MAX_ROWS]],
    load: impl Fn(usize) -> Option<(&'b SolverBody, &'b SolverBody)>,
) -> Option<usize> {
    let mut first = None;
    for i in 0..links.len() {
        // Most links of a rope chain are a one-row link in the system (a taut rope): nothing left out.
        let link = &links[i];
        if link.rows.count == 1 && link.active[0] {
            continue;
        }
        let left_out = link.left_out();
        if !left_out.contains(&true) {
            continue;
        }
        for r in (0..MAX_ROWS).filter(|&r| left_out[r]) {
            let link = &links[i];
            let row = &link.rows.rows[r];
            // A row just added has no solution yet (0), so it changes nothing for the rows after it.
            let mut free = row.target.bias + link.effect_on(row, None, &solution[i]);
            if let Some(prev) = i.checked_sub(1).and_then(|p| links.get(p))
                && let Some((prev_b, this_b)) = prev.shared_with_next
            {
                free += prev.effect_on(row, Some((this_b, prev_b)), &solution[i - 1]);
            }
            if let (Some((this_b, next_b)), Some(next)) = (link.shared_with_next, links.get(i + 1))
            {
                free += next.effect_on(row, Some((this_b, next_b)), &solution[i + 1]);
            }
            if link.mode == Mode::Velocity
                && let Some((a, b)) = load(i)
            {
                free += row.velocity(a, b);
            }
            let violated = if row.upper == 0.0 {
                free > 0.0
            } else {
                free < 0.0
            };
            if violated {
                links[i].active[r] = true;
                first = first.or(Some(i));
            }
        }
    }
    first
}
