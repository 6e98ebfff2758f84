//! [`PhysicsState`]: a rollback point — the facade's snapshot of the world plus the plugin's entity tables.
//! Taken and restored through [`crate::Physics::snapshot`] and [`crate::Physics::restore`], between steps.

use crate::Physics;
use crate::physics::{BodyRecord, ColliderRecord};
use bevy_ecs::entity::Entity;
use rebound::prelude::{BodyHandle, ColliderHandle, JointHandle, PhysicsSnapshot};
use std::collections::{BTreeMap, BTreeSet};

/// The physics state of an app at one moment: everything needed to continue bit-identically from there
/// (bodies, colliders, joints, contacts with their warm-start impulses, sleep), and which entity owns which
/// handle. Restoring it into the same app rolls the simulation back; entities must still be the ones it names.
#[derive(Debug, Clone)]
pub struct PhysicsState {
    world: PhysicsSnapshot,
    bodies: BTreeMap<Entity, BodyRecord>,
    colliders: BTreeMap<Entity, ColliderRecord>,
    joints: BTreeMap<Entity, JointHandle>,
    pending_colliders: BTreeSet<Entity>,
    pending_joints: BTreeSet<Entity>,
}

impl PhysicsState {
    pub(crate) fn capture(physics: &Physics) -> Self {
        Self {
            world: physics.world.snapshot(),
            bodies: physics.bodies.clone(),
            colliders: physics.colliders.clone(),
            joints: physics.joints.clone(),
            pending_colliders: physics.pending_colliders.clone(),
            pending_joints: physics.pending_joints.clone(),
        }
    }

    /// The facade's snapshot inside (serialisable with serde, for saving).
    #[must_use]
    pub fn world_snapshot(&self) -> &PhysicsSnapshot {
        &self.world
    }

    pub(crate) fn restore_into(&self, physics: &mut Physics) -> Result<(), rebound::Error> {
        physics.world.restore(&self.world)?;
        physics.bodies.clone_from(&self.bodies);
        physics.body_entities = self
            .bodies
            .iter()
            .map(|(&entity, record)| (record.handle, entity))
            .collect::<BTreeMap<BodyHandle, Entity>>();
        physics.colliders.clone_from(&self.colliders);
        physics.collider_entities = self
            .colliders
            .iter()
            .map(|(&entity, record)| (record.handle, entity))
            .collect::<BTreeMap<ColliderHandle, Entity>>();
        physics.joints.clone_from(&self.joints);
        physics.joint_entities = self
            .joints
            .iter()
            .map(|(&entity, &joint)| (joint, entity))
            .collect();
        physics
            .pending_colliders
            .clone_from(&self.pending_colliders);
        physics.pending_joints.clone_from(&self.pending_joints);
        physics.mass_dirty.clear();
        physics.removed_bodies.clear();
        physics.removed_colliders.clear();
        physics.resync = true;
        Ok(())
    }
}

/// Rollback lives beside the state it takes and gives back, so `physics` needs nothing from this module.
impl Physics {
    /// Captures the physics state and the entity tables, for a later [`Physics::restore`].
    #[must_use]
    pub fn snapshot(&self) -> PhysicsState {
        PhysicsState::capture(self)
    }

    /// Rolls the physics back to `state`. The next physics step first writes the restored poses,
    /// velocities and sleep states to the body entities' components (so they are not mistaken for edits),
    /// then steps on. Entities spawned after the snapshot keep their components but lose their bodies
    /// until their `Body` changes; despawn them on rollback.
    ///
    /// # Errors
    /// [`rebound::Error::BadSnapshot`] for a snapshot the world refuses; nothing changes.
    pub fn restore(&mut self, state: &PhysicsState) -> Result<(), rebound::Error> {
        state.restore_into(self)
    }
}
