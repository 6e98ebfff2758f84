//! The soak: a mixed scene — every collider shape, every joint kind, kinematic bodies driven by targets and by
//! velocity — stepped for a long time under random user edits (bodies spawned and removed, joints added and
//! removed, impulses, teleports, material and enable changes, snapshots restored), all drawn from a seeded
//! RNG so a run is reproducible. After every step: no panic, every body, contact impulse and joint state
//! finite. Every 500 steps a snapshot is taken and the next 100 steps (edits included) are run twice, from
//! the world and from the restored snapshot: the digests must agree. A body the quarantine takes out (out of
//! the bounds of `StepLimits`) is counted and removed.
//!
//! CI runs 10⁴ steps. The long run (10⁶ steps, in release, a few minutes):
//!
//! ```sh
//! SOAK_STEPS=1000000 cargo test --release -p rebound --test soak -- --ignored --nocapture
//! ```

#![allow(
    clippy::unwrap_used,
    reason = "test scenes are built from known-good values; a failed setup fails the test"
)]

mod support;

use proptest::prelude::RngExt;
use proptest::test_runner::{RngAlgorithm, TestRng};
use rebound::QuarantineReason;
use rebound::prelude::*;
use support::{assert_finite, fixed_box, quarantine_events};

const DT: f32 = 1.0 / 60.0;
/// The most dynamic bodies the edits keep in the scene.
const MAX_BODIES: usize = 40;

/// What a run did.
#[derive(Debug, Default, Clone, Copy, PartialEq, Eq)]
struct Figures {
    steps: u64,
    edits: u64,
    spawned: u64,
    removed: u64,
    joints_added: u64,
    restores: u64,
    quarantined: u64,
    contacts_seen: u64,
    most_bodies: usize,
}

struct Soak {
    world: PhysicsWorld,
    rng: TestRng,
    /// Dynamic bodies (the edits' targets), in creation order.
    bodies: Vec<BodyHandle>,
    joints: Vec<JointHandle>,
    /// A kinematic paddle driven by targets and a kinematic spinner driven by its velocity.
    paddle: BodyHandle,
    figures: Figures,
    /// Each quarantine: the step and the reason.
    quarantines: Vec<(u64, QuarantineReason)>,
    /// The step and kind of the last edit.
    last_edit: (u64, u32),
}

fn range(rng: &mut TestRng, lo: f32, hi: f32) -> f32 {
    rng.random_range(lo..hi)
}

fn point(rng: &mut TestRng, half: f32, y: (f32, f32)) -> Vec3 {
    Vec3::new(
        range(rng, -half, half),
        range(rng, y.0, y.1),
        range(rng, -half, half),
    )
}

/// A random convex shape of every kind a dynamic body can carry.
fn random_shape(rng: &mut TestRng) -> ColliderShape {
    let s = range(rng, 0.2, 0.6);
    match rng.random_range(0..7u32) {
        0 => ColliderShape::Ball { radius: s },
        1 => ColliderShape::Cuboid {
            half_extents: Vec3::new(s, range(rng, 0.1, 0.5), range(rng, 0.2, 0.6)),
        },
        2 => ColliderShape::Capsule {
            radius: 0.5 * s,
            half_height: s,
        },
        3 => ColliderShape::Cylinder {
            radius: s,
            half_height: 0.5 * s,
        },
        4 => ColliderShape::Cone {
            radius: s,
            half_height: s,
        },
        5 => ColliderShape::ConvexHull {
            points: (0..8).map(|_| point(rng, s, (-s, s))).collect(),
        },
        _ => ColliderShape::Compound {
            parts: vec![
                (
                    Pose::from_position(Vec3::new(-s, 0.0, 0.0)),
                    ColliderShape::Ball { radius: 0.5 * s },
                ),
                (
                    Pose::from_position(Vec3::new(s, 0.0, 0.0)),
                    ColliderShape::Cuboid {
                        half_extents: Vec3::splat(0.5 * s),
                    },
                ),
            ],
        },
    }
}

