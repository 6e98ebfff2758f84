//! `World`: owns the state (`state.rs`), the collision backend and the step's buffers, and steps them. The
//! API lives here; the step is in `step.rs`, one file per stage.

use crate::arena::Arena;
use crate::body_set::{BodyEntry, BodySet, NO_ISLAND};
use crate::error::WorldError;
use crate::events::Event;
use crate::handles::{BodyHandle, JointHandle};
use crate::islands;
use crate::manifold::{CollisionBackend, ContactManifold, NoCollision};
use crate::report::AdvanceReport;
use crate::scratch::Scratch;
use crate::settings::WorldSettings;
use crate::snapshot_check;
use crate::state::{JointEntry, WorldState};
use rebound_constraints::{Joint, JointState, KeptRows};
use rebound_dynamics::{BodyDesc, BodyType, RigidBody};
use rebound_math::Pose;
use rebound_math::validity::{check_finite, check_non_negative};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicU32, Ordering};

/// Counter behind the per-world handle generation base.
static NEXT_WORLD: AtomicU32 = AtomicU32::new(1);

/// A saved world state: restore it into the same world (rollback) or a fresh one (load), then step on; the
/// result is bit-identical to never having stopped. Serialisable with the `serde` feature.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct WorldSnapshot {
    /// Format version, checked on restore.
    version: u32,
    state: WorldState,
    /// The joint solver's rows kept for the next step (directly solved hinge paths carry their rows across
    /// the step boundary: see `rebound_constraints::path`).
    joint_rows: KeptRows,
}

/// 2: the joint solver's kept rows were added.
const SNAPSHOT_VERSION: u32 = 2;

impl WorldSnapshot {
    /// The bodies the snapshot holds (to check what refers to them before restoring).
    #[must_use]
    pub fn bodies(&self) -> &BodySet {
        &self.state.bodies
    }

    /// Whether the snapshot holds the joint `handle`.
    #[must_use]
    pub fn contains_joint(&self, handle: JointHandle) -> bool {
        self.state.joints.contains(handle.0)
    }

    /// The joint solver's rows kept for the next step (see [`KeptRows`]).
    #[must_use]
    pub fn kept_joint_rows(&self) -> &KeptRows {
        &self.joint_rows
    }
}

/// What [`World::remove_body`] took out.
#[derive(Debug, Clone, PartialEq)]
pub struct RemovedBody {
    /// The body as it was.
    pub body: RigidBody,
    /// The joints attached to it, removed with it, in handle order.
    pub joints: Vec<(JointHandle, Joint)>,
}

/// A physics world: bodies, joints, a collision backend, and the soft-step pipeline.
///
/// ```
/// use rebound_world::{World, WorldSettings};
/// use rebound_dynamics::BodyDesc;
/// use rebound_math::Vec3;
///
/// let mut world = World::new(WorldSettings::default())?;
/// let ball = world.insert_body(&BodyDesc::dynamic().with_position(Vec3::new(0.0, 10.0, 0.0)))?;
/// for _ in 0..60 {
///     world.step(1.0 / 60.0);
/// }
/// // One second of free fall (semi-implicit Euler, 4 substeps): about 4.9 m.
/// let y = world.body(ball).map(|b| b.position().y);
/// assert!(y.is_some_and(|y| (y - (10.0 - 4.9)).abs() < 0.05));
/// # Ok::<(), rebound_world::WorldError>(())
/// ```
#[derive(Debug)]
pub struct World<B: CollisionBackend = NoCollision> {
    pub(crate) state: WorldState,
    pub(crate) backend: B,
    pub(crate) events: Vec<Event>,
    /// Bodies woken since the last events stage (by the API or during the step); reported as `BodyWoke`.
    pub(crate) woken: Vec<BodyHandle>,
    pub(crate) scratch: Scratch,
}

