//! Joint graphs solved directly: joints that form no path — a ladder of two ropes per gap, a tree, a loop,
//! a four-bar linkage — held as chains are. Each test states its bound: the two-rope bridge stretches no
//! rope by more than 0.5 mm while it falls and 0.1 mm at rest, a hanging ragdoll tree keeps every joint
//! within 0.1 mm, a loop of 20 rods keeps its length to 0.01 %, a four-bar linkage's coupler point follows
//! the closed-form coupler curve to 1 mm. Over-constrained groups, whose dependent rows the exact solve
//! finds: a door on two hinges on one axis (10 rows on 6 degrees of freedom) swings with the compound
//! pendulum's period to 0.5 % and opens no hinge by 0.1 mm, and neither it nor the grounded four-bar of
//! hinges (20 rows on 18) moves faster than its energy allows.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound::prelude::*;
use rebound::ragdoll::{Part, Ragdoll, RagdollDesc};

const DT: f32 = 1.0 / 60.0;

/// The distance between a joint's two anchors in the world (m).
fn anchor_distance(world: &PhysicsWorld, joint: JointHandle) -> f32 {
    let j = world.joint(joint).unwrap();
    let (a, b) = world.joint_bodies(joint).unwrap();
    let pose_a = a
        .and_then(|a| world.body(a))
        .map_or(Pose::IDENTITY, rebound::RigidBody::pose);
    let pose_b = world.body(b).unwrap().pose();
    pose_b
        .transform_point(j.local_anchor_b())
        .distance(pose_a.transform_point(j.local_anchor_a()))
}

/// A sphere collider of radius `radius` (m) whose density makes it `mass` kg.
fn ball_of_mass(radius: f32, mass: f32) -> ColliderDesc {
    let volume = 4.0 / 3.0 * core::f32::consts::PI * radius.powi(3);
    ColliderDesc::ball(radius).with_density(mass / volume)
}

/// The two-rope bridge: 10 planks between two fixed posts, each of the 11 gaps joined by two side ropes
/// 1.5 times the gap long; returns the world, its ropes and the rope length.
fn two_rope_bridge() -> (PhysicsWorld, Vec<JointHandle>, f32) {
    const PLANKS: usize = 10;
    const HALF: Vec3 = Vec3::new(0.25, 0.05, 0.8);
    const GAP: f32 = 0.2;
    const SIDE: f32 = 0.7;
    let rope_length = 1.5 * GAP;
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let pitch = 2.0 * HALF.x + GAP;
    let x = |i: usize| (i as f32 - (PLANKS as f32 - 1.0) / 2.0) * pitch;
    let post = |x: f32| BodyDesc::fixed().with_position(Vec3::new(x, 0.0, 0.0));
    let left = world.insert_body(post(x(0) - pitch)).unwrap();
    let right = world.insert_body(post(x(PLANKS - 1) + pitch)).unwrap();
    let mut bodies = vec![left];
    for i in 0..PLANKS {
        let plank = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(x(i), 0.0, 0.0)))
            .unwrap();
        world
            .insert_collider(ColliderDesc::cuboid(HALF).with_density(600.0), plank)
            .unwrap();
        bodies.push(plank);
    }
    bodies.push(right);
    let mut ropes = Vec::new();
    for pair in bodies.windows(2) {
        for z in [-SIDE, SIDE] {
            let rope = Joint::new(Rope::new(rope_length).unwrap())
                .with_local_anchors(Vec3::new(HALF.x, 0.0, z), Vec3::new(-HALF.x, 0.0, z))
                .unwrap();
            let handle = world.insert_joint(rope, pair[0], pair[1]).unwrap();
            world.set_joint_contacts_enabled(handle, false).unwrap();
            ropes.push(handle);
        }
    }
    // The 100 kg ball, 1 m above the middle of the deck.
    let ball = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 1.0, 0.0)))
        .unwrap();
    world
        .insert_collider(ball_of_mass(0.3, 100.0), ball)
        .unwrap();
    (world, ropes, rope_length)
}

