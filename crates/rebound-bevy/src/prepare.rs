//! The prepare systems ([`crate::PhysicsSystems::Prepare`]): bring the world up to date with the components
//! before the step. In order: settings; despawned or removed components; new bodies and `Body` edits;
//! `Transform`, `Velocity` and `Sleeping` edits (teleports, kicks, wake-ups); colliders; joints; mass
//! overrides; forces, impulses and kinematic targets.
//!
//! Every value goes through the facade's checked calls. A refused value is logged and sent as a
//! [`PhysicsError`], and the world keeps what it had: edits of several fields of one body are made on a copy
//! of the body and committed together. New entities are handled in spawn order ([`spawn_order`]), so the
//! world's handles are the same from run to run.

use crate::body::pose_of;
use crate::physics::{BodyRecord, ColliderRecord};
use crate::{
    Body, Collider, ExternalForce, ExternalImpulse, KinematicTarget, MassOverride, Physics,
    PhysicsError, PhysicsJoint, PhysicsSettings, Sleeping, Velocity,
};
use bevy_ecs::change_detection::{DetectChanges, Ref};
use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::ChildOf;
use bevy_ecs::lifecycle::RemovedComponents;
use bevy_ecs::message::MessageWriter;
use bevy_ecs::query::{Changed, With, Without};
use bevy_ecs::system::{Query, Res, ResMut};
use bevy_transform::components::Transform;
use rebound::prelude::{BodyType, MassProperties, Pose, Vec3};
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

/// Inserts new bodies (and retries refused ones whose components changed), and applies `Body` edits.
pub(crate) fn insert_bodies(
    mut physics: ResMut<'_, Physics>,
    changed: Query<'_, '_, Entity, Changed<Body>>,
    query: Query<
        '_,
        '_,
        (
            Ref<'_, Body>,
            Ref<'_, Transform>,
            Ref<'_, Velocity>,
            &Sleeping,
            Option<&MassOverride>,
        ),
    >,
    mut errors: MessageWriter<'_, PhysicsError>,
) {
    // New or edited bodies, and refused ones whose pose or velocity has changed since.
    let mut todo: Vec<Entity> = changed.iter().collect();
    let physics = &mut *physics;
    physics
        .refused_bodies
        .retain(|&entity| query.contains(entity));
    todo.extend(physics.refused_bodies.iter().copied().filter(|&entity| {
        query.get(entity).is_ok_and(|(_, transform, velocity, ..)| {
            transform.is_changed() || velocity.is_changed()
        })
    }));
    if todo.is_empty() {
        return;
    }
    todo.sort_unstable_by_key(|&entity| spawn_order(entity));
    todo.dedup();
    for entity in todo {
        let Ok((body, transform, velocity, sleeping, mass)) = query.get(entity) else {
            continue;
        };
        if let Some(record) = physics.bodies.get(&entity).copied() {
            if let Err(error) = edit_body(physics, record.handle, &body) {
                report(&mut errors, PhysicsError::refused(entity, "Body", error));
            }
            continue;
        }
        let pose = pose_of(&transform);
        let desc = body.desc(pose, *velocity, sleeping.0, mass.map(|m| m.0));
        match physics.world.insert_body(desc) {
            Ok(handle) => {
                physics.refused_bodies.remove(&entity);
                physics.bodies.insert(
                    entity,
                    BodyRecord {
                        handle,
                        written_pose: pose,
                        written_velocity: (velocity.linear, velocity.angular),
                        written_sleeping: sleeping.0,
                        previous_pose: pose,
                        current_pose: pose,
                    },
                );
                physics.body_entities.insert(handle, entity);
            }
            Err(error) => {
                physics.refused_bodies.insert(entity);
                report(&mut errors, PhysicsError::refused(entity, "Body", error));
            }
        }
    }
}

