//! `World::step`: the soft-step pipeline as a list of stages (Box2D v3's `b2World_Step`, Catto's Solver2D
//! soft step). Each stage is a function in the file named for it; this file only calls them in order and
//! times them.
//!
//! ```text
//!  1. context             StepContext::new(dt): h, inverses, contact softness
//!  2. kinematic targets   kinematic.rs   target poses → velocities
//!  3. wake changed        islands.rs     a body a setter woke wakes its sleeping island
//!     quarantine          quarantine.rs  moving bodies beyond the bounds leave the step (checked when the
//!                                        bodies may have changed since the write-back compared them)
//!  4. collide             collide.rs     backend → manifolds, validated and warm-started; approach speeds
//!  5. wake touched        islands.rs     a sleeping body touched, about to be hit or jointed wakes
//!  6. prepare             prepare.rs     solver bodies (awake, then the fixed bodies needed, then the world
//!                                        anchor); contact and joint constraints
//!  7. substeps            solve.rs       integrate velocities → spring forces → warm start → solve (bias) →
//!                                        integrate positions → relax (no bias)
//!  8. project             solve.rs       the positions of each directly solved joint path (chains, bridges)
//!  9. restitution         solve.rs       ropes (contacts bounce inside the solve)
//!     quarantine          quarantine.rs  bodies the solve drove beyond the bounds leave the step, and 6–9
//!                                        run again without them
//! 10. store               store.rs       impulses back into manifolds and joint states; broken joints
//! 11. finalize            store.rs       poses and velocities back into the bodies, compared with the bounds
//!                         islands.rs     rest timers, islands, sleep
//!                         events.rs      contact begin/end, woken bodies
//! 12. report              report.rs      body counts, phase timings
//! ```

use crate::collide::Collision;
use crate::events::Event;
use crate::handles::BodyHandle;
use crate::limits::QuarantineReason;
use crate::manifold::CollisionBackend;
use crate::prepare::Solver;
use crate::quarantine::Bounds;
use crate::report::{Profile, StepReport, StepSkipped};
use crate::scratch::Scratch;
use crate::settings::MIN_STEP_DT;
use crate::state::WorldState;
use crate::world::World;
use crate::{collide, events, islands, kinematic, prepare, quarantine, solve, store};
use rebound_constraints::KeptRows;
use rebound_dynamics::StepContext;
use std::time::Instant;

/// How many times one step's *prepare* and solver passes may run again, each without the new suspects of
/// the last (see `quarantine.rs`). Past this, a non-finite result is refused at write-back and a finite one
/// beyond the bounds is quarantined at the next step's start.
const MAX_RERUNS: usize = 4;

/// Stages 6–9 (*prepare*, *substeps*, *project*, *restitution*) as one pass that the quarantine can run
/// again, with what they read and write.
struct Pass<'a> {
    collision: &'a mut Collision,
    solver: &'a mut Solver,
    ctx: &'a StepContext,
    report: &'a mut StepReport,
    profile: &'a mut Profile,
    /// The manifolds *collide* rejected (*prepare* adds its own).
    rejected: usize,
}

