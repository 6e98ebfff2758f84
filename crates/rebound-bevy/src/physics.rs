//! [`Physics`]: the resource holding the facade's [`PhysicsWorld`] and the two-way tables between entities and
//! the world's handles. Written by the prepare, step and writeback systems; read by queries and users.
//!
//! The tables are ordered maps (`BTreeMap`, keyed by `Entity` or by handle) so that every pass over them, and
//! so the order of calls into the world, is the same from run to run: the plugin is as deterministic as the
//! facade.

use bevy_ecs::entity::Entity;
use bevy_ecs::resource::Resource;
use rebound::prelude::{
    BodyHandle, ColliderHandle, JointHandle, PhysicsWorld, Pose, StepReport, Vec3,
};
use std::collections::{BTreeMap, BTreeSet};

/// What the plugin knows of a body entity: its handle and what it last wrote to the entity, to tell a user's
/// edit from its own writeback.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct BodyRecord {
    pub(crate) handle: BodyHandle,
    /// The pose last written to (or read from) the entity's `Transform`.
    pub(crate) written_pose: Pose,
    /// The velocity last written to (or read from) the entity's `Velocity`: (linear, angular).
    pub(crate) written_velocity: (Vec3, Vec3),
    /// The sleep state last written to (or read from) the entity's `Sleeping`.
    pub(crate) written_sleeping: bool,
    /// The body's pose after the step before the last one (for interpolation).
    pub(crate) previous_pose: Pose,
    /// The body's pose after the last step.
    pub(crate) current_pose: Pose,
}

/// What the plugin knows of a collider entity.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) struct ColliderRecord {
    pub(crate) handle: ColliderHandle,
    /// The body entity it is attached to.
    pub(crate) body: Entity,
}

/// The physics world of the Bevy app and the tables that tie its handles to entities.
///
/// Read it in systems with `Res<Physics>` (handles, bodies, contacts, the state digest); change the
/// simulation through components, not through the world, so the tables stay right. Its
/// [`Physics::snapshot`] and [`Physics::restore`] roll the simulation back.
#[derive(Resource, Debug)]
pub struct Physics {
    pub(crate) world: PhysicsWorld,
    pub(crate) bodies: BTreeMap<Entity, BodyRecord>,
    pub(crate) body_entities: BTreeMap<BodyHandle, Entity>,
    pub(crate) colliders: BTreeMap<Entity, ColliderRecord>,
    pub(crate) collider_entities: BTreeMap<ColliderHandle, Entity>,
    pub(crate) joints: BTreeMap<Entity, JointHandle>,
    pub(crate) joint_entities: BTreeMap<JointHandle, Entity>,
    /// Body entities the world refused; tried again when their `Transform` or `Velocity` changes.
    pub(crate) refused_bodies: BTreeSet<Entity>,
    /// Collider entities waiting for their body to exist.
    pub(crate) pending_colliders: BTreeSet<Entity>,
    /// Joint entities waiting for their bodies to exist.
    pub(crate) pending_joints: BTreeSet<Entity>,
    /// Body entities whose colliders changed since the last step (their [`crate::MassOverride`] is put back).
    pub(crate) mass_dirty: BTreeSet<Entity>,
    /// Handles removed since the last step, still named by that step's events (a contact that ends
    /// because a body was despawned).
    pub(crate) removed_bodies: BTreeMap<BodyHandle, Entity>,
    pub(crate) removed_colliders: BTreeMap<ColliderHandle, Entity>,
    /// Set by [`Physics::restore`]: the next prepare writes the world's state to the components instead of
    /// reading edits from them.
    pub(crate) resync: bool,
    /// Whether the last run of the step system moved the world (the writeback has something to write).
    pub(crate) stepped: bool,
    pub(crate) last_report: StepReport,
}

impl Physics {
    pub(crate) fn new(world: PhysicsWorld) -> Self {
        Self {
            world,
            bodies: BTreeMap::new(),
            body_entities: BTreeMap::new(),
            colliders: BTreeMap::new(),
            collider_entities: BTreeMap::new(),
            joints: BTreeMap::new(),
            joint_entities: BTreeMap::new(),
            refused_bodies: BTreeSet::new(),
            pending_colliders: BTreeSet::new(),
            pending_joints: BTreeSet::new(),
            mass_dirty: BTreeSet::new(),
            removed_bodies: BTreeMap::new(),
            removed_colliders: BTreeMap::new(),
            resync: false,
            stepped: false,
            last_report: StepReport::default(),
        }
    }

    /// The facade's world, read-only.
    #[must_use]
    pub fn world(&self) -> &PhysicsWorld {
        &self.world
    }

    /// The body handle of a body entity (`None` until the plugin has inserted it, or if it was refused).
    #[must_use]
    pub fn body_handle(&self, entity: Entity) -> Option<BodyHandle> {
        self.bodies.get(&entity).map(|record| record.handle)
    }

    /// The entity of a body handle.
    #[must_use]
    pub fn body_entity(&self, handle: BodyHandle) -> Option<Entity> {
        self.body_entities.get(&handle).copied()
    }

    /// The collider handle of a collider entity.
    #[must_use]
    pub fn collider_handle(&self, entity: Entity) -> Option<ColliderHandle> {
        self.colliders.get(&entity).map(|record| record.handle)
    }

    /// The entity of a collider handle.
    #[must_use]
    pub fn collider_entity(&self, handle: ColliderHandle) -> Option<Entity> {
        self.collider_entities.get(&handle).copied()
    }

    /// The joint handle of a joint entity.
    #[must_use]
    pub fn joint_handle(&self, entity: Entity) -> Option<JointHandle> {
        self.joints.get(&entity).copied()
    }

    /// The entity of a joint handle.
    #[must_use]
    pub fn joint_entity(&self, handle: JointHandle) -> Option<Entity> {
        self.joint_entities.get(&handle).copied()
    }

    /// The report of the last step.
    #[must_use]
    pub fn last_step_report(&self) -> &StepReport {
        &self.last_report
    }

    /// The world's 64-bit digest of every body's pose and velocities ([`PhysicsWorld::state_digest`]).
    #[must_use]
    pub fn state_digest(&self) -> u64 {
        self.world.state_digest()
    }

    /// Drops what the tables know of a body entity (its colliders' and joints' entries too); the world's
    /// body must already be gone. Its collider and joint entities wait for a body again.
    pub(crate) fn forget_body(&mut self, entity: Entity, handle: BodyHandle) {
        self.bodies.remove(&entity);
        self.body_entities.remove(&handle);
        self.removed_bodies.insert(handle, entity);
        let orphans: Vec<Entity> = self
            .colliders
            .iter()
            .filter(|(_, record)| record.body == entity)
            .map(|(&collider, _)| collider)
            .collect();
        for collider in orphans {
            if let Some(record) = self.colliders.remove(&collider) {
                self.collider_entities.remove(&record.handle);
                self.removed_colliders.insert(record.handle, collider);
            }
            self.pending_colliders.insert(collider);
        }
        let world = &self.world;
        let gone: Vec<Entity> = self
            .joints
            .iter()
            .filter(|&(_, &joint)| world.joint(joint).is_none())
            .map(|(&joint_entity, _)| joint_entity)
            .collect();
        for joint_entity in gone {
            if let Some(joint) = self.joints.remove(&joint_entity) {
                self.joint_entities.remove(&joint);
            }
            self.pending_joints.insert(joint_entity);
        }
    }
}
