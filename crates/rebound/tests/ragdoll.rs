//! The ragdoll: built standing, it starts with every joint held and within its limits; dropped from 1 m
//! onto the ground, tipped and moving, no joint opens past 5 mm, the landing bends no joint more than 1.2 rad
//! past its limit and in the last half second none is past by 0.02 rad, and no part sinks into the ground.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound::prelude::*;
use rebound::ragdoll::{PART_COUNT, Part, Ragdoll, RagdollDesc};

const DT: f32 = 1.0 / 60.0;

fn world_with_ground() -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0)), ground)
        .unwrap();
    world
}

#[test]
fn a_ragdoll_is_built_with_its_joints_held_and_within_their_limits() {
    let mut world = world_with_ground();
    let ragdoll = Ragdoll::build(&mut world, &RagdollDesc::default()).unwrap();
    assert!(
        ragdoll.worst_joint_gap(&world) < 1e-5,
        "{}",
        ragdoll.worst_joint_gap(&world)
    );
    assert!(
        ragdoll.worst_limit_excess(&world) < 1e-5,
        "{}",
        ragdoll.worst_limit_excess(&world)
    );
    let mass: f32 = ragdoll
        .parts
        .iter()
        .map(|&p| world.body(p).unwrap().mass_properties().mass())
        .sum();
    assert!((60.0..90.0).contains(&mass), "{mass} kg");
    let head = world.body(ragdoll.part(Part::Head)).unwrap().position();
    assert!((head.y - 1.65).abs() < 1e-4, "{head}");
}

#[test]
fn a_dropped_ragdoll_lands_with_its_joints_held_and_comes_back_within_its_limits() {
    let mut world = world_with_ground();
    let desc = RagdollDesc {
        position: Vec3::new(0.0, 1.0, 0.0),
        // Tipped forward and spun so that it lands on its front and side.
        rotation: Quat::from_rotation_x(0.4) * Quat::from_rotation_y(0.3),
        linear_velocity: Vec3::new(0.5, 0.0, 1.0),
        ..RagdollDesc::default()
    };
    let ragdoll = Ragdoll::build(&mut world, &desc).unwrap();
    let (mut gap, mut impact, mut rest) = (0.0f32, 0.0f32, 0.0f32);
    for step in 0..240 {
        world.step(DT);
        gap = gap.max(ragdoll.worst_joint_gap(&world));
        let excess = ragdoll.worst_limit_excess(&world);
        if step < 210 {
            impact = impact.max(excess);
        } else {
            rest = rest.max(excess);
        }
    }
    eprintln!("ragdoll: worst gap {gap} m, limit excess {impact} rad landing, {rest} rad at rest");
    assert!(gap < 5e-3, "a joint opened {gap} m");
    // Landing, the ground's contacts (solved after the joints in every pass) bend the light hands and feet
    // past their wrist and ankle limits for a few steps; in the last half second every joint is back within
    // its range.
    assert!(
        impact < 1.2,
        "a joint passed its limit by {impact} rad while landing"
    );
    assert!(rest < 0.02, "a joint rests {rest} rad past its limit");
    // At rest on the ground: nothing below it by more than the contact slop, and the energy of the drop
    // gone. Not every part at rest: with the tree's joints solved exactly a limb propped in the air can
    // swing on as the pendulum it is (at about 0.3 m/s, 10⁻⁴ of the drop's energy), no joint damping it.
    let (mut kinetic, mut mass) = (0.0f32, 0.0f32);
    for (i, &part) in ragdoll.parts.iter().enumerate() {
        let body = world.body(part).unwrap();
        assert!(
            body.position().y > 0.0,
            "part {i} sank to {}",
            body.position().y
        );
        let m = body.mass_properties().mass();
        kinetic += 0.5 * m * body.linear_velocity().length_squared();
        mass += m;
    }
    let drop = mass * 9.81 * desc.position.y;
    assert!(
        kinetic < 1e-3 * drop,
        "{kinetic} J still moving, {} of the drop's {drop} J",
        kinetic / drop
    );
    assert_eq!(ragdoll.parts.len(), PART_COUNT);
}
