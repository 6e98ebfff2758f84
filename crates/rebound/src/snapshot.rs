//! `PhysicsSnapshot`: a [`crate::PhysicsWorld`]'s full state, serialisable with serde. Not a step stage.
//!
//! It holds the world's own [`WorldSnapshot`] and, for the colliders, their descriptions
//! ([`ColliderDesc`], this crate's serialisable shape enum) with their bodies in the same handle slots,
//! generations and free list; parry shapes are rebuilt from the descriptions on restore. The narrow phase's
//! pair cache and the BVH are rebuilt too: neither influences the results (see the crate docs,
//! "Determinism").
//!
//! [`PhysicsWorld::snapshot`] and [`PhysicsWorld::restore`] live here, with the type they make and read, so
//! that the world type does not depend on its snapshot.

use crate::{Collider, ColliderDesc, ColliderHandle, ColliderSet, Error, PhysicsWorld};
use rebound_dynamics::MassProperties;
use rebound_math::validity::check_non_negative;
use rebound_world::arena::Arena;
use rebound_world::{BodyHandle, JointHandle, WorldError, WorldSnapshot};
use serde::{Deserialize, Serialize};

const SNAPSHOT_VERSION: u32 = 1;

/// A collider as a snapshot stores it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
struct ColliderRecord {
    desc: ColliderDesc,
    body: BodyHandle,
}

/// A saved [`crate::PhysicsWorld`]: restore it into the same world (rollback) or a fresh one (load), then
/// step on; the result is bit-identical to never having stopped.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PhysicsSnapshot {
    /// Format version, checked on restore.
    version: u32,
    world: WorldSnapshot,
    colliders: Arena<ColliderRecord>,
    /// Each body's own mass properties, in handle order.
    own_mass: Vec<(BodyHandle, MassProperties)>,
    joints_without_contacts: Vec<JointHandle>,
    sensor_overlaps: Vec<(ColliderHandle, ColliderHandle)>,
    accumulator: f32,
}

impl PhysicsWorld {
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
    /// [`Error::BadSnapshot`] for a snapshot of another format version or with inconsistent handle tables;
    /// [`Error::InvalidSnapshot`] naming the first invalid item (a collider's shape or material, a collider,
    /// mass, joint or sensor pair that refers to nothing in the snapshot) and the field and value;
    /// [`Error::World`] with the world's [`WorldError::InvalidSnapshot`] for its own part. The whole snapshot
    /// is refused and the world is unchanged.
    pub fn restore(&mut self, snapshot: &PhysicsSnapshot) -> Result<(), Error> {
        snapshot.restore_into(self)
    }
}

impl PhysicsSnapshot {
    /// Checks that every handle the facade's part holds resolves within the snapshot: each collider's body,
    /// each body with its own mass, each joint without contacts, each sensor pair's colliders.
    fn check_references(&self) -> Result<(), Error> {
        let invalid = |item: String, source: Error| Error::InvalidSnapshot {
            item,
            source: Box::new(source),
        };
        let bodies = self.world.bodies();
        for (index, record) in self.colliders.iter() {
            if !bodies.contains(record.body) {
                let item = format!("collider {}", index.index);
                return Err(invalid(item, WorldError::StaleBody(record.body).into()));
            }
        }
        for &(body, _) in &self.own_mass {
            if !bodies.contains(body) {
                let item = "own mass properties".to_owned();
                return Err(invalid(item, WorldError::StaleBody(body).into()));
            }
        }
        for &joint in &self.joints_without_contacts {
            if !self.world.contains_joint(joint) {
                let item = "joints without contacts".to_owned();
                return Err(invalid(item, WorldError::StaleJoint(joint).into()));
            }
        }
        // Sensor overlaps may name colliders removed since the last step (the next step reports their
        // overlaps as ended), as touching pairs may name removed bodies: they are not refused.
        Ok(())
    }

    pub(crate) fn capture(world: &PhysicsWorld) -> Self {
        let colliders = world
            .world
            .backend()
            .colliders
            .arena
            .map(|c| ColliderRecord {
                desc: c.desc.clone(),
                body: c.body,
            });
        Self {
            version: SNAPSHOT_VERSION,
            world: world.world.snapshot(),
            colliders,
            own_mass: world.own_mass.iter().map(|(h, m)| (*h, *m)).collect(),
            joints_without_contacts: world.joints_without_contacts.iter().copied().collect(),
            sensor_overlaps: world.sensor_overlaps.clone(),
            accumulator: world.accumulator,
        }
    }

    /// The world's part of the snapshot.
    #[must_use]
    pub fn world_snapshot(&self) -> &WorldSnapshot {
        &self.world
    }

    /// The number of colliders saved.
    #[must_use]
    pub fn collider_count(&self) -> usize {
        self.colliders.len()
    }

    pub(crate) fn restore_into(&self, target: &mut PhysicsWorld) -> Result<(), Error> {
        if self.version != SNAPSHOT_VERSION {
            return Err(Error::BadSnapshot(format!(
                "format version {} differs from {SNAPSHOT_VERSION}",
                self.version
            )));
        }
        if !self.colliders.is_consistent() {
            return Err(Error::BadSnapshot(
                "the collider table is inconsistent".into(),
            ));
        }
        self.check_references()?;
        let invalid = |item: String, source: Error| Error::InvalidSnapshot {
            item,
            source: Box::new(source),
        };
        let accumulator = check_non_negative("accumulator", self.accumulator);
        accumulator.map_err(|e| invalid("world".into(), e.into()))?;
        // Build every parry shape first: nothing changes unless all of them are valid.
        // `try_map` visits the colliders in slot order, as `iter` does.
        let slots: Vec<u32> = self.colliders.iter().map(|(i, _)| i.index).collect();
        let mut visited = 0;
        let arena: Arena<Collider> = self
            .colliders
            .try_map(|record| {
                visited += 1;
                Collider::new(record.desc.clone(), record.body)
            })
            .map_err(|e| {
                let slot = slots.get(visited - 1).copied().unwrap_or_default();
                invalid(format!("collider {slot}"), e)
            })?;
        // The world checks its own part, and changes nothing unless all of it is valid; after it nothing fails.
        target.world.restore(&self.world)?;

        let backend = target.world.backend_mut();
        backend.colliders = ColliderSet::from_arena(arena, backend.colliders.revision());
        backend.narrow_phase.clear();
        target.own_mass = self.own_mass.iter().copied().collect();
        target.joints_without_contacts = self.joints_without_contacts.iter().copied().collect();
        let mut overlaps = self.sensor_overlaps.clone();
        overlaps.sort_unstable();
        overlaps.dedup();
        target.sensor_overlaps = overlaps;
        target.accumulator = self.accumulator;
        target.update_disabled_pairs();
        target.rebuild_broad_phase();
        target.clear_events();
        Ok(())
    }
}
