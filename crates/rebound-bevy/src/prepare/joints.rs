//! Preparing joints: inserting new ones once both bodies exist, editing them in place, re-creating them
//! when they name other bodies.

use super::{report, spawn_order};
use crate::{Body, Physics, PhysicsError, PhysicsJoint};
use bevy_ecs::entity::Entity;
use bevy_ecs::message::MessageWriter;
use bevy_ecs::query::{Changed, With};
use bevy_ecs::system::{Query, ResMut};
use rebound::BodyHandle;

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