/// A random joint of every kind between bodies `a` and `b` as they are now: the point joints anchored
/// midway (so they start closed), the distance joints at the bodies' origins with a length near their
/// distance.
fn random_joint(rng: &mut TestRng, world: &PhysicsWorld, a: BodyHandle, b: BodyHandle) -> Joint {
    let (pa, pb) = (world.body(a).unwrap().pose(), world.body(b).unwrap().pose());
    let mid = 0.5 * (pa.position + pb.position);
    let length = (pa.position.distance(pb.position) * range(rng, 0.8, 1.2)).max(0.1);
    let at_mid = |kind: JointKind| Joint::from_world(kind, pa, pb, mid, mid, Quat::IDENTITY);
    let at_ends =
        |kind: JointKind| Joint::from_world(kind, pa, pb, pa.position, pb.position, Quat::IDENTITY);
    match rng.random_range(0..8u32) {
        0 => at_mid(BallJoint::new().into()),
        1 => at_mid(HingeJoint::new().with_limits(-1.0, 1.0).unwrap().into()),
        2 => at_mid(FixedJoint::new().into()),
        3 => at_mid(PrismaticJoint::new().into()),
        4 => at_mid(WheelJoint::default().into()),
        5 => at_ends(Rope::new(length).unwrap().into()),
        6 => at_ends(Rod::new(length).unwrap().into()),
        _ => at_ends(
            Spring::new(length, SpringModel::soft_frequency(2.0, 0.3).unwrap())
                .unwrap()
                .into(),
        ),
    }
    .unwrap()
}

