//! Newton's cradle: five steel balls on ropes, 1 mm apart, perfectly elastic. The first is lifted 30° and
//! released; the impulse passes along the row and the last ball flies off.

use super::About;
use rebound::prelude::*;

/// Ball radius (m).
pub const RADIUS: f32 = 0.1;
/// Rope length (m).
pub const LENGTH: f32 = 1.0;
/// Gap between neighbouring balls at rest (m).
pub const GAP: f32 = 0.001;
/// How far the first ball is lifted (degrees).
pub const LIFT_DEGREES: f32 = 30.0;

/// The scene file's name, run and view.
pub const ABOUT: About = About {
    name: "newtons_cradle",
    description: "Newton's cradle: five steel balls on 1 m ropes, 1 mm apart, perfectly elastic; the first \
                  is lifted 30 degrees and released, and the last swings out.",
    steps: 150,
    camera: (Vec3::new(0.4, -0.55, 2.6), Vec3::new(0.4, -0.75, 0.0), 40.0),
};

/// The cradle and its balls, first (lifted) to last.
#[derive(Debug)]
pub struct NewtonsCradle {
    /// The world.
    pub world: PhysicsWorld,
    /// The balls, from the lifted one to the last.
    pub balls: Vec<BodyHandle>,
}

/// Builds the cradle: each ball hangs from a world point on a rope of [`LENGTH`].
///
/// # Errors
/// Whatever Rebound refuses (a bug).
pub fn build() -> Result<NewtonsCradle, Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let mut balls = Vec::new();
    for i in 0..5 {
        let anchor = Vec3::new(i as f32 * (2.0 * RADIUS + GAP), 0.0, 0.0);
        let angle = if i == 0 {
            LIFT_DEGREES.to_radians()
        } else {
            0.0
        };
        let start = anchor + Vec3::new(-LENGTH * angle.sin(), -LENGTH * angle.cos(), 0.0);
        let ball = world.insert_body(BodyDesc::dynamic().with_position(start))?;
        world.insert_collider(
            ColliderDesc::ball(RADIUS)
                .with_density(7800.0)
                .with_restitution(1.0)
                .with_restitution_combine_rule(CombineRule::Max)
                .with_friction(0.0),
            ball,
        )?;
        let rope = Joint::new(Rope::new(LENGTH)?).with_local_anchors(anchor, Vec3::ZERO)?;
        world.insert_world_joint(rope, ball)?;
        balls.push(ball);
    }
    Ok(NewtonsCradle { world, balls })
}
