//! The character controller against closed forms: slope climbing at the commanded horizontal speed on a 30°
//! slope, no climbing and the frictionless-incline slide on a 50° one, autostep by height, snapping down a
//! 10° slope, platform carry, pushing by mass, no tunnelling through a 1 cm wall at 50 m/s, wall sliding,
//! the collision report, determinism, and every refused setting and argument.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;
/// The character: a capsule of radius 0.3 m and half-height 0.5 m (1.6 m tall), its centre 0.8 m above its
/// lowest point.
const RADIUS: f32 = 0.3;
const HALF_HEIGHT: f32 = 0.5;
const SKIN: f32 = 0.01;

fn capsule() -> ColliderShape {
    ColliderShape::Capsule {
        radius: RADIUS,
        half_height: HALF_HEIGHT,
    }
}

fn new_world() -> PhysicsWorld {
    PhysicsWorld::new(WorldSettings::default()).unwrap()
}

/// A fixed floor whose top is y = 0.
fn floor(world: &mut PhysicsWorld) -> BodyHandle {
    let body = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(50.0, 0.5, 50.0)), body)
        .unwrap();
    body
}

/// A fixed box whose top face is the plane through `through` rising along +x at `angle`; returns the
/// plane's unit normal `(−sin θ, cos θ, 0)`.
fn slope(world: &mut PhysicsWorld, angle: f32, through: Vec3) -> Vec3 {
    let rotation = Quat::from_rotation_z(angle);
    let normal = rotation * Vec3::Y;
    let body = world
        .insert_body(
            BodyDesc::fixed()
                .with_position(through - normal)
                .with_rotation(rotation),
        )
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(20.0, 1.0, 5.0)), body)
        .unwrap();
    normal
}

/// The gap between the capsule centred at `p` and the plane through `through` with normal `n` (m): its
/// bottom sphere is the closest part when `n·up > 0`.
fn gap_to_plane(p: Vec3, n: Vec3, through: Vec3) -> f32 {
    (p - Vec3::Y * HALF_HEIGHT - through).dot(n) - RADIUS
}

/// The capsule centre at `x` with the gap `gap` to the plane through the origin with normal `n`.
fn on_plane(x: f32, n: Vec3, gap: f32) -> Vec3 {
    // (x, y − h)·n = r + gap.
    let y = HALF_HEIGHT + (RADIUS + gap - x * n.x) / n.y;
    Vec3::new(x, y, 0.0)
}

/// A character moved by hand through `move_shape`: horizontal velocity from the caller, gravity integrated
/// while it is not grounded and reset to zero while it is.
struct Walker {
    controller: CharacterController,
    position: Vec3,
    vertical_speed: f32,
    grounded: bool,
}

impl Walker {
    fn new(settings: CharacterSettings, position: Vec3) -> Self {
        Self {
            controller: CharacterController::new(settings).unwrap(),
            position,
            vertical_speed: 0.0,
            grounded: true,
        }
    }

    fn walk(
        &mut self,
        world: &PhysicsWorld,
        horizontal_velocity: Vec3,
        gravity: bool,
    ) -> CharacterMove {
        if self.grounded || !gravity {
            self.vertical_speed = 0.0;
        } else {
            self.vertical_speed -= G * DT;
        }
        let desired = (horizontal_velocity + Vec3::Y * self.vertical_speed) * DT;
        let moved = self
            .controller
            .move_shape(
                world,
                &capsule(),
                Pose::from_position(self.position),
                desired,
                DT,
                &QueryFilter::new(),
            )
            .unwrap();
        self.position += moved.translation;
        self.grounded = moved.is_grounded();
        moved
    }
}

fn slope_limit(degrees: f32) -> CharacterSettings {
    CharacterSettings {
        max_slope_angle: degrees.to_radians(),
        ..CharacterSettings::default()
    }
}

