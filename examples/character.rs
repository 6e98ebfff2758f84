//! A character controller walking a course: up three 0.2 m stairs (autostep), down a 15° ramp (snapped to
//! it), into a 10 kg crate (pushed ahead), onto a low platform and then carried 3 m by it. The capsule is a
//! kinematic body moved by `CharacterController::move_collider`; the example prints what it did and checks
//! it against the course's numbers.
//!
//! Run: `cargo run --release --example character [-- --record character.rrec --gif character.gif]`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

mod support;

use rebound::RigidBody;
use rebound::prelude::*;
use rebound_suite::demos::{About, DT};

const RADIUS: f32 = 0.3;
const HALF_HEIGHT: f32 = 0.5;
const WALK_SPEED: f32 = 2.0;
const PLATFORM_SPEED: f32 = 1.0;
const G: f32 = 9.81;

const ABOUT: About = About {
    name: "character",
    description: "A capsule character walking up stairs, down a ramp, pushing a crate and riding a platform.",
    steps: 660,
    camera: (Vec3::new(7.0, 7.0, 15.0), Vec3::new(7.0, 0.5, 1.5), 50.0),
};

/// The course and the bodies the example watches.
struct Course {
    world: PhysicsWorld,
    character: BodyHandle,
    collider: ColliderHandle,
    crate_body: BodyHandle,
    platform: BodyHandle,
}

fn fixed_box(
    world: &mut PhysicsWorld,
    centre: Vec3,
    half_extents: Vec3,
    rotation: Quat,
) -> Result<(), Error> {
    let body = world.insert_body(
        BodyDesc::fixed()
            .with_position(centre)
            .with_rotation(rotation),
    )?;
    world.insert_collider(ColliderDesc::cuboid(half_extents), body)?;
    Ok(())
}

