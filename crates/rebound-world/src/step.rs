//! `World::step`: the soft-step pipeline, phase by phase (DESIGN.md §3; Box2D v3's `b2World_Step`, Catto's
//! Solver2D soft step). `step` itself only lists the phases; each is a method below.
//!
//! ```text
//! 1. context       StepContext::new(dt): h, inverses, contact softness
//! 2. collide       backend → manifolds; warm-start matching; waking by touch and by joints
//! 3. prepare       dense solver arrays (awake bodies, then the fixed bodies they touch, then the world
//!                  anchor); contact and joint constraints
//! 4. substeps      integrate velocities → spring forces → warm start → solve (bias) → integrate positions →
//!                  relax (no bias)
//!    project       the positions of each directly solved joint path (chains, bridges)
//! 5. restitution   ropes (contacts bounce inside the solve: their target velocity is +C_r·approach)
//! 6. store         impulses back into manifolds and joint states; broken joints
//! 7. finalize      write back poses and velocities; islands and sleep; events
//! ```

use crate::body_set::NO_ISLAND;
use crate::islands::UnionFind;
use crate::report::{Profile, StepSkipped};
use crate::world::skipped_report;
use crate::{
    BodyHandle, BodySet, CollisionBackend, ContactManifold, Event, JointHandle, StepReport, World,
};
use rebound_constraints::{Joint, JointBodies, JointSolver, JointState};
use rebound_dynamics::contact::Bias;
use rebound_dynamics::integrate::{integrate_positions, integrate_velocities};
use rebound_dynamics::{
    BodyParams, BodyType, Contact, ContactPoint, ContactSolver, Motion, SolverBody, StepContext,
};
use rebound_math::{Mat3, Vec3};
use std::time::Instant;

const NO_INDEX: u32 = u32::MAX;

/// Buffers reused from step to step (no allocation in a steady-state step). Not part of the state.
#[derive(Debug, Default)]
pub(crate) struct Scratch {
    /// Body slot → solver index, or `NO_INDEX`.
    solver_index: Vec<u32>,
    /// Solver index → body handle (`None` for the world anchor entry).
    solver_handles: Vec<Option<BodyHandle>>,
    states: Vec<SolverBody>,
    params: Vec<BodyParams>,
    /// Manifolds the backend reported this step.
    manifolds: Vec<ContactManifold>,
    /// Solver contacts and, for each, the manifold it came from.
    contacts: Vec<Contact>,
    contact_sources: Vec<usize>,
    /// Joints handed to the solver, their states and bodies, and the handles they came from.
    joints: Vec<Joint>,
    joint_states: Vec<JointState>,
    joint_bodies: Vec<JointBodies>,
    joint_handles: Vec<JointHandle>,
    broken: Vec<usize>,
    contact_solver: ContactSolver,
    pub(crate) joint_solver: JointSolver,
    touching: Vec<(BodyHandle, BodyHandle)>,
    /// For each manifold of this step, the approach speed before the step (m/s), for contact events.
    approach_speeds: Vec<f32>,
    /// Body slot → the rotation matrix of the body's orientation and the collide call that computed it
    /// (`collide_calls`): each body's matrix is computed once per collide stage, at its first manifold.
    rotations: Vec<(u64, Mat3)>,
    /// How many collide stages ran (so that a matrix of an earlier one is never read as current).
    collide_calls: u64,
    /// Touching body pairs of this step with their approach speeds (events stage).
    touching_speeds: Vec<((BodyHandle, BodyHandle), f32)>,
    /// Buffer for the contact events of a step.
    contact_events: Vec<Event>,
    /// For each manifold of this step, whether the solver pushed with it (a contact that touched during the
    /// step, even one that bounced off and ended with no accumulated impulse).
    pushed: Vec<bool>,
    union_find: UnionFind,
    can_rest: Vec<bool>,
    island_ok: Vec<bool>,
    links: Vec<(u32, u32)>,
    sleepers: Vec<(u32, BodyHandle)>,
    to_wake: Vec<BodyHandle>,
}

