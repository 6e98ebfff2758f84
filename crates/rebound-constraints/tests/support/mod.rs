//! A tiny fixed-step harness for the constraint tests: bodies and joints stepped through the real stages in
//! the world's order (prepare → substeps of integrate velocities, apply forces, warm start, solve, integrate
//! positions, relax → restitution → store → write back). The world crate owns the real pipeline; this exists so
//! the joints can be tested without it. No collision.

#![allow(
    dead_code,
    reason = "each test binary uses a different part of the harness"
)]

use rebound_constraints::{Joint, JointBodies, JointSettings, JointSolver, JointState};
use rebound_dynamics::contact::Bias;
use rebound_dynamics::integrate::{integrate_positions, integrate_velocities};
use rebound_dynamics::{BodyDesc, BodyParams, RigidBody, SolverBody, SolverSettings, StepContext};
use rebound_math::Vec3;

#[derive(Clone)]
pub struct Harness {
    pub bodies: Vec<RigidBody>,
    pub settings: SolverSettings,
    pub joints: Vec<Joint>,
    pub states: Vec<JointState>,
    pub pairs: Vec<JointBodies>,
    /// Indices of joints that broke, in the order they broke.
    pub broken: Vec<usize>,
    pub solver: JointSolver,
    solver_bodies: Vec<SolverBody>,
    params: Vec<BodyParams>,
}

impl Harness {
    pub fn new(settings: SolverSettings) -> Self {
        Self {
            bodies: Vec::new(),
            settings,
            joints: Vec::new(),
            states: Vec::new(),
            pairs: Vec::new(),
            broken: Vec::new(),
            solver: JointSolver::new(),
            solver_bodies: Vec::new(),
            params: Vec::new(),
        }
    }

    /// Default settings without gravity.
    pub fn zero_gravity() -> Self {
        Self::new(SolverSettings {
            gravity: Vec3::ZERO,
            ..SolverSettings::default()
        })
    }

    pub fn with_joint_settings(mut self, settings: JointSettings) -> Self {
        self.solver = JointSolver::with_settings(settings).expect("valid joint settings");
        self
    }

    pub fn add(&mut self, desc: &BodyDesc) -> usize {
        self.bodies
            .push(RigidBody::new(desc).expect("valid test body"));
        self.bodies.len() - 1
    }

    /// The world anchor: a fixed body at the origin with identity rotation, so that a joint's
    /// `local_anchor_a` on it is a world point.
    pub fn world_anchor(&mut self) -> usize {
        self.add(&BodyDesc::fixed())
    }

    pub fn join(&mut self, joint: Joint, a: usize, b: usize) -> usize {
        self.joints.push(joint);
        self.states.push(JointState::default());
        self.pairs.push(JointBodies { a, b });
        self.joints.len() - 1
    }

    /// One step of `dt` seconds. Returns how many joints the solver skipped.
    pub fn step(&mut self, dt: f32) -> usize {
        let ctx = StepContext::new(dt, &self.settings);
        self.solver_bodies.clear();
        self.solver_bodies
            .extend(self.bodies.iter().map(SolverBody::from_body));
        self.params.clear();
        self.params
            .extend(self.bodies.iter().map(BodyParams::from_body));

        let skipped = self.solver.prepare(
            &self.joints,
            &self.states,
            &self.pairs,
            &self.solver_bodies,
            &self.params,
            &ctx,
        );
        for _ in 0..ctx.substep_count {
            integrate_velocities(&mut self.solver_bodies, &self.params, &ctx);
            self.solver.apply_forces(&mut self.solver_bodies, &ctx);
            self.solver.warm_start(&mut self.solver_bodies);
            self.solver.solve(&mut self.solver_bodies, &ctx, Bias::On);
            integrate_positions(&mut self.solver_bodies, &self.params, &ctx);
            self.solver.solve(&mut self.solver_bodies, &ctx, Bias::Off);
        }
        self.solver.project_positions(&mut self.solver_bodies, &ctx);
        self.solver.apply_restitution(&mut self.solver_bodies, &ctx);
        self.solver
            .store_impulses(&mut self.states, &mut self.broken);
        for ((body, state), params) in self
            .bodies
            .iter_mut()
            .zip(&self.solver_bodies)
            .zip(&self.params)
        {
            write_back(params, state, body);
        }
        skipped
    }

    /// World position of a joint's anchor on body `body` at local point `local` (m).
    pub fn world_point(&self, body: usize, local: Vec3) -> Vec3 {
        self.bodies[body].pose().transform_point(local)
    }
}

fn write_back(params: &BodyParams, state: &SolverBody, body: &mut RigidBody) {
    let written = params.write_back(state, body);
    assert!(written, "the solver produced a non-finite state");
}
