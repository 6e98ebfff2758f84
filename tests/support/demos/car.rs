//! A car: a chassis on four wheel joints (suspension spring, free axle, rear-wheel drive) on a bumpy height
//! field.

use super::About;
use rebound::prelude::*;

/// Wheel radius (m).
pub const WHEEL_RADIUS: f32 = 0.4;

/// The scene file's name, run and view.
pub const ABOUT: About = About {
    name: "car",
    description: "A car: a chassis on four wheel joints with suspension springs, rear-wheel drive at 12 rad/s, \
                  over a bumpy 120 m height field.",
    steps: 240,
    camera: (Vec3::new(8.0, 5.0, 17.0), Vec3::new(8.0, 0.5, 0.0), 50.0),
};

/// The car.
#[derive(Debug)]
pub struct Car {
    /// The world.
    pub world: PhysicsWorld,
    /// The chassis.
    pub chassis: BodyHandle,
    /// The wheels: front left, front right, rear left, rear right.
    pub wheels: Vec<BodyHandle>,
}

/// Builds the terrain (120 m × 20 m, 1 m cells, bumps up to 15 cm) and the car on it.
///
/// # Errors
/// Whatever Rebound refuses (a bug).
pub fn build() -> Result<Car, Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    let (rows, cols) = (21usize, 121usize);
    let heights: Vec<f32> = (0..rows * cols)
        .map(|i| 0.15 * (0.5 * (i % cols) as f32).sin() * (0.7 * (i / cols) as f32).cos())
        .collect();
    let ground = world.insert_body(BodyDesc::fixed().with_position(Vec3::new(50.0, 0.0, 0.0)))?;
    world.insert_collider(
        ColliderDesc::heightfield(
            rows,
            cols,
            heights,
            Vec3::new((cols - 1) as f32, 1.0, (rows - 1) as f32),
        )
        .with_friction(1.0),
        ground,
    )?;

    let chassis = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 1.2, 0.0)))?;
    world.insert_collider(
        ColliderDesc::cuboid(Vec3::new(1.5, 0.25, 0.8)).with_density(300.0),
        chassis,
    )?;
    let mut wheels = Vec::new();
    for (x, z, driven) in [
        (1.1, 0.9, false),
        (1.1, -0.9, false),
        (-1.1, 0.9, true),
        (-1.1, -0.9, true),
    ] {
        let mount = Vec3::new(x, -0.35, z);
        let wheel = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 1.2, 0.0) + mount))?;
        world.insert_collider(
            ColliderDesc::ball(WHEEL_RADIUS)
                .with_density(400.0)
                .with_friction(1.0),
            wheel,
        )?;
        let mut kind = WheelJoint::new(SoftSpring::frequency(2.0, 0.7)?)?
            .with_suspension_limits(Limits::new(-0.3, 0.2)?);
        if driven {
            // Spinning about −z rolls the car towards +x; at most 600 N·m per wheel.
            kind = kind.with_motor(Motor::new(-12.0, 600.0)?);
        }
        let joint = Joint::new(kind)
            .with_local_anchors(mount, Vec3::ZERO)?
            .with_local_axes(Vec3::Z, Vec3::Z)?;
        let handle = world.insert_joint(joint, chassis, wheel)?;
        world.set_joint_contacts_enabled(handle, false)?;
        wheels.push(wheel);
    }
    Ok(Car {
        world,
        chassis,
        wheels,
    })
}
