//! Drawing a whole [`rebound::PhysicsWorld`]: every enabled collider at its body's pose in the colour of its
//! body's kind (sleeping bodies and sensors marked), bounding boxes, the last step's contacts and every
//! joint — as [`DebugSettings`] chooses.

use crate::{Color, DebugColors, DebugDraw, DebugSettings, JointView, shape_aabb};
use rebound::{BodyType, PhysicsWorld, RigidBody};

/// The colour of a collider of `body` (a sensor if `sensor`).
#[must_use]
pub fn body_color(
    colors: &DebugColors,
    kind: BodyType,
    sleeping: bool,
    sensor: bool,
    mark_sleeping: bool,
) -> Color {
    if sensor {
        colors.sensor
    } else if sleeping && mark_sleeping {
        colors.sleeping
    } else {
        match kind {
            BodyType::Dynamic => colors.dynamic,
            BodyType::Fixed => colors.fixed,
            BodyType::Kinematic => colors.kinematic,
        }
    }
}

/// Everything `settings` asks for in `world`, in a new [`DebugDraw`].
///
/// ```
/// use rebound::prelude::*;
/// use rebound_debug::{DebugSettings, draw_world};
/// let mut world = PhysicsWorld::new(WorldSettings::default())?;
/// let body = world.insert_body(BodyDesc::dynamic())?;
/// world.insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)), body)?;
/// let draw = draw_world(&world, &DebugSettings::default());
/// assert_eq!(draw.lines.len(), 12);
/// # Ok::<(), rebound::Error>(())
/// ```
#[must_use]
pub fn draw_world(world: &PhysicsWorld, settings: &DebugSettings) -> DebugDraw {
    let mut draw = DebugDraw::new();
    draw.world(world, settings);
    draw
}

impl DebugDraw {
    /// Adds everything `settings` asks for in `world`.
    pub fn world(&mut self, world: &PhysicsWorld, settings: &DebugSettings) {
        let colors = &settings.colors;
        for (_, collider) in world.colliders().iter() {
            let desc = collider.desc();
            if !desc.enabled || (desc.is_sensor && !settings.sensors) {
                continue;
            }
            let Some(body) = world.body(collider.body()) else {
                continue;
            };
            let pose = collider.world_pose(body.pose());
            let color = body_color(
                colors,
                body.body_type(),
                body.is_sleeping(),
                desc.is_sensor,
                settings.mark_sleeping,
            );
            self.shape(
                &desc.shape,
                pose,
                color,
                settings.outlines,
                settings.solids,
                settings.segments(),
            );
            if settings.bounding_boxes
                && let Some((min, max)) = shape_aabb(&desc.shape, pose)
            {
                self.aabb(min, max, colors.bounding_box);
            }
        }
        if settings.contacts {
            for manifold in world.contacts() {
                let (Some(a), Some(b)) = (world.body(manifold.body_a), world.body(manifold.body_b))
                else {
                    continue;
                };
                let count = manifold.point_count.min(manifold.points.len());
                for point in &manifold.points[..count] {
                    let at = point.world_point(a.pose(), b.pose());
                    self.contact(at, manifold.normal, point.normal_impulse, settings);
                }
            }
        }
        if settings.joints || settings.joint_axes || settings.joint_limits {
            for (handle, joint) in world.world().joints() {
                let Some((a, b)) = world.joint_bodies(handle) else {
                    continue;
                };
                let pose_a = a.and_then(|a| world.body(a)).map(RigidBody::pose);
                let Some(body_b) = world.body(b) else {
                    continue;
                };
                let broken = world.joint_state(handle).is_some_and(|s| s.broken);
                self.joint(
                    &JointView::new(joint, pose_a, body_b.pose(), broken),
                    settings,
                );
            }
        }
    }
}
