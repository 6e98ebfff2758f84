//! Determinism: hinged chains of spheres falling onto a half-space (in the spirit of Box2D's FallingHinges)
//! give bit-identical states when built twice, and a digest of the final state equal to a constant that is
//! updated deliberately when behaviour changes — in `cargo test` and `cargo test --release` alike.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound_constraints::{HingeJoint, Joint};
use rebound_dynamics::{BodyDesc, MassProperties};
use rebound_math::{Quat, Vec3};
use rebound_world::testing::SimpleBackend;
use rebound_world::{World, WorldSettings};

const DT: f32 = 1.0 / 60.0;
const CHAINS: usize = 4;
const LINKS: usize = 6;
const RADIUS: f32 = 0.2;

/// The state digest after 300 steps of [`falling_hinges`]. Update it only when a change of behaviour is
/// intended, and say why in the commit.
const EXPECTED_DIGEST: u64 = 0xd18f_dce9_95be_2b09;

fn falling_hinges() -> World<SimpleBackend> {
    let mut world = World::with_backend(WorldSettings::default(), SimpleBackend::new()).unwrap();
    let ground = world.insert_body(&BodyDesc::fixed()).unwrap();
    world
        .backend_mut()
        .add_half_space(ground, Vec3::Y, 0.6, 0.0);
    let mass = MassProperties::ball(1000.0, RADIUS).unwrap();
    for c in 0..CHAINS {
        let tilt =
            Quat::from_rotation_z(0.15 * c as f32 - 0.2) * Quat::from_rotation_y(0.3 * c as f32);
        let origin = Vec3::new(1.7 * c as f32 - 2.5, 1.0 + 0.6 * c as f32, 0.4 * c as f32);
        let mut previous = None;
        for i in 0..LINKS {
            let position = origin + tilt * Vec3::new(0.5 * i as f32, 0.0, 0.0);
            let body = world
                .insert_body(
                    &BodyDesc::dynamic()
                        .with_position(position)
                        .with_rotation(tilt)
                        .with_mass_properties(mass),
                )
                .unwrap();
            world.backend_mut().add_sphere(body, RADIUS, 0.6, 0.1);
            if let Some(prev) = previous {
                let hinge = Joint::new(HingeJoint::new())
                    .with_local_anchors(Vec3::new(0.25, 0.0, 0.0), Vec3::new(-0.25, 0.0, 0.0))
                    .unwrap()
                    .with_local_axes(Vec3::Z, Vec3::Z)
                    .unwrap();
                world.insert_joint(hinge, prev, body).unwrap();
            }
            previous = Some(body);
        }
    }
    world
}

#[test]
fn the_same_scene_built_twice_is_bit_identical_at_every_step() {
    let mut a = falling_hinges();
    let mut b = falling_hinges();
    for step in 0..300 {
        a.step(DT);
        b.step(DT);
        assert_eq!(
            a.state_digest(),
            b.state_digest(),
            "diverged at step {step}"
        );
    }
}

#[test]
fn falling_hinges_digest_matches_the_recorded_constant() {
    let mut world = falling_hinges();
    let mut touched = false;
    for _ in 0..300 {
        let report = world.step(DT);
        touched |= report.contact_count > 0;
    }
    assert!(
        touched,
        "the chains must reach the ground for the digest to cover contacts"
    );
    // Every chain is on the ground (no link below it, none left high), so the digest covers a real outcome.
    for (_, body) in world.bodies().iter().filter(|(_, b)| b.is_dynamic()) {
        let y = body.position().y;
        assert!(y > RADIUS - 0.01 && y < 1.5, "a link ended at y = {y}");
    }
    let digest = world.state_digest();
    assert_eq!(
        digest, EXPECTED_DIGEST,
        "the FallingHinges digest changed: {digest:#018x}; if the change of behaviour is intended, update EXPECTED_DIGEST"
    );
}