impl Soak {
    fn new(seed: u64) -> Self {
        let mut world = PhysicsWorld::new(WorldSettings::default()).unwrap();
        fixed_box(
            &mut world,
            Vec3::new(0.0, -0.5, 0.0),
            Vec3::new(12.0, 0.5, 12.0),
        );
        // A ramp of triangles and a bumpy patch: the fixed-only shapes.
        let ramp = world
            .insert_body(BodyDesc::fixed().with_position(Vec3::new(-6.0, 0.0, -6.0)))
            .unwrap();
        world
            .insert_collider(
                ColliderDesc::new(ColliderShape::TriMesh {
                    vertices: vec![
                        Vec3::new(-3.0, 0.0, -3.0),
                        Vec3::new(3.0, 0.0, -3.0),
                        Vec3::new(3.0, 2.0, 3.0),
                        Vec3::new(-3.0, 2.0, 3.0),
                    ],
                    indices: vec![[0, 2, 1], [0, 3, 2]],
                }),
                ramp,
            )
            .unwrap();
        let patch = world
            .insert_body(BodyDesc::fixed().with_position(Vec3::new(6.0, 0.05, 6.0)))
            .unwrap();
        world
            .insert_collider(
                ColliderDesc::new(ColliderShape::HeightField {
                    rows: 4,
                    cols: 4,
                    heights: (0..16).map(|i| 0.1 * (i % 3) as f32).collect(),
                    scale: Vec3::new(6.0, 1.0, 6.0),
                }),
                patch,
            )
            .unwrap();
        let paddle = world
            .insert_body(BodyDesc::kinematic().with_position(Vec3::new(3.0, 0.4, 0.0)))
            .unwrap();
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::new(0.2, 0.4, 1.5)), paddle)
            .unwrap();
        let spinner = world
            .insert_body(
                BodyDesc::kinematic()
                    .with_position(Vec3::new(-3.0, 0.3, 3.0))
                    .with_angular_velocity(Vec3::new(0.0, 1.5, 0.0)),
            )
            .unwrap();
        world
            .insert_collider(ColliderDesc::cuboid(Vec3::new(2.0, 0.3, 0.2)), spinner)
            .unwrap();
        let mut soak = Self {
            world,
            rng: TestRng::from_seed(RngAlgorithm::ChaCha, &seed_bytes(seed)),
            bodies: Vec::new(),
            joints: Vec::new(),
            paddle,
            figures: Figures::default(),
            quarantines: Vec::new(),
            last_edit: (0, 0),
        };
        for _ in 0..24 {
            soak.spawn();
        }
        // Joints of random kinds between pairs of bodies, and a rope to the world.
        for kind in 0..8 {
            let (a, b) = (soak.bodies[2 * kind], soak.bodies[2 * kind + 1]);
            let joint = random_joint(&mut soak.rng, &soak.world, a, b);
            if let Ok(h) = soak.world.insert_joint(joint, a, b) {
                soak.joints.push(h);
            }
        }
        let hang = Joint::new(Rope::new(1.5).unwrap())
            .with_local_anchors(Vec3::new(0.0, 6.0, 0.0), Vec3::ZERO)
            .unwrap();
        if let Ok(h) = soak.world.insert_world_joint(hang, soak.bodies[20]) {
            soak.joints.push(h);
        }
        soak
    }

    fn spawn(&mut self) {
        let position = point(&mut self.rng, 8.0, (1.0, 6.0));
        let body = self
            .world
            .insert_body(BodyDesc::dynamic().with_position(position))
            .unwrap();
        let shape = random_shape(&mut self.rng);
        let friction = range(&mut self.rng, 0.0, 1.0);
        let restitution = range(&mut self.rng, 0.0, 0.8);
        self.world
            .insert_collider(
                ColliderDesc::new(shape)
                    .with_friction(friction)
                    .with_restitution(restitution),
                body,
            )
            .unwrap();
        self.bodies.push(body);
        self.figures.spawned += 1;
    }

    fn remove(&mut self, i: usize) {
        let body = self.bodies.swap_remove(i);
        let removed = self.world.remove_body(body).unwrap();
        self.joints
            .retain(|j| removed.joints.iter().all(|(r, _)| r != j));
        self.figures.removed += 1;
    }

    /// One random user edit.
    fn edit(&mut self) {
        self.figures.edits += 1;
        let n = self.bodies.len();
        let pick = |rng: &mut TestRng| rng.random_range(0..n.max(1));
        let kind = self.rng.random_range(0..10u32);
        self.last_edit = (self.figures.steps, kind);
        match kind {
            0 | 1 if n < MAX_BODIES => self.spawn(),
            0..=2 if n > 8 => {
                let i = pick(&mut self.rng);
                self.remove(i);
            }
            3 if n > 0 => {
                let i = pick(&mut self.rng);
                // A kick of up to 5 m/s, whatever the body's mass.
                let kick = point(&mut self.rng, 3.0, (0.0, 4.0));
                let body = self.world.body_mut(self.bodies[i]).unwrap();
                let impulse = kick * body.mass_properties().mass();
                let _ = body.apply_impulse(impulse);
            }
            4 if n > 0 => {
                let i = pick(&mut self.rng);
                let to = point(&mut self.rng, 8.0, (1.0, 5.0));
                let _ = self
                    .world
                    .body_mut(self.bodies[i])
                    .unwrap()
                    .set_position(to);
            }
            5 if n > 1 => {
                let (i, j) = (pick(&mut self.rng), pick(&mut self.rng));
                let (a, b) = (self.bodies[i], self.bodies[j]);
                if a == b {
                    return;
                }
                let joint = random_joint(&mut self.rng, &self.world, a, b);
                if let Ok(h) = self.world.insert_joint(joint, a, b) {
                    self.joints.push(h);
                    self.figures.joints_added += 1;
                }
            }
            6 if !self.joints.is_empty() => {
                let i = self.rng.random_range(0..self.joints.len());
                let joint = self.joints.swap_remove(i);
                self.world.remove_joint(joint).unwrap();
            }
            7 if n > 0 => {
                let i = pick(&mut self.rng);
                let colliders: Vec<ColliderHandle> = self
                    .world
                    .colliders()
                    .iter()
                    .filter(|(_, c)| c.body() == self.bodies[i])
                    .map(|(h, _)| h)
                    .collect();
                let (friction, density) = (
                    range(&mut self.rng, 0.0, 1.2),
                    range(&mut self.rng, 0.2, 3.0),
                );
                let enabled = self.rng.random_bool(0.8);
                for c in colliders {
                    self.world.set_collider_friction(c, friction).unwrap();
                    self.world.set_collider_density(c, density).unwrap();
                    self.world.set_collider_enabled(c, enabled).unwrap();
                }
            }
            8 if n > 0 => {
                let i = pick(&mut self.rng);
                let v = point(&mut self.rng, 4.0, (-2.0, 4.0));
                let _ = self
                    .world
                    .body_mut(self.bodies[i])
                    .unwrap()
                    .set_linear_velocity(v);
            }
            _ => {
                let snapshot = self.world.snapshot();
                self.world.restore(&snapshot).unwrap();
                self.figures.restores += 1;
            }
        }
    }

    /// One step: the paddle's target, an edit now and then, bodies that left the scene removed.
    fn step(&mut self) {
        let t = self.figures.steps as f32 * DT;
        let target =
            Pose::from_position(Vec3::new(3.0 * (0.5 * t).cos(), 0.4, 3.0 * (0.5 * t).sin()));
        self.world
            .set_kinematic_target(self.paddle, target)
            .unwrap();
        if self.rng.random_bool(0.05) {
            self.edit();
        }
        let report = self.world.step(DT);
        self.figures.steps += 1;
        self.figures.quarantined += report.quarantined_body_count as u64;
        self.figures.contacts_seen += report.contact_count as u64;
        // A quarantined body is out of bounds (a body spun or flung beyond the limits): the run records it
        // and removes it, as a game would.
        let quarantined = quarantine_events(&self.world);
        for (body, reason) in quarantined {
            self.quarantines.push((self.figures.steps, reason));
            if let Some(i) = self.bodies.iter().position(|&b| b == body) {
                self.remove(i);
            }
        }
        let fallen: Vec<usize> = (0..self.bodies.len())
            .filter(|&i| self.world.body(self.bodies[i]).unwrap().position().y < -20.0)
            .collect();
        for i in fallen.into_iter().rev() {
            self.remove(i);
        }
        self.figures.most_bodies = self.figures.most_bodies.max(self.world.bodies().len());
        assert_finite(&self.world, &format_args!("step {}", self.figures.steps));
    }
}