fn build() -> Result<Course, Error> {
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    // The floor, top at y = 0.
    fixed_box(
        &mut world,
        Vec3::new(8.0, -0.5, 0.0),
        Vec3::new(20.0, 0.5, 20.0),
        Quat::IDENTITY,
    )?;
    // Three stairs 0.2 m high and 0.4 m deep from x = 2; the landing (top 0.6 m) ends at x = 5.
    for k in 0..3 {
        let (start, top) = (2.0 + 0.4 * k as f32, 0.2 * (k + 1) as f32);
        fixed_box(
            &mut world,
            Vec3::new((start + 5.0) / 2.0, top / 2.0, 0.0),
            Vec3::new((5.0 - start) / 2.0, top / 2.0, 1.5),
            Quat::IDENTITY,
        )?;
    }
    // A 15° ramp from the landing's edge (5, 0.6) down to the floor.
    let angle = 15f32.to_radians();
    let rotation = Quat::from_rotation_z(-angle);
    let normal = rotation * Vec3::Y;
    let length = 0.6 / angle.sin();
    let middle = Vec3::new(5.0 + 0.5 * length * angle.cos(), 0.3, 0.0);
    fixed_box(
        &mut world,
        middle - normal * 0.1,
        Vec3::new(0.5 * length, 0.1, 1.5),
        rotation,
    )?;
    // A 10 kg crate (0.8 m cube), its near face at x = 8.6.
    let crate_body =
        world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(9.0, 0.4, 0.0)))?;
    world.insert_collider(
        ColliderDesc::cuboid(Vec3::splat(0.4))
            .with_density(10.0 / 0.512)
            .with_friction(0.3),
        crate_body,
    )?;
    // A low kinematic platform (top 0.2 m) beside the crate's lane.
    let platform =
        world.insert_body(BodyDesc::kinematic().with_position(Vec3::new(11.0, 0.1, 4.0)))?;
    world.insert_collider(ColliderDesc::cuboid(Vec3::new(1.0, 0.1, 1.0)), platform)?;
    // The character: a 1.6 m capsule on a kinematic body, standing `skin` above the floor at x = 0.
    let character = world.insert_body(BodyDesc::kinematic().with_position(Vec3::new(
        0.0,
        HALF_HEIGHT + RADIUS + 0.01,
        0.0,
    )))?;
    let collider = world.insert_collider(ColliderDesc::capsule(RADIUS, HALF_HEIGHT), character)?;
    Ok(Course {
        world,
        character,
        collider,
        crate_body,
        platform,
    })
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let Course {
        mut world,
        character,
        collider,
        crate_body,
        platform,
    } = build()?;
    let controller = CharacterController::new(CharacterSettings {
        snap_to_ground: Some(0.3),
        ..CharacterSettings::default()
    })?;
    let mut output = support::Output::start(&world, &ABOUT)?;
    let position =
        |world: &PhysicsWorld, body| world.body(body).map_or(Vec3::NAN, RigidBody::position);
    let crate_start = position(&world, crate_body);
    let (mut highest_bottom, mut steps, mut pushes, mut airborne) = (0.0f32, 0, 0, 0);
    let mut vertical_speed = 0.0f32;
    let mut grounded = true;
    let mut ride_start: Option<Vec3> = None;
    let mut largest_drift = 0.0f32;
    for step in 0..ABOUT.steps {
        let t = step as f32 * DT;
        // 5.5 s along +x, 2 s along +z onto the platform, then still while it carries the character.
        let walk = if t < 5.5 {
            Vec3::X * WALK_SPEED
        } else if t < 7.5 {
            Vec3::Z * WALK_SPEED
        } else {
            Vec3::ZERO
        };
        if t >= 8.0 {
            let pose = world.body(platform).map_or(Pose::IDENTITY, RigidBody::pose);
            world.set_kinematic_target(
                platform,
                Pose::new(pose.position + Vec3::X * PLATFORM_SPEED * DT, pose.rotation),
            )?;
        }
        vertical_speed = if grounded {
            0.0
        } else {
            vertical_speed - G * DT
        };
        let desired = (walk + Vec3::Y * vertical_speed) * DT;
        let moved = controller.move_collider(&world, collider, desired, DT, &QueryFilter::new())?;
        pushes += controller.push_bodies(&mut world, &moved)?.len();
        grounded = moved.is_grounded();
        airborne += usize::from(!grounded);
        steps += usize::from(moved.stepped);
        let pose = world
            .body(character)
            .map_or(Pose::IDENTITY, RigidBody::pose);
        world.set_kinematic_target(
            character,
            Pose::new(pose.position + moved.translation, pose.rotation),
        )?;
        output.step(&mut world, DT)?;
        let here = position(&world, character);
        highest_bottom = highest_bottom.max(here.y - HALF_HEIGHT - RADIUS);
        if t >= 8.0 {
            let offset = here - position(&world, platform);
            let start = *ride_start.get_or_insert(offset);
            largest_drift = largest_drift.max((offset - start).length());
        }
        if step % 60 == 59 {
            println!(
                "t = {:>4.1} s: character at ({:5.2}, {:4.2}, {:4.2}) m, {}",
                t + DT,
                here.x,
                here.y - HALF_HEIGHT - RADIUS,
                here.z,
                match moved.ground {
                    Some(g) if g.body == platform => "on the platform".to_owned(),
                    Some(g) => format!(
                        "on ground sloped {:.0}°",
                        g.normal.angle_between(Vec3::Y).to_degrees()
                    ),
                    None => "in the air".to_owned(),
                }
            );
        }
    }
    let crate_moved = position(&world, crate_body).x - crate_start.x;
    let carried = position(&world, platform).x - 11.0;
    println!(
        "highest feet {highest_bottom:.2} m (stairs top 0.60 m) in {steps} autosteps; {airborne} moves off the ground"
    );
    println!(
        "crate pushed {crate_moved:.2} m by {pushes} pushes; carried {carried:.2} m by the platform, offset drift {:.1} mm",
        largest_drift * 1e3
    );
    assert!(highest_bottom > 0.6, "the stairs were not climbed");
    assert!(crate_moved > 1.0, "the crate was not pushed");
    assert!(
        largest_drift < 1e-3,
        "the character slipped on the platform"
    );
    for line in output.finish()? {
        println!("{line}");
    }
    Ok(())
}