#[test]
fn climbs_a_30_degree_slope_at_the_commanded_horizontal_speed_on_the_surface() {
    let mut world = new_world();
    let angle = 30f32.to_radians();
    let n = slope(&mut world, angle, Vec3::ZERO);
    let start = on_plane(-5.0, n, SKIN);
    let mut walker = Walker::new(slope_limit(45.0), start);
    let speed = 2.0;
    for frame in 0..180 {
        let before = walker.position;
        let moved = walker.walk(&world, Vec3::new(speed, 0.0, 0.0), true);
        let dx = walker.position.x - before.x;
        assert!(
            (dx - speed * DT).abs() < 1e-4,
            "frame {frame}: horizontal step {dx} m, commanded {} m",
            speed * DT
        );
        let gap = gap_to_plane(walker.position, n, Vec3::ZERO);
        assert!(
            (0.0..SKIN + 1e-3).contains(&gap),
            "frame {frame}: gap to the slope {gap} m"
        );
        assert!(moved.is_grounded(), "frame {frame}: not grounded");
        let ground = moved.ground.unwrap();
        // The cast's normal is GJK's, good to about 0.01 rad.
        assert!(
            ground.normal.angle_between(n) < 1e-2,
            "ground normal {}",
            ground.normal
        );
    }
    // Closed form: y rises by tan θ per metre of x, up to the change of the gap (within the skin, checked
    // above) over cos θ.
    let dy = walker.position.y - start.y;
    let expected = (walker.position.x - start.x) * angle.tan();
    let gap_change = gap_to_plane(walker.position, n, Vec3::ZERO) - SKIN;
    assert!(
        (dy - expected - gap_change / angle.cos()).abs() < 1e-4,
        "rose {dy} m, expected {expected} m + {gap_change} m / cos θ"
    );
}

#[test]
fn does_not_climb_a_50_degree_slope_from_the_floor_even_with_autostep() {
    let mut world = new_world();
    floor(&mut world);
    let angle = 50f32.to_radians();
    let n = slope(&mut world, angle, Vec3::ZERO);
    let settings = CharacterSettings {
        autostep: Some(Autostep {
            max_height: 0.35,
            ..Autostep::default()
        }),
        ..slope_limit(45.0)
    };
    let start = Vec3::new(-2.0, HALF_HEIGHT + RADIUS + SKIN, 0.0);
    let mut walker = Walker::new(settings, start);
    for _ in 0..120 {
        let moved = walker.walk(&world, Vec3::new(2.0, 0.0, 0.0), true);
        assert!(!moved.stepped, "stepped onto a 50° slope");
        assert!(
            walker.position.y - start.y < 1e-4,
            "climbed to y = {}",
            walker.position.y
        );
    }
    // Blocked where the bottom sphere is `skin` from the slope: −x sin θ + (r + skin) cos θ = r + skin.
    let blocked = (RADIUS + SKIN) * (angle.cos() - 1.0) / angle.sin();
    let gap = gap_to_plane(walker.position, n, Vec3::ZERO);
    assert!(
        (gap - SKIN).abs() < 1e-3,
        "stopped at x = {} (gap {gap} m), expected {blocked}",
        walker.position.x
    );
}

#[test]
fn slides_down_a_50_degree_slope_as_on_a_frictionless_incline() {
    let mut world = new_world();
    let angle = 50f32.to_radians();
    let n = slope(&mut world, angle, Vec3::ZERO);
    let start = on_plane(3.0, n, SKIN);
    let mut walker = Walker::new(slope_limit(45.0), start);
    walker.grounded = false;
    let frames = 60;
    for frame in 0..frames {
        let moved = walker.walk(&world, Vec3::ZERO, true);
        assert!(
            !moved.is_grounded(),
            "frame {frame}: grounded on a 50° slope"
        );
        let gap = gap_to_plane(walker.position, n, Vec3::ZERO);
        assert!(
            (0.0..SKIN + 1e-3).contains(&gap),
            "frame {frame}: gap to the slope {gap} m"
        );
    }
    // Each move asks for v_k·dt down with v_k = g·k·dt and keeps its component along the plane, whose
    // vertical part is sin²θ of it: the drop is g·dt²·sin²θ·N(N+1)/2 (½·g·sin²θ·t² as dt → 0).
    let count = frames as f32;
    let expected = G * DT * DT * angle.sin().powi(2) * count * (count + 1.0) / 2.0;
    let drop = start.y - walker.position.y;
    assert!(
        (drop - expected).abs() < 1e-3,
        "dropped {drop} m, expected {expected} m"
    );
    assert!(walker.position.x < start.x, "slid down towards −x");
}

#[test]
fn snapped_it_follows_a_10_degree_downhill_and_without_snapping_it_leaves_the_ground() {
    let angle = 10f32.to_radians();
    let speed = 3.0;
    let run = |snap: Option<f32>| {
        let mut world = new_world();
        let n = slope(&mut world, angle, Vec3::ZERO);
        let settings = CharacterSettings {
            snap_to_ground: snap,
            ..CharacterSettings::default()
        };
        let mut walker = Walker::new(settings, on_plane(8.0, n, SKIN));
        let mut largest_gap = 0.0f32;
        let mut airborne_frames = 0;
        for frame in 0..120 {
            let before = walker.position;
            let moved = walker.walk(&world, Vec3::new(-speed, 0.0, 0.0), true);
            largest_gap = largest_gap.max(gap_to_plane(walker.position, n, Vec3::ZERO));
            if moved.is_grounded() {
                let dx = walker.position.x - before.x;
                assert!(
                    (dx + speed * DT).abs() < 1e-4,
                    "frame {frame}: horizontal step {dx}"
                );
            } else {
                airborne_frames += 1;
            }
            assert!(gap_to_plane(walker.position, n, Vec3::ZERO) >= 0.0);
        }
        (largest_gap, airborne_frames)
    };
    let (gap, airborne) = run(Some(0.2));
    assert_eq!(airborne, 0, "snapped: left the ground");
    assert!(gap < SKIN + 1e-3, "snapped: largest gap {gap} m");
    let (gap, airborne) = run(None);
    assert!(airborne > 0, "without snapping it stays on the ground");
    assert!(
        gap > SKIN + 2e-3,
        "without snapping the largest gap is only {gap} m"
    );
}

