//! Stacks under load at the default settings, whose resting contacts hold the weight they carry at a fixed
//! overlap (`WorldSettings::resting_overlap`, by default 0.1 mm): every interface of a column of 40 unit
//! boxes overlaps by at most twice the resting overlap whatever it carries, the bottom one as much under 40
//! boxes as under 10, a 1 kg box holds a 1,000 kg one up, and the 820-box pyramid keeps its height
//! (`docs/physics.md`, "Contacts under load"). With `resting_overlap: None` they sink by the sum of
//! load / stiffness: 0.433 m, 1 m (the light box is squeezed out) and 0.108 m.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers build known-good scenes; a failed setup fails the test"
)]

use rebound::prelude::*;

const DT: f32 = 1.0 / 60.0;

/// A fixed cuboid whose top face is y = 0.
fn ground(world: &mut PhysicsWorld) {
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(100.0, 0.5, 100.0)), ground)
        .unwrap();
}

/// A cube of half-extent `half` and mass `mass` centred at `p`.
fn cube(world: &mut PhysicsWorld, p: Vec3, half: f32, mass: f32) -> BodyHandle {
    let body = world
        .insert_body(BodyDesc::dynamic().with_position(p))
        .unwrap();
    let volume = 8.0 * half * half * half;
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::splat(half)).with_density(mass / volume),
            body,
        )
        .unwrap();
    body
}

/// The settings the tests run at: the defaults, and sleep as asked.
fn settings(sleep: bool) -> WorldSettings {
    WorldSettings {
        sleep_enabled: sleep,
        ..WorldSettings::default()
    }
}

/// The default resting overlap (m).
fn overlap() -> f32 {
    WorldSettings::default().resting_overlap.unwrap()
}

fn sideways(p: Vec3, p0: Vec3) -> f32 {
    Vec3::new(p.x - p0.x, 0.0, p.z - p0.z).length()
}

/// A column of `count` unit boxes (1 kg) on the ground after `steps` steps: each box's height (m) and the
/// farthest any box moved sideways on the way (m).
fn column(count: usize, sleep: bool, steps: usize) -> (Vec<f32>, f32) {
    let mut w = PhysicsWorld::new(settings(sleep)).unwrap();
    ground(&mut w);
    let boxes: Vec<_> = (0..count)
        .map(|i| {
            let p = Vec3::new(0.0, 0.5 + i as f32, 0.0);
            (cube(&mut w, p, 0.5, 1.0), p)
        })
        .collect();
    let mut worst_sideways = 0.0_f32;
    for _ in 0..steps {
        w.step(DT);
        for &(b, p0) in &boxes {
            worst_sideways = worst_sideways.max(sideways(w.body(b).unwrap().position(), p0));
        }
    }
    let heights = boxes
        .iter()
        .map(|&(b, _)| w.body(b).unwrap().position().y)
        .collect();
    (heights, worst_sideways)
}

/// The overlap (m) of each interface of a column of unit boxes with centres at `heights`, bottom first: the
/// ground's top face is y = 0 and a unit box's centre rests 0.5 above what it stands on.
fn interface_overlaps(heights: &[f32]) -> Vec<f32> {
    core::iter::once(0.5 - heights[0])
        .chain(heights.windows(2).map(|pair| 1.0 - (pair[1] - pair[0])))
        .collect()
}

/// 40 unit boxes (1 kg) on the ground for 20 s. Soft contacts alone overlap by load / stiffness, which
/// grows down the column (the bottom interface carries 40 boxes: 2.8 mm, the one above it 39: 2.2 cm) and sums
/// to 0.433 m. At the defaults no interface overlaps by more than twice the resting overlap, the top is
/// within 1 cm of its rest height and no box moves 1 cm sideways.
fn column_of_40_stands(sleep: bool) {
    const COUNT: usize = 40;
    let (heights, worst_sideways) = column(COUNT, sleep, 1200);
    assert!(
        worst_sideways < 0.01,
        "a box moved {worst_sideways} m sideways"
    );
    for (k, depth) in interface_overlaps(&heights).into_iter().enumerate() {
        assert!(
            depth < 2.0 * overlap(),
            "interface {k} (carrying {} boxes) overlaps by {depth} m",
            COUNT - k
        );
    }
    let rest_height = 0.5 + (COUNT - 1) as f32;
    let drop = rest_height - heights[COUNT - 1];
    assert!(
        drop.abs() < 0.01,
        "the top is {drop} m below its rest height"
    );
}

