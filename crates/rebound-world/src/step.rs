//! `World::step`: the soft-step pipeline as a list of stages (Box2D v3's `b2World_Step`, Catto's Solver2D
//! soft step). Each stage is a function in the file named for it; this file only calls them in order and
//! times them.
//!
//! ```text
//!  1. context             StepContext::new(dt): h, inverses, contact softness
//!  2. kinematic targets   kinematic.rs   target poses → velocities
//!  3. wake changed        islands.rs     a body a setter woke wakes its sleeping island
//!  4. collide             collide.rs     backend → manifolds, validated and warm-started; approach speeds
//!  5. wake touched        islands.rs     a sleeping body touched, about to be hit or jointed wakes
//!  6. prepare             prepare.rs     solver bodies (awake, then the fixed bodies needed, then the world
//!                                        anchor); contact and joint constraints
//!  7. substeps            solve.rs       integrate velocities → spring forces → warm start → solve (bias) →
//!                                        integrate positions → relax (no bias)
//!  8. project             solve.rs       the positions of each directly solved joint path (chains, bridges)
//!  9. restitution         solve.rs       ropes (contacts bounce inside the solve)
//! 10. store               store.rs       impulses back into manifolds and joint states; broken joints
//! 11. finalize            store.rs       poses and velocities back into the bodies
//!                         islands.rs     rest timers, islands, sleep
//!                         events.rs      contact begin/end, woken bodies
//! 12. report              report.rs      body counts, phase timings
//! ```

use crate::manifold::CollisionBackend;
use crate::report::{Profile, StepReport, StepSkipped};
use crate::scratch::Scratch;
use crate::settings::MIN_STEP_DT;
use crate::world::World;
use crate::{collide, events, islands, kinematic, prepare, solve, store};
use rebound_dynamics::StepContext;
use std::time::Instant;

impl<B: CollisionBackend> World<B> {
    /// Advances the simulation by `dt` seconds with `settings.substep_count` soft substeps.
    ///
    /// Never fails: a `dt` that is not a positive finite number, or is shorter than [`crate::MIN_STEP_DT`],
    /// moves nothing, and the report says so. The
    /// events of the step replace those of the previous one.
    pub fn step(&mut self, dt: f32) -> StepReport {
        self.events.clear();
        if !dt.is_finite() {
            return StepReport::skipped(StepSkipped::NonFiniteDt(dt), &self.state.bodies);
        }
        if dt <= 0.0 {
            return StepReport::skipped(StepSkipped::NonPositiveDt(dt), &self.state.bodies);
        }
        if dt < MIN_STEP_DT {
            return StepReport::skipped(StepSkipped::DtTooSmall(dt), &self.state.bodies);
        }
        let start = Instant::now();
        let mut report = StepReport::default();
        let mut profile = Profile::default();
        let (state, events, woken) = (&mut self.state, &mut self.events, &mut self.woken);
        let Scratch {
            collision,
            solver,
            sleep,
            events: event_buffers,
        } = &mut self.scratch;

        let ctx = StepContext::new(dt, &state.settings.solver_settings());
        let mut phase = Instant::now();
        kinematic::apply_kinematic_targets(&mut state.bodies, dt);
        islands::wake_changed_bodies(state, woken, sleep);
        report.rejected_contact_count = collide::collide(&mut self.backend, state, dt, collision);
        islands::wake_touched(state, woken, collision, sleep, dt);
        profile.collide = phase.elapsed();

        phase = Instant::now();
        prepare::build_solver_bodies(&state.bodies, solver);
        prepare::build_contacts(
            &state.bodies,
            &collision.manifolds,
            solver,
            &ctx,
            &mut report,
        );
        prepare::build_joints(state, solver, &ctx, &mut report);
        profile.prepare = phase.elapsed();

        phase = Instant::now();
        solve::solve_substeps(solver, &ctx);
        solve::project_positions(solver, &ctx);
        profile.solve = phase.elapsed();

        phase = Instant::now();
        solve::apply_restitution(solver, &ctx);
        store::store_impulses(state, collision, solver, events, &mut report);
        profile.restitution = phase.elapsed();

        phase = Instant::now();
        store::write_back(&mut state.bodies, solver);
        events::push_force_events(state, solver, dt, events);
        islands::update_sleep(state, solver, sleep, events, dt);
        events::emit_events(
            state,
            &collision.pushed,
            &collision.approach_speeds,
            event_buffers,
            events,
            woken,
        );
        state.step_count += 1;
        profile.finalize = phase.elapsed();

        report.count_bodies(&state.bodies, &solver.solver_handles, &solver.params);
        profile.total = start.elapsed();
        report.profile = profile;
        report
    }
}
