//! A third-person camera on a damped spring behind a kinematic "player", in zero gravity.

use super::About;
use rebound::prelude::*;

/// Where the camera wants to be, relative to the player (m): 4 m behind, 2 m above.
pub const BOOM: Vec3 = Vec3::new(-4.0, 2.0, 0.0);

/// The scene file's name, run and view (the file holds the under-damped boom, ζ = 0.3).
pub const ABOUT: About = About {
    name: "spring_camera",
    description: "A camera body on a 2 Hz spring (damping ratio 0.3) to a point 4 m behind and 2 m above a \
                  kinematic player, in zero gravity (the example drives the player).",
    steps: 300,
    camera: (Vec3::new(4.0, 6.0, 16.0), Vec3::new(2.0, 1.0, 0.0), 50.0),
};

/// The player and the camera body.
#[derive(Debug)]
pub struct SpringCamera {
    /// The world.
    pub world: PhysicsWorld,
    /// The kinematic player.
    pub player: BodyHandle,
    /// The camera body on the spring.
    pub camera: BodyHandle,
}

/// Builds the player at the origin and the camera at [`BOOM`] on a 2 Hz spring of `damping_ratio`.
///
/// # Errors
/// A negative or non-finite `damping_ratio`.
pub fn build(damping_ratio: f32) -> Result<SpringCamera, Error> {
    let mut world = PhysicsWorld::new(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    })?;
    let player = world.insert_body(BodyDesc::kinematic())?;
    let camera = world.insert_body(
        BodyDesc::dynamic()
            .with_position(BOOM)
            .with_can_sleep(false),
    )?;
    world.insert_collider(
        ColliderDesc::ball(0.2).with_density(50.0).with_sensor(true),
        camera,
    )?;
    let spring = Joint::new(Spring::new(
        0.0,
        SpringModel::soft_frequency(2.0, damping_ratio)?,
    )?)
    .with_local_anchors(BOOM, Vec3::ZERO)?;
    world.insert_joint(spring, player, camera)?;
    Ok(SpringCamera {
        world,
        player,
        camera,
    })
}