#[test]
fn the_two_rope_bridge_stretches_no_rope_past_half_a_millimetre_while_it_falls() {
    let (mut world, ropes, length) = two_rope_bridge();
    let stretch = |world: &PhysicsWorld| {
        ropes
            .iter()
            .map(|&r| anchor_distance(world, r) - length)
            .fold(0.0f32, f32::max)
    };
    let (mut falling, mut resting) = (0.0f32, 0.0f32);
    // The deck drops onto its ropes and the ball lands on it within the first 2 s; at rest from 5 s.
    for step in 0..360 {
        world.step(DT);
        let s = stretch(&world);
        if step < 300 {
            falling = falling.max(s);
        } else {
            resting = resting.max(s);
        }
    }
    assert!(
        falling < 5e-4,
        "a rope stretched by {falling} m while the deck fell"
    );
    assert!(resting < 1e-4, "a rope stretched by {resting} m at rest");
}

#[test]
fn a_ragdoll_hanging_by_its_head_keeps_every_joint_within_a_tenth_of_a_millimetre() {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    // Tipped forward so that it swings: the tree's joints carry the limbs' weight and their swing.
    let desc = RagdollDesc {
        rotation: Quat::from_rotation_x(0.5),
        ..RagdollDesc::default()
    };
    let ragdoll = Ragdoll::build(&mut world, &desc).unwrap();
    let head = ragdoll.part(Part::Head);
    let top = world.body(head).unwrap().position() + Vec3::new(0.0, 0.12, 0.0);
    let hook = Joint::new(BallJoint::new())
        .with_local_anchors(
            top,
            world
                .body(head)
                .unwrap()
                .pose()
                .inverse_transform_point(top),
        )
        .unwrap();
    let hook = world.insert_world_joint(hook, head).unwrap();
    let mut worst = 0.0f32;
    for _ in 0..180 {
        world.step(DT);
        worst = worst
            .max(ragdoll.worst_joint_gap(&world))
            .max(anchor_distance(&world, hook));
    }
    assert!(worst < 1e-4, "a joint opened by {worst} m");
}

#[test]
fn a_closed_loop_of_twenty_rods_keeps_its_length_to_a_hundredth_of_a_percent() {
    const RODS: usize = 20;
    const LENGTH: f32 = 0.25;
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    // A regular 20-gon in the horizontal plane, hung from a fixed hook by its first ball: it falls and
    // folds, each rod pulled by the balls swinging below it.
    let radius = LENGTH / (2.0 * (core::f32::consts::PI / RODS as f32).sin());
    let balls: Vec<BodyHandle> = (0..RODS)
        .map(|i| {
            let angle = i as f32 * core::f32::consts::TAU / RODS as f32;
            let position = Vec3::new(radius * angle.cos() - radius, 0.0, radius * angle.sin());
            let ball = world
                .insert_body(BodyDesc::dynamic().with_position(position))
                .unwrap();
            world
                .insert_collider(ball_of_mass(0.02, 1.0), ball)
                .unwrap();
            ball
        })
        .collect();
    for i in 0..RODS {
        let rod = Joint::new(Rod::new(LENGTH).unwrap());
        let handle = world
            .insert_joint(rod, balls[i], balls[(i + 1) % RODS])
            .unwrap();
        world.set_joint_contacts_enabled(handle, false).unwrap();
    }
    world
        .insert_world_joint(
            Joint::new(BallJoint::new())
                .with_local_anchors(Vec3::ZERO, Vec3::ZERO)
                .unwrap(),
            balls[0],
        )
        .unwrap();
    let perimeter = |world: &PhysicsWorld| -> f32 {
        (0..RODS)
            .map(|i| {
                let p = |h: BodyHandle| world.body(h).unwrap().position();
                p(balls[i]).distance(p(balls[(i + 1) % RODS]))
            })
            .sum()
    };
    let total = RODS as f32 * LENGTH;
    let mut worst = 0.0f32;
    for _ in 0..240 {
        world.step(DT);
        worst = worst.max((perimeter(&world) - total).abs() / total);
    }
    assert!(worst < 1e-4, "the loop's length changed by {worst} of it");
}

/// The coupler point of a four-bar linkage with ground pivots `(0, 0)` and `(d, 0)`, crank `a`, coupler
/// `b`, rocker `c`, at crank angle `theta`: the crank end `A`, and `B` on the circle of radius `b` about
/// `A` and `c` about the rocker pivot, on the side of `A→O₄` given by `upper` (the assembly the linkage
/// starts in); the coupler point is the middle of `AB`.
fn coupler_point((a, b, c, d): (f32, f32, f32, f32), theta: f32, upper: bool) -> Vec3 {
    let pa = Vec3::new(a * theta.cos(), a * theta.sin(), 0.0);
    let o4 = Vec3::new(d, 0.0, 0.0);
    let e = (o4 - pa).length();
    // Along A→O₄ by `along`, then across it by `h`: the intersection of the two circles.
    let along = (b * b - c * c + e * e) / (2.0 * e);
    let h = (b * b - along * along).max(0.0).sqrt();
    let unit = (o4 - pa) / e;
    let normal = Vec3::new(-unit.y, unit.x, 0.0);
    let pb = pa + unit * along + normal * if upper { h } else { -h };
    (pa + pb) * 0.5
}

