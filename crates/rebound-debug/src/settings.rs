//! [`DebugSettings`]: what a [`crate::DebugDraw`] draws and in which colours. Public fields with
//! [`Default`]; struct-update syntax picks a few: `DebugSettings { contacts: false, ..Default::default() }`.

use crate::Color;

/// Which parts of a scene to draw, how big the markers are, and the colours.
#[derive(Debug, Clone, PartialEq)]
pub struct DebugSettings {
    /// Collider outlines (line segments). Default: true.
    pub outlines: bool,
    /// Collider surfaces (triangles). Default: false.
    pub solids: bool,
    /// Axis-aligned bounding boxes of the colliders. Default: false.
    pub bounding_boxes: bool,
    /// Contact points, normals and impulses. Default: true.
    pub contacts: bool,
    /// Joint anchors and the line between them. Default: true.
    pub joints: bool,
    /// Joint axes (hinge axis, slide axis, wheel axle and suspension). Default: true.
    pub joint_axes: bool,
    /// Joint limits (hinge arcs, slide and suspension ranges). Default: true.
    pub joint_limits: bool,
    /// Draw sleeping bodies' colliders in [`DebugColors::sleeping`]. Default: true.
    pub mark_sleeping: bool,
    /// Sensors (drawn in [`DebugColors::sensor`]). Default: true.
    pub sensors: bool,
    /// Segments per full circle of a round shape (≥ 3; fewer are drawn as 3). Default: 24.
    pub circle_segments: u32,
    /// Half the size of a contact or anchor cross (m). Default: 0.05.
    pub marker_size: f32,
    /// Length of a contact's normal segment (m). Default: 0.25.
    pub normal_length: f32,
    /// Length of a contact's impulse segment per unit of normal impulse (m per N·s). Default: 0.1.
    pub impulse_scale: f32,
    /// Length of a drawn joint axis (m); also the radius of a hinge's limit arc. Default: 0.5.
    pub joint_axis_length: f32,
    /// The colours.
    pub colors: DebugColors,
}

impl Default for DebugSettings {
    fn default() -> Self {
        Self {
            outlines: true,
            solids: false,
            bounding_boxes: false,
            contacts: true,
            joints: true,
            joint_axes: true,
            joint_limits: true,
            mark_sleeping: true,
            sensors: true,
            circle_segments: 24,
            marker_size: 0.05,
            normal_length: 0.25,
            impulse_scale: 0.1,
            joint_axis_length: 0.5,
            colors: DebugColors::default(),
        }
    }
}

impl DebugSettings {
    /// Everything on, solids included.
    #[must_use]
    pub fn all() -> Self {
        Self {
            solids: true,
            bounding_boxes: true,
            ..Self::default()
        }
    }

    /// [`DebugSettings::circle_segments`], at least 3.
    #[must_use]
    pub fn segments(&self) -> u32 {
        self.circle_segments.max(3)
    }
}

/// The colours of each kind of thing drawn.
#[derive(Debug, Clone, PartialEq)]
pub struct DebugColors {
    /// Colliders of dynamic bodies. Default: orange.
    pub dynamic: Color,
    /// Colliders of fixed bodies. Default: grey.
    pub fixed: Color,
    /// Colliders of kinematic bodies. Default: light blue.
    pub kinematic: Color,
    /// Colliders of sleeping bodies (with [`DebugSettings::mark_sleeping`]). Default: dark blue-grey.
    pub sleeping: Color,
    /// Sensors. Default: translucent green.
    pub sensor: Color,
    /// Bounding boxes. Default: yellow.
    pub bounding_box: Color,
    /// Contact point crosses. Default: red.
    pub contact_point: Color,
    /// Contact normals. Default: magenta.
    pub contact_normal: Color,
    /// Contact impulses. Default: yellow-orange.
    pub contact_impulse: Color,
    /// Joint anchors and the line between them. Default: cyan.
    pub joint: Color,
    /// Joint axes. Default: blue.
    pub joint_axis: Color,
    /// Joint limits. Default: violet.
    pub joint_limit: Color,
    /// Broken joints. Default: dark red.
    pub broken_joint: Color,
}

impl Default for DebugColors {
    fn default() -> Self {
        Self {
            dynamic: Color::rgb(0.95, 0.55, 0.15),
            fixed: Color::rgb(0.6, 0.6, 0.6),
            kinematic: Color::rgb(0.4, 0.7, 1.0),
            sleeping: Color::rgb(0.35, 0.4, 0.55),
            sensor: Color::rgba(0.2, 0.9, 0.3, 0.5),
            bounding_box: Color::rgb(0.9, 0.9, 0.2),
            contact_point: Color::RED,
            contact_normal: Color::rgb(0.9, 0.2, 0.9),
            contact_impulse: Color::rgb(1.0, 0.75, 0.1),
            joint: Color::rgb(0.1, 0.9, 0.9),
            joint_axis: Color::rgb(0.2, 0.3, 1.0),
            joint_limit: Color::rgb(0.65, 0.35, 0.95),
            broken_joint: Color::rgb(0.55, 0.05, 0.05),
        }
    }
}
