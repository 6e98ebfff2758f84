//! `PhysicsWorld`: the world of `rebound-world` with the parry3d backend, colliders, sensors, queries,
//! events and snapshots — the type most users hold. The step itself is the world's (`docs/architecture.md`,
//! "The step pipeline and its data flow"); this type adds what happens around it: colliders' mass summed into
//! bodies on insertion and removal, the query BVH refreshed and sensor overlaps found after each step.

use crate::backend::SharedHooks;
use crate::hooks::ContactHooks;
use crate::sensors::{SensorPresence, update_sensors};
use crate::sweep::{SweepScratch, sweep};
use crate::{ColliderHandle, Error, Event, ParryBackend};
use parry3d::bounding_volume::Aabb;
use rebound_dynamics::{BodyDesc, MassProperties, RigidBody};
use rebound_math::Pose;
use rebound_world::{
    AdvanceReport, BodyHandle, BodySet, ContactManifold, JointHandle, RemovedBody, StepReport,
    World, WorldError, WorldSettings,
};
use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;
use std::sync::atomic::{AtomicU32, Ordering};

mod colliders;
mod joints;
mod queries;
#[cfg(feature = "parallel")]
mod threads;
#[cfg(feature = "parallel")]
pub use threads::MIN_WORK_FOR_THREADS;

/// Counter behind the per-world collider handle generation base (as the world's own for bodies and joints).
static NEXT_WORLD: AtomicU32 = AtomicU32::new(1);

/// A physics world: bodies, joints and colliders on parry3d shapes, stepped by Rebound's soft step.
///
/// ```
/// use rebound::prelude::*;
///
/// let mut world = PhysicsWorld::new(WorldSettings::default())?;
/// let ground = world.insert_body(BodyDesc::fixed())?;
/// world.insert_collider(ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0)), ground)?;
/// let ball = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 4.0, 0.0)))?;
/// world.insert_collider(ColliderDesc::ball(0.5).with_restitution(0.5), ball)?;
/// for _ in 0..240 {
///     world.step(1.0 / 60.0);
/// }
/// let y = world.body(ball).map_or(f32::NAN, |b| b.position().y);
/// assert!((y - 1.0).abs() < 0.02, "resting on the ground (top at 0.5 m): {y}");
/// # Ok::<(), rebound::Error>(())
/// ```
#[derive(Debug)]
pub struct PhysicsWorld {
    pub(crate) world: World<ParryBackend>,
    /// Each body's own mass properties (from its description), used while its colliders add no mass.
    pub(crate) own_mass: BTreeMap<BodyHandle, MassProperties>,
    /// Joints whose two bodies do not collide with each other.
    pub(crate) joints_without_contacts: BTreeSet<JointHandle>,
    /// (sensor, collider) pairs overlapping after the last step, sorted.
    pub(crate) sensor_overlaps: Vec<(ColliderHandle, ColliderHandle)>,
    /// Whether the colliders hold a sensor: without one (and no overlap left to end), no sensor pass.
    sensors: SensorPresence,
    /// Time [`PhysicsWorld::advance`] has not yet stepped (s).
    pub(crate) accumulator: f32,
    events: Vec<Event>,
    /// The rotational sweep's buffers.
    sweep: SweepScratch,
    /// The pool the step runs on (`None`: rayon's global pool, or the one installed around the call).
    #[cfg(feature = "parallel")]
    thread_pool: Option<Arc<rebound_math::par::rayon::ThreadPool>>,
    /// The last step's bodies moved plus contact manifolds solved (`None` before the first step, when the
    /// body count stands for it): below `min_work_for_threads` the next step runs on one thread.
    #[cfg(feature = "parallel")]
    last_work: Option<usize>,
    /// See [`PhysicsWorld::set_min_work_for_threads`].
    #[cfg(feature = "parallel")]
    min_work_for_threads: usize,
}

