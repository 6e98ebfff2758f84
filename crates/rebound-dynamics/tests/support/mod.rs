//! A tiny fixed-step harness for the dynamics tests: bodies plus a collision closure that reports contacts
//! from the current poses, stepped through the real stages (prepare → substeps of integrate velocities, warm
//! start, solve, integrate positions, relax → restitution → store → write back). The world crate owns the
//! real pipeline; this exists so the kernel can be tested without it.

#![allow(
    dead_code,
    reason = "each test binary uses a different part of the harness"
)]

use rebound_dynamics::contact::Bias;
use rebound_dynamics::integrate::{integrate_positions, integrate_velocities};
use rebound_dynamics::{
    BodyDesc, BodyParams, Contact, ContactPoint, ContactSolver, RigidBody, SolverBody,
    SolverSettings, StepContext,
};
use rebound_math::Vec3;

pub struct Harness {
    pub bodies: Vec<RigidBody>,
    pub settings: SolverSettings,
    pub contacts: Vec<Contact>,
    solver: ContactSolver,
    states: Vec<SolverBody>,
    params: Vec<BodyParams>,
}

impl Harness {
    pub fn new(settings: SolverSettings) -> Self {
        Self {
            bodies: Vec::new(),
            settings,
            contacts: Vec::new(),
            solver: ContactSolver::new(),
            states: Vec::new(),
            params: Vec::new(),
        }
    }

    pub fn add(&mut self, desc: &BodyDesc) -> usize {
        self.bodies
            .push(RigidBody::new(desc).expect("valid test body"));
        self.bodies.len() - 1
    }

    /// One step of `dt`; `collide` reports the contacts of the current poses (impulses zero: the harness
    /// warm-starts them from the last step by body pair and feature id).
    pub fn step(&mut self, dt: f32, collide: &mut dyn FnMut(&[RigidBody]) -> Vec<Contact>) {
        let ctx = StepContext::new(dt, &self.settings);
        self.states.clear();
        self.states
            .extend(self.bodies.iter().map(SolverBody::from_body));
        self.params.clear();
        self.params
            .extend(self.bodies.iter().map(BodyParams::from_body));

        let mut contacts = collide(&self.bodies);
        for contact in &mut contacts {
            let Some(old) = self
                .contacts
                .iter()
                .find(|c| c.body_a == contact.body_a && c.body_b == contact.body_b)
            else {
                continue;
            };
            for point in &mut contact.points[..contact.point_count] {
                if let Some(previous) = old
                    .points()
                    .iter()
                    .find(|p| p.feature_id == point.feature_id)
                {
                    point.normal_impulse = previous.normal_impulse;
                    point.tangent_impulse = previous.tangent_impulse;
                }
            }
        }
        let skipped = self
            .solver
            .prepare(&contacts, &self.states, &self.params, &ctx);
        assert_eq!(
            skipped, 0,
            "the test's collision closure made a malformed contact"
        );
        for _ in 0..ctx.substep_count {
            integrate_velocities(&mut self.states, &self.params, &ctx);
            self.solver.warm_start(&mut self.states);
            self.solver.solve(&mut self.states, &ctx, Bias::On);
            integrate_positions(&mut self.states, &self.params, &ctx);
            self.solver.solve(&mut self.states, &ctx, Bias::Off);
        }
        self.solver.store_impulses(&mut contacts);
        for ((body, state), params) in self.bodies.iter_mut().zip(&self.states).zip(&self.params) {
            assert!(
                params.write_back(state, body),
                "the solver produced a non-finite state"
            );
        }
        self.contacts = contacts;
    }

    pub fn step_free(&mut self, dt: f32) {
        self.step(dt, &mut |_| Vec::new());
    }
}

/// Contacts of a box (body `body`, half-extents `half`) with the plane y = 0 of the fixed body `ground`: one
/// point per corner closer than `margin` (m), feature id = corner index. Normal +y (from ground to box).
pub fn box_on_plane(
    bodies: &[RigidBody],
    ground: usize,
    body: usize,
    half: Vec3,
    friction: f32,
    restitution: f32,
    margin: f32,
) -> Vec<Contact> {
    let b = &bodies[body];
    let com_b = b.center_of_mass();
    let com_ground = bodies[ground].center_of_mass();
    let mut corners: Vec<(u32, Vec3)> = (0..8u32)
        .map(|i| {
            let sign = Vec3::new(
                if i & 1 == 0 { -1.0 } else { 1.0 },
                if i & 2 == 0 { -1.0 } else { 1.0 },
                if i & 4 == 0 { -1.0 } else { 1.0 },
            );
            (i, b.pose().transform_point(sign * half))
        })
        .filter(|(_, p)| p.y < margin)
        .collect();
    // Deepest four, in a stable order.
    corners.sort_by(|x, y| x.1.y.total_cmp(&y.1.y).then(x.0.cmp(&y.0)));
    corners.truncate(4);
    if corners.is_empty() {
        return Vec::new();
    }
    let mut contact = Contact::new(ground, body, Vec3::Y, friction, restitution);
    for (id, p) in corners {
        contact.push_point(ContactPoint {
            anchor_a: Vec3::new(p.x, 0.0, p.z) - com_ground,
            anchor_b: p - com_b,
            separation: p.y,
            feature_id: id,
            ..ContactPoint::default()
        });
    }
    vec![contact]
}

/// Contact of a ball (body `body`, `radius`) with the plane y = 0 of the fixed body `ground`, when closer than
/// `margin` (m).
pub fn ball_on_plane(
    bodies: &[RigidBody],
    ground: usize,
    body: usize,
    radius: f32,
    restitution: f32,
    margin: f32,
) -> Vec<Contact> {
    let c = bodies[body].center_of_mass();
    let separation = c.y - radius;
    if separation > margin {
        return Vec::new();
    }
    let point = Vec3::new(c.x, 0.0, c.z);
    let mut contact = Contact::new(ground, body, Vec3::Y, 0.0, restitution);
    contact.push_point(ContactPoint {
        anchor_a: point - bodies[ground].center_of_mass(),
        anchor_b: point - c,
        separation,
        feature_id: 0,
        ..ContactPoint::default()
    });
    vec![contact]
}
