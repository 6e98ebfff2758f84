//! The prepare systems ([`crate::PhysicsSystems::Prepare`]): bring the world up to date with the components
//! before the step. In order: settings; despawned or removed components; new bodies and `Body` edits;
//! `Transform`, `Velocity` and `Sleeping` edits (teleports, kicks, wake-ups); colliders; joints; mass
//! overrides; forces, impulses and kinematic targets.
//!
//! Every value goes through the facade's checked calls. A refused value is logged and sent as a
//! [`PhysicsError`], and the world keeps what it had: edits of several fields of one body are made on a copy
//! of the body and committed together. New entities are handled in spawn order ([`spawn_order`]), so the
//! world's handles are the same from run to run.
//!
//! One file per kind of thing prepared: [`bodies`], [`colliders`], [`joints`], [`forces`]; settings and
//! removals are here.
mod bodies;
mod colliders;
mod forces;
mod joints;

pub(crate) use bodies::{apply_mass_overrides, insert_bodies, sync_body_edits};
pub(crate) use colliders::insert_colliders;
pub(crate) use forces::apply_forces;
pub(crate) use joints::insert_joints;

use crate::{Body, Collider, Physics, PhysicsError, PhysicsJoint, PhysicsSettings};
use bevy_ecs::change_detection::DetectChanges;
use bevy_ecs::entity::Entity;
use bevy_ecs::lifecycle::RemovedComponents;
use bevy_ecs::message::MessageWriter;
use bevy_ecs::system::{Res, ResMut};
use rebound::prelude::{Pose, Vec3};
use rebound::{BodyHandle, RigidBody};
/// Sends (and logs) a refused value.
pub(crate) fn report(errors: &mut MessageWriter<'_, PhysicsError>, error: PhysicsError) {
    log::error!("rebound: {error}");
    errors.write(error);
}

/// Whether two poses are the same bit for bit (a NaN equals itself, so a refused NaN is not refused again).
pub(crate) fn same_pose(a: Pose, b: Pose) -> bool {
    same_vec3(a.position, b.position)
        && a.rotation.to_array().map(f32::to_bits) == b.rotation.to_array().map(f32::to_bits)
}

/// Whether two vectors are the same bit for bit.
pub(crate) fn same_vec3(a: Vec3, b: Vec3) -> bool {
    a.to_array().map(f32::to_bits) == b.to_array().map(f32::to_bits)
}

/// Applies changed [`PhysicsSettings`] to the world.
pub(crate) fn apply_settings(
    settings: Res<'_, PhysicsSettings>,
    mut physics: ResMut<'_, Physics>,
    mut errors: MessageWriter<'_, PhysicsError>,
) {
    if !settings.is_changed() || *physics.world.settings() == settings.world {
        return;
    }
    if let Err(error) = physics.world.set_settings(settings.world) {
        report(&mut errors, PhysicsError::Settings(error));
    }
}

/// Removes the joints, colliders and bodies whose components were removed or whose entities were despawned.
pub(crate) fn remove_despawned(
    mut physics: ResMut<'_, Physics>,
    mut removed_joints: RemovedComponents<'_, '_, PhysicsJoint>,
    mut removed_colliders: RemovedComponents<'_, '_, Collider>,
    mut removed_bodies: RemovedComponents<'_, '_, Body>,
) {
    let physics = &mut *physics;
    for entity in sorted(removed_joints.read()) {
        physics.pending_joints.remove(&entity);
        if let Some(joint) = physics.joints.remove(&entity) {
            physics.joint_entities.remove(&joint);
            // Stale only if a body removal took the joint with it, which the tables already reflect.
            let _ = physics.world.remove_joint(joint);
        }
    }
    for entity in sorted(removed_colliders.read()) {
        physics.pending_colliders.remove(&entity);
        if let Some(record) = physics.colliders.remove(&entity) {
            physics.collider_entities.remove(&record.handle);
            physics.removed_colliders.insert(record.handle, entity);
            let _ = physics.world.remove_collider(record.handle);
            physics.mass_dirty.insert(record.body);
        }
    }
    for entity in sorted(removed_bodies.read()) {
        physics.refused_bodies.remove(&entity);
        if let Some(record) = physics.bodies.get(&entity).copied() {
            let _ = physics.world.remove_body(record.handle);
            physics.forget_body(entity, record.handle);
        }
    }
}

/// Applies `edit` to a copy of a body and commits it only if every part succeeded.
fn edit_copy(
    world: &mut rebound::PhysicsWorld,
    handle: BodyHandle,
    edit: impl FnOnce(&mut RigidBody) -> Result<(), rebound::DynamicsError>,
) -> Result<(), rebound::Error> {
    let mut edited = world
        .body(handle)
        .cloned()
        .ok_or(rebound::WorldError::StaleBody(handle))?;
    edit(&mut edited)?;
    if let Some(slot) = world.body_mut(handle) {
        *slot = edited;
    }
    Ok(())
}

/// The order new entities reach the world in: by index, then generation — for fresh entities, the order they
/// were spawned in. (`Entity`'s own `Ord` compares its bit pattern, which runs the other way.)
pub(crate) fn spawn_order(entity: Entity) -> (u32, u64) {
    (entity.index_u32(), entity.to_bits())
}

/// The entities of an iterator, sorted (removal order does not depend on the ECS's internal order).
fn sorted(entities: impl Iterator<Item = Entity>) -> Vec<Entity> {
    let mut entities: Vec<Entity> = entities.collect();
    entities.sort_unstable_by_key(|&entity| spawn_order(entity));
    entities.dedup();
    entities
}

#[cfg(test)]
mod tests {
    use super::*;
    use rebound::prelude::Quat;

    #[test]
    fn same_pose_is_bitwise_and_nan_equals_itself() {
        let a = Pose::new(Vec3::new(1.0, f32::NAN, 0.0), Quat::IDENTITY);
        assert!(same_pose(a, a));
        let b = Pose::new(Vec3::new(1.0, 0.0, -0.0), Quat::IDENTITY);
        let c = Pose::new(Vec3::new(1.0, 0.0, 0.0), Quat::IDENTITY);
        assert!(!same_pose(b, c), "-0 and +0 differ bit for bit");
    }
}
