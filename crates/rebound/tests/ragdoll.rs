//! The ragdoll: built standing, it starts with every joint held and within its limits; dropped from 1 m
//! onto the ground, tipped and moving, no joint opens past 1 mm, the landing bends no joint more than
//! 1 mrad past its limits and in the last half second none is past by 0.02 rad, and no part sinks into the
//! ground; tumbling down six stairs, no joint opens past 1 mm and none passes its limits by 1 mrad.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound::prelude::*;
use rebound::ragdoll::{JOINT_COUNT, PART_COUNT, Part, Ragdoll, RagdollDesc};

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
    let (mut gap, mut landing, mut rest) = (0.0f32, [0.0f32; JOINT_COUNT], 0.0f32);
    for step in 0..240 {
        world.step(DT);
        gap = gap.max(ragdoll.worst_joint_gap(&world));
        let excess = ragdoll.limit_excesses(&world);
        if step < 210 {
            for (worst, now) in landing.iter_mut().zip(excess) {
                *worst = worst.max(now);
            }
        } else {
            rest = rest.max(excess.into_iter().fold(0.0, f32::max));
        }
    }
    let (balls, hinges) = split_by_kind(&world, &ragdoll, landing);
    eprintln!(
        "ragdoll: worst gap {gap} m, limit excess {balls} rad (ball joints), {hinges} rad (hinges) \
         landing, {rest} rad at rest"
    );
    assert!(gap < 1e-3, "a joint opened {gap} m");
    // Landing, the ground's contacts (solved after the joints in every pass) push the light hands and feet
    // hard. The limits of the ball joints (wrists, ankles, shoulders, hips) and of the hinges (elbows,
    // knees) are rows of the tree's exact solve and of its position projection. In the last half second
    // every joint is back within its range.
    assert!(
        balls < 1e-3,
        "a ball joint passed its limits by {balls} rad while landing"
    );
    assert!(
        hinges < 1e-3,
        "a hinge passed its limits by {hinges} rad while landing"
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

/// Six stairs of 0.25 m rise and 0.45 m run descending along +z from a 1.5 m landing (the ragdoll demo's
/// flight), on a ground at y = 0.
fn world_with_stairs() -> (PhysicsWorld, f32) {
    const STEPS: usize = 6;
    const RISE: f32 = 0.25;
    const RUN: f32 = 0.45;
    let mut world = world_with_ground();
    let block = |world: &mut PhysicsWorld, top: f32, z0: f32, z1: f32| {
        let centre = Vec3::new(0.0, 0.5 * top, 0.5 * (z0 + z1));
        let body = world
            .insert_body(BodyDesc::fixed().with_position(centre))
            .unwrap();
        let half = Vec3::new(2.0, 0.5 * top, 0.5 * (z1 - z0));
        world
            .insert_collider(ColliderDesc::cuboid(half).with_friction(0.8), body)
            .unwrap();
    };
    let landing = STEPS as f32 * RISE;
    block(&mut world, landing, -1.5, 0.0);
    for k in 0..STEPS - 1 {
        let top = (STEPS - 1 - k) as f32 * RISE;
        block(&mut world, top, k as f32 * RUN, (k + 1) as f32 * RUN);
    }
    (world, landing)
}

#[test]
fn a_ragdoll_tumbling_down_stairs_keeps_every_joint_within_a_milliradian_of_its_limits() {
    let (mut world, landing) = world_with_stairs();
    let desc = RagdollDesc {
        position: Vec3::new(0.0, landing, -0.35),
        rotation: Quat::from_rotation_x(0.25),
        linear_velocity: Vec3::new(0.0, 0.0, 1.5),
        ..RagdollDesc::default()
    };
    let ragdoll = Ragdoll::build(&mut world, &desc).unwrap();
    let (mut gap, mut excess) = (0.0f32, [0.0f32; JOINT_COUNT]);
    for _ in 0..300 {
        world.step(DT);
        gap = gap.max(ragdoll.worst_joint_gap(&world));
        for (worst, now) in excess.iter_mut().zip(ragdoll.limit_excesses(&world)) {
            *worst = worst.max(now);
        }
    }
    let pelvis = world.body(ragdoll.part(Part::Pelvis)).unwrap().position();
    let (balls, hinges) = split_by_kind(&world, &ragdoll, excess);
    eprintln!(
        "stairs: worst gap {gap} m, limit excess {balls} rad (ball joints), {hinges} rad (hinges), \
         pelvis at {pelvis}"
    );
    // It went down the flight: from the landing 1.5 m up to the last steps.
    assert!(
        pelvis.z > 1.0 && pelvis.y < 0.8,
        "the ragdoll stopped at {pelvis}"
    );
    assert!(gap < 1e-3, "a joint opened {gap} m");
    // The ball joints' and the hinges' limits are rows of the tree's exact solve and projection.
    assert!(
        balls < 1e-3,
        "a ball joint passed its limits by {balls} rad"
    );
    assert!(hinges < 1e-3, "a hinge passed its limits by {hinges} rad");
}

/// The worst of `excess` (one per joint of `ragdoll`, rad) over its ball joints and over its hinges.
fn split_by_kind(
    world: &PhysicsWorld,
    ragdoll: &Ragdoll,
    excess: [f32; JOINT_COUNT],
) -> (f32, f32) {
    let (mut balls, mut hinges) = (0.0f32, 0.0f32);
    for (&joint, excess) in ragdoll.joints.iter().zip(excess) {
        match world.joint(joint).unwrap().kind() {
            JointKind::Hinge(_) => hinges = hinges.max(excess),
            _ => balls = balls.max(excess),
        }
    }
    (balls, hinges)
}