/// The floor and a 0.3 m step whose riser is at x = 1 (top from x = 1 to 5); the capsule walks +x at 2 m/s
/// for 1.5 s from x = 0. Returns the walker and whether any move stepped.
fn walk_to_step(max_height: f32) -> (Walker, bool) {
    let mut world = new_world();
    floor(&mut world);
    let step = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(3.0, 0.15, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(2.0, 0.15, 2.0)), step)
        .unwrap();
    let settings = CharacterSettings {
        autostep: Some(Autostep {
            max_height,
            ..Autostep::default()
        }),
        ..CharacterSettings::default()
    };
    let mut walker = Walker::new(settings, Vec3::new(0.0, HALF_HEIGHT + RADIUS + SKIN, 0.0));
    let mut stepped = false;
    for _ in 0..90 {
        stepped |= walker.walk(&world, Vec3::new(2.0, 0.0, 0.0), true).stepped;
    }
    (walker, stepped)
}

#[test]
fn climbs_a_30_cm_step_with_autostep_35_cm() {
    let (walker, stepped) = walk_to_step(0.35);
    assert!(stepped);
    // On top: the lowest point `skin` above y = 0.3, at the commanded x = 2 m/s × 1.5 s.
    let bottom = walker.position.y - HALF_HEIGHT - RADIUS;
    assert!((bottom - (0.3 + SKIN)).abs() < 1e-3, "bottom at {bottom} m");
    assert!(
        (walker.position.x - 3.0).abs() < 1e-3,
        "x = {}",
        walker.position.x
    );
    assert!(walker.grounded);
}

#[test]
fn does_not_climb_a_30_cm_step_with_autostep_25_cm() {
    let (walker, stepped) = walk_to_step(0.25);
    assert!(!stepped);
    let bottom = walker.position.y - HALF_HEIGHT - RADIUS;
    assert!((bottom - SKIN).abs() < 1e-3, "bottom at {bottom} m");
    // Stopped `skin` before the riser.
    let blocked = 1.0 - RADIUS - SKIN;
    assert!(
        (walker.position.x - blocked).abs() < 1e-3,
        "x = {}, expected {blocked}",
        walker.position.x
    );
}

#[test]
fn does_not_step_onto_a_ledge_that_is_not_walkable() {
    // A 0.2 m step whose top is a 50° slope rising from its edge.
    let mut world = new_world();
    floor(&mut world);
    let riser = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(3.0, 0.1, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(2.0, 0.1, 2.0)), riser)
        .unwrap();
    slope(&mut world, 50f32.to_radians(), Vec3::new(1.0, 0.2, 0.0));
    let settings = CharacterSettings {
        autostep: Some(Autostep {
            max_height: 0.35,
            ..Autostep::default()
        }),
        ..CharacterSettings::default()
    };
    let start = Vec3::new(0.0, HALF_HEIGHT + RADIUS + SKIN, 0.0);
    let mut walker = Walker::new(settings, start);
    for _ in 0..90 {
        let moved = walker.walk(&world, Vec3::new(2.0, 0.0, 0.0), true);
        assert!(
            !moved.stepped,
            "stepped onto a steep ledge at x = {}",
            walker.position.x
        );
    }
    // The slope's face also runs below the step's edge, down to the floor: the character stops against it,
    // short of the riser.
    assert!(walker.position.y - start.y < 1e-3);
    assert!(
        walker.position.x < 1.0 - RADIUS,
        "x = {}",
        walker.position.x
    );
}

