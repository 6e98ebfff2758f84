//! Stages *substeps*, *project* and *restitution*: the solver passes over the prepared arrays. Each substep
//! integrates velocities, applies the joints' spring forces, warm starts, solves with bias, integrates
//! positions and relaxes (solves without bias); then the positions of each directly solved joint path
//! (chains, bridges) are projected, and ropes that went taut jerk back.

use crate::prepare::Solver;
use rebound_constraints::Substep;
use rebound_dynamics::StepContext;
use rebound_dynamics::contact::Bias;
use rebound_dynamics::integrate::{integrate_positions, integrate_velocities};

/// Stage *substeps*.
pub(crate) fn solve_substeps(s: &mut Solver, ctx: &StepContext) {
    for index in 0..ctx.substep_count {
        let substep = Substep::new(index, ctx.substep_count);
        integrate_velocities(&mut s.states, &s.params, ctx);
        s.joint_solver.apply_forces(&mut s.states, ctx);
        s.joint_solver.warm_start(&mut s.states);
        s.contact_solver.warm_start(&mut s.states);
        s.joint_solver
            .solve_substep(&mut s.states, ctx, Bias::On, substep);
        s.contact_solver.solve(&mut s.states, ctx, Bias::On);
        integrate_positions(&mut s.states, &s.params, ctx);
        s.joint_solver
            .solve_substep(&mut s.states, ctx, Bias::Off, substep);
        s.contact_solver.solve(&mut s.states, ctx, Bias::Off);
    }
}

/// Stage *project*: the positions of each directly solved joint path.
pub(crate) fn project_positions(s: &mut Solver, ctx: &StepContext) {
    s.joint_solver.project_positions(&mut s.states, ctx);
}

/// Stage *restitution*: ropes that went taut jerk back. (Contacts bounce inside the solve, where impulses
/// can pass along a row of touching bodies — Newton's cradle — see `rebound_dynamics::contact`.)
pub(crate) fn apply_restitution(s: &mut Solver, ctx: &StepContext) {
    s.joint_solver.apply_restitution(&mut s.states, ctx);
}