impl PhysicsWorld {
    /// An empty world.
    ///
    /// # Errors
    /// Invalid `settings` ([`WorldSettings::validate`]), as [`Error::World`].
    pub fn new(settings: WorldSettings) -> Result<Self, Error> {
        let base = NEXT_WORLD
            .fetch_add(1, Ordering::Relaxed)
            .wrapping_mul(0x85EB_CA6B);
        let world = World::with_backend(settings, ParryBackend::with_generation_base(base))?;
        Ok(Self {
            world,
            own_mass: BTreeMap::new(),
            joints_without_contacts: BTreeSet::new(),
            sensor_overlaps: Vec::new(),
            sensors: SensorPresence::default(),
            accumulator: 0.0,
            events: Vec::new(),
            sweep: SweepScratch::default(),
            #[cfg(feature = "parallel")]
            thread_pool: None,
            #[cfg(feature = "parallel")]
            last_work: None,
            #[cfg(feature = "parallel")]
            min_work_for_threads: MIN_WORK_FOR_THREADS,
        })
    }

    /// The underlying world (bodies, joints, contacts, the backend with its colliders), read-only. Every
    /// change goes through `PhysicsWorld`, which keeps colliders, masses and the BVH in step.
    #[must_use]
    pub fn world(&self) -> &World<ParryBackend> {
        &self.world
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &WorldSettings {
        self.world.settings()
    }

    /// Replaces the settings.
    ///
    /// # Errors
    /// Invalid `settings`; the old ones stay.
    pub fn set_settings(&mut self, settings: WorldSettings) -> Result<(), Error> {
        Ok(self.world.set_settings(settings)?)
    }

    // ---- bodies ----

    /// Adds a body. Its description's mass properties are kept as the body's own: they apply while none of
    /// its colliders adds mass (density 0, or no colliders).
    ///
    /// # Errors
    /// An invalid description ([`Error::World`] naming the field); the world is unchanged.
    pub fn insert_body(&mut self, desc: BodyDesc) -> Result<BodyHandle, Error> {
        let handle = self.world.insert_body(&desc)?;
        self.own_mass.insert(handle, desc.mass_properties);
        Ok(handle)
    }

    /// Removes a body with its colliders and the joints attached to it (returned).
    ///
    /// # Errors
    /// [`WorldError::StaleBody`].
    pub fn remove_body(&mut self, handle: BodyHandle) -> Result<RemovedBody, Error> {
        let boxes: Vec<Aabb> = self
            .colliders()
            .of_body(handle)
            .iter()
            .filter_map(|&c| self.collider_aabb(c))
            .collect();
        let removed = self.world.remove_body(handle)?;
        let backend = self.world.backend_mut();
        for collider in backend.colliders.of_body(handle).to_vec() {
            backend.colliders.remove(collider);
            backend.broad_phase.remove_leaf(collider);
        }
        self.own_mass.remove(&handle);
        for (joint, _) in &removed.joints {
            self.joints_without_contacts.remove(joint);
        }
        self.update_disabled_pairs();
        self.wake_bodies_touching(&boxes);
        Ok(removed)
    }

    /// The body behind `handle`.
    #[inline]
    #[must_use]
    pub fn body(&self, handle: BodyHandle) -> Option<&RigidBody> {
        self.world.body(handle)
    }

    /// The body behind `handle`, mutably (its setters validate). A pose changed here reaches queries after the
    /// next step or [`PhysicsWorld::refresh_queries`]; until then queries test every collider (correct, but
    /// slower). Mass properties set here are replaced when the body's colliders change while any of them
    /// has a density: use [`PhysicsWorld::set_body_mass_properties`].
    pub fn body_mut(&mut self, handle: BodyHandle) -> Option<&mut RigidBody> {
        if self.world.body(handle).is_some() {
            self.world.backend_mut().broad_phase.mark_stale();
        }
        self.world.body_mut(handle)
    }

    /// All bodies.
    #[must_use]
    pub fn bodies(&self) -> &BodySet {
        self.world.bodies()
    }

    /// Sets a body's own mass properties: used while none of its colliders adds mass. Wakes the body.
    ///
    /// # Errors
    /// [`WorldError::StaleBody`].
    pub fn set_body_mass_properties(
        &mut self,
        handle: BodyHandle,
        mass_properties: MassProperties,
    ) -> Result<(), Error> {
        if self.world.body(handle).is_none() {
            return Err(WorldError::StaleBody(handle).into());
        }
        let previous = self.own_mass.insert(handle, mass_properties);
        match self.body_mass(handle, None, None) {
            Ok(mass) => {
                self.set_mass(handle, mass);
                Ok(())
            }
            Err(error) => {
                if let Some(previous) = previous {
                    self.own_mass.insert(handle, previous);
                }
                Err(error)
            }
        }
    }

    /// Asks a kinematic body to reach `target` at the end of the next step (see
    /// [`World::set_kinematic_target`]).
    ///
    /// # Errors
    /// A stale handle, a body that is not kinematic, or an invalid pose.
    pub fn set_kinematic_target(&mut self, handle: BodyHandle, target: Pose) -> Result<(), Error> {
        Ok(self.world.set_kinematic_target(handle, target)?)
    }

    /// Wakes a body and its island.
    ///
    /// # Errors
    /// [`WorldError::StaleBody`].
    pub fn wake_body(&mut self, handle: BodyHandle) -> Result<(), Error> {
        Ok(self.world.wake_body(handle)?)
    }

    /// Whether the body is asleep (`None` for a stale handle).
    #[must_use]
    pub fn is_sleeping(&self, handle: BodyHandle) -> Option<bool> {
        self.world.is_sleeping(handle)
    }

    /// Whether the body is quarantined (`None` for a stale handle; see [`World::is_quarantined`]).
    #[must_use]
    pub fn is_quarantined(&self, handle: BodyHandle) -> Option<bool> {
        self.world.is_quarantined(handle)
    }

    /// Puts a quarantined body back into the steps (see [`World::release_quarantine`]).
    ///
    /// # Errors
    /// [`WorldError::StaleBody`].
    pub fn release_quarantine(&mut self, handle: BodyHandle) -> Result<(), Error> {
        Ok(self.world.release_quarantine(handle)?)
    }

    // ---- time ----

    /// Advances the simulation by `dt` seconds (see [`World::step`]): never fails; a `dt` that is not a
    /// positive finite number moves nothing and the report says so. Afterwards the query BVH holds the new
    /// poses and sensor overlaps are updated; [`PhysicsWorld::events`] holds this step's events.
    pub fn step(&mut self, dt: f32) -> StepReport {
        self.events.clear();
        self.step_and_collect(dt)
    }

    fn step_and_collect(&mut self, dt: f32) -> StepReport {
        #[cfg(feature = "parallel")]
        if let Some(pool) = self.thread_pool.clone() {
            return pool.install(|| self.step_here(dt));
        }
        self.step_here(dt)
    }

    /// One step on the current thread pool (see [`PhysicsWorld::set_thread_pool`]), with the pool's other
    /// threads kept awake between its parallel sections (`par::with_pool_awake`); on this thread alone
    /// (`par::serially`) after a step smaller than [`PhysicsWorld::set_min_work_for_threads`] says.
    fn step_here(&mut self, dt: f32) -> StepReport {
        // Before the first step, the bodies stand for the work.
        #[cfg(feature = "parallel")]
        if self.last_work.unwrap_or_else(|| self.world.bodies().len()) < self.min_work_for_threads {
            return rebound_math::par::serially(|| self.step_awake(dt));
        }
        rebound_math::par::with_pool_awake(|| self.step_awake(dt))
    }

    /// [`PhysicsWorld::step_here`]'s step.
    fn step_awake(&mut self, dt: f32) -> StepReport {
        let mut report = self.world.step(dt);
        report.hook_failure_count = self.world.backend().hook_failures;
        #[cfg(feature = "parallel")]
        if report.skipped.is_none() {
            self.last_work = Some(report.awake_body_count + report.contact_count);
        }
        let narrow_phase = &self.world.backend().narrow_phase;
        self.events
            .extend(self.world.events().iter().map(|&event| match event {
                rebound_world::Event::ContactForce(force) => Event::ContactForce {
                    colliders: narrow_phase.force_pair(force.key),
                    force,
                },
                event => Event::from(event),
            }));
        if report.broken_joint_count > 0 {
            // A broken joint no longer keeps its bodies apart.
            self.update_disabled_pairs();
        }
        if report.skipped.is_none() {
            self.after_step();
            if !self.world.backend().broad_phase.swept().is_empty() {
                sweep(&mut self.sweep, &mut self.world, dt);
            }
        }
        report
    }

    /// Sets the contact hooks, replacing any ([`ContactHooks`]): `hooks` may drop candidate pairs and
    /// edit every manifold before the solver sees it, each step, in pair order. A closure
    /// `|pair: &ContactPair, contacts: &mut ContactEdit| { .. }` is a hook. Hooks are not part of a snapshot.
    pub fn set_contact_hooks(&mut self, hooks: impl ContactHooks + 'static) {
        self.world.backend_mut().hooks = Some(SharedHooks(Arc::new(hooks)));
    }

    /// Removes the contact hooks.
    pub fn clear_contact_hooks(&mut self) {
        self.world.backend_mut().hooks = None;
    }

    /// Refreshes the query BVH at the current poses and updates sensor overlaps.
    fn after_step(&mut self) {
        // The world lends out its bodies or its backend, not both; the backend is moved out for the moment.
        let mut backend = core::mem::take(self.world.backend_mut());
        let bodies = self.world.bodies();
        backend.broad_phase.refresh(&backend.colliders, bodies);
        if !self.sensor_overlaps.is_empty() || self.sensors.any(&backend.colliders) {
            let mut sensor_events = Vec::new();
            update_sensors(
                &backend.colliders,
                bodies,
                &backend.broad_phase,
                &mut self.sensor_overlaps,
                &mut sensor_events,
            );
            self.events.extend(sensor_events);
        }
        *self.world.backend_mut() = backend;
    }

    /// Runs as many whole steps of `settings.fixed_dt` as fit in the time accumulated so far plus `elapsed`
    /// (s), at most `settings.max_steps_per_advance`, and keeps the remainder for the next call: the
    /// fixed-timestep game loop. [`PhysicsWorld::events`] then holds the events of all the steps run. A
    /// negative or non-finite `elapsed` adds nothing. The report's `alpha` interpolates rendered poses.
    pub fn advance(&mut self, elapsed: f32) -> AdvanceReport {
        self.events.clear();
        let mut report = AdvanceReport::default();
        if elapsed.is_finite() && elapsed >= 0.0 {
            self.accumulator += elapsed;
        }
        let settings = *self.world.settings();
        let dt = settings.fixed_dt;
        while self.accumulator >= dt && report.steps < settings.max_steps_per_advance {
            report.last_step = Some(self.step_and_collect(dt));
            self.accumulator -= dt;
            report.steps += 1;
        }
        if self.accumulator >= dt {
            let keep = self.accumulator % dt;
            report.dropped_time = self.accumulator - keep;
            self.accumulator = keep;
        }
        report.alpha = (self.accumulator / dt).clamp(0.0, 1.0);
        report
    }

    /// Steps taken since the world was made (or since the snapshot it was restored from was taken).
    #[must_use]
    pub fn step_count(&self) -> u64 {
        self.world.step_count()
    }

    // ---- contacts and events ----

    /// The events of the last [`PhysicsWorld::step`] (or of every step of the last
    /// [`PhysicsWorld::advance`]): the world's events, then sensor events.
    #[must_use]
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// Takes the events (they are also cleared at the start of the next step).
    pub fn drain_events(&mut self) -> std::vec::Drain<'_, Event> {
        self.events.drain(..)
    }