impl Pass<'_> {
    /// One pass from the step's start state, skipping quarantined (and trial-excluded) bodies.
    fn run(&mut self, state: &WorldState) {
        let phase = Instant::now();
        self.report.rejected_contact_count = self.rejected;
        self.report.contact_point_count = 0;
        prepare::build_solver_bodies(&state.bodies, self.solver);
        prepare::build_contacts(
            &state.bodies,
            &self.collision.manifolds,
            self.solver,
            self.ctx,
            self.report,
        );
        prepare::build_joints(state, self.solver, self.ctx, self.report);
        self.profile.prepare += phase.elapsed();

        let phase = Instant::now();
        solve::solve_substeps(self.solver, self.ctx);
        solve::project_positions(self.solver, self.ctx);
        solve::apply_restitution(self.solver, self.ctx);
        self.profile.solve += phase.elapsed();
    }

    /// [`Pass::run`] again after a pass whose results were out of bounds, without the joint rows that pass
    /// left to be carried: rows built in a failed pass may hold its non-finite values, which a carried row
    /// would feed into this pass and the next step's (and a snapshot would hold). The paths build their
    /// rows anew.
    fn rerun(&mut self, state: &WorldState) {
        self.solver
            .joint_solver
            .restore_kept_rows(&KeptRows::default());
        self.run(state);
    }

    /// After a pass whose results for `suspects` were out of bounds: finds which of them are to blame (see
    /// `quarantine.rs`), quarantines those, and runs the pass a last time without them. Returns how many
    /// were quarantined.
    fn quarantine_bad(
        &mut self,
        state: &mut WorldState,
        suspects: &mut Vec<(BodyHandle, QuarantineReason)>,
        events: &mut Vec<Event>,
    ) -> usize {
        // Without every suspect, and without those each rerun adds, until a pass is clean.
        let mut found = core::mem::take(suspects);
        let mut clean = false;
        for _ in 0..MAX_RERUNS {
            for &(body, _) in &found {
                quarantine::set_excluded(state, body, true);
            }
            suspects.append(&mut found);
            self.rerun(state);
            quarantine::find_bad_results(state, self.solver, &mut found);
            if found.is_empty() {
                clean = true;
                break;
            }
        }
        // Each suspect back in turn: the innocent stay in.
        let mut guilty = Vec::new();
        if clean && suspects.len() <= quarantine::MAX_TRIED_SUSPECTS {
            for &(body, reason) in suspects.iter() {
                quarantine::set_excluded(state, body, false);
                self.rerun(state);
                quarantine::find_bad_results(state, self.solver, &mut found);
                if !found.is_empty() {
                    quarantine::set_excluded(state, body, true);
                    guilty.push((body, reason));
                }
            }
        } else {
            // Too many to try one by one, or a pass that never came clean: all of them, and what the last
            // pass still found.
            for &(body, _) in &found {
                quarantine::set_excluded(state, body, true);
            }
            guilty.extend_from_slice(suspects);
            guilty.append(&mut found);
        }
        quarantine::quarantine(state, &guilty, events);
        self.collision.drop_quarantined(&state.bodies);
        // The last pass, without the guilty and their manifolds (the store stage maps the solver's contacts
        // to the manifolds they came from).
        self.rerun(state);
        suspects.clear();
        guilty.len()
    }
}

impl<B: CollisionBackend> World<B> {
    /// Advances the simulation by `dt` seconds with `settings.substep_count` soft substeps.
    ///
    /// Never fails: a `dt` that is not a positive finite number, or is shorter than [`crate::MIN_STEP_DT`],
    /// moves nothing, and the report says so. A body beyond the bounds of [`crate::StepLimits`] is
    /// quarantined (see [`crate::Event::BodyQuarantined`]). The events of the step replace those of the
    /// previous one.
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
            suspects,
            start_check,
        } = &mut self.scratch;

        let ctx = StepContext::new(dt, &state.settings.solver_settings());
        let phase = Instant::now();
        let bounds = Bounds::new(&state.settings.limits);
        let targets_within = kinematic::apply_kinematic_targets(&mut state.bodies, dt, &bounds);
        islands::wake_changed_bodies(state, woken, sleep);
        report.quarantined_body_count =
            quarantine::check_bodies(state, start_check, targets_within, events);
        let dropped = collide::collide(&mut self.backend, state, dt, collision);
        report.rejected_contact_count = dropped.rejected;
        report.capped_manifold_count = dropped.capped;
        report.capped_pair_count = self.backend.capped_pair_count();
        islands::wake_touched(state, woken, collision, sleep, dt);
        profile.collide = phase.elapsed();

        // Prepare and solve; again without the bodies the solve drove out of bounds, if any.
        let rejected = report.rejected_contact_count;
        let mut pass = Pass {
            collision,
            solver,
            ctx: &ctx,
            report: &mut report,
            profile: &mut profile,
            rejected,
        };
        pass.run(state);
        quarantine::find_bad_results(state, pass.solver, suspects);
        // Every solved velocity within the bounds (the passes run again below are not checked at the end).
        let velocities_within = suspects.is_empty();
        if !suspects.is_empty() {
            let count = pass.quarantine_bad(state, suspects, events);
            pass.report.quarantined_body_count += count;
        }

        let mut phase = Instant::now();
        store::store_impulses(state, collision, solver, events, &mut report);
        profile.restitution = phase.elapsed();

        phase = Instant::now();
        let positions_within = store::write_back(
            &mut state.bodies,
            solver,
            state.settings.limits.max_position,
        );
        start_check.written(state, velocities_within && positions_within);
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