#[test]
fn never_passes_a_1_cm_wall_at_50_m_per_s() {
    let mut world = new_world();
    floor(&mut world);
    let wall = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(2.0, 1.0, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(0.005, 1.0, 50.0)), wall)
        .unwrap();
    let limit = 2.0 - 0.005 - RADIUS - SKIN;
    for direction in [Vec3::X, Vec3::new(1.0, 0.0, 0.3).normalize()] {
        let mut walker = Walker::new(
            CharacterSettings::default(),
            Vec3::new(-3.0, HALF_HEIGHT + RADIUS + SKIN, 0.0),
        );
        for frame in 0..60 {
            walker.walk(&world, direction * 50.0, true);
            // Never through, nor into it: about half the skin at least is kept.
            assert!(
                walker.position.x <= limit + 0.6 * SKIN,
                "frame {frame}: x = {} past the wall face at {limit}",
                walker.position.x
            );
        }
        assert!(
            (walker.position.x - limit).abs() < 0.6 * SKIN,
            "x = {}",
            walker.position.x
        );
    }
}

#[test]
fn slides_along_a_wall_with_the_tangential_part_of_the_motion() {
    let mut world = new_world();
    floor(&mut world);
    let wall = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(1.0, 1.0, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(0.5, 1.0, 20.0)), wall)
        .unwrap();
    let face = 0.5 - RADIUS - SKIN;
    let mut walker = Walker::new(
        CharacterSettings::default(),
        Vec3::new(face, HALF_HEIGHT + RADIUS + SKIN, 0.0),
    );
    let velocity = Vec3::new(2.0, 0.0, 1.5);
    for _ in 0..60 {
        let before = walker.position;
        let moved = walker.walk(&world, velocity, true);
        let dz = walker.position.z - before.z;
        assert!(
            (dz - 1.5 * DT).abs() < 1e-4,
            "slid {dz} m, expected {}",
            1.5 * DT
        );
        assert!(
            (walker.position.x - face).abs() < 1e-3,
            "x = {}",
            walker.position.x
        );
        let wall_hit = moved.collisions.iter().find(|c| c.body == wall).unwrap();
        assert!(wall_hit.normal.angle_between(-Vec3::X) < 1e-3);
    }
}

#[test]
fn walks_through_sensors() {
    let mut world = new_world();
    floor(&mut world);
    let trigger = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(2.0, 1.0, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::new(0.5, 1.0, 5.0)).with_sensor(true),
            trigger,
        )
        .unwrap();
    let moved = CharacterController::default()
        .move_shape(
            &world,
            &capsule(),
            Pose::from_position(Vec3::new(0.0, HALF_HEIGHT + RADIUS + SKIN, 0.0)),
            Vec3::new(4.0, 0.0, 0.0),
            DT,
            &QueryFilter::new(),
        )
        .unwrap();
    assert!((moved.translation.x - 4.0).abs() < 1e-5);
    assert!(moved.collisions.is_empty());
}

#[test]
fn reports_each_collision_with_where_it_happened() {
    let mut world = new_world();
    floor(&mut world);
    let wall = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(2.0, 1.0, 0.0)))
        .unwrap();
    let wall_collider = world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(0.5, 1.0, 5.0)), wall)
        .unwrap();
    let controller = CharacterController::default();
    let start = Vec3::new(0.0, HALF_HEIGHT + RADIUS + SKIN, 0.0);
    let moved = controller
        .move_shape(
            &world,
            &capsule(),
            Pose::from_position(start),
            Vec3::new(3.0, 0.0, 0.0),
            DT,
            &QueryFilter::new(),
        )
        .unwrap();
    let hit = moved.collisions.first().unwrap();
    assert_eq!(hit.collider, wall_collider);
    assert_eq!(hit.body, wall);
    assert!(hit.normal.angle_between(-Vec3::X) < 1e-3);
    assert!((hit.point.x - 1.5).abs() < 1e-3, "contact at {}", hit.point);
    let reached = 1.5 - RADIUS - SKIN;
    assert!((hit.translation_before.x - reached).abs() < 1e-3);
    assert!((hit.translation_remaining.x - (3.0 - reached)).abs() < 1e-3);
    assert!((moved.translation.x - reached).abs() < 1e-3);
    assert!(moved.is_grounded() && !moved.stepped);
}

/// A kinematic character body with the capsule collider standing `skin` above `top`.
fn character_body(world: &mut PhysicsWorld, x: f32, top: f32) -> (BodyHandle, ColliderHandle) {
    let body = world
        .insert_body(BodyDesc::kinematic().with_position(Vec3::new(
            x,
            top + HALF_HEIGHT + RADIUS + SKIN,
            0.0,
        )))
        .unwrap();
    let collider = world
        .insert_collider(ColliderDesc::capsule(RADIUS, HALF_HEIGHT), body)
        .unwrap();
    (body, collider)
}