impl World<NoCollision> {
    /// A world without collision detection (joints, forces and gravity only).
    ///
    /// # Errors
    /// Invalid `settings` ([`WorldSettings::validate`]).
    pub fn new(settings: WorldSettings) -> Result<Self, WorldError> {
        Self::with_backend(settings, NoCollision)
    }
}

impl<B: CollisionBackend> World<B> {
    /// A world that finds contacts with `backend`.
    ///
    /// # Errors
    /// Invalid `settings` ([`WorldSettings::validate`]).
    pub fn with_backend(settings: WorldSettings, backend: B) -> Result<Self, WorldError> {
        settings.validate()?;
        // Each world numbers its handles from its own generation base, so a handle from another world is
        // refused rather than resolved to the wrong body. Worlds made in the same order get the same bases.
        let base = NEXT_WORLD
            .fetch_add(1, Ordering::Relaxed)
            .wrapping_mul(0x9E37_79B9);
        Ok(Self {
            state: WorldState {
                settings,
                bodies: BodySet {
                    arena: Arena::with_generation_base(base),
                    revision: 0,
                },
                joints: Arena::with_generation_base(base ^ 0x5555_5555),
                manifolds: Vec::new(),
                touching: Vec::new(),
                islands: BTreeMap::new(),
                next_island: 0,
                accumulator: 0.0,
                step_count: 0,
            },
            backend,
            events: Vec::new(),
            woken: Vec::new(),
            scratch: Scratch::default(),
        })
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &WorldSettings {
        &self.state.settings
    }

    /// Replaces the settings.
    ///
    /// # Errors
    /// Invalid `settings`; the old ones stay.
    pub fn set_settings(&mut self, settings: WorldSettings) -> Result<(), WorldError> {
        settings.validate()?;
        self.state.settings = settings;
        Ok(())
    }

    /// The collision backend.
    #[must_use]
    pub fn backend(&self) -> &B {
        &self.backend
    }

    /// The collision backend, mutably (to add shapes).
    pub fn backend_mut(&mut self) -> &mut B {
        &mut self.backend
    }

    /// Forgets the [`ContactBasis`](crate::ContactBasis) of every manifold of `body`, so that the backend
    /// computes its contacts from scratch next step: for a backend whose shapes of `body` changed (a collider
    /// added, removed or moved on it), which its recycling could not see in the bodies' poses.
    pub fn forget_contact_bases(&mut self, body: BodyHandle) {
        for m in &mut self.state.manifolds {
            if m.body_a == body || m.body_b == body {
                m.basis = None;
            }
        }
    }

    /// Steps taken since the world was made (or since the snapshot it was restored from was taken).
    #[must_use]
    pub fn step_count(&self) -> u64 {
        self.state.step_count
    }

    // ---- bodies ----

    /// Adds a body.
    ///
    /// # Errors
    /// An invalid description ([`WorldError::Dynamics`] naming the field); the world is unchanged.
    pub fn insert_body(&mut self, desc: &BodyDesc) -> Result<BodyHandle, WorldError> {
        let body = RigidBody::new(desc)?;
        let entry = BodyEntry {
            body,
            sleep_time: 0.0,
            island: NO_ISLAND,
            kinematic_target: None,
            quarantined: false,
        };
        let index = self
            .state
            .bodies
            .arena
            .insert(entry)
            .ok_or(WorldError::Full("bodies"))?;
        let handle = BodyHandle(index);
        self.state.bodies.bump_revision();
        if desc.sleeping && desc.body_type == BodyType::Dynamic {
            // A body created asleep forms an island of its own.
            let island = islands::new_island(&mut self.state);
            if let Some(entry) = self.state.bodies.entry_mut(handle) {
                entry.island = island;
                entry.body.set_sleeping(true);
            }
            self.state.islands.insert(island, vec![handle]);
        } else if let Some(entry) = self.state.bodies.entry_mut(handle) {
            entry.body.set_sleeping(false);
        }
        Ok(handle)
    }

    /// Removes a body and every joint attached to it.
    ///
    /// # Errors
    /// [`WorldError::StaleBody`] if `handle` is not in this world.
    pub fn remove_body(&mut self, handle: BodyHandle) -> Result<RemovedBody, WorldError> {
        if !self.state.bodies.contains(handle) {
            return Err(WorldError::StaleBody(handle));
        }
        self.wake_island_of(handle);
        let attached: Vec<JointHandle> = self
            .state
            .joints
            .iter()
            .filter(|(_, j)| j.body_b == handle || j.body_a == Some(handle))
            .map(|(i, _)| JointHandle(i))
            .collect();
        let mut joints = Vec::with_capacity(attached.len());
        for joint in attached {
            if let Some(entry) = self.state.joints.remove(joint.0) {
                if let Some(a) = entry.body_a {
                    self.wake_island_of(a);
                }
                self.wake_island_of(entry.body_b);
                joints.push((joint, entry.joint));
            }
        }
        let entry = self
            .state
            .bodies
            .arena
            .remove(handle.0)
            .ok_or(WorldError::StaleBody(handle))?;
        self.state.bodies.bump_revision();
        self.state
            .manifolds
            .retain(|m| m.body_a != handle && m.body_b != handle);
        Ok(RemovedBody {
            body: entry.body,
            joints,
        })
    }

    /// The body behind `handle`.
    #[inline]
    #[must_use]
    pub fn body(&self, handle: BodyHandle) -> Option<&RigidBody> {
        self.state.bodies.get(handle)
    }

    /// The body behind `handle`, mutably. Its setters validate their input; any change of motion (a
    /// velocity, a force, an impulse, a teleport) wakes the body and its island at the next step. Counts
    /// as an edit in [`BodySet::revision`] (if `handle` is live).
    pub fn body_mut(&mut self, handle: BodyHandle) -> Option<&mut RigidBody> {
        let bodies = &mut self.state.bodies;
        if bodies.contains(handle) {
            bodies.bump_revision();
        }
        bodies.entry_mut(handle).map(|e| &mut e.body)
    }

    /// All bodies.
    #[must_use]
    pub fn bodies(&self) -> &BodySet {
        &self.state.bodies
    }

    /// Asks a kinematic body to reach `target` at the end of the next step: the step gives it the linear and
    /// angular velocity that gets it there, so it pushes what it meets. Cleared after the step.
    ///
    /// # Errors
    /// A stale handle, a body that is not kinematic ([`WorldError::NotKinematic`]), or a target that is not
    /// finite with a unit rotation. Nothing changes on error.
    pub fn set_kinematic_target(
        &mut self,
        handle: BodyHandle,
        target: Pose,
    ) -> Result<(), WorldError> {
        let target = Pose::try_new(target.position, target.rotation)?;
        let entry = self
            .state
            .bodies
            .entry_mut(handle)
            .ok_or(WorldError::StaleBody(handle))?;
        let body_type = entry.body.body_type();
        if body_type != BodyType::Kinematic {
            return Err(WorldError::NotKinematic { handle, body_type });
        }
        entry.kinematic_target = Some(target);
        entry.body.set_sleeping(false);
        Ok(())
    }

    /// Wakes a body and its island now.
    ///
    /// # Errors
    /// [`WorldError::StaleBody`].
    pub fn wake_body(&mut self, handle: BodyHandle) -> Result<(), WorldError> {
        if !self.state.bodies.contains(handle) {
            return Err(WorldError::StaleBody(handle));
        }
        self.wake_island_of(handle);
        Ok(())
    }

    /// Whether any body is asleep (O(1)): callers that would search for sleeping bodies to wake can skip the
    /// search when none is.
    #[must_use]
    pub fn has_sleeping_bodies(&self) -> bool {
        !self.state.islands.is_empty()
    }

    /// Whether the body is quarantined: taken out of every step because its state left the bounds of
    /// [`crate::StepLimits`] (`None` for a stale handle). See [`crate::Event::BodyQuarantined`].
    #[must_use]
    pub fn is_quarantined(&self, handle: BodyHandle) -> Option<bool> {
        self.state.bodies.entry(handle).map(|e| e.quarantined)
    }

    /// Puts a quarantined body back into the steps (at rest where it is, unless its state was changed since);
    /// the next step checks it again. A body that is not quarantined is left as it is.
    ///
    /// # Errors
    /// [`WorldError::StaleBody`].
    pub fn release_quarantine(&mut self, handle: BodyHandle) -> Result<(), WorldError> {
        let entry = self
            .state
            .bodies
            .entry_mut(handle)
            .ok_or(WorldError::StaleBody(handle))?;
        if entry.quarantined {
            entry.quarantined = false;
            // The body is back among those the step's start checks (see `quarantine.rs`).
            self.state.bodies.bump_revision();
        }
        Ok(())
    }

    /// Whether the body is asleep (`None` for a stale handle).
    #[must_use]
    pub fn is_sleeping(&self, handle: BodyHandle) -> Option<bool> {
        self.body(handle).map(RigidBody::is_sleeping)
    }

    // ---- joints ----

    /// Connects two bodies with `joint` (its anchor A on `body_a`, anchor B on `body_b`). Wakes both.
    ///
    /// # Errors
    /// An invalid joint ([`Joint::validated`]: a description that bypassed its constructors, deserialised),
    /// a stale handle, or the same body twice. Nothing changes on error.
    pub fn insert_joint(
        &mut self,
        joint: Joint,
        body_a: BodyHandle,
        body_b: BodyHandle,
    ) -> Result<JointHandle, WorldError> {
        if !self.state.bodies.contains(body_a) {
            return Err(WorldError::StaleBody(body_a));
        }
        if body_a == body_b {
            return Err(WorldError::SameBody(body_a));
        }
        self.insert_joint_entry(joint, Some(body_a), body_b)
    }

    /// Connects `body` to a fixed point of the world with `joint`: the joint's anchor A is a world-space
    /// point (m), anchor B is on `body`. Drag and drop, a camera boom, a pendulum. Wakes the body.
    ///
    /// # Errors
    /// An invalid joint ([`Joint::validated`]) or a stale handle. Nothing changes on error.
    pub fn insert_world_joint(
        &mut self,
        joint: Joint,
        body: BodyHandle,
    ) -> Result<JointHandle, WorldError> {
        self.insert_joint_entry(joint, None, body)
    }

    fn insert_joint_entry(
        &mut self,
        joint: Joint,
        body_a: Option<BodyHandle>,
        body_b: BodyHandle,
    ) -> Result<JointHandle, WorldError> {
        let joint = joint.validated()?;
        if !self.state.bodies.contains(body_b) {
            return Err(WorldError::StaleBody(body_b));
        }
        let entry = JointEntry {
            joint,
            body_a,
            body_b,
            state: JointState::default(),
        };
        let index = self
            .state
            .joints
            .insert(entry)
            .ok_or(WorldError::Full("joints"))?;
        if let Some(a) = body_a {
            self.wake_island_of(a);
        }
        self.wake_island_of(body_b);
        Ok(JointHandle(index))
    }

    /// Removes a joint and wakes the bodies it held.
    ///
    /// # Errors
    /// [`WorldError::StaleJoint`].
    pub fn remove_joint(&mut self, handle: JointHandle) -> Result<Joint, WorldError> {
        let entry = self
            .state
            .joints
            .remove(handle.0)
            .ok_or(WorldError::StaleJoint(handle))?;
        if let Some(a) = entry.body_a {
            self.wake_island_of(a);
        }
        self.wake_island_of(entry.body_b);
        Ok(entry.joint)
    }

    /// The joint behind `handle`.
    #[must_use]
    pub fn joint(&self, handle: JointHandle) -> Option<&Joint> {
        self.state.joints.get(handle.0).map(|e| &e.joint)
    }

    /// The joint behind `handle`, mutably (its setters validate). Wakes the bodies it connects and clears
    /// its warm-start impulses, since the change may be of kind or frame (whether it is broken stays).
    pub fn joint_mut(&mut self, handle: JointHandle) -> Option<&mut Joint> {
        let (a, b) = {
            let entry = self.state.joints.get(handle.0)?;
            (entry.body_a, entry.body_b)
        };
        if let Some(a) = a {
            self.wake_island_of(a);
        }
        self.wake_island_of(b);
        let entry = self.state.joints.get_mut(handle.0)?;
        entry.state = JointState {
            broken: entry.state.broken,
            ..JointState::default()
        };
        Some(&mut entry.joint)
    }

    /// Mends a broken joint: it is solved again from the next step.
    ///
    /// # Errors
    /// [`WorldError::StaleJoint`].
    pub fn repair_joint(&mut self, handle: JointHandle) -> Result<(), WorldError> {
        let entry = self
            .state
            .joints
            .get_mut(handle.0)
            .ok_or(WorldError::StaleJoint(handle))?;
        entry.state = JointState::default();
        let (a, b) = (entry.body_a, entry.body_b);
        if let Some(a) = a {
            self.wake_island_of(a);
        }
        self.wake_island_of(b);
        Ok(())
    }

    /// The solver state of a joint (accumulated impulses, whether it broke).
    #[must_use]
    pub fn joint_state(&self, handle: JointHandle) -> Option<&JointState> {
        self.state.joints.get(handle.0).map(|e| &e.state)
    }

    /// The bodies a joint connects: `(None, b)` for a world joint.
    #[must_use]
    pub fn joint_bodies(&self, handle: JointHandle) -> Option<(Option<BodyHandle>, BodyHandle)> {
        self.state
            .joints
            .get(handle.0)
            .map(|e| (e.body_a, e.body_b))
    }

    /// All joints with their handles, in handle order.
    pub fn joints(&self) -> impl Iterator<Item = (JointHandle, &Joint)> {
        self.state
            .joints
            .iter()
            .map(|(i, e)| (JointHandle(i), &e.joint))
    }

    // ---- contacts and events ----

    /// The contact manifolds of the last step, with their impulses, in body-pair order.
    #[must_use]
    pub fn contacts(&self) -> &[ContactManifold] {
        &self.state.manifolds
    }

    /// The events of the last step, in a deterministic order. Bodies woken by API calls between steps are
    /// reported with the next step's events.
    #[must_use]
    pub fn events(&self) -> &[Event] {
        &self.events
    }

    /// Takes the events of the last step (they are also cleared at the start of the next step).
    pub fn drain_events(&mut self) -> std::vec::Drain<'_, Event> {
        self.events.drain(..)
    }