impl<B: CollisionBackend> World<B> {
    /// Advances the simulation by `dt` seconds with `settings.substep_count` soft substeps.
    ///
    /// Never fails: a `dt` that is not a positive finite number moves nothing, and the report says so. The
    /// events of the step replace those of the previous one.
    pub fn step(&mut self, dt: f32) -> StepReport {
        self.events.clear();
        if !dt.is_finite() {
            return skipped_report(StepSkipped::NonFiniteDt(dt), &self.state.bodies);
        }
        if dt <= 0.0 {
            return skipped_report(StepSkipped::NonPositiveDt(dt), &self.state.bodies);
        }
        let start = Instant::now();
        let mut report = StepReport::default();
        let mut profile = Profile::default();

        let ctx = StepContext::new(dt, &self.state.settings.solver_settings());
        let mut phase = Instant::now();
        self.apply_kinematic_targets(dt);
        self.wake_changed_bodies();
        self.collide(dt, &mut report);
        profile.collide = phase.elapsed();

        phase = Instant::now();
        self.build_solver_bodies();
        self.build_contacts(&ctx, &mut report);
        self.build_joints(&ctx, &mut report);
        profile.prepare = phase.elapsed();

        phase = Instant::now();
        self.solve_substeps(&ctx);
        profile.solve = phase.elapsed();

        phase = Instant::now();
        self.apply_restitution(&ctx);
        self.store_impulses(&mut report);
        profile.restitution = phase.elapsed();

        phase = Instant::now();
        self.write_back();
        self.update_sleep(dt);
        self.emit_events();
        self.state.step_count += 1;
        profile.finalize = phase.elapsed();

        report.body_count = self.state.bodies.len();
        report.awake_body_count = self
            .scratch
            .solver_handles
            .iter()
            .filter(|h| h.is_some())
            .count();
        report.awake_body_count -= self
            .scratch
            .params
            .iter()
            .filter(|p| !p.is_dynamic())
            .count()
            .min(report.awake_body_count);
        report.sleeping_body_count = self
            .state
            .bodies
            .iter()
            .filter(|(_, b)| b.is_sleeping())
            .count();
        profile.total = start.elapsed();
        report.profile = profile;
        report
    }

    /// Kinematic targets become velocities for this step: `v = Δx/dt`, `ω = axis·angle/dt`.
    fn apply_kinematic_targets(&mut self, dt: f32) {
        for (_, entry) in self.state.bodies.arena.iter_mut() {
            let Some(target) = entry.kinematic_target.take() else {
                continue;
            };
            if entry.body.body_type() != BodyType::Kinematic {
                continue;
            }
            let linear = (target.position - entry.body.position()) / dt;
            let mut delta = target.rotation * entry.body.rotation().conjugate();
            if delta.w < 0.0 {
                delta = -delta;
            }
            let (axis, angle) = delta.to_axis_angle();
            // Both are finite: the target and the pose were validated, dt > 0.
            let _ = entry.body.set_linear_velocity(linear);
            let _ = entry.body.set_angular_velocity(axis * (angle / dt));
        }
    }

    /// Bodies in a sleeping island whose own flag was cleared (by a setter, a force, an impulse) wake their
    /// whole island.
    fn wake_changed_bodies(&mut self) {
        // Reuses the wake buffer of the collide stage: no allocation per step.
        let mut changed = core::mem::take(&mut self.scratch.to_wake);
        changed.clear();
        changed.extend(
            self.state
                .bodies
                .arena
                .iter()
                .filter(|(_, e)| e.island != NO_ISLAND && !e.body.is_sleeping())
                .map(|(i, _)| BodyHandle(i)),
        );
        for &handle in &changed {
            self.wake_island_of(handle);
        }
        self.scratch.to_wake = changed;
    }

