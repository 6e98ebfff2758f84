//! Preparing forces: held forces, one-shot impulses and kinematic targets, applied before each step.

use super::{edit_copy, report, same_vec3};
use crate::{Body, ExternalForce, ExternalImpulse, KinematicTarget, Physics, PhysicsError};
use bevy_ecs::change_detection::{DetectChanges, Ref};
use bevy_ecs::entity::Entity;
use bevy_ecs::message::MessageWriter;
use bevy_ecs::system::{Query, ResMut};
use rebound::prelude::{BodyType, Vec3};

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
        if body.desc.body_type != BodyType::Kinematic {
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
