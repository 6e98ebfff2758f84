//! The peer scenes (docs/scenes.md) as Rebound builds them (`tests/support/scenes/`): the exact body and joint counts,
//! the construction (generator draws, lattice, touching boxes, satisfied bridge joints, spring energy) and the
//! metric names the rapier side reports. Fast: the scenes are built, and stepped a few times at most; the
//! 600-step runs belong to `cargo run --release --bin compare`.

use rebound::prelude::*;
use rebound_suite::XorShift64Star;
use rebound_suite::scenes::bridge::Arc;
use rebound_suite::scenes::{
    self, Balls, Bridge, Chain, Link, Pyramid, Scene, SceneOptions, Springs, balls, bridge, chain,
    pyramid,
};

/// The position of a body (panics on a stale handle: a test failure).
fn position(world: &PhysicsWorld, handle: BodyHandle) -> Vec3 {
    world.body(handle).expect("a live body").position()
}

/// Bit-exact equality of two `f32` (the constructions are exact, so the comparisons are too).
#[track_caller]
fn assert_bits(actual: f32, expected: f32) {
    assert_eq!(
        actual.to_bits(),
        expected.to_bits(),
        "{actual} is not exactly {expected}"
    );
}

#[test]
fn generator_draws_match_values_computed_independently() {
    // First outputs and first draws of both scene seeds, computed by a separate Python implementation of
    // the recurrence of docs/scenes.md (f32 rounding after each operation).
    assert_eq!(
        XorShift64Star::new(balls::SEED).next_u64(),
        0xadc0_a73a_d9d7_122c
    );
    assert_eq!(
        XorShift64Star::new(bridge::SEED).next_u64(),
        0x2467_20ac_4ae1_4a34
    );
    let mut g = XorShift64Star::new(balls::SEED);
    let draws: Vec<u32> = (0..4).map(|_| g.uniform(-0.04, 0.04).to_bits()).collect();
    assert_eq!(draws, [0x3c6a_40c8, 0xbc00_f358, 0x3c28_4398, 0xbc73_8f76]);
    let mut g = XorShift64Star::new(bridge::SEED);
    assert_eq!(g.uniform(-0.2, 0.2).to_bits(), 0xbe12_8e33);
    assert_eq!(g.uniform(-0.3, 0.3).to_bits(), 0xbe2a_65cb);
}

#[test]
fn balls_lattice_with_the_seeded_jitter() {
    let scene = Balls::new(SceneOptions::default(), balls::SIDE).expect("builds");
    assert_eq!((scene.body_count(), scene.joint_count()), (4096, 0));
    let world = scene.world();
    // Ball (0, 0, 0): x = −7.5·1.1 + jx, z = −7.5·1.1 + jz (values from the Python reference).
    let p = position(world, scene.balls()[0]);
    assert_bits(p.x, f32::from_bits(0xc103_c570));
    assert_bits(p.y, 0.6);
    assert_bits(p.z, f32::from_bits(0xc104_203d));
    // Every ball within the jitter of its lattice point, in loop order i, j, k.
    let mut index = 0;
    for i in 0..16 {
        for j in 0..16 {
            for k in 0..16 {
                let p = position(world, scene.balls()[index]);
                let lattice = Vec3::new(
                    (i as f32 - 7.5) * 1.1,
                    0.6 + j as f32 * 1.1,
                    (k as f32 - 7.5) * 1.1,
                );
                let d = p - lattice;
                assert!(
                    d.x.abs() <= 0.04 && d.y.abs() < 1e-6 && d.z.abs() <= 0.04,
                    "ball {index}: {p}"
                );
                index += 1;
            }
        }
    }
    // The scaling footprints.
    let small = Balls::new(SceneOptions::default(), 8).expect("builds");
    assert_eq!(small.body_count(), 1024);
}

#[test]
fn pyramid_boxes_touch_exactly() {
    let scene = Pyramid::new(SceneOptions::default(), pyramid::BASE).expect("builds");
    assert_eq!((scene.body_count(), scene.joint_count()), (820, 0));
    let world = scene.world();
    let boxes = scene.boxes();
    let mut first = 0;
    for r in 0..40 {
        let row = &boxes[first..first + 40 - r];
        for (j, &(handle, p0)) in row.iter().enumerate() {
            let p = position(world, handle);
            assert_eq!(
                p.to_array().map(f32::to_bits),
                p0.to_array().map(f32::to_bits)
            );
            // Bottom face on the top face of the row below (the ground at y = 0 for row 0).
            assert_bits(p.y - pyramid::HALF, r as f32);
            assert_bits(p.z, 0.0);
            if j > 0 {
                // Side by side with no gap and no overlap.
                assert_bits(p.x - position(world, row[j - 1].0).x, 1.0);
            }
        }
        // Each row is centred, so every box rests half on each of the two boxes below it.
        assert_bits(position(world, row[0].0).x, (r as f32 - 39.0) / 2.0);
        first += 40 - r;
    }
    let (top, _) = *boxes.last().expect("boxes");
    assert_eq!(
        position(world, top).to_array().map(f32::to_bits),
        [0.0f32, 39.5, 0.0].map(f32::to_bits)
    );
    assert_eq!(
        Pyramid::new(SceneOptions::default(), 20)
            .expect("builds")
            .body_count(),
        210
    );
}