    /// Stage *collide*: the backend's manifolds for the current poses, sorted, validated and matched with last
    /// step's for warm starting; an awake body touching a sleeping one, or jointed to it, wakes it.
    fn collide(&mut self, dt: f32, report: &mut StepReport) {
        let mut manifolds = core::mem::take(&mut self.scratch.manifolds);
        manifolds.clear();
        self.backend.collide(
            &self.state.bodies,
            &self.state.settings,
            dt,
            &self.state.manifolds,
            &mut manifolds,
        );
        let bodies = &self.state.bodies;
        // Unstable sort: no buffer to allocate, and the result does not depend on the input order because a
        // backend's keys are unique per body pair (equal keys — a faulty backend — still sort the same way
        // for the same input: the sort is deterministic). The key reads no number, so the manifolds the walk
        // below rejects (`is_usable`) sort like the others.
        manifolds.sort_unstable_by_key(ContactManifold::order_key);

        // Warm start: copy impulses from last step's manifold with the same key, point by point by feature id;
        // a persisting point also keeps its lever arms (see `LEVER_ARM_TOLERANCE`). Both lists are sorted by
        // key, so one forward walk through last step's finds every match (`walk_to`).
        //
        // The same walk finds the manifolds whose approach speed (m/s, before the step) is needed: those of a
        // contact that may begin this step (no touching manifold last step: the speed goes in the event) and
        // those with a sleeping body (waking). The others get 0 — computing every speed was 4 % of a pile's
        // step.
        //
        // The walk also validates (one pass over the manifolds, and the bodies looked up once): an unusable
        // manifold is dropped, the kept ones move down over it in order.
        let mut speeds = core::mem::take(&mut self.scratch.approach_speeds);
        speeds.clear();
        let mut contacts = core::mem::take(&mut self.scratch.contacts);
        contacts.clear();
        let mut rotations = core::mem::take(&mut self.scratch.rotations);
        rotations.resize(bodies.slot_count(), (0, Mat3::IDENTITY));
        self.scratch.collide_calls += 1;
        let call = self.scratch.collide_calls;
        // A body's rotation matrix, computed at its first manifold of the stage: a point's lever arm is then
        // one matrix product, `R·(p_local − c_local)`, where rotating the point and the centre of mass by the
        // quaternion took two rotations of twice the arithmetic.
        let mut rotation_of = |handle: BodyHandle, body: &rebound_dynamics::RigidBody| {
            let entry = &mut rotations[BodySet::slot(handle)];
            if entry.0 != call {
                *entry = (call, Mat3::from_quat(body.rotation()));
            }
            entry.1
        };
        let mut previous = self.state.manifolds.iter().peekable();
        let mut kept = 0;
        for index in 0..manifolds.len() {
            let (body_a, body_b) = (manifolds[index].body_a, manifolds[index].body_b);
            let (Some(body_a), Some(body_b)) = (bodies.get(body_a), bodies.get(body_b)) else {
                continue;
            };
            if !is_usable(&manifolds[index]) {
                continue;
            }
            if kept != index {
                manifolds.swap(kept, index);
            }
            let manifold = &mut manifolds[kept];
            kept += 1;
            let key = manifold.order_key();
            let old = walk_to(&mut previous, &key, ContactManifold::order_key);
            let may_begin = old.is_none_or(|o| !o.is_touching());
            speeds.push(
                if may_begin || body_a.is_sleeping() || body_b.is_sleeping() {
                    approach_speed(manifold, body_a, body_b)
                } else {
                    0.0
                },
            );
            let count = manifold.point_count.min(crate::MAX_MANIFOLD_POINTS);
            let old_points = old.map_or(&[][..], ContactManifold::points);
            // The solver's contact is written here, with the points in cache, its bodies' solver indices
            // left for `build_contacts` (they are known once waking is done); in place in the list (a contact
            // is 232 bytes: building it on the stack and pushing it copied each one once more).
            contacts.push(Contact::new(
                usize::MAX,
                usize::MAX,
                manifold.normal,
                manifold.friction,
                manifold.restitution,
            ));
            let Some(contact) = contacts.last_mut() else {
                continue;
            };
            contact.rolling_friction = manifold.rolling_friction;
            let rotations = [
                rotation_of(manifold.body_a, body_a),
                rotation_of(manifold.body_b, body_b),
            ];
            let centers = [
                body_a.mass_properties().local_center_of_mass(),
                body_b.mass_properties().local_center_of_mass(),
            ];
            for point in &mut manifold.points[..count] {
                let fresh = [
                    rotations[0] * (point.local_anchor_a - centers[0]),
                    rotations[1] * (point.local_anchor_b - centers[1]),
                ];
                if let Some(previous) = point.refresh_lever_arms(fresh, old_points) {
                    point.normal_impulse = previous.normal_impulse;
                    point.tangent_impulse = previous.tangent_impulse;
                }
                let [anchor_a, anchor_b] = point.solver_lever_arms.unwrap_or(fresh);
                contact.push_point(ContactPoint {
                    anchor_a,
                    anchor_b,
                    separation: point.separation,
                    normal_impulse: point.normal_impulse,
                    tangent_impulse: point.tangent_impulse,
                    feature_id: point.feature_id,
                });
            }
        }
        report.rejected_contact_count = manifolds.len() - kept;
        manifolds.truncate(kept);
        self.scratch.contacts = contacts;
        self.scratch.rotations = rotations;

        // Waking: repeat until nothing changes (a woken island may touch another sleeping one). Nothing to do
        // when no body sleeps (always so with sleeping off): one scan of the bodies instead of a look at every
        // manifold and joint.
        if !self.state.bodies.iter().any(|(_, body)| body.is_sleeping()) {
            self.scratch.approach_speeds = speeds;
            self.scratch.manifolds = manifolds;
            return;
        }
        let mut to_wake = core::mem::take(&mut self.scratch.to_wake);
        loop {
            to_wake.clear();
            for (m, &speed) in manifolds.iter().zip(&speeds) {
                // Touching, or closing the gap within this step: a sleeping body about to be hit must be in
                // the solver when the hit comes.
                let gap = m
                    .points()
                    .iter()
                    .map(|p| p.separation)
                    .fold(f32::INFINITY, f32::min);
                if gap <= speed * dt {
                    collect_wake(&self.state.bodies, m.body_a, m.body_b, &mut to_wake);
                }
            }
            for (_, joint) in self.state.joints.iter() {
                if joint.state.broken {
                    continue;
                }
                if let Some(a) = joint.body_a {
                    collect_wake(&self.state.bodies, a, joint.body_b, &mut to_wake);
                }
            }
            if to_wake.is_empty() {
                break;
            }
            for &handle in &to_wake {
                self.wake_island_of(handle);
            }
        }
        self.scratch.to_wake = to_wake;
        self.scratch.approach_speeds = speeds;
        self.scratch.manifolds = manifolds;
    }

