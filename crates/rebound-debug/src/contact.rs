//! Drawing a contact point: a cross at the point, its normal, and its normal impulse as a segment along the
//! normal whose length is proportional to the impulse.

use crate::{DebugDraw, DebugSettings, Layer};
use rebound::Vec3;

impl DebugDraw {
    /// Draws a contact at the world point `point` with unit normal `normal` (from body A to body B) and normal
    /// impulse `normal_impulse` (N·s): a cross of half-size [`DebugSettings::marker_size`], the normal from
    /// `point` to `point + normal_length·normal`, and, if the impulse is positive, a segment from `point` to
    /// `point + impulse_scale·normal_impulse·normal`.
    pub fn contact(
        &mut self,
        point: Vec3,
        normal: Vec3,
        normal_impulse: f32,
        settings: &DebugSettings,
    ) {
        let colors = &settings.colors;
        self.cross(
            point,
            settings.marker_size,
            colors.contact_point,
            Layer::Contact,
        );
        self.line(
            point,
            point + normal * settings.normal_length,
            colors.contact_normal,
            Layer::Contact,
        );
        if normal_impulse > 0.0 {
            self.line(
                point,
                point + normal * (settings.impulse_scale * normal_impulse),
                colors.contact_impulse,
                Layer::Contact,
            );
        }
    }
}
