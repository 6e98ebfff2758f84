//! The velocity stages of every substep — *apply forces*, *warm start*, *solve* (bias on) and *relax*
//! (bias off) — and the stages after the substeps that are not the projection: *restitution* and *store
//! impulses*. Each dispatches over the joint kinds; the paths are solved by `path_pass`.

use super::dispatch::PreparedJoint;
use super::dispatch::reaction_impulses;
use super::joint_solver::JointSolver;
use super::pool::JOINTS_PER_TASK;
use crate::pair::BodyPair;
use crate::stage::{Stage, Substep};
use crate::state::{JointState, JointStates};
use rebound_dynamics::{Bias, SolverBody, StepContext};
use rebound_math::par;

impl JointSolver {
    /// Stage *apply forces* (every substep, right after integrate velocities): each spring's impulse over
    /// the substep — the exact oscillator step of a [`crate::SpringModel::Soft`] spring, the explicit Hooke
    /// force `Δv = f·h·n/m` of a [`crate::SpringModel::Force`] one (course items 1–2) — on both bodies; then
    /// the oscillator step of the springs of hinge, prismatic and wheel joints (`docs/physics.md`, "Joint
    /// springs").
    pub fn apply_forces(&mut self, solver_bodies: &mut [SolverBody], ctx: &StepContext) {
        if self.pool.is_active() {
            let (h, coordinate_springs) = (ctx.h, self.coordinate_springs);
            // Each joint's two stages back to back: no other joint touches its bodies.
            self.joints_on_pool(solver_bodies, |j, pair, bodies| {
                j.kind.apply_forces(pair, &mut j.state, bodies, h);
                if coordinate_springs {
                    j.kind
                        .apply_coordinate_spring(pair, &mut j.state, bodies, h);
                }
            });
            return;
        }
        for j in &mut self.joints {
            j.kind
                .apply_forces(&j.pair, &mut j.state, solver_bodies, ctx.h);
        }
        // The springs of hinge, prismatic and wheel joints, the same oscillator step on their coordinate: a
        // second visit, made only in a step that has one, so that scenes without them (chains, bridges,
        // distance springs) test one variant per joint as before.
        if self.coordinate_springs {
            for j in &mut self.joints {
                j.kind
                    .apply_coordinate_spring(&j.pair, &mut j.state, solver_bodies, ctx.h);
            }
        }
    }

    /// Stage *warm start* (every substep): applies the impulses accumulated in the last substep again, along
    /// the current directions.
    pub fn warm_start(&self, solver_bodies: &mut [SolverBody]) {
        for j in &self.joints {
            // A spring's substep is *apply forces* alone: its bodies are not even looked up.
            if j.kind.acts_in_no_pass() {
                continue;
            }
            // The bodies in place: a warm start changes velocities only (`prepare` never keeps a joint whose
            // two bodies are one).
            let Some([a, b]) = j.pair.bodies_mut(solver_bodies) else {
                continue;
            };
            let (pair, state) = (&j.pair, &j.state);
            j.kind.warm_start(pair, state, a, b);
        }
        for t in &self.tethers {
            let Some((mut a, mut b)) = t.pair.load(solver_bodies) else {
                continue;
            };
            t.warm_start(&mut a, &mut b);
            t.pair.store(solver_bodies, a, b);
        }
    }

    /// [`JointSolver::solve_substep`] for a loop that does not name its substeps: the `k`-th relax pass since
    /// [`JointSolver::prepare`] counts as substep `k − 1` of `ctx.substep_count`, and a solve pass as the
    /// substep of the relax pass that follows it. A loop of `ctx.substep_count` substeps of one solve and one
    /// relax pass each, as the crate README shows, gives the same passes as naming them.
    pub fn solve(&mut self, solver_bodies: &mut [SolverBody], ctx: &StepContext, bias: Bias) {
        let substep = Substep::new(self.relax_passes, ctx.substep_count);
        if bias == Bias::Off {
            self.relax_passes = self.relax_passes.saturating_add(1);
        }
        self.solve_substep(solver_bodies, ctx, bias, substep);
    }