/// One frame of a character body: move its collider by `velocity·dt`, push, aim the body there, step.
fn drive(
    world: &mut PhysicsWorld,
    controller: &CharacterController,
    body: BodyHandle,
    collider: ColliderHandle,
    velocity: Vec3,
) -> (CharacterMove, Vec<CharacterPush>) {
    let moved = controller
        .move_collider(world, collider, velocity * DT, DT, &QueryFilter::new())
        .unwrap();
    let pushes = controller.push_bodies(world, &moved).unwrap();
    let pose = world.body(body).unwrap().pose();
    world
        .set_kinematic_target(
            body,
            Pose::new(pose.position + moved.translation, pose.rotation),
        )
        .unwrap();
    world.step(DT);
    (moved, pushes)
}

#[test]
fn keeps_its_offset_on_platforms_moving_at_2_m_per_s() {
    for (kind, velocity) in [
        (BodyDesc::kinematic(), Vec3::new(2.0, 0.0, 0.0)),
        (BodyDesc::kinematic(), Vec3::new(0.0, 2.0, 0.0)),
        (BodyDesc::kinematic(), Vec3::new(-1.2, -1.6, 0.0)),
        (BodyDesc::dynamic(), Vec3::new(2.0, 0.0, 0.0)),
    ] {
        let dynamic = kind.body_type == BodyType::Dynamic;
        let mut world = PhysicsWorld::new(WorldSettings {
            gravity: Vec3::ZERO,
            ..WorldSettings::default()
        })
        .unwrap();
        let platform = world
            .insert_body(kind.with_position(Vec3::new(0.0, -0.25, 0.0)))
            .unwrap();
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::new(3.0, 0.25, 3.0)), platform)
            .unwrap();
        world
            .body_mut(platform)
            .unwrap()
            .set_linear_velocity(velocity)
            .unwrap();
        let (body, collider) = character_body(&mut world, 0.5, 0.0);
        let controller = CharacterController::default();
        let offset = |world: &PhysicsWorld| {
            world.body(body).unwrap().position() - world.body(platform).unwrap().position()
        };
        let start = offset(&world);
        for frame in 0..120 {
            let (moved, _) = drive(&mut world, &controller, body, collider, Vec3::ZERO);
            assert!(
                moved.is_grounded(),
                "{velocity}: frame {frame} not grounded"
            );
            assert_eq!(moved.ground.map(|g| g.body), Some(platform));
            let drift = offset(&world) - start;
            assert!(
                drift.abs().max_element() < 1e-3,
                "{velocity} ({}): frame {frame} offset drifted by {drift}",
                if dynamic { "dynamic" } else { "kinematic" }
            );
        }
        let travelled = world
            .body(platform)
            .unwrap()
            .position()
            .distance(Vec3::new(0.0, -0.25, 0.0));
        assert!(
            (travelled - velocity.length() * 2.0).abs() < 1e-2,
            "platform went {travelled} m"
        );
    }
}

#[test]
fn rides_round_on_a_turning_platform() {
    let mut world = PhysicsWorld::new(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    })
    .unwrap();
    let platform = world
        .insert_body(BodyDesc::kinematic().with_position(Vec3::new(0.0, -0.25, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cylinder(3.0, 0.25), platform)
        .unwrap();
    let omega = 1.0;
    world
        .body_mut(platform)
        .unwrap()
        .set_angular_velocity(Vec3::Y * omega)
        .unwrap();
    let radius = 1.5;
    let (body, collider) = character_body(&mut world, radius, 0.0);
    let height = world.body(body).unwrap().position().y;
    let controller = CharacterController::default();
    let frames = 120;
    for frame in 0..frames {
        let (moved, _) = drive(&mut world, &controller, body, collider, Vec3::ZERO);
        assert!(moved.is_grounded(), "frame {frame}");
    }
    // A point of the platform: turned by ω·t about y, (r, h, 0) → (r cos ωt, h, −r sin ωt).
    let angle = omega * frames as f32 * DT;
    let expected = Vec3::new(radius * angle.cos(), height, -radius * angle.sin());
    let at = world.body(body).unwrap().position();
    assert!(
        at.distance(expected) < 1e-3,
        "at {at}, expected {expected} ({} mm off)",
        at.distance(expected) * 1e3
    );
}

/// The floor and a settled crate of `mass` (kg: a 1 m cube, friction 0.2) with its face at x = 1.5.
fn world_with_crate(mass: f32) -> (PhysicsWorld, BodyHandle) {
    let mut world = new_world();
    floor(&mut world);
    let crate_body = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(2.0, 0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(0.5))
                .with_density(mass)
                .with_friction(0.2),
            crate_body,
        )
        .unwrap();
    for _ in 0..30 {
        world.step(DT);
    }
    (world, crate_body)
}

