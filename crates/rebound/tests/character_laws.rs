//! Laws of the character controller over random scenes of boxes in any orientation, for a capsule, a ball, a
//! box and a cylinder: the corrected
//! translation never leaves the shape overlapping a collider by more than 1 mm, is never longer than the
//! desired one over `cos(max_slope_angle)` (walkable slopes keep the horizontal motion and add the climb;
//! the skin may add up to `skin`) when autostep and snapping are off, and repeats bit for bit.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use proptest::prelude::*;
use rebound::prelude::*;

const RADIUS: f32 = 0.3;
const HALF_HEIGHT: f32 = 0.5;
/// The overlap allowed at the end of a move (m).
const TOLERANCE: f32 = 1e-3;

#[derive(Debug, Clone)]
struct Obstacle {
    centre: Vec3,
    half_extents: Vec3,
    axis: Vec3,
    angle: f32,
}

fn obstacle() -> impl Strategy<Value = Obstacle> {
    (
        (-3.0f32..3.0, 0.0f32..1.5, -3.0f32..3.0),
        (0.05f32..1.0, 0.05f32..1.0, 0.05f32..1.0),
        (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
        0.0f32..3.1,
    )
        .prop_map(|(c, h, a, angle)| Obstacle {
            centre: Vec3::new(c.0, c.1, c.2),
            half_extents: Vec3::new(h.0, h.1, h.2),
            axis: Vec3::new(a.0, a.1, a.2),
            angle,
        })
}

fn scene(obstacles: &[Obstacle]) -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
    let floor = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(20.0, 0.5, 20.0)), floor)
        .unwrap();
    for o in obstacles {
        let rotation = o
            .axis
            .try_normalize()
            .map_or(Quat::IDENTITY, |axis| Quat::from_axis_angle(axis, o.angle));
        let body = world
            .insert_body(
                BodyDesc::fixed()
                    .with_position(o.centre)
                    .with_rotation(rotation),
            )
            .unwrap();
        world
            .insert_collider(ColliderDesc::cuboid(o.half_extents), body)
            .unwrap();
    }
    world
}

/// The character's shape, `grown` (m) thicker on every side (negative: thinner): a capsule, a ball, a box or
/// a cylinder, about as wide.
fn character(kind: u8, grown: f32) -> ColliderShape {
    let radius = RADIUS + grown;
    match kind % 4 {
        0 => ColliderShape::Capsule {
            radius,
            half_height: HALF_HEIGHT,
        },
        1 => ColliderShape::Ball { radius },
        2 => ColliderShape::Cuboid {
            half_extents: Vec3::new(radius, RADIUS + HALF_HEIGHT + grown, radius),
        },
        _ => ColliderShape::Cylinder {
            radius,
            half_height: RADIUS + HALF_HEIGHT + grown,
        },
    }
}

fn overlaps(world: &PhysicsWorld, kind: u8, position: Vec3, grown: f32) -> bool {
    !world
        .intersect_shape(
            &character(kind, grown),
            Pose::from_position(position),
            &QueryFilter::new(),
        )
        .unwrap()
        .is_empty()
}

fn settings(full: bool) -> CharacterSettings {
    if full {
        CharacterSettings::default()
    } else {
        CharacterSettings {
            autostep: None,
            snap_to_ground: None,
            ..CharacterSettings::default()
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(96))]

    #[test]
    fn moves_end_clear_of_every_collider_and_no_longer_than_the_slope_allows(
        obstacles in prop::collection::vec(obstacle(), 0..6),
        start in (-3.0f32..3.0, 0.82f32..2.5, -3.0f32..3.0),
        desired in (-2.0f32..2.0, -2.0f32..2.0, -2.0f32..2.0),
        full in any::<bool>(),
        kind in any::<u8>(),
    ) {
        let world = scene(&obstacles);
        let start = Vec3::new(start.0, start.1, start.2);
        let desired = Vec3::new(desired.0, desired.1, desired.2);
        let settings = settings(full);
        // Start clear of everything by the skin.
        prop_assume!(!overlaps(&world, kind, start, settings.skin));
        let controller = CharacterController::new(settings).unwrap();
        let call = || {
            controller
                .move_shape(
                    &world,
                    &character(kind, 0.0),
                    Pose::from_position(start),
                    desired,
                    1.0 / 60.0,
                    &QueryFilter::new(),
                )
                .unwrap()
        };
        let moved = call();
        let end = start + moved.translation;
        prop_assert!(
            !overlaps(&world, kind, end, -TOLERANCE),
            "ends overlapping at {end} after {}", moved.translation
        );
        if !full {
            let bound = desired.length() / settings.max_slope_angle.cos() + settings.skin;
            prop_assert!(
                moved.translation.length() <= bound + 1e-4,
                "moved {} (|{}|) for {desired} (bound {bound})",
                moved.translation, moved.translation.length()
            );
        }
        let again = call();
        prop_assert_eq!(
            moved.translation.to_array().map(f32::to_bits),
            again.translation.to_array().map(f32::to_bits)
        );
    }
}

/// Any number, the odd ones (NaN, ±∞, zero, negative, huge) often.
fn any_number() -> impl Strategy<Value = f32> {
    prop_oneof![
        Just(f32::NAN),
        Just(f32::INFINITY),
        Just(f32::NEG_INFINITY),
        Just(0.0),
        Just(-1.0),
        Just(1e30),
        -10.0f32..10.0,
        any::<f32>(),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Whatever the settings and arguments, a call returns (a move or a typed error) and never panics; a
    /// refused setting names a field.
    #[test]
    fn never_panics_on_any_settings_or_arguments(
        numbers in prop::collection::vec(any_number(), 16),
        iterations in any::<u32>(),
        toggles in any::<u8>(),
    ) {
        let n = |i: usize| numbers[i];
        let settings = CharacterSettings {
            up: Vec3::new(n(0), n(1), n(2)),
            skin: n(3),
            max_slope_angle: n(4),
            autostep: (toggles & 1 != 0).then_some(Autostep {
                max_height: n(5),
                min_width: n(6),
                include_dynamic_bodies: toggles & 2 != 0,
            }),
            snap_to_ground: (toggles & 4 != 0).then_some(n(7)),
            push: (toggles & 8 != 0).then_some(Push { max_mass: n(8), max_impulse: n(9) }),
            carry_with_ground: toggles & 16 != 0,
            max_iterations: iterations % 80,
        };
        let controller = match CharacterController::new(settings) {
            Ok(controller) => controller,
            Err(error) => {
                prop_assert!(matches!(error, Error::Character(_)));
                // Fall back on valid settings with the odd arguments below.
                CharacterController::default()
            }
        };
        let mut world = scene(&[]);
        let crate_body = world
            .insert_body(BodyDesc::dynamic().with_position(Vec3::new(1.0, 0.5, 0.0)))
            .unwrap();
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)), crate_body)
            .unwrap();
        let pose = Pose::from_position(Vec3::new(n(10), n(11), n(12)));
        let desired = Vec3::new(n(13), n(14), n(15));
        if let Ok(moved) = controller.move_shape(
            &world,
            &character(toggles, 0.0),
            pose,
            desired,
            n(3).abs(),
            &QueryFilter::new(),
        ) {
            prop_assert!(moved.translation.is_finite());
            let _ = controller.push_bodies(&mut world, &moved);
        }
    }
}