/// A four-bar linkage swinging under gravity for 4 s — crank 0.3 m, coupler 0.8 m, rocker 0.6 m, ground
/// 0.7 m (a Grashof crank–rocker), bars of 4 cm square section — with its ground link fixed (`floating` =
/// false: four hinges, a path between two fixed bodies) or a bar hung from the world by a hinge at its
/// middle (`floating`: a loop of four dynamic bodies, a joint graph), its four pivots hinges or, `balls`,
/// ball joints. The grounded linkage of hinges has 20 rows on 18 degrees of freedom, three of them
/// dependent while it stays planar: a joint graph, whose factorisation finds them. The floating loop of
/// hinges (25 rows on 24) is left to Gauss–Seidel and is not tested here (see `docs/physics.md`, "Joint
/// graphs"). Returns the farthest the middle of the coupler got from the closed-form coupler
/// curve at the crank angle of the simulation (both in the ground link's frame, m), the range of crank
/// angles swept (rad) and the worst excess of any body's speed over what energy conservation allows it
/// ([`speed_excess`], m/s).
fn four_bar(floating: bool, balls: bool) -> (f32, f32, f32) {
    let (a, b, c, d) = (0.3f32, 0.8f32, 0.6f32, 0.7f32);
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let theta0: f32 = 1.2;
    let pa = Vec3::new(a * theta0.cos(), a * theta0.sin(), 0.0);
    let pb = coupler_point((a, b, c, d), theta0, true) * 2.0 - pa;
    let o4 = Vec3::new(d, 0.0, 0.0);
    // Each bar a thin box between its two pivots, turned to lie along them; without a collider, so that
    // the bars, which cross in one plane, swing through each other.
    let bar = |world: &mut PhysicsWorld, from: Vec3, to: Vec3| {
        let along = to - from;
        let half = Vec3::new(along.length() / 2.0, 0.02, 0.02);
        let body = world
            .insert_body(
                BodyDesc::dynamic()
                    .with_position((from + to) * 0.5)
                    .with_rotation(Quat::from_rotation_z(along.y.atan2(along.x)))
                    .with_mass_properties(MassProperties::cuboid(2000.0, half).unwrap()),
            )
            .unwrap();
        (body, half.x)
    };
    let (crank, ha) = bar(&mut world, Vec3::ZERO, pa);
    let (coupler, hb) = bar(&mut world, pa, pb);
    let (rocker, hc) = bar(&mut world, o4, pb);
    // Ball-jointed pivots leave the out-of-plane motion to the hinge the ground link hangs from; hinges
    // constrain it three times over.
    let hinge = |anchor_a: Vec3, anchor_b: Vec3| {
        if balls {
            return Joint::new(BallJoint::new())
                .with_local_anchors(anchor_a, anchor_b)
                .unwrap();
        }
        Joint::new(HingeJoint::new())
            .with_local_anchors(anchor_a, anchor_b)
            .unwrap()
            .with_local_axes(Vec3::Z, Vec3::Z)
            .unwrap()
    };
    let x = |h: f32| Vec3::new(h, 0.0, 0.0);
    let mut joints = vec![
        world
            .insert_joint(hinge(x(ha), x(-hb)), crank, coupler)
            .unwrap(),
        world
            .insert_joint(hinge(x(hb), x(hc)), coupler, rocker)
            .unwrap(),
    ];
    let ground = if floating {
        let (ground, half) = bar(&mut world, Vec3::ZERO, o4);
        joints.push(
            world
                .insert_joint(hinge(x(-half), x(-ha)), ground, crank)
                .unwrap(),
        );
        joints.push(
            world
                .insert_joint(hinge(x(half), x(-hc)), ground, rocker)
                .unwrap(),
        );
        joints.push(
            world
                .insert_world_joint(
                    Joint::new(HingeJoint::new())
                        .with_local_anchors(o4 * 0.5, Vec3::ZERO)
                        .unwrap()
                        .with_local_axes(Vec3::Z, Vec3::Z)
                        .unwrap(),
                    ground,
                )
                .unwrap(),
        );
        Some(ground)
    } else {
        joints.push(
            world
                .insert_world_joint(hinge(Vec3::ZERO, x(-ha)), crank)
                .unwrap(),
        );
        joints.push(world.insert_world_joint(hinge(o4, x(-hc)), rocker).unwrap());
        None
    };
    for &j in &joints {
        world.set_joint_contacts_enabled(j, false).unwrap();
    }
    // World points in the ground link's frame (origin at the crank pivot, x toward the rocker pivot).
    let local = |world: &PhysicsWorld, p: Vec3| match ground {
        Some(g) => world.body(g).unwrap().pose().inverse_transform_point(p) + o4 * 0.5,
        None => p,
    };
    let bodies: Vec<BodyHandle> = [Some(crank), Some(coupler), Some(rocker), ground]
        .into_iter()
        .flatten()
        .collect();
    let energy = total_energy(&world, &bodies);
    let mut worst = 0.0f32;
    let mut excess = 0.0f32;
    let mut swept = (f32::INFINITY, f32::NEG_INFINITY);
    for _ in 0..240 {
        world.step(DT);
        excess = excess.max(speed_excess(&world, &bodies, energy));
        let crank_end = local(
            &world,
            world.body(crank).unwrap().pose().transform_point(x(ha)),
        );
        let theta = crank_end.y.atan2(crank_end.x);
        swept = (swept.0.min(theta), swept.1.max(theta));
        let simulated = local(&world, world.body(coupler).unwrap().position());
        let expected = coupler_point((a, b, c, d), theta, true);
        worst = worst.max(simulated.distance(expected));
    }
    (worst, swept.1 - swept.0, excess)
}