fn pushing(push: Push) -> CharacterController {
    CharacterController::new(CharacterSettings {
        push: Some(push),
        ..CharacterSettings::default()
    })
    .unwrap()
}

/// The character walking +x at 1.5 m/s for 2 s from x = 0 into the crate of `mass`: the crate's
/// displacement, the character's final x, the number of pushes.
fn push_crate(mass: f32, push: Push) -> (f32, f32, usize) {
    let (mut world, crate_body) = world_with_crate(mass);
    let settled = world.body(crate_body).unwrap().position();
    let (body, collider) = character_body(&mut world, 0.0, 0.0);
    let controller = pushing(push);
    let mut push_count = 0;
    for _ in 0..120 {
        let (_, pushes) = drive(
            &mut world,
            &controller,
            body,
            collider,
            Vec3::new(1.5, 0.0, 0.0),
        );
        push_count += pushes.len();
    }
    (
        world.body(crate_body).unwrap().position().x - settled.x,
        world.body(body).unwrap().position().x,
        push_count,
    )
}

const PUSH_100_KG: Push = Push {
    max_mass: 100.0,
    max_impulse: f32::INFINITY,
};

#[test]
fn pushes_a_10_kg_crate_and_not_a_1000_kg_one() {
    let (moved, character_x, pushes) = push_crate(10.0, PUSH_100_KG);
    assert!(pushes > 10, "{pushes} pushes");
    // The character walked at about its speed (1.5 m/s × 2 s = 3 m), the crate ahead of it: the crate's
    // near face started 1.5 − r − skin ahead of the character.
    assert!(character_x > 2.7, "character at x = {character_x}");
    let ahead = moved - (character_x - (1.5 - RADIUS - SKIN));
    assert!(
        (0.0..0.3).contains(&ahead),
        "crate moved {moved} m, character at {character_x}"
    );
    let (moved, character_x, pushes) = push_crate(1000.0, PUSH_100_KG);
    assert_eq!(pushes, 0);
    assert!(moved.abs() < 1e-3, "the heavy crate moved {moved} m");
    let blocked = 1.5 - RADIUS - SKIN;
    assert!(
        (character_x - blocked).abs() < 1e-3,
        "character at x = {character_x}, expected {blocked}"
    );
}

#[test]
fn a_push_brings_the_contact_point_to_the_desired_speed_within_the_impulse_limit() {
    for max_impulse in [f32::INFINITY, 2.0] {
        let (mut world, crate_body) = world_with_crate(10.0);
        // Touching the crate (gap `skin`), walking into it at 1.5 m/s.
        let (_, collider) = character_body(&mut world, 1.5 - RADIUS - SKIN, 0.0);
        let controller = pushing(Push {
            max_impulse,
            ..PUSH_100_KG
        });
        let moved = controller
            .move_collider(
                &world,
                collider,
                Vec3::new(1.5 * DT, 0.0, 0.0),
                DT,
                &QueryFilter::new(),
            )
            .unwrap();
        let before = world.body(crate_body).unwrap().linear_velocity();
        let pushes = controller.push_bodies(&mut world, &moved).unwrap();
        assert_eq!(pushes.len(), 1);
        let push = pushes[0];
        assert_eq!(push.body, crate_body);
        let crate_now = world.body(crate_body).unwrap();
        // Momentum: Δv of the centre of mass is J/m.
        let dv = crate_now.linear_velocity() - before;
        assert!(
            (dv - push.impulse / 10.0).length() < 1e-4,
            "Δv {dv}, J {}",
            push.impulse
        );
        let point_speed = crate_now.velocity_at_point(push.point).x;
        if max_impulse.is_finite() {
            assert!((push.impulse.length() - max_impulse).abs() < 1e-5);
            assert!(point_speed < 1.5);
        } else {
            assert!(
                (point_speed - 1.5).abs() < 1e-4,
                "contact point at {point_speed} m/s"
            );
        }
    }
}

#[test]
fn same_calls_give_bit_identical_moves() {
    let run = || {
        let (walker, _) = walk_to_step(0.35);
        walker.position
    };
    let (a, b) = (run(), run());
    assert_eq!(
        a.to_array().map(f32::to_bits),
        b.to_array().map(f32::to_bits)
    );
}

