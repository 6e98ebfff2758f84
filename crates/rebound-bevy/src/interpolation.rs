//! Interpolation of rendered transforms between fixed steps: a body with [`TransformInterpolation`] shows, each
//! frame, the pose between its last two physics poses at the fraction of a timestep the fixed clock has
//! accumulated (`Time<Fixed>::overstep_fraction`). Runs once per frame after the fixed main loop.
//!
//! Written here rather than taken from an interpolation crate: those depend on the full `bevy` crate.
//! Showing the pose between the last two steps puts the picture up to one timestep behind the simulation, the
//! usual price of smooth motion at any frame rate.

use crate::body::pose_of;
use crate::prepare::same_pose;
use crate::{Body, Physics};
use bevy_ecs::component::Component;
use bevy_ecs::entity::Entity;
use bevy_ecs::query::With;
use bevy_ecs::system::{Query, Res, ResMut};
use bevy_time::{Fixed, Time};
use bevy_transform::components::Transform;
use rebound::prelude::Pose;

/// Marks a body whose `Transform` is interpolated between physics steps for smooth rendering. Its
/// `Transform` then shows the interpolated pose; editing it still teleports the body.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct TransformInterpolation;

/// The pose a fraction `alpha` of the way from `previous` to `current`: positions interpolated linearly,
/// rotations spherically (shortest arc). `alpha` is clamped to [0, 1]: 0 gives `previous`, 1 `current`.
///
/// ```
/// use rebound_bevy::interpolate_pose;
/// use rebound_bevy::prelude::{Pose, Quat, Vec3};
/// let a = Pose::new(Vec3::ZERO, Quat::IDENTITY);
/// let b = Pose::new(Vec3::new(2.0, 0.0, 0.0), Quat::from_rotation_y(1.0));
/// let mid = interpolate_pose(a, b, 0.5);
/// assert!((mid.position.x - 1.0).abs() < 1e-6);
/// assert!(mid.rotation.angle_between(Quat::from_rotation_y(0.5)) < 1e-5);
/// ```
#[must_use]
pub fn interpolate_pose(previous: Pose, current: Pose, alpha: f32) -> Pose {
    let alpha = alpha.clamp(0.0, 1.0);
    Pose::new(
        previous.position.lerp(current.position, alpha),
        previous.rotation.slerp(current.rotation, alpha).normalize(),
    )
}

/// Writes the interpolated pose of every interpolated body. A `Transform` the user edited since the plugin
/// last wrote it is left alone: the next step reads it as a teleport.
pub(crate) fn interpolate_transforms(
    mut physics: ResMut<'_, Physics>,
    time: Option<Res<'_, Time<Fixed>>>,
    mut query: Query<'_, '_, (Entity, &mut Transform), (With<Body>, With<TransformInterpolation>)>,
) {
    let Some(time) = time else {
        return;
    };
    let alpha = time.overstep_fraction();
    for (entity, mut transform) in &mut query {
        let Some(record) = physics.bodies.get_mut(&entity) else {
            continue;
        };
        if !same_pose(pose_of(&transform), record.written_pose) {
            continue;
        }
        let pose = interpolate_pose(record.previous_pose, record.current_pose, alpha);
        if !same_pose(pose, record.written_pose) {
            transform.translation = pose.position;
            transform.rotation = pose.rotation;
            record.written_pose = pose;
        }
    }
}