#[test]
fn chain_starts_straight_at_full_length() {
    for link in [Link::Rope, Link::Spherical] {
        let scene = Chain::new(SceneOptions::default(), link).expect("builds");
        assert_eq!((scene.body_count(), scene.joint_count()), (500, 500));
        assert!(scene.max_stretch().abs() < 1e-6, "{}", scene.max_stretch());
        let total: f32 = scene.link_lengths().sum();
        assert!((total - chain::BALLS as f32 * chain::LINK).abs() < 1e-3);
    }
}

/// Issue 28: after 10 steps the pairs keep `exp(−2ζω·t)` = 0.0357 of their energy (ζ = 0.0707, ω = 141.4
/// rad/s, t = 1/6 s), within 10 % of the 0.036 the physical damping alone leaves — no numerical damping.
#[test]
fn springs_lose_energy_at_their_physical_damping_rate() {
    let mut scene = Springs::new(SceneOptions::default()).expect("builds");
    let e0 = scene.initial_energy();
    for _ in 0..10 {
        scene.step();
    }
    let ratio = scene.energy() / e0;
    println!("E10/E0 = {ratio:.5}");
    assert!((ratio / 0.036 - 1.0).abs() < 0.1, "E10/E0 = {ratio}");
}

#[test]
fn springs_start_with_1250_joules_per_pair() {
    let scene = Springs::new(SceneOptions::default()).expect("builds");
    assert_eq!((scene.body_count(), scene.joint_count()), (2000, 1000));
    for &(a, b) in scene.pairs() {
        for h in [a, b] {
            let body = scene.world().body(h).expect("a live body");
            assert!((body.inv_mass() - 1.0).abs() < 1e-6, "1 kg balls");
        }
        let d = position(scene.world(), b) - position(scene.world(), a);
        assert!((d - Vec3::new(1.5, 0.0, 0.0)).length() < 1e-5);
    }
    let e0 = scene.initial_energy();
    assert!((e0 - 1000.0 * 1250.0).abs() < 1e-3 * e0, "E0 = {e0}");
}

#[test]
fn bridge_joints_start_satisfied() {
    let arc = Arc::solve();
    assert!((arc.radius - 45.30).abs() < 0.01, "R = {}", arc.radius);
    let scene = Bridge::new(SceneOptions::default()).expect("builds");
    assert_eq!((scene.body_count(), scene.joint_count()), (150, 101));
    let separation = scene.max_joint_separation();
    assert!(separation < 1e-4, "initial joint gap {separation} m");
    assert!(
        (scene.initial_sag() - 6.7245).abs() < 1e-3,
        "{}",
        scene.initial_sag()
    );
    for &joint in scene.joints() {
        assert_eq!(scene.world().joint_contacts_enabled(joint), Some(false));
    }
    // Ball 0 from the first two draws (values from the Python reference).
    let p = position(scene.world(), scene.balls()[0]);
    let x = -0.5 * bridge::SPAN + 2.0 + f32::from_bits(0xbe12_8e33);
    assert_bits(p.x, x);
    assert_bits(p.z, f32::from_bits(0xbe2a_65cb));
    assert_bits(
        p.y,
        arc.deck(x) + bridge::PLANK_HALF[1] + bridge::BALL_RADIUS + 0.2,
    );
}

#[test]
fn metric_names_are_the_rapier_sides() {
    let expected: [(&str, &[&str]); 6] = [
        (
            "balls",
            &[
                "min_center_y",
                "max_center_y",
                "max_speed",
                "below_ground",
                "contact_pairs",
            ],
        ),
        (
            "pyramid",
            &[
                "top_y",
                "top_y0",
                "top_dy",
                "max_horiz_drift",
                "max_z_drift",
                "max_z_drift_run",
                "standing",
            ],
        ),
        (
            "chain",
            &[
                "max_link_stretch_end",
                "max_link_stretch_run",
                "chain_length_ratio",
                "tip",
            ],
        ),
        (
            "chain_spherical",
            &[
                "max_link_stretch_end",
                "max_link_stretch_run",
                "chain_length_ratio",
                "tip",
            ],
        ),
        (
            "springs",
            &[
                "E10/E0",
                "steps_to_E<1e-3E0",
                "min_len_run",
                "len_err_end_max",
                "len_err_end_mean",
                "max_speed_end",
            ],
        ),
        (
            "bridge",
            &[
                "sag0",
                "sag_end",
                "sag_mean_last60",
                "max_joint_sep_end",
                "max_joint_sep_run",
                "balls_on_bridge",
            ],
        ),
    ];
    for (name, keys) in expected {
        let scene = scenes::build(name, SceneOptions::default())
            .expect("builds")
            .expect("a known name");
        let names: Vec<&str> = scene.quality().iter().map(|&(k, _)| k).collect();
        assert_eq!(names, keys, "{name}");
    }
    assert!(
        scenes::build("nope", SceneOptions::default())
            .expect("no error")
            .is_none()
    );
}

