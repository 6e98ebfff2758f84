//! Stacks under load with preloaded resting contacts (`WorldSettings::resting_overlap`): every interface of
//! a column of 40 unit boxes and of the 820-box pyramid overlaps by at most the resting overlap, whatever it
//! carries, so the tops sink by at most one overlap per interface (`docs/physics.md`, "Contacts under
//! load"). Without it they sink by the sum of load / stiffness: 0.433 m and 0.108 m.

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

/// The resting overlap the tests set (m): the smallest measured to keep the 40-box column standing.
const OVERLAP: f32 = 1e-3;

fn sideways(p: Vec3, p0: Vec3) -> f32 {
    Vec3::new(p.x - p0.x, 0.0, p.z - p0.z).length()
}

fn preloaded() -> PhysicsWorld {
    PhysicsWorld::new(WorldSettings {
        resting_overlap: Some(OVERLAP),
        ..WorldSettings::default()
    })
    .unwrap()
}

/// 40 unit boxes (1 kg) on the ground for 20 s. Soft contacts alone overlap by load / stiffness, which
/// grows down the column (the bottom interface carries 39 boxes: 2.2 cm) and sums to 0.433 m; preloaded,
/// no interface overlaps by more than `OVERLAP` (tolerance 10 %), the top sinks by at most 40 of them and
/// no box moves 1 cm sideways.
#[test]
fn a_preloaded_column_of_40_boxes_overlaps_by_at_most_the_resting_overlap_at_every_interface() {
    const COUNT: usize = 40;
    let mut w = preloaded();
    ground(&mut w);
    let boxes: Vec<_> = (0..COUNT)
        .map(|i| {
            let p = Vec3::new(0.0, 0.5 + i as f32, 0.0);
            (cube(&mut w, p, 0.5, 1.0), p)
        })
        .collect();
    let mut worst_sideways = 0.0_f32;
    for _ in 0..1200 {
        w.step(DT);
        for &(b, p0) in &boxes {
            worst_sideways = worst_sideways.max(sideways(w.body(b).unwrap().position(), p0));
        }
    }
    assert!(
        worst_sideways < 0.01,
        "a box moved {worst_sideways} m sideways"
    );
    let heights: Vec<f32> = boxes
        .iter()
        .map(|&(b, _)| w.body(b).unwrap().position().y)
        .collect();
    // The ground's top face is y = 0; a unit box's centre rests 0.5 above what it stands on.
    let overlaps = core::iter::once(0.5 - heights[0])
        .chain(heights.windows(2).map(|pair| 1.0 - (pair[1] - pair[0])));
    for (k, overlap) in overlaps.enumerate() {
        assert!(
            overlap < 1.1 * OVERLAP,
            "interface {k} (carrying {} boxes) overlaps by {overlap} m",
            COUNT - k
        );
    }
    let drop = boxes[COUNT - 1].1.y - heights[COUNT - 1];
    assert!(
        drop < COUNT as f32 * OVERLAP * 1.1,
        "the top sank {drop} m, more than {COUNT} resting overlaps"
    );
}

/// The 820-box pyramid (base 40, the `pyramid` peer scene), 10 s at the defaults but for the preload: the
/// top box sinks by at most one resting overlap per row (soft contacts alone: 0.108 m) and no box moves
/// 2 cm sideways.
#[test]
fn a_preloaded_pyramid_of_820_boxes_sinks_at_most_one_resting_overlap_per_row() {
    const BASE: usize = 40;
    let mut w = preloaded();
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
    assert!(
        drop < BASE as f32 * OVERLAP,
        "the top sank {drop} m, more than {BASE} resting overlaps"
    );
}
