//! [`StackLoads`] on hand-made contact graphs, against the weights they must carry: each interface of a
//! column carries `g` times the mass above it, whatever order the manifolds come in and whichever way their
//! normals point; a bridge on two pillars hands each half its weight; a manifold that is open, tilted past
//! 45° or between fixed bodies carries nothing; a reused propagation forgets the last graph; an unpushed
//! loaded manifold starts from the impulse that holds its load.

use rebound_dynamics::{
    BodyDesc, BodyParams, Contact, ContactPoint, MassProperties, RigidBody, StackLoads,
};
use rebound_math::Vec3;

const G: Vec3 = Vec3::new(0.0, -9.81, 0.0);
const H: f32 = 1.0 / 240.0;
/// Relative tolerance of a load: a few roundings of f32 sums.
const TOLERANCE: f32 = 1e-5;

/// A fixed ground (index 0) and unit cubes of the given masses (kg), indices 1, 2, ...
fn bodies(masses: &[f32]) -> Vec<BodyParams> {
    let ground = RigidBody::new(&BodyDesc::fixed()).expect("valid fixed body");
    let mut params = vec![BodyParams::from_body(&ground)];
    for &m in masses {
        let mass = MassProperties::cuboid(m, Vec3::splat(0.5)).expect("valid mass");
        let body = RigidBody::new(&BodyDesc::dynamic().with_mass_properties(mass))
            .expect("valid dynamic body");
        params.push(BodyParams::from_body(&body));
    }
    params
}

/// A manifold between `a` and `b` with normal `normal` (from a to b) and one point at `separation` (m).
fn manifold(a: usize, b: usize, normal: Vec3, separation: f32) -> Contact {
    let mut c = Contact::new(a, b, normal, 0.5, 0.0);
    c.push_point(ContactPoint {
        anchor_a: Vec3::ZERO,
        anchor_b: Vec3::ZERO,
        separation,
        normal_impulse: 0.0,
        tangent_impulse: Vec3::ZERO,
        feature_id: 0,
    });
    c
}

fn assert_load(c: &Contact, expected: f32) {
    assert!(
        (c.load - expected).abs() <= TOLERANCE * expected.max(1.0),
        "load {} N, expected {expected} N",
        c.load
    );
}

#[test]
fn each_interface_of_a_column_carries_the_weight_above_it() {
    let masses = [4.0, 3.0, 2.0, 1.0];
    let params = bodies(&masses);
    // Shuffled, and the upper two with body_a above (normal pointing down, from a to b).
    let mut contacts = vec![
        manifold(3, 2, -Vec3::Y, -1e-4),
        manifold(0, 1, Vec3::Y, -1e-4),
        manifold(4, 3, -Vec3::Y, 0.0),
        manifold(1, 2, Vec3::Y, 5e-4),
    ];
    StackLoads::new().compute(&mut contacts, &params, G, H);
    let above = |lowest: usize| masses[lowest - 1..].iter().sum::<f32>() * 9.81;
    assert_load(&contacts[1], above(1));
    assert_load(&contacts[3], above(2));
    assert_load(&contacts[0], above(3));
    assert_load(&contacts[2], above(4));
    // Unpushed, each starts from the impulse that holds its load over a substep.
    for c in &contacts {
        assert!((c.points[0].normal_impulse - c.load * H).abs() <= TOLERANCE * c.load * H);
    }
}

#[test]
fn a_bridge_on_two_pillars_hands_each_half_its_weight() {
    // Pillars 1 and 2 (5 kg each) on the ground, bridge 3 (2 kg) on both.
    let params = bodies(&[5.0, 5.0, 2.0]);
    let mut contacts = vec![
        manifold(0, 1, Vec3::Y, 0.0),
        manifold(0, 2, Vec3::Y, 0.0),
        manifold(1, 3, Vec3::Y, 0.0),
        manifold(2, 3, Vec3::Y, 0.0),
    ];
    StackLoads::new().compute(&mut contacts, &params, G, H);
    assert_load(&contacts[2], 9.81);
    assert_load(&contacts[3], 9.81);
    assert_load(&contacts[0], 6.0 * 9.81);
    assert_load(&contacts[1], 6.0 * 9.81);
}

#[test]
fn open_tilted_and_fixed_manifolds_carry_nothing() {
    let params = bodies(&[1.0, 1.0, 1.0]);
    let tilted = Vec3::new(3f32.sqrt() / 2.0, 0.5, 0.0); // 60° from up
    let mut contacts = vec![
        manifold(0, 1, Vec3::Y, 2e-3), // open: 2 mm apart
        manifold(0, 2, tilted, 0.0),   // steeper than 45°
        manifold(0, 0, Vec3::Y, 0.0),  // a body with itself
        manifold(0, 3, Vec3::Y, 0.0),  // the one support
    ];
    let mut loads = StackLoads::new();
    loads.compute(&mut contacts, &params, G, H);
    for c in &contacts[..3] {
        assert!(
            c.load.abs() <= 0.0,
            "load {} N on a manifold that supports nothing",
            c.load
        );
    }
    assert_load(&contacts[3], 9.81);
    // Without gravity nothing is loaded, and the loads of the last call are cleared.
    loads.compute(&mut contacts, &params, Vec3::ZERO, H);
    assert!(contacts.iter().all(|c| c.load.abs() <= 0.0));
}

#[test]
fn a_reused_propagation_gives_the_same_loads_on_another_graph() {
    let mut loads = StackLoads::new();
    let column = bodies(&[4.0, 3.0, 2.0, 1.0]);
    let mut first = vec![
        manifold(0, 1, Vec3::Y, 0.0),
        manifold(1, 2, Vec3::Y, 0.0),
        manifold(2, 3, Vec3::Y, 0.0),
        manifold(3, 4, Vec3::Y, 0.0),
    ];
    loads.compute(&mut first, &column, G, H);
    // Fewer bodies, other links: what the column left behind must not leak in.
    let bridge = bodies(&[5.0, 5.0, 2.0]);
    let mut second = vec![
        manifold(0, 1, Vec3::Y, 0.0),
        manifold(0, 2, Vec3::Y, 0.0),
        manifold(1, 3, Vec3::Y, 0.0),
        manifold(2, 3, Vec3::Y, 0.0),
    ];
    let mut fresh = second.clone();
    loads.compute(&mut second, &bridge, G, H);
    StackLoads::new().compute(&mut fresh, &bridge, G, H);
    for (reused, new) in second.iter().zip(&fresh) {
        assert!(
            (reused.load - new.load).abs() <= 0.0,
            "{} N vs {} N",
            reused.load,
            new.load
        );
    }
}

#[test]
fn a_stored_impulse_is_kept() {
    let params = bodies(&[1.0]);
    let mut contacts = vec![manifold(0, 1, Vec3::Y, 0.0)];
    contacts[0].points[0].normal_impulse = 0.01;
    StackLoads::new().compute(&mut contacts, &params, G, H);
    assert_load(&contacts[0], 9.81);
    assert!((contacts[0].points[0].normal_impulse - 0.01).abs() <= f32::EPSILON);
}
