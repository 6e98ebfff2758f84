//! Preparing bodies: inserting new ones, applying `Body` edits, reading `Transform`, `Velocity` and
//! `Sleeping` edits (teleports, kicks, wake-ups), and mass overrides.

use super::{edit_copy, report, same_pose, same_vec3, spawn_order};
use crate::body::pose_of;
use crate::physics::BodyRecord;
use crate::{Body, MassOverride, Physics, PhysicsError, Sleeping, Velocity};
use bevy_ecs::change_detection::{DetectChanges, Ref};
use bevy_ecs::entity::Entity;
use bevy_ecs::lifecycle::RemovedComponents;
use bevy_ecs::message::MessageWriter;
use bevy_ecs::query::{Changed, With};
use bevy_ecs::system::{Query, ResMut};
use bevy_transform::components::Transform;
use rebound::BodyHandle;
use rebound::prelude::MassProperties;

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
        if let Some((field, value, component)) = body.foreign_field() {
            let error = PhysicsError::BodyField {
                entity,
                field,
                value,
                component,
            };
            if !physics.bodies.contains_key(&entity) {
                physics.refused_bodies.insert(entity);
            }
            report(&mut errors, error);
            continue;
        }
        if let Some(record) = physics.bodies.get(&entity).copied() {
            if let Err(error) = edit_body(&mut physics.world, record.handle, &body) {
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
fn edit_body(
    world: &mut rebound::PhysicsWorld,
    handle: BodyHandle,
    body: &Body,
) -> Result<(), rebound::Error> {
    let desc = &body.desc;
    edit_copy(world, handle, |edited| {
        if edited.body_type() != desc.body_type {
            edited.set_body_type(desc.body_type);
        }
        edited.set_gravity_scale(desc.gravity_scale)?;
        edited.set_linear_damping(desc.linear_damping)?;
        edited.set_angular_damping(desc.angular_damping)?;
        edited.set_integrator(desc.integrator);
        edited.set_can_sleep(desc.can_sleep);
        edited.set_gyroscopic(desc.gyroscopic);
        edited.set_locked_axes(desc.locked_axes);
        Ok(())
    })
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
            if let Err(error) = edit_copy(world, record.handle, |body| {
                body.set_linear_velocity(value.0)?;
                body.set_angular_velocity(value.1)
            }) {
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