/// Applies a changed [`Body`] to the world's body, all fields or none.
fn edit_body(physics: &mut Physics, handle: BodyHandle, body: &Body) -> Result<(), rebound::Error> {
    let mut edited = physics
        .world
        .body(handle)
        .cloned()
        .ok_or(rebound::WorldError::StaleBody(handle))?;
    if edited.body_type() != body.body_type {
        edited.set_body_type(body.body_type);
    }
    edited.set_gravity_scale(body.gravity_scale)?;
    edited.set_linear_damping(body.linear_damping)?;
    edited.set_angular_damping(body.angular_damping)?;
    edited.set_can_sleep(body.can_sleep);
    edited.set_gyroscopic(body.gyroscopic);
    commit(physics, handle, edited)
}

/// Replaces the world's body behind `handle` with an edited copy.
fn commit(
    physics: &mut Physics,
    handle: BodyHandle,
    edited: RigidBody,
) -> Result<(), rebound::Error> {
    let slot = physics
        .world
        .body_mut(handle)
        .ok_or(rebound::WorldError::StaleBody(handle))?;
    *slot = edited;
    Ok(())
}

/// Reads user edits of `Transform` (a teleport), `Velocity` and `Sleeping` on body entities: a value that is
/// not the one the plugin last wrote is the user's. After a [`Physics::restore`] it writes the world's state
/// to those components instead.
pub(crate) fn sync_body_edits(
    mut physics: ResMut<'_, Physics>,
    mut query: Query<'_, '_, (Entity, &mut Transform, &mut Velocity, &mut Sleeping), With<Body>>,
    mut errors: MessageWriter<'_, PhysicsError>,
) {
    let physics = &mut *physics;
    if physics.resync {
        physics.resync = false;
        for (entity, mut transform, mut velocity, mut sleeping) in &mut query {
            let Some(record) = physics.bodies.get_mut(&entity) else {
                continue;
            };
            let Some(body) = physics.world.body(record.handle) else {
                continue;
            };
            let pose = body.pose();
            transform.translation = pose.position;
            transform.rotation = pose.rotation;
            *velocity = Velocity::new(body.linear_velocity(), body.angular_velocity());
            sleeping.0 = physics.world.is_sleeping(record.handle).unwrap_or(false);
            record.written_pose = pose;
            record.written_velocity = (velocity.linear, velocity.angular);
            record.written_sleeping = sleeping.0;
        }
        return;
    }
    // Walking the ordered table and looking each entity up is cheaper than a table lookup per entity.
    let Physics { world, bodies, .. } = physics;
    for (&entity, record) in bodies.iter_mut() {
        let Ok((_, transform, velocity, sleeping)) = query.get_mut(entity) else {
            continue;
        };
        if !(transform.is_changed() || velocity.is_changed() || sleeping.is_changed()) {
            continue;
        }
        let pose = pose_of(&transform);
        if !same_pose(pose, record.written_pose) {
            record.written_pose = pose;
            match world.body_mut(record.handle).map(|b| b.set_pose(pose)) {
                Some(Ok(())) => {
                    record.previous_pose = pose;
                    record.current_pose = pose;
                }
                Some(Err(error)) => {
                    report(
                        &mut errors,
                        PhysicsError::refused(entity, "Transform", error),
                    );
                }
                None => {}
            }
        }
        let value = (velocity.linear, velocity.angular);
        if !same_vec3(value.0, record.written_velocity.0)
            || !same_vec3(value.1, record.written_velocity.1)
        {
            record.written_velocity = value;
            if let Err(error) = set_velocity(world, record.handle, value) {
                report(
                    &mut errors,
                    PhysicsError::refused(entity, "Velocity", error),
                );
            }
        }
        if sleeping.0 != record.written_sleeping {
            record.written_sleeping = sleeping.0;
            if sleeping.0 {
                if let Some(body) = world.body_mut(record.handle) {
                    body.set_sleeping(true);
                }
            } else if let Err(error) = world.wake_body(record.handle) {
                report(
                    &mut errors,
                    PhysicsError::refused(entity, "Sleeping", error),
                );
            }
        }
    }
}

