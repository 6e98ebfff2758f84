//! A pyramid of boxes, base 20 (210 boxes), left to stand.

use super::About;
use rebound::prelude::*;

/// Boxes in the bottom row.
pub const BASE: usize = 20;

/// The scene file's name, run and view.
pub const ABOUT: About = About {
    name: "pyramid",
    description: "A pyramid of 210 unit boxes, base 20, standing on the ground for 10 s.",
    steps: 600,
    camera: (Vec3::new(14.0, 12.0, 26.0), Vec3::new(0.0, 7.0, 0.0), 45.0),
};

/// The pyramid and its boxes with their starting positions.
#[derive(Debug)]
pub struct Pyramid {
    /// The world.
    pub world: PhysicsWorld,
    /// Each box and where it started (m), bottom row first; the last is the top box.
    pub boxes: Vec<(BodyHandle, Vec3)>,
}

/// Builds the pyramid on a 100 m ground.
///
/// # Errors
/// Whatever Rebound refuses (a bug).
pub fn build() -> Result<Pyramid, Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let ground = world.insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))?;
    world.insert_collider(ColliderDesc::cuboid(Vec3::new(50.0, 0.5, 50.0)), ground)?;
    let mut boxes = Vec::new();
    for row in 0..BASE {
        for j in 0..(BASE - row) {
            let x = j as f32 - (BASE - row - 1) as f32 / 2.0;
            let y = 0.5 + row as f32;
            let body =
                world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(x, y, 0.0)))?;
            world.insert_collider(
                ColliderDesc::cuboid(Vec3::splat(0.5)).with_density(1.0),
                body,
            )?;
            boxes.push((body, Vec3::new(x, y, 0.0)));
        }
    }
    Ok(Pyramid { world, boxes })
}