#[test]
fn refuses_bad_settings_naming_the_field_and_value() {
    let base = CharacterSettings::default();
    let cases: Vec<(CharacterSettings, &str)> = vec![
        (
            CharacterSettings {
                skin: f32::NAN,
                ..base
            },
            "skin",
        ),
        (
            CharacterSettings {
                skin: -0.01,
                ..base
            },
            "skin",
        ),
        (CharacterSettings { skin: 0.0, ..base }, "skin"),
        (
            CharacterSettings {
                max_slope_angle: 0.0,
                ..base
            },
            "max_slope_angle",
        ),
        (
            CharacterSettings {
                max_slope_angle: core::f32::consts::FRAC_PI_2,
                ..base
            },
            "max_slope_angle",
        ),
        (
            CharacterSettings {
                max_slope_angle: 2.0,
                ..base
            },
            "max_slope_angle",
        ),
        (
            CharacterSettings {
                max_slope_angle: f32::NAN,
                ..base
            },
            "max_slope_angle",
        ),
        (
            CharacterSettings {
                up: Vec3::new(0.0, 2.0, 0.0),
                ..base
            },
            "up",
        ),
        (
            CharacterSettings {
                up: Vec3::NAN,
                ..base
            },
            "up",
        ),
        (
            CharacterSettings {
                autostep: Some(Autostep {
                    max_height: -0.3,
                    ..Autostep::default()
                }),
                ..base
            },
            "autostep.max_height",
        ),
        (
            CharacterSettings {
                autostep: Some(Autostep {
                    min_width: f32::INFINITY,
                    ..Autostep::default()
                }),
                ..base
            },
            "autostep.min_width",
        ),
        (
            CharacterSettings {
                snap_to_ground: Some(0.0),
                ..base
            },
            "snap_to_ground",
        ),
        (
            CharacterSettings {
                push: Some(Push {
                    max_mass: f32::NAN,
                    ..Push::default()
                }),
                ..base
            },
            "push.max_mass",
        ),
        (
            CharacterSettings {
                push: Some(Push {
                    max_impulse: -1.0,
                    ..Push::default()
                }),
                ..base
            },
            "push.max_impulse",
        ),
        (
            CharacterSettings {
                max_iterations: 0,
                ..base
            },
            "max_iterations",
        ),
        (
            CharacterSettings {
                max_iterations: 1000,
                ..base
            },
            "max_iterations",
        ),
    ];
    for (settings, field) in cases {
        let error = CharacterController::new(settings).unwrap_err();
        assert!(matches!(error, Error::Character(_)), "{error:?}");
        let message = error.to_string();
        assert!(message.contains(field), "{message} does not name {field}");
        let mut controller = CharacterController::default();
        assert!(controller.set_settings(settings).is_err());
        assert_eq!(
            controller.settings(),
            &CharacterSettings::default(),
            "changed on error"
        );
    }
    let message = CharacterController::new(CharacterSettings {
        skin: -0.25,
        ..base
    })
    .unwrap_err()
    .to_string();
    assert!(message.contains("-0.25"), "{message}");
}

#[test]
fn refuses_bad_move_arguments() {
    let mut world = new_world();
    floor(&mut world);
    let controller = CharacterController::default();
    let pose = Pose::from_position(Vec3::new(0.0, 1.0, 0.0));
    let filter = QueryFilter::new();
    let shape = capsule();
    let call = |shape: &ColliderShape, pose: Pose, desired: Vec3, dt: f32| {
        controller.move_shape(&world, shape, pose, desired, dt, &filter)
    };
    assert!(matches!(
        call(&shape, pose, Vec3::NAN, DT),
        Err(Error::Math(_))
    ));
    assert!(matches!(
        call(&shape, pose, Vec3::X, 0.0),
        Err(Error::Math(_))
    ));
    assert!(matches!(
        call(&shape, pose, Vec3::X, f32::NAN),
        Err(Error::Math(_))
    ));
    assert!(matches!(
        call(&shape, pose, Vec3::X, f32::INFINITY),
        Err(Error::Math(_))
    ));
    assert!(matches!(
        call(&shape, pose, Vec3::X * 1e7, DT),
        Err(Error::Character(CharacterError::TooLong { .. }))
    ));
    let bad_pose = Pose::new(Vec3::ZERO, Quat::from_xyzw(0.0, 0.0, 0.0, 2.0));
    assert!(call(&shape, bad_pose, Vec3::X, DT).is_err());
    let mesh = ColliderShape::TriMesh {
        vertices: vec![Vec3::ZERO, Vec3::X, Vec3::Z],
        indices: vec![[0, 1, 2]],
    };
    assert!(matches!(
        call(&mesh, pose, Vec3::X, DT),
        Err(Error::Character(CharacterError::NonConvexShape { .. }))
    ));
    assert!(call(&ColliderShape::Ball { radius: -1.0 }, pose, Vec3::X, DT).is_err());
    // A collider handle from another world.
    let mut other = new_world();
    let body = other.insert_body(BodyDesc::kinematic()).unwrap();
    let foreign = other
        .insert_collider(ColliderDesc::ball(0.5), body)
        .unwrap();
    assert!(matches!(
        controller.move_collider(&world, foreign, Vec3::X, DT, &filter),
        Err(Error::StaleCollider(_))
    ));
}