/// Sets both velocities of a body, or neither.
fn set_velocity(
    world: &mut rebound::PhysicsWorld,
    handle: BodyHandle,
    (linear, angular): (Vec3, Vec3),
) -> Result<(), rebound::Error> {
    let mut edited = world
        .body(handle)
        .cloned()
        .ok_or(rebound::WorldError::StaleBody(handle))?;
    edited.set_linear_velocity(linear)?;
    edited.set_angular_velocity(angular)?;
    if let Some(slot) = world.body_mut(handle) {
        *slot = edited;
    }
    Ok(())
}

/// Where a collider entity attaches: the body entity found on it or its nearest ancestor, and the pose of
/// the collider entity in that body's frame (the chain of `Transform`s below the body).
fn attachment(
    entity: Entity,
    bodies: &Query<'_, '_, (), With<Body>>,
    parents: &Query<'_, '_, (&ChildOf, &Transform)>,
) -> Option<(Entity, Pose)> {
    let mut current = entity;
    let mut pose = Pose::IDENTITY;
    // A hierarchy is finite and acyclic (bevy's relationships forbid cycles); the bound only guards the loop.
    for _ in 0..1024 {
        if bodies.contains(current) {
            return Some((current, pose));
        }
        let (child_of, transform) = parents.get(current).ok()?;
        pose = pose_of(transform).mul_pose(&pose);
        current = child_of.parent();
    }
    None
}

/// Inserts new colliders (and those waiting for a body), replaces edited ones, and moves child colliders
/// whose `Transform` changed.
pub(crate) fn insert_colliders(
    mut physics: ResMut<'_, Physics>,
    changed: Query<'_, '_, Entity, Changed<Collider>>,
    moved: Query<'_, '_, Entity, (With<Collider>, Without<Body>, Changed<Transform>)>,
    colliders: Query<'_, '_, &Collider>,
    bodies: Query<'_, '_, (), With<Body>>,
    parents: Query<'_, '_, (&ChildOf, &Transform)>,
    mut errors: MessageWriter<'_, PhysicsError>,
) {
    let physics = &mut *physics;
    let mut todo: Vec<Entity> = changed.iter().collect();
    todo.extend(physics.pending_colliders.iter().copied());
    todo.extend(
        moved
            .iter()
            .filter(|entity| physics.colliders.contains_key(entity)),
    );
    if todo.is_empty() {
        return;
    }
    todo.sort_unstable_by_key(|&entity| spawn_order(entity));
    todo.dedup();
    for entity in todo {
        let Ok(collider) = colliders.get(entity) else {
            physics.pending_colliders.remove(&entity);
            continue;
        };
        let Some((body_entity, entity_pose)) = attachment(entity, &bodies, &parents) else {
            physics.pending_colliders.insert(entity);
            continue;
        };
        let Some(body) = physics.bodies.get(&body_entity).map(|r| r.handle) else {
            physics.pending_colliders.insert(entity);
            continue;
        };
        physics.pending_colliders.remove(&entity);
        let mut desc = collider.desc.clone();
        desc.local_pose = entity_pose.mul_pose(&desc.local_pose);
        let old = physics.colliders.get(&entity).copied();
        match physics.world.insert_collider(desc, body) {
            Ok(handle) => {
                if let Some(old) = old {
                    physics.collider_entities.remove(&old.handle);
                    let _ = physics.world.remove_collider(old.handle);
                    physics.mass_dirty.insert(old.body);
                }
                physics.colliders.insert(
                    entity,
                    ColliderRecord {
                        handle,
                        body: body_entity,
                    },
                );
                physics.collider_entities.insert(handle, entity);
                physics.mass_dirty.insert(body_entity);
            }
            Err(error) => report(
                &mut errors,
                PhysicsError::refused(entity, "Collider", error),
            ),
        }
    }
}

/// How a joint's entity resolves to a body handle.
enum Resolved {
    Body(BodyHandle),
    /// The entity has a `Body` that is not in the world yet (or was refused): wait.
    Waiting,
    /// The entity has no `Body`.
    NotABody,
}

fn resolve(physics: &Physics, entity: Entity, bodies: &Query<'_, '_, (), With<Body>>) -> Resolved {
    match physics.bodies.get(&entity) {
        Some(record) => Resolved::Body(record.handle),
        None if bodies.contains(entity) => Resolved::Waiting,
        None => Resolved::NotABody,
    }
}