    /// Stage *prepare*, part 1: the dense solver arrays. Awake moving bodies in handle order get indices
    /// first; fixed bodies are added when a contact or joint needs them; the world anchor (a fixed body at the
    /// origin) last, if a world joint exists.
    fn build_solver_bodies(&mut self) {
        let s = &mut self.scratch;
        s.solver_index.clear();
        s.solver_index
            .resize(self.state.bodies.slot_count(), NO_INDEX);
        s.solver_handles.clear();
        s.states.clear();
        s.params.clear();
        for (index, entry) in self.state.bodies.arena.iter() {
            let body = &entry.body;
            if body.is_sleeping() || body.body_type() == BodyType::Fixed {
                continue;
            }
            s.solver_index[index.index as usize] = s.states.len() as u32;
            s.solver_handles.push(Some(BodyHandle(index)));
            s.states.push(SolverBody::from_body(body));
            s.params.push(BodyParams::from_body(body));
        }
    }

    /// The solver index of `handle`, adding a fixed body on first use. `None` for sleeping bodies (whose
    /// constraints wait) and stale handles.
    fn solver_index_of(
        scratch: &mut Scratch,
        bodies: &BodySet,
        handle: BodyHandle,
    ) -> Option<usize> {
        let slot = BodySet::slot(handle);
        let existing = *scratch.solver_index.get(slot)?;
        if existing != NO_INDEX {
            return Some(existing as usize);
        }
        let body = bodies.get(handle)?;
        if body.body_type() != BodyType::Fixed {
            return None;
        }
        let index = scratch.states.len();
        scratch.solver_index[slot] = index as u32;
        scratch.solver_handles.push(Some(handle));
        scratch.states.push(SolverBody::STATIC);
        scratch.params.push(BodyParams::from_body(body));
        Some(index)
    }

