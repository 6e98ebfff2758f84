//! Stages *substeps*, *project* and *restitution*: the solver passes over the prepared arrays. Each substep
//! integrates velocities, applies the joints' spring forces, warm starts, solves with bias, integrates
//! positions and relaxes (solves without bias); then the positions of each directly solved joint path
//! (chains, bridges) are projected, and ropes that went taut jerk back.

use crate::prepare::Solver;
use crate::solve_parts::{lock_axes_in, summing};
use rebound_constraints::Substep;
use rebound_dynamics::StepContext;
use rebound_dynamics::contact::Bias;
use rebound_dynamics::integrate::{integrate_positions, integrate_velocities};

/// Stage *substeps*.
pub(crate) fn solve_substeps(s: &mut Solver, ctx: &StepContext) {
    #[cfg(feature = "parallel")]
    if rebound_math::par::is_parallel() && crate::solve_team::solve_substeps(s.team_arrays(), ctx) {
        return;
    }
    for index in 0..ctx.substep_count {
        let substep = Substep::new(index, ctx.substep_count);
        integrate_velocities(&mut s.states, &s.params, ctx);
        lock_axes_of(s);
        s.joint_solver.apply_forces(&mut s.states, ctx);
        s.joint_solver.warm_start(&mut s.states);
        s.contact_solver.warm_start(&mut s.states);
        s.joint_solver
            .solve_substep(&mut s.states, ctx, Bias::On, substep);
        lock_axes_of(s);
        s.contact_solver.solve(&mut s.states, ctx, Bias::On);
        lock_axes_of(s);
        integrate_positions(&mut s.states, &s.params, ctx);
        s.joint_solver
            .solve_substep(&mut s.states, ctx, Bias::Off, substep);
        lock_axes_of(s);
        s.contact_solver.solve(&mut s.states, ctx, Bias::Off);
        lock_axes_of(s);
        if !s.step_impulses.is_empty() {
            sum_step_impulses(s, substep.is_last());
        }
    }
}

/// Adds each contact point's accumulated normal impulse after a substep to its sum over the step (what the
/// substep pushed with, see `ContactSolver::for_each_normal_impulse`), and after the last one the bounces.
fn sum_step_impulses(s: &mut Solver, last: bool) {
    s.contact_solver
        .for_each_normal_impulse(summing(&mut s.step_impulses, last));
}

/// Sets the locked velocity components (and displacements) of the bodies with locked axes to zero: after
/// every constraint pass, so that no pass hands the next a locked axis in motion.
fn lock_axes_of(s: &mut Solver) {
    lock_axes_in(&mut s.states, &s.params, &s.locked);
}

/// Stage *project*: the positions of each directly solved joint path.
pub(crate) fn project_positions(s: &mut Solver, ctx: &StepContext) {
    s.joint_solver.project_positions(&mut s.states, ctx);
    lock_axes_of(s);
}

/// Stage *restitution*: ropes that went taut jerk back. (Contacts bounce inside the solve, where impulses
/// can pass along a row of touching bodies — Newton's cradle — see `rebound_dynamics::contact`.)
pub(crate) fn apply_restitution(s: &mut Solver, ctx: &StepContext) {
    s.joint_solver.apply_restitution(&mut s.states, ctx);
}