/// Inserts new joints (and those waiting for their bodies) and applies joint edits.
pub(crate) fn insert_joints(
    mut physics: ResMut<'_, Physics>,
    changed: Query<'_, '_, Entity, Changed<PhysicsJoint>>,
    joints: Query<'_, '_, &PhysicsJoint>,
    bodies: Query<'_, '_, (), With<Body>>,
    mut errors: MessageWriter<'_, PhysicsError>,
) {
    let physics = &mut *physics;
    let mut todo: Vec<(Entity, bool)> = changed.iter().map(|e| (e, true)).collect();
    todo.extend(
        physics
            .pending_joints
            .iter()
            .filter(|e| !changed.contains(**e))
            .map(|&e| (e, false)),
    );
    if todo.is_empty() {
        return;
    }
    todo.sort_unstable_by_key(|&(entity, _)| spawn_order(entity));
    for (entity, is_new_value) in todo {
        let Ok(joint) = joints.get(entity) else {
            physics.pending_joints.remove(&entity);
            continue;
        };
        let a = joint
            .body_a
            .map(|a| (resolve(physics, a, &bodies), "body_a", a));
        let b = (
            resolve(physics, joint.body_b, &bodies),
            "body_b",
            joint.body_b,
        );
        let mut handles = [None, None];
        let mut waiting = false;
        for (slot, side) in [a, Some(b)].into_iter().enumerate() {
            match side {
                Some((Resolved::Body(handle), ..)) => handles[slot] = Some(handle),
                Some((Resolved::Waiting, ..)) => waiting = true,
                Some((Resolved::NotABody, field, target)) => {
                    waiting = true;
                    if is_new_value {
                        report(
                            &mut errors,
                            PhysicsError::NotABody {
                                entity,
                                field,
                                target,
                            },
                        );
                    }
                }
                None => {}
            }
        }
        let Some(body_b) = handles[1] else {
            physics.pending_joints.insert(entity);
            continue;
        };
        if waiting {
            physics.pending_joints.insert(entity);
            continue;
        }
        physics.pending_joints.remove(&entity);
        if let Err(error) = place_joint(physics, entity, joint, handles[0], body_b) {
            report(
                &mut errors,
                PhysicsError::refused(entity, "PhysicsJoint", error),
            );
        }
    }
}

/// Puts a joint into the world: edits the existing one in place when it joins the same bodies, else
/// inserts the new one and only then removes the old one.
fn place_joint(
    physics: &mut Physics,
    entity: Entity,
    joint: &PhysicsJoint,
    body_a: Option<BodyHandle>,
    body_b: BodyHandle,
) -> Result<(), rebound::Error> {
    let old = physics.joints.get(&entity).copied();
    if let Some(old) = old
        && physics.world.joint_bodies(old) == Some((body_a, body_b))
    {
        if let Some(slot) = physics.world.joint_mut(old) {
            *slot = joint.joint;
        }
        physics
            .world
            .set_joint_contacts_enabled(old, joint.contacts_enabled)?;
        return Ok(());
    }
    let handle = match body_a {
        Some(body_a) => physics.world.insert_joint(joint.joint, body_a, body_b)?,
        None => physics.world.insert_world_joint(joint.joint, body_b)?,
    };
    if !joint.contacts_enabled {
        physics.world.set_joint_contacts_enabled(handle, false)?;
    }
    if let Some(old) = old {
        physics.joint_entities.remove(&old);
        let _ = physics.world.remove_joint(old);
    }
    physics.joints.insert(entity, handle);
    physics.joint_entities.insert(handle, entity);
    Ok(())
}

