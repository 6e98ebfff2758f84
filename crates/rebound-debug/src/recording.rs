//! Drawing a frame of a recording ([`rebound_record::Frame`]) with the descriptions its recording holds at
//! that frame ([`rebound_record::Catalog`]): the same drawing as [`crate::draw_world`] gives for the live
//! world the frame was taken from.

use crate::{DebugDraw, DebugSettings, JointGeometry, JointView, body_color, shape_aabb};
use rebound::{Pose, Quat};
use rebound_record::{Catalog, Frame, JointEntry, JointKindName};

impl JointGeometry {
    /// The geometry of a recorded joint's description.
    #[must_use]
    pub fn of_entry(entry: &JointEntry) -> Self {
        let limits = entry.limits.map(|l| (l.lower, l.upper));
        match entry.kind {
            JointKindName::Ball | JointKindName::Fixed => Self::Point,
            JointKindName::Spring | JointKindName::Rope | JointKindName::Rod => Self::Distance,
            JointKindName::Hinge => Self::Hinge { limits },
            JointKindName::Prismatic => Self::Slider { limits },
            JointKindName::Wheel => Self::Wheel { limits },
            JointKindName::SixDof => Self::Frame,
        }
    }
}

/// Everything `settings` asks for in a recorded frame, in a new [`DebugDraw`]. `catalog` must describe the
/// recording as of this frame (`Recording::catalog_at`, or `FrameReader::catalog` right after reading it).
#[must_use]
pub fn draw_frame(catalog: &Catalog, frame: &Frame, settings: &DebugSettings) -> DebugDraw {
    let mut draw = DebugDraw::new();
    draw.frame(catalog, frame, settings);
    draw
}

impl DebugDraw {
    /// Adds everything `settings` asks for in a recorded frame; see [`draw_frame`].
    pub fn frame(&mut self, catalog: &Catalog, frame: &Frame, settings: &DebugSettings) {
        let colors = &settings.colors;
        for (body, sample) in catalog.bodies().iter().zip(&frame.bodies) {
            if !sample.present {
                continue;
            }
            let body_pose = Pose::new(sample.position, sample.rotation);
            for collider in &body.colliders {
                if !collider.enabled || (collider.sensor && !settings.sensors) {
                    continue;
                }
                let pose = body_pose.mul_pose(&collider.local_pose);
                let color = body_color(
                    colors,
                    sample.kind.into(),
                    sample.sleeping,
                    collider.sensor,
                    settings.mark_sleeping,
                );
                self.shape(
                    &collider.shape,
                    pose,
                    color,
                    settings.outlines,
                    settings.solids,
                    settings.segments(),
                );
                if settings.bounding_boxes
                    && let Some((min, max)) = shape_aabb(&collider.shape, pose)
                {
                    self.aabb(min, max, colors.bounding_box);
                }
            }
        }
        if settings.contacts {
            for contact in &frame.contacts {
                self.contact(
                    contact.point,
                    contact.normal,
                    contact.normal_impulse,
                    settings,
                );
            }
        }
        if settings.joints || settings.joint_axes || settings.joint_limits {
            let rotation = |body: Option<u32>| {
                body.and_then(|b| frame.bodies.get(b as usize))
                    .map_or(Quat::IDENTITY, |s| s.rotation)
            };
            for (entry, sample) in catalog.joints().iter().zip(&frame.joints) {
                if !sample.present {
                    continue;
                }
                let view = JointView {
                    anchor_a: sample.anchor_a,
                    anchor_b: sample.anchor_b,
                    frame_a: rotation(entry.body_a) * entry.local_basis_a,
                    frame_b: rotation(Some(entry.body_b)) * entry.local_basis_b,
                    geometry: JointGeometry::of_entry(entry),
                    broken: sample.broken,
                };
                self.joint(&view, settings);
            }
        }
    }
}