#[test]
fn a_four_bar_linkage_follows_its_coupler_curve_to_a_millimetre() {
    let cases = [(false, false), (true, true)];
    let results = cases.map(|(floating, balls)| (floating, balls, four_bar(floating, balls)));
    for (floating, balls, (worst, swept, _)) in results {
        assert!(swept > 0.5, "the crank swung through {swept} rad only");
        assert!(
            worst < 1e-3,
            "the coupler point left its curve by {worst} m (ground link floating: {floating}, ball \
             joints: {balls})"
        );
    }
}

/// The bodies' kinetic energy and their potential energy in gravity (`m·g·y`, y up), J.
fn world_energy(world: &PhysicsWorld, bodies: &[BodyHandle]) -> (f32, f32) {
    let g = 9.81;
    bodies.iter().fold((0.0, 0.0), |(kinetic, potential), &h| {
        let body = world.body(h).unwrap();
        let mass = body.mass_properties().mass();
        (
            kinetic + body.kinetic_energy(),
            potential + mass * g * body.center_of_mass().y,
        )
    })
}

/// The bodies' kinetic and potential energy together (J).
fn total_energy(world: &PhysicsWorld, bodies: &[BodyHandle]) -> f32 {
    let (kinetic, potential) = world_energy(world, bodies);
    kinetic + potential
}

/// How far any of `bodies` moves faster than energy conservation allows, given the energy `start` (J,
/// kinetic + potential) they started with (m/s, 0 when none does): no body's kinetic energy can exceed the
/// potential energy the group has lost, `½·m·|v|² ≤ E₀ − U`, with 1 % and 1 mJ for the integrator's
/// drift. A dependent row solved as a huge impulse shows here first.
fn speed_excess(world: &PhysicsWorld, bodies: &[BodyHandle], start: f32) -> f32 {
    let (_, potential) = world_energy(world, bodies);
    let budget = 1.01 * (start - potential).max(0.0) + 1e-3;
    bodies
        .iter()
        .map(|&h| {
            let body = world.body(h).unwrap();
            let mass = body.mass_properties().mass();
            let allowed = (2.0 * budget / mass).sqrt();
            (body.linear_velocity().length() - allowed).max(0.0)
        })
        .fold(0.0, f32::max)
}