/// Gives bodies their [`MassOverride`] when it changes, when their colliders change, and gives them back their
/// colliders' mass when it is removed.
pub(crate) fn apply_mass_overrides(
    mut physics: ResMut<'_, Physics>,
    changed: Query<'_, '_, Entity, (With<Body>, Changed<MassOverride>)>,
    overrides: Query<'_, '_, &MassOverride>,
    mut removed: RemovedComponents<'_, '_, MassOverride>,
    mut errors: MessageWriter<'_, PhysicsError>,
) {
    let physics = &mut *physics;
    let mut todo: Vec<Entity> = changed.iter().chain(removed.read()).collect();
    // Colliders changed the mass of these bodies; only an override needs putting back.
    let dirty = core::mem::take(&mut physics.mass_dirty);
    todo.extend(
        dirty
            .into_iter()
            .filter(|&entity| overrides.contains(entity)),
    );
    if todo.is_empty() {
        return;
    }
    todo.sort_unstable_by_key(|&entity| spawn_order(entity));
    todo.dedup();
    for entity in todo {
        let Some(handle) = physics.body_handle(entity) else {
            continue;
        };
        let result = match overrides.get(entity) {
            Ok(mass) => override_mass(&mut physics.world, handle, mass.0),
            // Without an override the facade's own rule applies: the colliders' mass, or the default body's.
            Err(_) => physics
                .world
                .set_body_mass_properties(handle, MassProperties::default()),
        };
        if let Err(error) = result {
            report(
                &mut errors,
                PhysicsError::refused(entity, "MassOverride", error),
            );
        }
    }
}

/// Makes `mass` the body's mass properties whatever its colliders add.
fn override_mass(
    world: &mut rebound::PhysicsWorld,
    handle: BodyHandle,
    mass: MassProperties,
) -> Result<(), rebound::Error> {
    world.set_body_mass_properties(handle, mass)?;
    if let Some(body) = world.body_mut(handle) {
        body.set_mass_properties(mass);
    }
    Ok(())
}

/// Applies held forces, one-shot impulses (then zeroes them) and kinematic targets.
pub(crate) fn apply_forces(
    mut physics: ResMut<'_, Physics>,
    forces: Query<'_, '_, (Entity, Ref<'_, ExternalForce>)>,
    mut impulses: Query<'_, '_, (Entity, &mut ExternalImpulse)>,
    targets: Query<'_, '_, (Entity, Ref<'_, KinematicTarget>, &Body)>,
    mut errors: MessageWriter<'_, PhysicsError>,
) {
    let physics = &mut *physics;
    for (entity, force) in &forces {
        if same_vec3(force.force, Vec3::ZERO) && same_vec3(force.torque, Vec3::ZERO) {
            continue;
        }
        let Some(handle) = physics.body_handle(entity) else {
            continue;
        };
        let result = edit_copy(&mut physics.world, handle, |body| {
            body.apply_force(force.force)?;
            body.apply_torque(force.torque)
        });
        // A held force is applied at every step; its error is reported when the value is set.
        if let Err(error) = result
            && force.is_changed()
        {
            report(
                &mut errors,
                PhysicsError::refused(entity, "ExternalForce", error),
            );
        }
    }
    for (entity, mut impulse) in &mut impulses {
        if same_vec3(impulse.impulse, Vec3::ZERO) && same_vec3(impulse.angular_impulse, Vec3::ZERO)
        {
            continue;
        }
        let Some(handle) = physics.body_handle(entity) else {
            continue;
        };
        let result = edit_copy(&mut physics.world, handle, |body| {
            body.apply_impulse(impulse.impulse)?;
            body.apply_angular_impulse(impulse.angular_impulse)
        });
        if let Err(error) = result {
            report(
                &mut errors,
                PhysicsError::refused(entity, "ExternalImpulse", error),
            );
        }
        // One-shot: a refused impulse is dropped too, not refused again at every step.
        *impulse = ExternalImpulse::default();
    }
    for (entity, target, body) in &targets {
        if body.body_type != BodyType::Kinematic {
            continue;
        }
        let Some(handle) = physics.body_handle(entity) else {
            continue;
        };
        if let Err(error) = physics.world.set_kinematic_target(handle, target.pose())
            && target.is_changed()
        {
            report(
                &mut errors,
                PhysicsError::refused(entity, "KinematicTarget", error),
            );
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
