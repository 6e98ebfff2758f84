//! A 100-link rope chain released horizontally from a fixed point, with a 10× heavier ball at its end.

use super::About;
use rebound::prelude::*;

/// Links (balls) in the chain.
pub const LINKS: usize = 100;
/// Rope length between neighbouring balls (m).
pub const LINK: f32 = 0.25;

/// The scene file's name, run and view.
pub const ABOUT: About = About {
    name: "chain",
    description: "A 100-link rope chain released horizontally from a fixed point, a ten times heavier ball \
                  at its end: it swings down and hangs.",
    steps: 600,
    camera: (
        Vec3::new(0.0, -10.0, 48.0),
        Vec3::new(0.0, -11.0, 0.0),
        55.0,
    ),
};

/// The chain and its balls, from the anchor outwards.
#[derive(Debug)]
pub struct Chain {
    /// The world.
    pub world: PhysicsWorld,
    /// The balls, from the one next to the anchor to the heavy end.
    pub balls: Vec<BodyHandle>,
}

/// Builds the chain along +x from the world origin.
///
/// # Errors
/// Whatever Rebound refuses (a bug).
pub fn build() -> Result<Chain, Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let mut balls = Vec::new();
    let mut previous = None;
    for i in 0..LINKS {
        let density = if i == LINKS - 1 { 10_000.0 } else { 1_000.0 };
        let ball = world.insert_body(
            BodyDesc::dynamic()
                .with_position(Vec3::new((i + 1) as f32 * LINK, 0.0, 0.0))
                .with_can_sleep(false),
        )?;
        world.insert_collider(ColliderDesc::ball(0.1).with_density(density), ball)?;
        let rope = Joint::new(Rope::new(LINK)?);
        match previous {
            None => world.insert_world_joint(rope, ball)?,
            Some(prev) => world.insert_joint(rope, prev, ball)?,
        };
        balls.push(ball);
        previous = Some(ball);
    }
    Ok(Chain { world, balls })
}