/// The complete elliptic integral of the first kind `K(k)`, by the arithmetic–geometric mean:
/// `K(k) = π / (2·agm(1, √(1 − k²)))`.
fn elliptic_k(k: f64) -> f64 {
    let (mut a, mut b) = (1.0f64, (1.0 - k * k).sqrt());
    for _ in 0..30 {
        (a, b) = (0.5 * (a + b), (a * b).sqrt());
    }
    core::f64::consts::PI / (2.0 * a)
}

/// A door of 40 kg, 1.0 × 0.8 × 0.04 m, hung on two hinges 0.8 m apart on one horizontal axis (its top
/// edge, along x) — 10 rows on 6 degrees of freedom, 5 of them redundant — let go 0.6 rad from hanging
/// straight down, for 6 s. Returns the angle from the vertical each step (rad), the widest any hinge
/// opened (m) and the worst excess of the door's speed over its energy's ([`speed_excess`], m/s).
fn swinging_door() -> (Vec<f32>, f32, f32) {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let half = Vec3::new(0.5, 0.4, 0.02);
    let theta0: f32 = 0.6;
    let axis_height = 2.0;
    let rotation = Quat::from_rotation_x(theta0);
    let door = world
        .insert_body(
            BodyDesc::dynamic()
                .with_position(
                    Vec3::new(0.0, axis_height, 0.0) + rotation * Vec3::new(0.0, -half.y, 0.0),
                )
                .with_rotation(rotation)
                .with_mass_properties(
                    MassProperties::cuboid(40.0 / (8.0 * half.x * half.y * half.z), half).unwrap(),
                ),
        )
        .unwrap();
    let hinges: Vec<JointHandle> = [-0.4f32, 0.4]
        .into_iter()
        .map(|x| {
            let hinge = Joint::new(HingeJoint::new())
                .with_local_anchors(Vec3::new(x, axis_height, 0.0), Vec3::new(x, half.y, 0.0))
                .unwrap()
                .with_local_axes(Vec3::X, Vec3::X)
                .unwrap();
            world.insert_world_joint(hinge, door).unwrap()
        })
        .collect();
    let energy = total_energy(&world, &[door]);
    let (mut angles, mut gap, mut excess) = (Vec::new(), 0.0f32, 0.0f32);
    for _ in 0..360 {
        world.step(DT);
        let body = world.body(door).unwrap();
        let down = body.rotation() * Vec3::NEG_Y;
        angles.push(down.z.atan2(-down.y));
        for &h in &hinges {
            gap = gap.max(anchor_distance(&world, h));
        }
        excess = excess.max(speed_excess(&world, &[door], energy));
    }
    (angles, gap, excess)
}

#[test]
fn a_door_on_two_hinges_swings_with_the_compound_pendulums_period() {
    let (angles, gap, _) = swinging_door();
    // The period from the downward zero crossings, each placed by linear interpolation between steps.
    let crossings: Vec<f64> = angles
        .windows(2)
        .enumerate()
        .filter(|(_, w)| w[0] > 0.0 && w[1] <= 0.0)
        .map(|(i, w)| (i as f64 + f64::from(w[0] / (w[0] - w[1])) + 1.0) * f64::from(DT))
        .collect();
    assert!(
        crossings.len() >= 3,
        "the door crossed the vertical {} times",
        crossings.len()
    );
    let measured = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f64;
    // A compound pendulum: I about the axis = m·(h² + t²)/12 + m·d² with h = 0.8, t = 0.04, d = 0.4 m;
    // T = 4·√(I/(m·g·d))·K(sin(θ₀/2)) at amplitude θ₀.
    let (h, t, d, g, theta0) = (0.8f64, 0.04f64, 0.4f64, 9.81f64, 0.6f64);
    let inertia_per_mass = (h * h + t * t) / 12.0 + d * d;
    let expected = 4.0 * (inertia_per_mass / (g * d)).sqrt() * elliptic_k((theta0 / 2.0).sin());
    assert!(
        ((measured - expected) / expected).abs() < 5e-3,
        "period {measured} s against {expected} s"
    );
    assert!(gap < 1e-4, "a hinge opened by {gap} m");
}

#[test]
fn over_constrained_joint_groups_move_no_faster_than_their_energy_allows() {
    let (_, _, door) = swinging_door();
    let (_, _, four_bar) = four_bar(false, false);
    for (name, excess) in [
        ("door on two hinges", door),
        ("grounded four-bar of hinges", four_bar),
    ] {
        assert!(
            excess < 1e-3,
            "the {name} moved {excess} m/s faster than its energy allows"
        );
    }
}
