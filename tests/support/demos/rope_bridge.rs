//! A rope bridge: 40 planks on hinges between two anchors 19 m apart, slack, with 10 balls dropped on it.

use super::About;
use rebound::prelude::*;

/// Planks in the deck.
pub const PLANKS: usize = 40;
/// A plank's half-extents (m).
pub const HALF: Vec3 = Vec3::new(0.25, 0.05, 0.8);
/// Distance between the two anchors (m).
pub const SPAN: f32 = 19.0;
/// Height of the anchors (m).
pub const ANCHOR_HEIGHT: f32 = 10.0;
/// How far above the deck the balls start (m).
pub const DROP_HEIGHT: f32 = 1.0;

/// The scene file's name, run and view.
pub const ABOUT: About = About {
    name: "rope_bridge",
    description: "A rope bridge: 40 planks on hinges between anchors 19 m apart, 20 m of deck, with ten \
                  balls dropped on it from 1 m above.",
    steps: 600,
    camera: (Vec3::new(4.0, 12.0, 22.0), Vec3::new(0.0, 7.5, 0.0), 50.0),
};

/// The bridge, its hinges and the balls.
#[derive(Debug)]
pub struct RopeBridge {
    /// The world.
    pub world: PhysicsWorld,
    /// The planks, left to right.
    pub planks: Vec<BodyHandle>,
    /// The hinges: left anchor, between planks, right anchor.
    pub joints: Vec<JointHandle>,
    /// The balls.
    pub balls: Vec<BodyHandle>,
    /// The deck's starting sag below the anchors at mid-span (m).
    pub start_sag: f32,
}

/// Builds the bridge with its planks on the circular arc that leaves every hinge satisfied, and the balls
/// [`DROP_HEIGHT`] above the deck.
///
/// # Errors
/// Whatever Rebound refuses (a bug).
pub fn build() -> Result<RopeBridge, Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let deck = PLANKS as f32 * 2.0 * HALF.x;
    let (left, right) = (
        Vec3::new(-SPAN / 2.0, ANCHOR_HEIGHT, 0.0),
        Vec3::new(SPAN / 2.0, ANCHOR_HEIGHT, 0.0),
    );
    let hinge = |a: Vec3, b: Vec3| {
        Joint::new(HingeJoint::new())
            .with_local_anchors(a, b)?
            .with_local_axes(Vec3::Z, Vec3::Z)
    };

    // The planks start as the chords of a circular arc through both anchors, so every hinge starts
    // satisfied: R solves 2R·sin(n·asin(a/R)) = span (a = half a plank), by bisection.
    let n = PLANKS as f32;
    let chord = |r: f32| 2.0 * r * (n * (HALF.x / r).asin()).sin() - SPAN;
    let (mut lo, mut hi) = (deck / 3.0, 1000.0f32);
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if chord(mid) < 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    let radius = 0.5 * (lo + hi);
    let theta = 2.0 * (HALF.x / radius).asin();
    let half_angle = 0.5 * n * theta;
    let centre_y = ANCHOR_HEIGHT + radius * half_angle.cos();
    let point = |phi: f32| Vec3::new(radius * phi.sin(), centre_y - radius * phi.cos(), 0.0);

    let mut planks = Vec::new();
    let mut joints = Vec::new();
    for i in 0..PLANKS {
        let (a, b) = (
            point(-half_angle + i as f32 * theta),
            point(-half_angle + (i + 1) as f32 * theta),
        );
        let angle = -half_angle + (i as f32 + 0.5) * theta;
        let plank = world.insert_body(
            BodyDesc::dynamic()
                .with_position((a + b) * 0.5)
                .with_rotation(Quat::from_rotation_z(angle)),
        )?;
        world.insert_collider(
            ColliderDesc::cuboid(HALF)
                .with_density(600.0)
                .with_friction(0.8),
            plank,
        )?;
        let joint = match planks.last() {
            None => world.insert_world_joint(hinge(left, Vec3::new(-HALF.x, 0.0, 0.0))?, plank)?,
            Some(&prev) => world.insert_joint(
                hinge(Vec3::new(HALF.x, 0.0, 0.0), Vec3::new(-HALF.x, 0.0, 0.0))?,
                prev,
                plank,
            )?,
        };
        world.set_joint_contacts_enabled(joint, false)?;
        joints.push(joint);
        planks.push(plank);
    }
    if let Some(&last) = planks.last() {
        joints.push(world.insert_world_joint(hinge(right, Vec3::new(HALF.x, 0.0, 0.0))?, last)?);
    }
    let mut balls = Vec::new();
    for k in 0..10 {
        let x = -7.0 + k as f32 * 1.5;
        let deck_y = centre_y - (radius * radius - x * x).sqrt();
        let ball = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(
            x,
            deck_y + DROP_HEIGHT,
            0.1 * (k % 3) as f32,
        )))?;
        world.insert_collider(
            ColliderDesc::ball(0.25)
                .with_density(1000.0)
                .with_friction(0.8),
            ball,
        )?;
        balls.push(ball);
    }
    Ok(RopeBridge {
        world,
        planks,
        joints,
        balls,
        start_sag: ANCHOR_HEIGHT - (centre_y - radius),
    })
}