    // ---- time ----

    /// Runs as many whole steps of `settings.fixed_dt` as fit in the time accumulated so far plus `elapsed`
    /// (s), at most `settings.max_steps_per_advance`, and keeps the remainder for the next call: the usual
    /// fixed-timestep game loop. Returns the interpolation factor for rendering. A negative or non-finite
    /// `elapsed` adds nothing.
    pub fn advance(&mut self, elapsed: f32) -> AdvanceReport {
        let mut report = AdvanceReport::default();
        if check_finite("elapsed", elapsed)
            .and_then(|e| check_non_negative("elapsed", e))
            .is_ok()
        {
            self.state.accumulator += elapsed;
        }
        let dt = self.state.settings.fixed_dt;
        while self.state.accumulator >= dt
            && report.steps < self.state.settings.max_steps_per_advance
        {
            report.last_step = Some(self.step(dt));
            self.state.accumulator -= dt;
            report.steps += 1;
        }
        if self.state.accumulator >= dt {
            let keep = self.state.accumulator % dt;
            report.dropped_time = self.state.accumulator - keep;
            self.state.accumulator = keep;
        }
        report.alpha = (self.state.accumulator / dt).clamp(0.0, 1.0);
        report
    }

    // ---- snapshots and determinism ----

    /// Captures everything needed to continue: bodies, joints and their warm-start impulses, the joint
    /// solver's rows kept for the next step, contacts, sleep timers and islands, handle free lists, the
    /// advance accumulator. Not the collision backend's own state (the facade snapshots its colliders
    /// itself).
    #[must_use]
    pub fn snapshot(&self) -> WorldSnapshot {
        let mut state = self.state.clone();
        // The manifolds' unused point slots hold whatever the list held before: not part of the state.
        for manifold in &mut state.manifolds {
            manifold.clear_unused_points();
        }
        WorldSnapshot {
            version: SNAPSHOT_VERSION,
            state,
            joint_rows: self.scratch.solver.joint_solver.kept_rows(),
        }
    }

