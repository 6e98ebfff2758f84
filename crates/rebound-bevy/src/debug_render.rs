//! [`PhysicsDebugRender`]: the debug-draw description of the physics world (collider outlines, bounding
//! boxes, contacts, joints as coloured line segments and triangles, from `rebound-debug`) as a resource any
//! renderer can draw. Filled after each step's writeback while enabled.

use crate::Physics;
use bevy_ecs::resource::Resource;
use bevy_ecs::system::{Res, ResMut};
use rebound_debug::{DebugDraw, DebugSettings};

/// The world's debug lines and triangles, refilled after every physics step while `enabled`.
///
/// With full Bevy, draw it with gizmos:
///
/// ```rust,ignore
/// fn draw_physics(debug: Res<PhysicsDebugRender>, mut gizmos: Gizmos) {
///     for line in &debug.draw.lines {
///         let [r, g, b, a] = line.color.to_array();
///         gizmos.line(line.a, line.b, Color::linear_rgba(r, g, b, a));
///     }
/// }
/// ```
#[derive(Resource, Debug, Clone, PartialEq, Default)]
pub struct PhysicsDebugRender {
    /// Whether the description is built (it costs a pass over every collider, contact and joint). Default:
    /// false.
    pub enabled: bool,
    /// What to draw and in which colours. Default: [`DebugSettings::default`] (outlines, contacts, joints).
    pub settings: DebugSettings,
    /// The description after the last step (world space, m): empty while disabled.
    pub draw: DebugDraw,
}

impl PhysicsDebugRender {
    /// Debug drawing switched on with the default settings.
    #[must_use]
    pub fn enabled() -> Self {
        Self {
            enabled: true,
            ..Self::default()
        }
    }
}

/// Rebuilds the description from the world (or empties it when disabled).
pub(crate) fn build_debug_render(
    physics: Res<'_, Physics>,
    mut debug: ResMut<'_, PhysicsDebugRender>,
) {
    let debug = &mut *debug;
    debug.draw.clear();
    if debug.enabled {
        debug.draw.world(physics.world(), &debug.settings);
    }
}