    /// Stage *prepare*, part 2: the contacts between an awake body and anything it can push (the collide stage
    /// wrote one per manifold, with anchors relative to the centres of mass) get their bodies' solver indices;
    /// the others are dropped, the kept ones moving down in order. Then the contact solver's preparation.
    fn build_contacts(&mut self, ctx: &StepContext, report: &mut StepReport) {
        let s = &mut self.scratch;
        s.contact_sources.clear();
        let mut kept = 0;
        for source in 0..s.manifolds.len().min(s.contacts.len()) {
            let (handle_a, handle_b) = (s.manifolds[source].body_a, s.manifolds[source].body_b);
            let ia = Self::solver_index_of(s, &self.state.bodies, handle_a);
            let ib = Self::solver_index_of(s, &self.state.bodies, handle_b);
            let (Some(ia), Some(ib)) = (ia, ib) else {
                continue;
            };
            if !s.params[ia].is_dynamic() && !s.params[ib].is_dynamic() {
                continue;
            }
            if kept != source {
                s.contacts.swap(kept, source);
            }
            let contact = &mut s.contacts[kept];
            kept += 1;
            (contact.body_a, contact.body_b) = (ia, ib);
            report.contact_point_count += contact.point_count;
            s.contact_sources.push(source);
        }
        s.contacts.truncate(kept);
        report.contact_count = s.contacts.len();
        report.rejected_contact_count +=
            s.contact_solver
                .prepare(&s.contacts, &s.states, &s.params, ctx);
    }

    /// Stage *prepare*, part 3: joints whose bodies are awake (or fixed), then the joint solver's preparation.
    fn build_joints(&mut self, ctx: &StepContext, report: &mut StepReport) {
        let s = &mut self.scratch;
        s.joints.clear();
        s.joint_states.clear();
        s.joint_bodies.clear();
        s.joint_handles.clear();
        let mut world_anchor: Option<usize> = None;
        for (index, entry) in self.state.joints.iter() {
            if entry.state.broken {
                continue;
            }
            let Some(b) = Self::solver_index_of(s, &self.state.bodies, entry.body_b) else {
                continue;
            };
            let a = match entry.body_a {
                Some(handle) => match Self::solver_index_of(s, &self.state.bodies, handle) {
                    Some(a) => a,
                    None => continue,
                },
                None => *world_anchor.get_or_insert_with(|| {
                    let index = s.states.len();
                    s.solver_handles.push(None);
                    s.states.push(SolverBody::STATIC);
                    s.params.push(BodyParams::WORLD);
                    index
                }),
            };
            if !s.params[a].is_dynamic() && !s.params[b].is_dynamic() {
                continue;
            }
            s.joints.push(entry.joint);
            s.joint_states.push(entry.state);
            s.joint_bodies.push(JointBodies { a, b });
            s.joint_handles.push(JointHandle(index));
        }
        report.joint_count = s.joints.len();
        if s.joint_solver.settings() != &self.state.settings.joints {
            // `WorldSettings` are validated whenever they are set, so this cannot fail.
            let applied = s.joint_solver.set_settings(self.state.settings.joints);
            debug_assert!(applied.is_ok(), "world settings are validated on entry");
        }
        let skipped = s.joint_solver.prepare(
            &s.joints,
            &s.joint_states,
            &s.joint_bodies,
            &s.states,
            &s.params,
            ctx,
        );
        debug_assert_eq!(
            skipped, 0,
            "the world hands the joint solver only valid joints"
        );
    }

    /// Stage *substeps*.
    fn solve_substeps(&mut self, ctx: &StepContext) {
        let s = &mut self.scratch;
        for _ in 0..ctx.substep_count {
            integrate_velocities(&mut s.states, &s.params, ctx);
            s.joint_solver.apply_forces(&mut s.states, ctx);
            s.joint_solver.warm_start(&mut s.states);
            s.contact_solver.warm_start(&mut s.states);
            s.joint_solver.solve(&mut s.states, ctx, Bias::On);
            s.contact_solver.solve(&mut s.states, ctx, Bias::On);
            integrate_positions(&mut s.states, &s.params, ctx);
            s.joint_solver.solve(&mut s.states, ctx, Bias::Off);
            s.contact_solver.solve(&mut s.states, ctx, Bias::Off);
        }
        s.joint_solver.project_positions(&mut s.states, ctx);
    }

    /// Stage *restitution*: ropes that went taut jerk back. (Contacts bounce inside the solve, where impulses
    /// can pass along a row of touching bodies — Newton's cradle — see `rebound_dynamics::contact`.)
    fn apply_restitution(&mut self, ctx: &StepContext) {
        let s = &mut self.scratch;
        s.joint_solver.apply_restitution(&mut s.states, ctx);
    }