    /// Restores a snapshot. Handles taken before the snapshot resolve again; handles created after it are
    /// stale. Pending events are cleared.
    ///
    /// # Errors
    /// [`WorldError::BadSnapshot`] for a snapshot of another format version or with inconsistent handle
    /// tables; [`WorldError::InvalidSnapshot`] naming the first item, field and value that its constructor
    /// would have refused, or a handle that resolves to nothing in the snapshot (a joint or manifold on a
    /// body that does not exist). The whole snapshot is refused and the world is unchanged.
    pub fn restore(&mut self, snapshot: &WorldSnapshot) -> Result<(), WorldError> {
        if snapshot.version != SNAPSHOT_VERSION {
            return Err(WorldError::BadSnapshot("format version differs"));
        }
        // A deserialised snapshot bypassed every constructor: check what the step will trust.
        snapshot_check::check_state(&snapshot.state, &snapshot.joint_rows)?;
        let revision = self.state.bodies.revision;
        self.state = snapshot.state.clone();
        self.state.bodies.revision = revision;
        self.state.bodies.bump_revision();
        self.scratch
            .solver
            .joint_solver
            .restore_kept_rows(&snapshot.joint_rows);
        self.events.clear();
        self.woken.clear();
        Ok(())
    }

    /// A 64-bit FNV-1a digest of the bits of every body's position, rotation, linear and angular velocity, in
    /// handle order (with each body's slot index, not its generation, so two worlds built by the same calls
    /// agree): equal digests mean, with overwhelming probability, bit-identical states. For determinism tests
    /// and lockstep networking.
    #[must_use]
    pub fn state_digest(&self) -> u64 {
        let mut hash = Fnv1a::new();
        for (handle, body) in self.state.bodies.iter() {
            let (index, _generation) = handle.into_raw_parts();
            hash.write_u32(index);
            let pose = body.pose();
            for v in [
                pose.position,
                body.linear_velocity(),
                body.angular_velocity(),
            ] {
                for x in v.to_array() {
                    hash.write_u32(x.to_bits());
                }
            }
            for x in pose.rotation.to_array() {
                hash.write_u32(x.to_bits());
            }
        }
        hash.finish()
    }

    // ---- islands ----

    /// Wakes the sleeping island of `handle` (if any), emitting `BodyWoke` for each of its bodies.
    fn wake_island_of(&mut self, handle: BodyHandle) {
        islands::wake_island_of(&mut self.state, &mut self.woken, handle);
    }
}

/// 64-bit FNV-1a.
struct Fnv1a(u64);

impl Fnv1a {
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;

    fn new() -> Self {
        Self(Self::OFFSET)
    }

    fn write_u32(&mut self, value: u32) {
        for byte in value.to_le_bytes() {
            self.0 ^= u64::from(byte);
            self.0 = self.0.wrapping_mul(Self::PRIME);
        }
    }

    fn finish(&self) -> u64 {
        self.0
    }
}
