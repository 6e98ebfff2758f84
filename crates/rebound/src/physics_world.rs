//! `PhysicsWorld`: the world of `rebound-world` with the parry3d backend, colliders, sensors, queries,
//! events and snapshots — the type most users hold. The step itself is the world's (DESIGN.md §3); this type
//! adds what happens around it: colliders' mass summed into bodies on insertion and removal, the query BVH
//! refreshed and sensor overlaps found after each step.

use crate::broad_phase::{aabb_at, ordered};
use crate::collider::check_solvable;
use crate::query::Scene;
use crate::sensors::update_sensors;
use crate::{
    Collider, ColliderDesc, ColliderHandle, ColliderSet, ColliderShape, CollisionGroups, Error,
    Event, ParryBackend, PhysicsSnapshot, PickHit, PointHit, QueryFilter, RayHit, ShapeHit,
};
use parry3d::bounding_volume::{Aabb, BoundingVolume};
use rebound_constraints::{Joint, JointState};
use rebound_dynamics::{BodyDesc, MassProperties, RigidBody};
use rebound_math::{Pose, Vec3};
use rebound_world::{
    AdvanceReport, BodyHandle, BodySet, ContactManifold, JointHandle, RemovedBody, StepReport,
    World, WorldError, WorldSettings,
};
use std::collections::{BTreeMap, BTreeSet};
use std::sync::atomic::{AtomicU32, Ordering};

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
    /// Time [`PhysicsWorld::advance`] has not yet stepped (s).
    pub(crate) accumulator: f32,
    events: Vec<Event>,
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
            accumulator: 0.0,
            events: Vec::new(),
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
    /// A stale handle or an invalid pose.
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

    // ---- colliders ----

    /// Attaches a collider to `body` and adds its mass (if its density is > 0) to the body's: the body's
    /// mass properties become the combination of its colliders'. Wakes the body.
    ///
    /// # Errors
    /// A stale body, or an invalid description: [`Error::Shape`] for the shape, [`Error::Math`] or
    /// [`Error::OutOfRange`] naming a material field. The world is unchanged.
    pub fn insert_collider(
        &mut self,
        desc: impl Into<ColliderDesc>,
        body: BodyHandle,
    ) -> Result<ColliderHandle, Error> {
        let body_pose = self
            .world
            .body(body)
            .ok_or(WorldError::StaleBody(body))?
            .pose();
        let collider = Collider::new(desc.into(), body)?;
        let mass = self.body_mass(body, None, Some(&collider))?;
        let backend = self.world.backend_mut();
        let handle = backend.colliders.insert(collider).ok_or(Error::Full)?;
        if let Some(collider) = backend.colliders.get(handle) {
            backend.broad_phase.insert_leaf(handle, collider, body_pose);
        }
        // A collider in a freed slot has its predecessor's manifold keys: nothing may be recycled.
        self.world.forget_contact_bases(body);
        self.set_mass(body, mass);
        let boxes: Vec<Aabb> = self.collider_aabb(handle).into_iter().collect();
        self.wake_bodies_touching(&boxes);
        Ok(handle)
    }

    /// Removes a collider and takes its mass out of its body's. Wakes the body.
    ///
    /// # Errors
    /// [`Error::StaleCollider`].
    pub fn remove_collider(&mut self, handle: ColliderHandle) -> Result<ColliderDesc, Error> {
        let body = self
            .collider(handle)
            .ok_or(Error::StaleCollider(handle))?
            .body();
        let mass = if self.world.body(body).is_some() {
            Some(self.body_mass(body, Some((handle, None)), None)?)
        } else {
            None
        };
        let boxes: Vec<Aabb> = self.collider_aabb(handle).into_iter().collect();
        let backend = self.world.backend_mut();
        let collider = backend
            .colliders
            .remove(handle)
            .ok_or(Error::StaleCollider(handle))?;
        backend.broad_phase.remove_leaf(handle);
        self.world.forget_contact_bases(body);
        if let Some(mass) = mass {
            self.set_mass(body, mass);
        }
        self.wake_bodies_touching(&boxes);
        Ok(collider.desc)
    }

    /// The collider behind `handle`.
    #[must_use]
    pub fn collider(&self, handle: ColliderHandle) -> Option<&Collider> {
        self.world.backend().colliders.get(handle)
    }

    /// All colliders.
    #[must_use]
    pub fn colliders(&self) -> &ColliderSet {
        &self.world.backend().colliders
    }

    /// Changes a collider's density (kg/m³, ≥ 0) and its body's mass. Wakes the body.
    ///
    /// # Errors
    /// A stale handle; a negative or non-finite density; mass properties that overflow.
    pub fn set_collider_density(
        &mut self,
        handle: ColliderHandle,
        density: f32,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.density = density)
    }

    /// Moves a collider on its body (pose relative to the body origin) and updates the body's mass. Wakes
    /// the body.
    ///
    /// # Errors
    /// A stale handle; a non-finite position or a non-unit rotation.
    pub fn set_collider_local_pose(
        &mut self,
        handle: ColliderHandle,
        local_pose: Pose,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.local_pose = local_pose)
    }

    /// Changes a collider's friction coefficient (≥ 0). Wakes its body.
    ///
    /// # Errors
    /// A stale handle; a negative or non-finite value.
    pub fn set_collider_friction(
        &mut self,
        handle: ColliderHandle,
        friction: f32,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.friction = friction)
    }

    /// Changes a collider's coefficient of restitution (in [0, 1]). Wakes its body.
    ///
    /// # Errors
    /// A stale handle; a value outside [0, 1].
    pub fn set_collider_restitution(
        &mut self,
        handle: ColliderHandle,
        restitution: f32,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.restitution = restitution)
    }

    /// Changes a collider's collision groups. Wakes its body.
    ///
    /// # Errors
    /// A stale handle.
    pub fn set_collider_groups(
        &mut self,
        handle: ColliderHandle,
        groups: CollisionGroups,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.groups = groups)
    }

    /// Makes a collider a sensor or a solid collider. Wakes its body.
    ///
    /// # Errors
    /// A stale handle.
    pub fn set_collider_sensor(
        &mut self,
        handle: ColliderHandle,
        is_sensor: bool,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.is_sensor = is_sensor)
    }

    /// Enables or disables a collider (a disabled collider takes no part in collisions, sensors, queries or
    /// its body's mass). Wakes its body.
    ///
    /// # Errors
    /// A stale handle.
    pub fn set_collider_enabled(
        &mut self,
        handle: ColliderHandle,
        enabled: bool,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.enabled = enabled)
    }

    /// Applies `edit` to a copy of a collider's description (not its shape), checks it, recomputes the body's
    /// mass, and only then commits both.
    fn edit_collider(
        &mut self,
        handle: ColliderHandle,
        edit: impl FnOnce(&mut ColliderDesc),
    ) -> Result<(), Error> {
        let old = self.collider(handle).ok_or(Error::StaleCollider(handle))?;
        let mut desc = old.desc.clone();
        edit(&mut desc);
        let body = old.body;
        let updated = Collider::with_shape(desc, body, old.shape.clone())?;
        let body_pose = self.world.body(body).map(RigidBody::pose);
        let mass = match body_pose {
            Some(_) => Some(self.body_mass(body, Some((handle, Some(&updated))), None)?),
            None => None,
        };
        let mut boxes: Vec<Aabb> = self.collider_aabb(handle).into_iter().collect();
        let backend = self.world.backend_mut();
        if let Some(slot) = backend.colliders.get_mut(handle) {
            *slot = updated;
        }
        if let (Some(pose), Some(collider)) = (body_pose, backend.colliders.get(handle)) {
            backend.broad_phase.insert_leaf(handle, collider, pose);
        }
        // A moved collider's contacts cannot be recycled (its body's pose did not change).
        self.world.forget_contact_bases(body);
        if let Some(mass) = mass {
            self.set_mass(body, mass);
        }
        boxes.extend(self.collider_aabb(handle));
        self.wake_bodies_touching(&boxes);
        Ok(())
    }

    /// The box of a collider at its body's current pose, grown by the speculative margin.
    fn collider_aabb(&self, handle: ColliderHandle) -> Option<Aabb> {
        let collider = self.collider(handle)?;
        let body = self.world.body(collider.body())?;
        Some(aabb_at(collider, body.pose()).loosened(self.settings().speculative_margin))
    }

    /// Wakes the bodies whose colliders overlap any of `boxes`: what rested on a collider that was removed,
    /// moved or changed must notice (a sleeping body is never tested against a fixed one, so nothing else
    /// would wake it).
    fn wake_bodies_touching(&mut self, boxes: &[Aabb]) {
        // Nothing asleep, nothing to wake: building a scene of n bodies before its first step would otherwise
        // test every collider for every insertion (the query tree is stale until the step), O(n²).
        if boxes.is_empty() || !self.world.has_sleeping_bodies() {
            return;
        }
        let backend = self.world.backend();
        let mut handles = Vec::new();
        backend.broad_phase.candidates(
            &backend.colliders,
            self.world.bodies(),
            |other| boxes.iter().any(|b| b.intersects(other)),
            &mut handles,
        );
        let mut bodies: Vec<BodyHandle> = handles
            .iter()
            .filter_map(|&h| backend.colliders.get(h).map(Collider::body))
            .filter(|&b| self.world.is_sleeping(b) == Some(true))
            .collect();
        bodies.sort_unstable();
        bodies.dedup();
        for body in bodies {
            let _ = self.world.wake_body(body);
        }
    }

    /// The mass properties of `body` from its colliders, with one collider replaced (or removed, `None`) and
    /// one added: the combination of the parts with mass, or the body's own mass properties if there are none.
    fn body_mass(
        &self,
        body: BodyHandle,
        replace: Option<(ColliderHandle, Option<&Collider>)>,
        add: Option<&Collider>,
    ) -> Result<MassProperties, Error> {
        let colliders = &self.world.backend().colliders;
        let mut parts: Vec<MassProperties> = colliders
            .of_body(body)
            .iter()
            .filter_map(|&h| match replace {
                Some((replaced, with)) if replaced == h => with,
                _ => colliders.get(h),
            })
            .filter_map(Collider::mass_properties)
            .collect();
        parts.extend(add.and_then(Collider::mass_properties));
        if parts.is_empty() {
            return Ok(self.own_mass.get(&body).copied().unwrap_or_default());
        }
        let combined = MassProperties::combine(&parts)?;
        check_solvable(&combined)?;
        Ok(combined)
    }

    /// Gives `body` new mass properties and wakes it.
    fn set_mass(&mut self, body: BodyHandle, mass: MassProperties) {
        if let Some(b) = self.world.body_mut(body) {
            b.set_mass_properties(mass);
        }
        let _ = self.world.wake_body(body);
    }

    // ---- joints ----

    /// Connects two bodies with `joint` (its anchor A on `body_a`, anchor B on `body_b`). The two bodies
    /// keep colliding with each other unless [`PhysicsWorld::set_joint_contacts_enabled`] says otherwise.
    /// Wakes both.
    ///
    /// # Errors
    /// A stale handle, or the same body twice. Nothing changes on error.
    pub fn insert_joint(
        &mut self,
        joint: impl Into<Joint>,
        body_a: BodyHandle,
        body_b: BodyHandle,
    ) -> Result<JointHandle, Error> {
        Ok(self.world.insert_joint(joint.into(), body_a, body_b)?)
    }

    /// Connects `body` to a fixed point of the world: the joint's anchor A is a world point (m). Wakes the
    /// body.
    ///
    /// # Errors
    /// A stale handle.
    pub fn insert_world_joint(
        &mut self,
        joint: impl Into<Joint>,
        body: BodyHandle,
    ) -> Result<JointHandle, Error> {
        Ok(self.world.insert_world_joint(joint.into(), body)?)
    }

    /// Removes a joint and wakes the bodies it held.
    ///
    /// # Errors
    /// [`WorldError::StaleJoint`].
    pub fn remove_joint(&mut self, handle: JointHandle) -> Result<Joint, Error> {
        let joint = self.world.remove_joint(handle)?;
        if self.joints_without_contacts.remove(&handle) {
            self.update_disabled_pairs();
        }
        Ok(joint)
    }

    /// The joint behind `handle`.
    #[must_use]
    pub fn joint(&self, handle: JointHandle) -> Option<&Joint> {
        self.world.joint(handle)
    }

    /// The joint behind `handle`, mutably (its setters validate). Wakes the bodies it connects.
    pub fn joint_mut(&mut self, handle: JointHandle) -> Option<&mut Joint> {
        self.world.joint_mut(handle)
    }

    /// The solver state of a joint (accumulated impulses, whether it broke).
    #[must_use]
    pub fn joint_state(&self, handle: JointHandle) -> Option<&JointState> {
        self.world.joint_state(handle)
    }

    /// The bodies a joint connects: `(None, b)` for a world joint.
    #[must_use]
    pub fn joint_bodies(&self, handle: JointHandle) -> Option<(Option<BodyHandle>, BodyHandle)> {
        self.world.joint_bodies(handle)
    }

    /// Whether the two bodies of a joint may collide with each other (`None` for a stale handle). Default:
    /// true.
    #[must_use]
    pub fn joint_contacts_enabled(&self, handle: JointHandle) -> Option<bool> {
        self.world
            .joint(handle)
            .map(|_| !self.joints_without_contacts.contains(&handle))
    }

    /// Lets the two bodies of a joint collide with each other, or not (a rope bridge's planks, a ragdoll's
    /// limbs). Contacts stay disabled while at least one unbroken joint between the pair disables them (a
    /// joint that breaks lets its bodies collide again). Wakes both bodies. No effect on world joints.
    ///
    /// # Errors
    /// [`WorldError::StaleJoint`].
    pub fn set_joint_contacts_enabled(
        &mut self,
        handle: JointHandle,
        enabled: bool,
    ) -> Result<(), Error> {
        let (a, b) = self
            .world
            .joint_bodies(handle)
            .ok_or(WorldError::StaleJoint(handle))?;
        if enabled {
            self.joints_without_contacts.remove(&handle);
        } else {
            self.joints_without_contacts.insert(handle);
        }
        self.update_disabled_pairs();
        if let Some(a) = a {
            let _ = self.world.wake_body(a);
        }
        let _ = self.world.wake_body(b);
        Ok(())
    }

    /// Recomputes the backend's set of body pairs without contacts from the (unbroken) joints that disable
    /// them.
    pub(crate) fn update_disabled_pairs(&mut self) {
        let world = &self.world;
        self.joints_without_contacts
            .retain(|&joint| world.joint(joint).is_some());
        let pairs: BTreeSet<(BodyHandle, BodyHandle)> = self
            .joints_without_contacts
            .iter()
            .filter(|&&joint| world.joint_state(joint).is_some_and(|s| !s.broken))
            .filter_map(|&joint| match world.joint_bodies(joint) {
                Some((Some(a), b)) => Some(ordered(a, b)),
                _ => None,
            })
            .collect();
        self.world.backend_mut().disabled_pairs = pairs;
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
        let report = self.world.step(dt);
        self.events
            .extend(self.world.events().iter().copied().map(Event::from));
        if report.broken_joint_count > 0 {
            // A broken joint no longer keeps its bodies apart.
            self.update_disabled_pairs();
        }
        if report.skipped.is_none() {
            self.after_step();
        }
        report
    }

    /// Refreshes the query BVH at the current poses and updates sensor overlaps.
    fn after_step(&mut self) {
        // The world lends out its bodies or its backend, not both; the backend is moved out for the moment.
        let mut backend = core::mem::take(self.world.backend_mut());
        let bodies = self.world.bodies();
        backend.broad_phase.refresh(&backend.colliders, bodies);
        let mut sensor_events = Vec::new();
        update_sensors(
            &backend.colliders,
            bodies,
            &backend.broad_phase,
            &mut self.sensor_overlaps,
            &mut sensor_events,
        );
        self.events.extend(sensor_events);
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

    // ---- snapshots ----

    /// Captures everything needed to continue: the world's snapshot (bodies, joints, contacts with their
    /// warm-start impulses, sleep, handles) plus the colliders (descriptions, bodies, handles), the bodies'
    /// own mass properties, the joints without contacts, the sensor overlaps and the advance accumulator.
    /// The narrow phase's pair cache is not part of it: a restored world steps bit-identically anyway (see
    /// the crate docs, "Determinism").
    #[must_use]
    pub fn snapshot(&self) -> PhysicsSnapshot {
        PhysicsSnapshot::capture(self)
    }

    /// Restores a snapshot into this world (a rollback, or a load into a fresh world). Handles from the
    /// snapshot resolve again; pending events are cleared; parry shapes are rebuilt from the descriptions.
    ///
    /// # Errors
    /// [`Error::BadSnapshot`] for a snapshot of another format version, with inconsistent handle tables or
    /// invalid colliders, or that the world refuses; the world is unchanged.
    pub fn restore(&mut self, snapshot: &PhysicsSnapshot) -> Result<(), Error> {
        snapshot.restore_into(self)
    }

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

    // ---- queries ----

    fn scene(&self) -> Scene<'_> {
        let backend = self.world.backend();
        Scene {
            colliders: &backend.colliders,
            bodies: self.world.bodies(),
            broad_phase: &backend.broad_phase,
        }
    }

    /// The first collider a ray from `origin` along `direction` (any non-zero length; normalised) hits within
    /// `max_distance` (m, may be +∞). A ray starting inside a collider hits it at distance 0. Ties go to the
    /// lower collider handle.
    ///
    /// # Errors
    /// A non-finite origin, a zero or non-finite direction, a negative or NaN `max_distance`.
    pub fn cast_ray(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<RayHit>, Error> {
        self.scene()
            .cast_ray(origin, direction, max_distance, filter)
    }

    /// Every collider the ray hits within `max_distance`, nearest first (ties by handle).
    ///
    /// # Errors
    /// As [`PhysicsWorld::cast_ray`].
    pub fn cast_ray_all(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Vec<RayHit>, Error> {
        self.scene()
            .cast_ray_all(origin, direction, max_distance, filter)
    }

    /// Sweeps `shape` from `pose` along `direction` (normalised) for up to `max_distance` (m, finite) and
    /// returns the first collider it touches.
    ///
    /// # Errors
    /// An invalid shape or pose, a zero direction, a negative or non-finite `max_distance`.
    pub fn cast_shape(
        &self,
        shape: &ColliderShape,
        pose: Pose,
        direction: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<ShapeHit>, Error> {
        self.scene()
            .cast_shape(shape, pose, direction, max_distance, filter)
    }

    /// The collider closest to `point` within `max_distance` (m, may be +∞), with the closest point on it.
    ///
    /// # Errors
    /// A non-finite point, a negative or NaN `max_distance`.
    pub fn project_point(
        &self,
        point: Vec3,
        max_distance: f32,
        filter: &QueryFilter,
    ) -> Result<Option<PointHit>, Error> {
        self.scene().project_point(point, max_distance, filter)
    }

    /// The colliders overlapping `shape` placed at `pose`, sorted by handle.
    ///
    /// # Errors
    /// An invalid shape or pose.
    pub fn intersect_shape(
        &self,
        shape: &ColliderShape,
        pose: Pose,
        filter: &QueryFilter,
    ) -> Result<Vec<ColliderHandle>, Error> {
        self.scene().intersect_shape(shape, pose, filter)
    }

    /// Drag and drop: the dynamic body under a ray (sensors ignored), with the hit point in world space and in
    /// the body's frame (the anchor for a drag spring). `None` when the ray hits nothing, or hits a fixed or
    /// kinematic collider first.
    ///
    /// # Errors
    /// As [`PhysicsWorld::cast_ray`].
    pub fn pick_body(
        &self,
        origin: Vec3,
        direction: Vec3,
        max_distance: f32,
    ) -> Result<Option<PickHit>, Error> {
        self.scene().pick_body(origin, direction, max_distance)
    }
}