fn seed_bytes(seed: u64) -> [u8; 32] {
    let mut bytes = [0u8; 32];
    bytes[..8].copy_from_slice(&seed.to_le_bytes());
    bytes
}

/// Runs `steps` steps; every 500, the next 100 are run from a snapshot too, in lockstep, and must agree bit
/// for bit: with `strict`, a difference fails the run; otherwise it is recorded (the checkpoint's step, the
/// step that differed, the last edit before it) and the run goes on. Returns the figures, the quarantines and
/// the differences.
fn soak(seed: u64, steps: u64, strict: bool) -> Run {
    let mut soak = Soak::new(seed);
    let mut mismatches = Vec::new();
    while soak.figures.steps < steps {
        if !soak.figures.steps.is_multiple_of(500) {
            soak.step();
            continue;
        }
        let snapshot = soak.world.snapshot();
        let mut replay = Soak {
            world: PhysicsWorld::new(WorldSettings::default()).unwrap(),
            rng: soak.rng.clone(),
            bodies: soak.bodies.clone(),
            joints: soak.joints.clone(),
            paddle: soak.paddle,
            figures: soak.figures,
            quarantines: soak.quarantines.clone(),
            last_edit: soak.last_edit,
        };
        replay.world.restore(&snapshot).unwrap();
        let from = soak.figures.steps;
        for _ in 0..100 {
            soak.step();
            replay.step();
            if replay.world.state_digest() != soak.world.state_digest() {
                let at = (from, soak.figures.steps, soak.last_edit);
                assert!(!strict, "replay from step {from} differs at {at:?}");
                mismatches.push(at);
                break;
            }
            assert_eq!(replay.figures, soak.figures);
            assert_eq!(replay.quarantines, soak.quarantines);
        }
    }
    Run {
        figures: soak.figures,
        quarantines: soak.quarantines,
        mismatches,
    }
}

/// What [`soak`] returns.
struct Run {
    figures: Figures,
    quarantines: Vec<(u64, QuarantineReason)>,
    /// (checkpoint step, step that differed, (step, kind) of the last edit).
    mismatches: Vec<(u64, u64, (u64, u32))>,
}

#[test]
fn ten_thousand_steps_of_a_mixed_scene_under_random_edits_stay_finite_and_replay_exactly() {
    let Run {
        figures,
        quarantines,
        ..
    } = soak(30, 10_000, true);
    assert!(figures.steps >= 10_000);
    // The edits did happen: bodies came and went, joints were added, snapshots restored.
    assert!(figures.edits > 300, "{figures:?}");
    assert!(figures.spawned > 24 && figures.removed > 0 && figures.joints_added > 0);
    assert!(
        figures.restores > 0 && figures.contacts_seen > 0,
        "{figures:?}"
    );
    // Each quarantine was reported once, by event and count.
    assert_eq!(quarantines.len() as u64, figures.quarantined);
}

#[test]
#[ignore = "the long soak (10⁶ steps by default): run in release with --ignored, see the module docs"]
fn the_long_soak() {
    let steps = std::env::var("SOAK_STEPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1_000_000);
    let start = std::time::Instant::now();
    let run = soak(30, steps, false);
    eprintln!("soak: {:?} in {:?}", run.figures, start.elapsed());
    eprintln!("quarantines (step, reason): {:?}", run.quarantines);
    eprintln!(
        "replays that differed ({} of {} checkpoints; checkpoint, step, last edit): {:?}",
        run.mismatches.len(),
        steps.div_ceil(500),
        run.mismatches
    );
    assert_eq!(run.quarantines.len() as u64, run.figures.quarantined);
}