#[test]
fn any_convex_shape_stops_a_skin_short_of_a_wall() {
    let mut world = new_world();
    let wall = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(3.0, 0.0, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(0.5, 5.0, 5.0)), wall)
        .unwrap();
    let controller = CharacterController::default();
    // Each shape's half-width along x.
    let shapes = [
        (ColliderShape::Ball { radius: 0.4 }, 0.4),
        (
            ColliderShape::Cuboid {
                half_extents: Vec3::new(0.25, 0.5, 0.25),
            },
            0.25,
        ),
        (
            ColliderShape::Cylinder {
                radius: 0.35,
                half_height: 0.6,
            },
            0.35,
        ),
        (
            ColliderShape::ConvexHull {
                points: vec![
                    Vec3::new(-0.3, -0.3, -0.3),
                    Vec3::new(0.3, -0.3, -0.3),
                    Vec3::new(0.0, -0.3, 0.3),
                    Vec3::new(0.0, 0.4, 0.0),
                ],
            },
            0.3,
        ),
    ];
    for (shape, half_width) in shapes {
        let moved = controller
            .move_shape(
                &world,
                &shape,
                Pose::IDENTITY,
                Vec3::new(5.0, 0.0, 0.0),
                DT,
                &QueryFilter::new(),
            )
            .unwrap();
        let expected = 2.5 - half_width - SKIN;
        assert!(
            (moved.translation.x - expected).abs() < 1e-3,
            "{}: moved {}, expected {expected}",
            shape.kind_name(),
            moved.translation.x
        );
        assert_eq!(moved.collisions.len(), 1, "{}", shape.kind_name());
    }
}

#[test]
fn walks_and_climbs_on_triangle_meshes_and_height_fields() {
    // A triangle-mesh floor (y = 0) and a 30° triangle-mesh ramp rising from x = 2 along +x.
    let angle = 30f32.to_radians();
    let rise = 4.0 * angle.tan();
    let mut world = new_world();
    let body = world.insert_body(BodyDesc::fixed()).unwrap();
    let vertices = vec![
        Vec3::new(-10.0, 0.0, -5.0),
        Vec3::new(2.0, 0.0, -5.0),
        Vec3::new(2.0, 0.0, 5.0),
        Vec3::new(-10.0, 0.0, 5.0),
        Vec3::new(6.0, rise, -5.0),
        Vec3::new(6.0, rise, 5.0),
    ];
    let indices = vec![[0, 2, 1], [0, 3, 2], [1, 2, 5], [1, 5, 4]];
    world
        .insert_collider(ColliderDesc::trimesh(vertices, indices), body)
        .unwrap();
    let start = Vec3::new(0.0, HALF_HEIGHT + RADIUS + SKIN, 0.0);
    let mut walker = Walker::new(slope_limit(45.0), start);
    for frame in 0..90 {
        let before = walker.position;
        let moved = walker.walk(&world, Vec3::new(2.0, 0.0, 0.0), true);
        assert!(
            moved.is_grounded(),
            "frame {frame}: not grounded at {}",
            walker.position
        );
        let dx = walker.position.x - before.x;
        assert!((dx - 2.0 * DT).abs() < 1e-3, "frame {frame}: dx {dx}");
    }
    // 3 m at 2 m/s: from x = 0 to 3, the last metre up the ramp (its crease rounds the capsule over).
    let n = Quat::from_rotation_z(angle) * Vec3::Y;
    let gap = gap_to_plane(walker.position, n, Vec3::new(2.0, 0.0, 0.0));
    assert!((0.0..SKIN + 1e-3).contains(&gap), "gap to the ramp {gap}");

    // A flat height field 20 m × 20 m at y = 0.
    let mut world = new_world();
    let body = world.insert_body(BodyDesc::fixed()).unwrap();
    world
        .insert_collider(
            ColliderDesc::heightfield(5, 5, vec![0.0; 25], Vec3::new(20.0, 1.0, 20.0)),
            body,
        )
        .unwrap();
    let mut walker = Walker::new(CharacterSettings::default(), start);
    for frame in 0..60 {
        let moved = walker.walk(&world, Vec3::new(1.0, 0.0, 2.0), true);
        assert!(
            moved.is_grounded(),
            "frame {frame}: not grounded on the height field"
        );
    }
    let bottom = walker.position.y - HALF_HEIGHT - RADIUS;
    assert!((bottom - SKIN).abs() < 1e-3, "bottom at {bottom}");
    assert!((walker.position - start - Vec3::new(1.0, 0.0, 2.0)).length() < 1e-2);
}