/// Penetration at rest does not grow with the load: after 10 s the bottom interface of a column of 40 unit
/// boxes (392 N on it) overlaps as much as that of a column of 10 (98 N), to 0.02 mm, a fifth of the resting
/// overlap. Soft contacts alone give load / stiffness: 2.8 mm against 0.7 mm.
#[test]
fn the_overlap_at_rest_of_a_column_s_bottom_does_not_grow_with_its_load() {
    const TOLERANCE: f32 = 2e-5;
    let bottom = |count: usize| interface_overlaps(&column(count, true, 600).0)[0];
    let (ten, forty) = (bottom(10), bottom(40));
    assert!(
        (forty - ten).abs() <= TOLERANCE,
        "the bottom overlaps by {ten} m under 10 boxes and by {forty} m under 40"
    );
    assert!(
        ten > 0.0 && ten <= 2.0 * overlap(),
        "the bottom of the 10-box column overlaps by {ten} m"
    );
}

#[test]
fn a_column_of_40_boxes_keeps_its_height_within_1_cm_for_20_s() {
    column_of_40_stands(true);
}

#[test]
fn a_column_of_40_boxes_keeps_its_height_within_1_cm_for_20_s_awake() {
    column_of_40_stands(false);
}

/// A 1 kg unit box on the ground under a 1,000 kg one, 20 s. Soft contacts alone would overlap by
/// 0.28 m between them (the stiffness follows the lighter body); the light box is squeezed out and the heavy
/// one ends 1 m low. Preloaded, the heavy box's centre stays within 2 mm of its rest height (0.35 mm
/// measured) and neither moves 1 cm sideways.
fn heavy_on_light_stands(sleep: bool) {
    let mut w = PhysicsWorld::new(settings(sleep)).unwrap();
    ground(&mut w);
    let p0 = Vec3::new(0.0, 0.5, 0.0);
    let p1 = Vec3::new(0.0, 1.5, 0.0);
    let light = cube(&mut w, p0, 0.5, 1.0);
    let heavy = cube(&mut w, p1, 0.5, 1000.0);
    let mut worst_sideways = 0.0_f32;
    for _ in 0..1200 {
        w.step(DT);
        worst_sideways = worst_sideways
            .max(sideways(w.body(light).unwrap().position(), p0))
            .max(sideways(w.body(heavy).unwrap().position(), p1));
    }
    assert!(
        worst_sideways < 0.01,
        "a box moved {worst_sideways} m sideways"
    );
    let drop = p1.y - w.body(heavy).unwrap().position().y;
    assert!(
        drop.abs() < 2e-3,
        "the heavy box is {drop} m below its rest height"
    );
}

#[test]
fn a_1_kg_box_holds_a_1000_kg_box_within_2_mm_for_20_s() {
    heavy_on_light_stands(true);
}

#[test]
fn a_1_kg_box_holds_a_1000_kg_box_within_2_mm_for_20_s_awake() {
    heavy_on_light_stands(false);
}

/// The 820-box pyramid (base 40, the `pyramid` peer scene), 10 s, preloaded: the top box sinks less
/// than 1 cm (soft contacts alone: 0.108 m) and no box moves 2 cm sideways.
#[test]
fn the_820_box_pyramid_top_drops_less_than_1_cm_in_10_s() {
    const BASE: usize = 40;
    let mut w = PhysicsWorld::new(settings(true)).unwrap();
    ground(&mut w);
    let mut boxes = Vec::new();
    for r in 0..BASE {
        let count = BASE - r;
        for j in 0..count {
            let p = Vec3::new(j as f32 - (count - 1) as f32 / 2.0, 0.5 + r as f32, 0.0);
            boxes.push((cube(&mut w, p, 0.5, 1.0), p));
        }
    }
    for _ in 0..600 {
        w.step(DT);
    }
    let worst_sideways = boxes
        .iter()
        .map(|&(b, p0)| sideways(w.body(b).unwrap().position(), p0))
        .fold(0.0_f32, f32::max);
    assert!(
        worst_sideways < 0.02,
        "a box moved {worst_sideways} m sideways"
    );
    let (top, p0) = *boxes.last().unwrap();
    let drop = p0.y - w.body(top).unwrap().position().y;
    assert!(drop.abs() < 0.01, "the top sank {drop} m");
}