    /// Stage *store impulses*: manifolds keep theirs for the next step; joint states likewise; joints that
    /// exceeded their break limits are marked broken and reported.
    fn store_impulses(&mut self, report: &mut StepReport) {
        let s = &mut self.scratch;
        // Straight into the manifolds (the solver's contacts are not read again): impulses for the next
        // step's warm start, and whether each manifold pushed (for the touching test of the events).
        s.pushed.clear();
        s.pushed.resize(s.manifolds.len(), false);
        let (manifolds, pushed, sources) = (&mut s.manifolds, &mut s.pushed, &s.contact_sources);
        s.contact_solver
            .for_each_point_result(|contact, k, normal, tangent, max| {
                let Some(&source) = sources.get(contact) else {
                    return;
                };
                if let Some(point) = manifolds[source].points.get_mut(k) {
                    point.normal_impulse = normal;
                    point.tangent_impulse = tangent;
                }
                pushed[source] |= max > 0.0;
            });
        s.broken.clear();
        s.joint_solver
            .store_impulses(&mut s.joint_states, &mut s.broken);
        for (handle, state) in s.joint_handles.iter().zip(&s.joint_states) {
            if let Some(entry) = self.state.joints.get_mut(handle.0) {
                entry.state = *state;
            }
        }
        report.broken_joint_count = s.broken.len();
        for &i in &s.broken {
            if let Some(handle) = s.joint_handles.get(i) {
                self.events.push(Event::JointBroken { joint: *handle });
            }
        }
        core::mem::swap(&mut self.state.manifolds, &mut s.manifolds);
    }

    /// Stage *finalize*: poses and velocities back into the bodies.
    fn write_back(&mut self) {
        let s = &self.scratch;
        for ((handle, state), params) in s.solver_handles.iter().zip(&s.states).zip(&s.params) {
            let Some(handle) = handle else { continue };
            if let Some(entry) = self.state.bodies.entry_mut(*handle) {
                // A refused (non-finite) result leaves the body where it was; the finite-state tests guard
                // that this never happens.
                let _accepted = params.write_back(state, &mut entry.body);
            }
        }
    }

