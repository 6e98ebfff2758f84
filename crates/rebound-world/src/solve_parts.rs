//! What the substep loop on one thread (`solve.rs`) and on a team (`solve_team.rs`) both run on the solver
//! arrays besides the solvers' passes: the axis locks after each pass, the impulse sums after each substep.

use rebound_dynamics::integrate::lock_axes;
use rebound_dynamics::{BodyParams, MAX_CONTACT_POINTS, SolverBody};

/// Sets the locked velocity components (and displacements) of the bodies `locked` to zero, from their
/// `states` and `params`.
pub(crate) fn lock_axes_in(states: &mut [SolverBody], params: &[BodyParams], locked: &[usize]) {
    for &i in locked {
        if let (Some(state), Some(params)) = (states.get_mut(i), params.get(i)) {
            lock_axes(state, params.locks);
        }
    }
}

/// What the sum of the step's impulses after a substep does with each point's impulses (`source`, point
/// `k`, normal and bounce impulse, N·s): adds them to `sums`, the bounce after the `last` substep only.
pub(crate) fn summing(
    sums: &mut [[f32; MAX_CONTACT_POINTS]],
    last: bool,
) -> impl FnMut(usize, usize, f32, f32) + '_ {
    move |source, k, normal, bounce| {
        if let Some(sum) = sums.get_mut(source).and_then(|p| p.get_mut(k)) {
            *sum += if last { normal + bounce } else { normal };
        }
    }
}
