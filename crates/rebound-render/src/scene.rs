//! `RenderScene`: what one picture shows — meshes at world poses with colours, and the optional contact
//! points and joint segments drawn over them. Built by hand, from a live [`PhysicsWorld`], or from a
//! recorded frame.

use std::sync::Arc;

use rebound::PhysicsWorld;
use rebound::prelude::{Pose, Vec3};

use crate::{DEFAULT_ROUND_SUBDIVISIONS, Mesh, RenderError, Rgba};

/// A mesh placed in the world.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneObject {
    /// The triangles, in the object's frame (shared: a recording tessellates each shape once).
    pub mesh: Arc<Mesh>,
    /// Where the object is: the mesh frame in the world (m, unit quaternion).
    pub pose: Pose,
    /// Its colour before shading (alpha ignored: solids are opaque).
    pub colour: Rgba,
}

/// A contact point, drawn as a dot with a stroke along its normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactMark {
    /// The point (m, world).
    pub point: Vec3,
    /// The contact normal (unit, world; drawn from `point`).
    pub normal: Vec3,
}

/// A joint, drawn as the segment between its two world anchors with a dot at each end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointSegment {
    /// Anchor on the first body (m, world).
    pub anchor_a: Vec3,
    /// Anchor on the second body (m, world).
    pub anchor_b: Vec3,
}

/// Everything one picture shows.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RenderScene {
    /// The solids.
    pub objects: Vec<SceneObject>,
    /// Contact points (drawn over the solids when [`crate::RenderOptions::contacts`] is on).
    pub contacts: Vec<ContactMark>,
    /// Joint segments (drawn over the solids when [`crate::RenderOptions::joints`] is on).
    pub joints: Vec<JointSegment>,
}

/// Colour of fixed bodies' colliders.
pub const FIXED_COLOUR: Rgba = Rgba::opaque(150, 150, 145);

/// Colours given to dynamic bodies in turn, by body index.
pub const PALETTE: [Rgba; 6] = [
    Rgba::opaque(222, 110, 75),
    Rgba::opaque(80, 145, 210),
    Rgba::opaque(235, 190, 70),
    Rgba::opaque(110, 185, 120),
    Rgba::opaque(170, 120, 200),
    Rgba::opaque(95, 190, 190),
];

/// Share of its colour a sleeping body keeps.
pub const SLEEPING_SHADE: f32 = 0.6;

/// The colour of body number `index` (its handle's slot in a world, its index in a recording — the same for
/// a world whose bodies were never removed): [`FIXED_COLOUR`] unless `dynamic`, else [`PALETTE`] in turn,
/// darkened by [`SLEEPING_SHADE`] while `sleeping`.
#[must_use]
pub fn body_colour(index: u32, dynamic: bool, sleeping: bool) -> Rgba {
    if !dynamic {
        return FIXED_COLOUR;
    }
    let colour = PALETTE[index as usize % PALETTE.len()];
    if sleeping {
        colour.scaled(SLEEPING_SHADE)
    } else {
        colour
    }
}

impl RenderScene {
    /// An empty scene.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Adds a mesh at `pose` in `colour`.
    pub fn push(&mut self, mesh: Arc<Mesh>, pose: Pose, colour: Rgba) {
        self.objects.push(SceneObject { mesh, pose, colour });
    }

    /// The enabled, non-sensor colliders of `world` at their current poses, coloured by [`body_colour`],
    /// and the contact
    /// points of its manifolds (on body A's surface, with the normal from A to B). No joints: a live world
    /// does not expose its joints' world anchors; a recording does.
    ///
    /// # Errors
    /// [`RenderError::Shape`] if a collider's shape cannot be tessellated (never, for shapes the world holds).
    pub fn from_world(world: &PhysicsWorld) -> Result<Self, RenderError> {
        let mut scene = Self::new();
        for (_, collider) in world.colliders().iter() {
            if collider.is_sensor() || !collider.is_enabled() {
                continue;
            }
            let Some(body) = world.body(collider.body()) else {
                continue;
            };
            let mesh = Mesh::from_shape(&collider.desc().shape, DEFAULT_ROUND_SUBDIVISIONS)?;
            let colour = if body.is_dynamic() {
                let (index, _) = collider.body().into_raw_parts();
                let colour = PALETTE[index as usize % PALETTE.len()];
                if body.is_sleeping() {
                    colour.scaled(0.6)
                } else {
                    colour
                }
            } else {
                FIXED_COLOUR
            };
            scene.push(Arc::new(mesh), collider.world_pose(body.pose()), colour);
        }
        for manifold in world.contacts() {
            let Some(body_a) = world.body(manifold.body_a) else {
                continue;
            };
            let pose = body_a.pose();
            for point in manifold.points.iter().take(manifold.point_count) {
                scene.contacts.push(ContactMark {
                    point: pose.transform_point(point.local_anchor_a),
                    normal: manifold.normal,
                });
            }
        }
        Ok(scene)
    }
}