    /// Stage *islands and sleep*: rest timers, then islands of awake bodies linked by touching contacts and
    /// joints; an island whose bodies have all rested long enough falls asleep.
    fn update_sleep(&mut self, dt: f32) {
        let settings = self.state.settings;
        let s = &mut self.scratch;
        let n = s.solver_handles.len();
        // Rest timers of the awake moving bodies; `can_rest[i]` is false for bodies that keep an island awake.
        let mut can_rest = core::mem::take(&mut s.can_rest);
        can_rest.clear();
        can_rest.resize(n, false);
        for (i, handle) in s.solver_handles.iter().enumerate() {
            let Some(handle) = handle else { continue };
            let Some(entry) = self.state.bodies.entry_mut(*handle) else {
                continue;
            };
            let body = &entry.body;
            if body.body_type() == BodyType::Fixed {
                continue;
            }
            let resting = body.linear_velocity().length() < settings.linear_sleep_threshold
                && body.angular_velocity().length() < settings.angular_sleep_threshold;
            entry.sleep_time = if resting { entry.sleep_time + dt } else { 0.0 };
            can_rest[i] = settings.sleep_enabled
                && body.can_sleep()
                && body.body_type() == BodyType::Dynamic
                && entry.sleep_time >= settings.time_to_sleep;
        }
        if !can_rest.contains(&true) {
            // No island can fall asleep (sleeping off, or everything moving): no islands to build.
            s.can_rest = can_rest;
            return;
        }
        s.union_find.reset(n);
        // Only dynamic bodies link islands: fixed and kinematic bodies are shared by many islands.
        let moving = |i: usize| s.params.get(i).is_some_and(BodyParams::is_dynamic);
        let mut links = core::mem::take(&mut s.links);
        links.clear();
        // Every manifold links its bodies, speculative ones too: bodies within the speculative margin of
        // each other can meet within a step, so they sleep and wake together (a row of balls 1 mm apart
        // must all be awake when the first is struck).
        for contact in &s.contacts {
            if moving(contact.body_a) && moving(contact.body_b) {
                links.push((contact.body_a as u32, contact.body_b as u32));
            }
        }
        for bodies in &s.joint_bodies {
            if moving(bodies.a) && moving(bodies.b) {
                links.push((bodies.a as u32, bodies.b as u32));
            }
        }
        for &(a, b) in &links {
            s.union_find.union(a, b);
        }
        s.links = links;
        // An island may sleep only if every member may.
        let mut island_ok = core::mem::take(&mut s.island_ok);
        island_ok.clear();
        island_ok.resize(n, true);
        for (i, &rest) in can_rest.iter().enumerate() {
            if s.params.get(i).is_some_and(|p| p.motion != Motion::Fixed) {
                let root = s.union_find.find(i as u32) as usize;
                island_ok[root] &= rest;
            }
        }
        s.can_rest = can_rest;
        let mut sleepers = core::mem::take(&mut s.sleepers);
        sleepers.clear();
        for i in 0..n {
            let Some(handle) = s.solver_handles[i] else {
                continue;
            };
            if s.params[i].motion == Motion::Fixed {
                continue;
            }
            let root = s.union_find.find(i as u32);
            if island_ok[root as usize] {
                sleepers.push((root, handle));
            }
        }
        s.island_ok = island_ok;
        // Roots are the lowest solver index of each island, handles are in handle order: deterministic.
        sleepers.sort_unstable();
        let mut current_root = None;
        let mut island_id = 0;
        for &(root, handle) in &sleepers {
            if current_root != Some(root) {
                current_root = Some(root);
                island_id = self.state.next_island;
                self.state.next_island = self.state.next_island.wrapping_add(1);
                self.state.islands.insert(island_id, Vec::new());
            }
            if let Some(entry) = self.state.bodies.entry_mut(handle) {
                entry.island = island_id;
                entry.body.set_sleeping(true);
                // A sleeping body is at rest: clear the residual velocity so that it wakes exactly as it slept.
                let _ = entry.body.set_linear_velocity(Vec3::ZERO);
                let _ = entry.body.set_angular_velocity(Vec3::ZERO);
                entry.body.set_sleeping(true);
            }
            if let Some(members) = self.state.islands.get_mut(&island_id) {
                members.push(handle);
            }
            self.events.push(Event::BodyFellAsleep { body: handle });
        }
        self.scratch.sleepers = sleepers;
    }

    /// Stage *events*: contact begin/end from the touching pairs, woken bodies; sorted.
    fn emit_events(&mut self) {
        let s = &mut self.scratch;
        // Touching pairs with their approach speeds, sorted by pair: O(m log m) for m manifolds.
        s.touching_speeds.clear();
        for ((m, &pushed), &speed) in self
            .state
            .manifolds
            .iter()
            .zip(&s.pushed)
            .zip(&s.approach_speeds)
        {
            // Touching: overlapping, or pushed this step (a speculative contact that closed its gap, a bounce).
            if m.is_touching() || pushed {
                let pair = if m.body_a <= m.body_b {
                    (m.body_a, m.body_b)
                } else {
                    (m.body_b, m.body_a)
                };
                s.touching_speeds.push((pair, speed));
            }
        }
        s.touching_speeds.sort_unstable_by_key(|x| x.0);
        s.touching.clear();
        let mut contact_events = core::mem::take(&mut s.contact_events);
        contact_events.clear();
        let mut last = self.state.touching.iter().peekable();
        let mut i = 0;
        while i < s.touching_speeds.len() {
            let pair = s.touching_speeds[i].0;
            let mut approach_speed = 0.0f32;
            while i < s.touching_speeds.len() && s.touching_speeds[i].0 == pair {
                approach_speed = approach_speed.max(s.touching_speeds[i].1);
                i += 1;
            }
            s.touching.push(pair);
            // Both lists are sorted: a forward walk through last step's.
            if walk_to(&mut last, &pair, |&old| old).is_none() {
                contact_events.push(Event::ContactBegan {
                    body_a: pair.0,
                    body_b: pair.1,
                    approach_speed,
                });
            }
        }
        let mut now = s.touching.iter().peekable();
        for pair in &self.state.touching {
            if walk_to(&mut now, pair, |&new| new).is_none() {
                contact_events.push(Event::ContactEnded {
                    body_a: pair.0,
                    body_b: pair.1,
                });
            }
        }
        core::mem::swap(&mut self.state.touching, &mut s.touching);
        // Contact events first (pair order), then what the step already pushed (broken joints, sleep), then
        // wakes.
        // `events` holds what the step already pushed; put the contact events in front of it.
        contact_events.append(&mut self.events);
        core::mem::swap(&mut self.events, &mut contact_events);
        self.scratch.contact_events = contact_events;
        self.woken.sort_unstable();
        self.woken.dedup();
        self.events
            .extend(self.woken.drain(..).map(|body| Event::BodyWoke { body }));
    }
}

