//! Preparing colliders: attaching new ones to the body of their entity or nearest ancestor, replacing
//! edited ones, moving child colliders whose `Transform` changed.

use super::{report, spawn_order};
use crate::body::pose_of;
use crate::physics::ColliderRecord;
use crate::{Body, Collider, Physics, PhysicsError};
use bevy_ecs::entity::Entity;
use bevy_ecs::hierarchy::ChildOf;
use bevy_ecs::message::MessageWriter;
use bevy_ecs::query::{Changed, With, Without};
use bevy_ecs::system::{Query, ResMut};
use bevy_transform::components::Transform;
use rebound::prelude::Pose;

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