    /// Stages *solve* (`Bias::On`: [`crate::JointSettings::solve_iterations`] Gauss–Seidel passes with soft position
    /// correction) and *relax* (`Bias::Off`: [`crate::JointSettings::relax_iterations`] passes on velocities only;
    /// soft springs are left alone, see [`crate::spring`]). Each pass visits the joints in the order given to
    /// [`JointSolver::prepare`] (all but those a direct path solves entirely), then the paths, then the
    /// tethers.
    ///
    /// `substep` is the substep of the step the pass runs in, as the step counts them.
    ///
    /// A *closed* path (every row of its joints in the direct solve, no other joint or tether on its bodies)
    /// is relaxed in the last substep only. The relax pass of an inner substep leaves the velocities at the
    /// pose where the next substep's solve pass starts, and that pass solves the same rows of the same path
    /// exactly: for rigid rows its result does not depend on the velocity along the rows at all (a
    /// projection: `P·(P·v + g·h) = P·(v + g·h)`), and the soft step keeps `1 − mass_scale` of it (about a
    /// tenth at the default joint softness). The last relax pass stays: it takes the bias velocity out of
    /// the step's final velocities, and builds the rows the position projection starts from. A chain or a
    /// bridge so skips a third of its direct solves (`docs/physics.md`, "Relaxing a closed path"). A path
    /// with other rows on its bodies is relaxed every substep: without the path's relax, the path's exact
    /// solve pushes a hinge limit solved by Gauss–Seidel before it past the limit (`tests/hinge.rs`).
    pub fn solve_substep(
        &mut self,
        solver_bodies: &mut [SolverBody],
        ctx: &StepContext,
        bias: Bias,
        substep: Substep,
    ) {
        let stage = Stage {
            bias,
            h: ctx.h,
            inv_h: ctx.inv_h,
            joint_softness: self.joint_softness,
        };
        let iterations = match bias {
            Bias::On => self.settings.solve_iterations,
            Bias::Off => self.settings.relax_iterations,
        };
        // The last relax pass of the step builds the paths' rows at the final pose instead of carrying them:
        // the position projection ([`JointSolver::project_positions`]) starts at that pose and then reuses
        // the rows and, for paths whose rows all stay in the system (hinges, ball joints, taut ropes), their
        // factorisation — one factorisation of every such path a step fewer than building them there.
        let last_relax = bias == Bias::Off && substep.is_last();
        let mut carry_angle = self.carry_angle;
        if last_relax {
            carry_angle = 0.0;
            // Every link is built again at the final pose, and with this step's inverse inertias.
            for link in &mut self.links {
                link.end_last_step();
            }
        }
        for _ in 0..iterations {
            // Joints on a direct path are solved below, all but a hinge's limit and motor rows (they
            // are not in `iterated`).
            for &index in &self.iterated {
                let Some(j) = self.joints.get_mut(index) else {
                    continue;
                };
                // The bodies in place (a pass changes velocities only).
                let Some([a, b]) = j.pair.bodies_mut(solver_bodies) else {
                    continue;
                };
                let on_path = j.path.is_some();
                j.kind.solve(&j.pair, &mut j.state, (a, b), &stage, on_path);
            }
            for path in 0..self.topology.paths.len() {
                // A closed path is relaxed in the step's last substep only: see the method docs.
                if bias == Bias::Off && !last_relax && self.topology.closed.get(path) == Some(&true)
                {
                    continue;
                }
                self.solve_path(path, solver_bodies, &stage, carry_angle);
            }
            for t in &mut self.tethers {
                let Some((mut a, mut b)) = t.pair.load(solver_bodies) else {
                    continue;
                };
                t.solve(&mut a, &mut b, &stage);
                t.pair.store(solver_bodies, a, b);
            }
        }
    }

    /// Stage *restitution* (once, after the substeps): a rope with restitution `e` that snapped taut during
    /// the step while its anchors separated faster than `ctx.restitution_threshold` gets `Ċ = −e·Ċ⁻`.
    pub fn apply_restitution(&mut self, solver_bodies: &mut [SolverBody], ctx: &StepContext) {
        if !self.restitution {
            return;
        }
        for j in &mut self.joints {
            j.kind
                .apply_restitution(&j.pair, &mut j.state, solver_bodies, ctx);
        }
    }

    /// Stage *store impulses*: writes each prepared joint's impulses and reaction force and torque (N, N·m)
    /// into `states` (the slice given to [`JointSolver::prepare`]) for warm starting the next step. A joint
    /// whose reaction exceeds its break force or torque is marked broken and its index pushed into `broken`
    /// (which is not cleared first).
    pub fn store_impulses(&self, states: &mut [JointState], broken: &mut Vec<usize>) {
        self.store_impulses_to(states, broken);
    }

    /// [`JointSolver::store_impulses`] into the states where they are kept ([`JointStates`]): joint `i` of
    /// [`JointSolver::prepare_from`] is written to `states.state_mut(i)`, once. A state with a non-finite
    /// number is stored as zero impulses (whether the joint broke is kept).
    pub fn store_impulses_to<S: JointStates + ?Sized>(
        &self,
        states: &mut S,
        broken: &mut Vec<usize>,
    ) {
        let inv_h = if self.h > 0.0 { 1.0 / self.h } else { 0.0 };
        for (j, record) in self.joints.iter().zip(&self.records) {
            let Some(out) = states.state_mut(j.source) else {
                continue;
            };
            let (linear, angular) = reaction_impulses(&j.kind, &j.state);
            let tether = record.tether.and_then(|k| self.tethers.get(k));
            *out = JointState {
                reaction_force: linear * inv_h,
                reaction_torque: angular * inv_h,
                tether_impulse: tether.map_or(0.0, |t| t.impulse),
                broken: false,
                ..j.state
            };
            if out.reaction_force > record.break_force || out.reaction_torque > record.break_torque
            {
                out.broken = true;
                broken.push(j.source);
            }
            // Never a non-finite impulse into the state (the next step would warm start from it).
            if !out.is_finite() {
                *out = JointState {
                    broken: out.broken,
                    ..JointState::default()
                };
            }
        }
    }
}

impl JointSolver {
    /// Runs `f(joint, its two bodies as a pair with indices 0 and 1, [a, b])` for every joint over the pool
    /// (see the module docs), then writes the bodies back in joint order.
    pub(super) fn joints_on_pool<F>(&mut self, solver_bodies: &mut [SolverBody], f: F)
    where
        F: Fn(&mut PreparedJoint, &BodyPair, &mut [SolverBody; 2]) + Sync + Send,
    {
        let JointSolver { joints, pool, .. } = self;
        let read = |index: usize| {
            solver_bodies
                .get(index)
                .copied()
                .unwrap_or(SolverBody::STATIC)
        };
        par::map_collect_in_order(joints, &mut pool.bodies, JOINTS_PER_TASK, |_, j| {
            [read(j.pair.index_a), read(j.pair.index_b)]
        });
        par::for_each_zip_both_mut(joints, &mut pool.bodies, JOINTS_PER_TASK, |j, bodies| {
            let local = BodyPair {
                index_a: 0,
                index_b: 1,
                ..j.pair
            };
            f(j, &local, bodies);
        });
        for (j, &[a, b]) in joints.iter().zip(&pool.bodies) {
            j.pair.store(solver_bodies, a, b);
        }
    }
}