/// One step of a forward walk through a list sorted by `key_of`, for keys asked in increasing order: skips the
/// items below `key` and returns the one equal to it, if any (O(n + m) for two sorted lists, and sequential
/// reads, where a binary search per key misses the cache at every probe).
fn walk_to<'a, T: 'a, K: Ord>(
    walk: &mut core::iter::Peekable<impl Iterator<Item = &'a T>>,
    key: &K,
    key_of: impl Fn(&T) -> K,
) -> Option<&'a T> {
    while walk.next_if(|item| key_of(item) < *key).is_some() {}
    walk.next_if(|item| key_of(item) == *key)
}

/// Whether a backend's manifold (between live bodies) can be used: distinct bodies, finite unit normal, at most
/// [`crate::MAX_MANIFOLD_POINTS`] points, all finite.
fn is_usable(m: &ContactManifold) -> bool {
    m.body_a != m.body_b
        && m.point_count <= crate::MAX_MANIFOLD_POINTS
        && m.normal.is_finite()
        // |n|² within 2e-3 of 1 (|n| within 1e-3 of 1, to first order), without the square root.
        && (m.normal.length_squared() - 1.0).abs() < 2.0e-3
        && m.friction.is_finite()
        && m.friction >= 0.0
        && m.restitution.is_finite()
        && m.restitution >= 0.0
        && m.rolling_friction.is_finite()
        && m.rolling_friction >= 0.0
        && points_are_finite(m.points())
}

/// Whether every anchor and separation of `points` is finite, without a branch per number: `x·0` is `±0` for
/// a finite `x` and NaN for an infinite or NaN one, so the sum of the products is zero exactly when every
/// number is finite (a pile's step checks ~10,000 points).
fn points_are_finite(points: &[crate::ManifoldPoint]) -> bool {
    let zero_if_finite = points.iter().fold(Vec3::ZERO, |sum, p| {
        sum + p.local_anchor_a * 0.0 + p.local_anchor_b * 0.0 + Vec3::splat(p.separation * 0.0)
    });
    zero_if_finite == Vec3::ZERO
}

/// If exactly one of two bodies is awake and moving and the other asleep, the sleeper must wake.
fn collect_wake(bodies: &BodySet, a: BodyHandle, b: BodyHandle, out: &mut Vec<BodyHandle>) {
    let (Some(ea), Some(eb)) = (bodies.entry(a), bodies.entry(b)) else {
        return;
    };
    let active = |e: &crate::body_set::BodyEntry| {
        !e.body.is_sleeping() && e.body.body_type() != BodyType::Fixed
    };
    let asleep = |e: &crate::body_set::BodyEntry| e.body.is_sleeping();
    if active(ea) && asleep(eb) {
        out.push(b);
    } else if active(eb) && asleep(ea) {
        out.push(a);
    }
}

/// The approach speed of a manifold before the step: the fastest closing normal velocity over its points
/// (m/s, ≥ 0).
fn approach_speed(
    m: &ContactManifold,
    a: &rebound_dynamics::RigidBody,
    b: &rebound_dynamics::RigidBody,
) -> f32 {
    // The centres of mass found once per manifold (each is a rotation of the local centre), not per point.
    let (center_a, center_b) = (a.center_of_mass(), b.center_of_mass());
    m.points().iter().fold(0.0f32, |speed, p| {
        let world = a.pose().transform_point(p.local_anchor_a);
        let closing = -(b.velocity_at_offset(world - center_b)
            - a.velocity_at_offset(world - center_a))
        .dot(m.normal);
        speed.max(closing)
    })
}
