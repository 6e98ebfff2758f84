//! Drag and drop: a box on the ground, to be picked by a ray and carried by a spring from a moving cursor.

use super::About;
use rebound::prelude::*;

/// The scene file's name, run and view.
pub const ABOUT: About = About {
    name: "drag_and_drop",
    description: "A 1 m box of 200 kg/m³ on the ground, ready to be picked by a ray and dragged on a spring \
                  (the example does the dragging; the file holds the box and the ground).",
    steps: 120,
    camera: (Vec3::new(1.5, 3.0, 7.0), Vec3::new(1.0, 1.0, 0.0), 45.0),
};

/// The ground and the box.
#[derive(Debug)]
pub struct DragAndDrop {
    /// The world.
    pub world: PhysicsWorld,
    /// The box.
    pub crate_box: BodyHandle,
}

/// Builds the ground and the box resting on it.
///
/// # Errors
/// Whatever Rebound refuses (a bug).
pub fn build() -> Result<DragAndDrop, Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let ground = world.insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))?;
    world.insert_collider(ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0)), ground)?;
    let crate_box =
        world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.5, 0.0)))?;
    world.insert_collider(
        ColliderDesc::cuboid(Vec3::splat(0.5)).with_density(200.0),
        crate_box,
    )?;
    Ok(DragAndDrop { world, crate_box })
}