#[test]
fn a_few_steps_keep_the_joint_scenes_together() {
    // Not the benchmark: three steps, to see the scenes step and observe without anything odd.
    let mut bridge = Bridge::new(SceneOptions::default()).expect("builds");
    let mut chain = Chain::new(SceneOptions::default(), Link::Rope).expect("builds");
    for step in 1..=3 {
        bridge.step();
        bridge.observe(step);
        chain.step();
        chain.observe(step);
    }
    assert!(bridge.max_joint_separation() < 0.01);
    assert!(chain.max_stretch() < 0.01);
    for (_, value) in bridge.quality().into_iter().chain(chain.quality()) {
        if let Some(x) = value.as_f64() {
            assert!(x.is_finite());
        }
    }
}

/// Issue 7's joint targets on the peer scenes, 10 s each: the bridge's joints never open by more than
/// 1 cm (rapier: 5.9 cm; Rebound solving joint by joint: 3.3 cm), the chain of ball joints never stretches a
/// link by more than 1 % (joint by joint: 140 %), and neither does the rope chain — links that go slack,
/// bunch up and snap taut at the whip (measured 0.14 %; 6.0 % before the direct solve's soft step was taken
/// for all rows at once; joint by joint 23 %).
#[test]
fn the_joint_scenes_hold_their_joints_for_10_s() {
    let mut bridge = Bridge::new(SceneOptions::default()).expect("builds");
    let mut spherical = Chain::new(SceneOptions::default(), Link::Spherical).expect("builds");
    let mut rope = Chain::new(SceneOptions::default(), Link::Rope).expect("builds");
    let (mut gap, mut stretch_spherical, mut stretch_rope) = (0.0f32, 0.0f32, 0.0f32);
    for _ in 0..600 {
        bridge.step();
        spherical.step();
        rope.step();
        gap = gap.max(bridge.max_joint_separation());
        stretch_spherical = stretch_spherical.max(spherical.max_stretch());
        stretch_rope = stretch_rope.max(rope.max_stretch());
    }
    assert!(gap <= 0.01, "bridge joint gap reached {gap} m");
    assert!(
        stretch_spherical <= 0.01,
        "ball-joint chain stretched {stretch_spherical}"
    );
    assert!(stretch_rope <= 0.01, "rope chain stretched {stretch_rope}");
}

/// The rope chain's whip from nudged starts: the 1 % bound must not hold by luck. Before the projection's
/// stiffened Newton step, the unperturbed chain measured 0.14 % but starting ball 10 or ball 200 just 10 µm
/// further along x left 2.7 % (step 320) and 2.0 % (step 323): at the whip the plain Newton step of the
/// position projection moved the light balls of the nearly straight, heavily pulled links near the anchor
/// sideways by up to 10 cm and was rejected, and the sweeps after it barely help (`docs/physics.md`, "Chains
/// solved directly"). Now every such start stays near 0.04 %. The chain scene up to just past the whip
/// (330 steps; shorter chains whip too gently to show it).
#[test]
fn the_rope_chain_holds_through_the_whip_from_nudged_starts() {
    for nudged in [10, 200] {
        let settings = SceneOptions::default().settings(Vec3::new(0.0, -9.81, 0.0));
        let mut world = PhysicsWorld::new(settings).expect("valid settings");
        let mut bodies = vec![world.insert_body(BodyDesc::fixed()).expect("inserts")];
        for i in 0..chain::BALLS {
            let mut x = (i + 1) as f32 * chain::LINK;
            if i == nudged {
                x += 1e-5;
            }
            let ball = world
                .insert_body(SceneOptions::default().dynamic(Vec3::new(x, 0.0, 0.0)))
                .expect("inserts");
            world
                .insert_collider(ColliderDesc::ball(chain::RADIUS).with_density(1.0), ball)
                .expect("inserts");
            let rope = Joint::new(Rope::new(chain::LINK).expect("a valid length"));
            world.insert_joint(rope, bodies[i], ball).expect("inserts");
            bodies.push(ball);
        }
        let mut worst = 0.0f32;
        for _ in 0..330 {
            world.step(scenes::DT);
            for pair in bodies.windows(2) {
                let length = position(&world, pair[0]).distance(position(&world, pair[1]));
                worst = worst.max(length / chain::LINK - 1.0);
            }
        }
        assert!(
            worst <= 0.01,
            "ball {nudged} nudged: a link stretched by {worst}"
        );
    }
}