    /// The contact manifolds of the last step, with their impulses, in body-pair order.
    #[must_use]
    pub fn contacts(&self) -> &[ContactManifold] {
        self.world.contacts()
    }

    /// The (sensor, collider) pairs overlapping after the last step, sorted.
    #[must_use]
    pub fn sensor_overlaps(&self) -> &[(ColliderHandle, ColliderHandle)] {
        &self.sensor_overlaps
    }

    // ---- snapshots (`PhysicsWorld::snapshot` and `restore` are in snapshot.rs) ----

    /// A 64-bit digest of every body's pose and velocities ([`World::state_digest`]): equal digests mean
    /// bit-identical motion state.
    #[must_use]
    pub fn state_digest(&self) -> u64 {
        self.world.state_digest()
    }

    /// Puts every collider's box at its body's current pose into the query BVH. Steps do this themselves;
    /// call it after moving bodies with [`PhysicsWorld::body_mut`] if many queries follow.
    pub fn refresh_queries(&mut self) {
        let mut backend = core::mem::take(self.world.backend_mut());
        backend
            .broad_phase
            .refresh(&backend.colliders, self.world.bodies());
        *self.world.backend_mut() = backend;
    }

    /// Rebuilds the BVH from scratch (after a restore).
    pub(crate) fn rebuild_broad_phase(&mut self) {
        let mut backend = core::mem::take(self.world.backend_mut());
        backend
            .broad_phase
            .rebuild(&backend.colliders, self.world.bodies());
        *self.world.backend_mut() = backend;
    }

    pub(crate) fn clear_events(&mut self) {
        self.events.clear();
    }
}
