//! The validation scenes of docs/scenes.md through the `rebound` facade with real parry shapes (ground = a fixed cuboid
//! whose top face is y = 0), each against its closed form with the stated tolerance; plus a pyramid of base
//! 20 that must stand, balls on a height field that must stay above it, and a 100 m/s ball that must not
//! tunnel through a 0.1 m wall.

#![allow(
    clippy::unwrap_used,
    reason = "test helpers fail loudly on the first unexpected error"
)]

use rebound::RigidBody;
use rebound::prelude::*;
use rebound_suite::symplectic_euler_position;

const DT: f32 = 1.0 / 60.0;
const G: f32 = 9.81;

fn world_with(settings: WorldSettings) -> PhysicsWorld {
    PhysicsWorld::new(settings).unwrap()
}

fn world() -> PhysicsWorld {
    world_with(WorldSettings::default())
}

/// A fixed cuboid 200 × 1 × 200 m centred at y = −0.5: its top face is y = 0.
fn add_ground(world: &mut PhysicsWorld, friction: f32, restitution: f32) -> BodyHandle {
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .unwrap();
    world
        .insert_collider(
            ColliderDesc::cuboid(Vec3::new(100.0, 0.5, 100.0))
                .with_friction(friction)
                .with_restitution(restitution),
            ground,
        )
        .unwrap();
    ground
}

fn add_ball(world: &mut PhysicsWorld, desc: BodyDesc, radius: f32, restitution: f32) -> BodyHandle {
    let body = world.insert_body(desc).unwrap();
    world
        .insert_collider(
            ColliderDesc::ball(radius)
                .with_density(1000.0)
                .with_restitution(restitution)
                .with_restitution_combine_rule(CombineRule::Max),
            body,
        )
        .unwrap();
    body
}

fn body(world: &PhysicsWorld, handle: BodyHandle) -> &RigidBody {
    world.body(handle).unwrap()
}

#[test]
fn free_fall_matches_the_semi_implicit_euler_prediction() {
    let mut w = world();
    let ball = add_ball(
        &mut w,
        BodyDesc::dynamic().with_position(Vec3::new(0.0, 100.0, 0.0)),
        0.5,
        0.0,
    );
    let substeps = w.settings().substep_count;
    for step in 1..=120 {
        w.step(DT);
        let predicted =
            symplectic_euler_position(100.0, 0.0, -f64::from(G), f64::from(DT), step, substeps);
        let y = f64::from(body(&w, ball).position().y);
        assert!(
            (y - predicted).abs() < 1e-5 * predicted.abs().max(1.0),
            "step {step}: {y} vs {predicted}"
        );
    }
}

#[test]
fn head_on_elastic_collision() {
    let mut w = world_with(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    });
    // m1 = 1 kg at 4 m/s, m2 = 3 kg at −1 m/s. Colliders of density 0 add no mass, so the masses set on the
    // bodies stand.
    let ball = |w: &mut PhysicsWorld, x: f32, v: f32, mass: f32| {
        let desc = BodyDesc::dynamic()
            .with_position(Vec3::new(x, 0.0, 0.0))
            .with_linear_velocity(Vec3::X * v);
        let b = w.insert_body(desc).unwrap();
        w.insert_collider(
            ColliderDesc::ball(0.25)
                .with_density(0.0)
                .with_restitution(1.0),
            b,
        )
        .unwrap();
        let mass = MassProperties::new(mass, Vec3::ZERO, Vec3::splat(0.025 * mass)).unwrap();
        w.set_body_mass_properties(b, mass).unwrap();
        b
    };
    let b1 = ball(&mut w, -1.0, 4.0, 1.0);
    let b2 = ball(&mut w, 1.0, -1.0, 3.0);
    for _ in 0..60 {
        w.step(DT);
    }
    let (v1, v2) = (
        body(&w, b1).linear_velocity().x,
        body(&w, b2).linear_velocity().x,
    );
    assert!((v1 + 3.5).abs() < 0.035, "v1' = {v1}, expected −3.5 ± 1 %");
    assert!((v2 - 1.5).abs() < 0.015, "v2' = {v2}, expected 1.5 ± 1 %");
    let p = v1 + 3.0 * v2;
    assert!((p - 1.0).abs() < 0.005, "momentum {p} vs 1 kg·m/s");
    let e = 0.5 * v1 * v1 + 1.5 * v2 * v2;
    assert!((e - 9.5).abs() < 0.005 * 9.5, "kinetic energy {e} vs 9.5 J");
}

#[test]
fn a_dropped_ball_rebounds_to_restitution_squared_times_the_height() {
    for restitution in [0.0f32, 0.5, 0.8, 1.0] {
        let mut w = world();
        add_ground(&mut w, 0.5, restitution);
        let radius = 0.25;
        let ball = add_ball(
            &mut w,
            BodyDesc::dynamic().with_position(Vec3::new(0.0, radius + 2.0, 0.0)),
            radius,
            restitution,
        );
        // Wait for the impact (the ball stops falling), then take the highest point of the rebound.
        let mut impact = false;
        let mut apex = 0.0f32;
        for _ in 0..240 {
            w.step(DT);
            let b = body(&w, ball);
            if !impact {
                impact = b.linear_velocity().y > -0.5 && b.position().y - radius < 0.5;
                continue;
            }
            apex = apex.max(b.position().y - radius);
            if b.linear_velocity().y < -0.1 {
                break;
            }
        }
        assert!(impact, "C_r = {restitution}: the ball never landed");
        let expected = restitution * restitution * 2.0;
        if restitution == 0.0 {
            assert!(
                apex <= 0.01,
                "C_r = 0: rebound {apex} m, must stay within 1 cm"
            );
        } else {
            assert!(
                (apex - expected).abs() < 0.03 * expected,
                "C_r = {restitution}: apex {apex} m vs {expected} m ± 3 %"
            );
        }
    }
}

#[test]
fn a_ball_bounces_off_an_immovable_body_at_its_own_speed() {
    let mut w = world_with(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    });
    let wall = w
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(2.0, 0.0, 0.0)))
        .unwrap();
    w.insert_collider(
        ColliderDesc::cuboid(Vec3::new(0.5, 2.0, 2.0)).with_restitution(1.0),
        wall,
    )
    .unwrap();
    let ball = add_ball(
        &mut w,
        BodyDesc::dynamic().with_linear_velocity(Vec3::X * 5.0),
        0.25,
        1.0,
    );
    for _ in 0..60 {
        w.step(DT);
    }
    let v = body(&w, ball).linear_velocity().x;
    assert!(
        (v + 5.0).abs() < 0.05,
        "returns at {v} m/s, expected −5 ± 1 %"
    );
    assert_eq!(
        body(&w, wall).position(),
        Vec3::new(2.0, 0.0, 0.0),
        "the fixed body does not move, exactly"
    );
    assert_eq!(body(&w, wall).linear_velocity(), Vec3::ZERO);
}

/// A world without gravity holding one 1 kg body at `position` (inertia 0.01 kg·m² on every axis).
fn one_kg_without_gravity(position: Vec3) -> (PhysicsWorld, BodyHandle) {
    let mut w = world_with(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    });
    let mass = w
        .insert_body(BodyDesc::dynamic().with_position(position))
        .unwrap();
    let properties = MassProperties::new(1.0, Vec3::ZERO, Vec3::splat(0.01)).unwrap();
    w.set_body_mass_properties(mass, properties).unwrap();
    (w, mass)
}

/// A spring of rest length 1 m from the world origin (its anchor A) to a body's centre.
fn spring(model: SpringModel) -> Joint {
    Joint::new(Spring::new(1.0, model).unwrap())
}

#[test]
fn spring_oscillator_period() {
    let (mut w, mass) = one_kg_without_gravity(Vec3::new(1.2, 0.0, 0.0));
    // k = 100 N/m, no damping.
    w.insert_world_joint(
        spring(SpringModel::soft_stiffness(100.0, 0.0).unwrap()),
        mass,
    )
    .unwrap();
    let mut crossings = Vec::new();
    let mut previous = 0.2f32;
    for step in 0..600 {
        w.step(DT);
        let x = body(&w, mass).position().x - 1.0;
        if previous > 0.0 && x <= 0.0 {
            crossings.push((step as f32 + previous / (previous - x)) * DT);
        }
        previous = x;
    }
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f32;
    let expected = core::f32::consts::TAU * (1.0f32 / 100.0).sqrt();
    assert!(
        (period - expected).abs() < 0.01 * expected,
        "period {period} s vs {expected} s"
    );
}

/// Runs a 1 kg body on an undamped spring of stiffness k from a 0.1 m stretch and returns the largest
/// stretch seen in `steps` steps.
fn force_spring_peak(dt: f32, steps: usize, model: SpringModel) -> f32 {
    let (mut w, mass) = one_kg_without_gravity(Vec3::new(1.1, 0.0, 0.0));
    w.insert_world_joint(spring(model), mass).unwrap();
    let mut peak = 0.0f32;
    for _ in 0..steps {
        w.step(dt);
        let stretch = (body(&w, mass).position().length() - 1.0).abs();
        peak = peak.max(if stretch.is_finite() {
            stretch
        } else {
            f32::INFINITY
        });
    }
    peak
}

#[test]
fn the_explicit_spring_is_bounded_below_h_omega_2() {
    // h = dt / substeps; choose k so that h·ω = 1.9 with ω = √(k/m), m = 1 kg.
    let substeps = WorldSettings::default().substep_count as f32;
    let h = DT / substeps;
    let k = (1.9 / h).powi(2);
    let bounded = force_spring_peak(DT, 300, SpringModel::force(k, 0.0).unwrap());
    assert!(
        bounded < 1.0,
        "h·ω = 1.9 stays bounded, peak stretch {bounded} m from 0.1 m"
    );
}

/// `substeps` substeps of length `h` of the explicit spring on a body of mass 1 kg, `ω = √(k/m)`, from stretch
/// `x` (m) and velocity `v` (m/s): symplectic Euler of `ẍ = −ω²·x`, `v ← v − h·ω²·x` then `x ← x + h·v`.
fn explicit_spring_substeps(x: f64, v: f64, h: f64, omega: f64, substeps: u32) -> (f64, f64) {
    (0..substeps).fold((x, v), |(x, v), _| {
        let v = v - h * omega * omega * x;
        (x + h * v, v)
    })
}

#[test]
fn the_explicit_spring_above_h_omega_2_grows_by_its_amplification_factor_until_quarantined() {
    // The substep maps (x, v) by [[1 − (hω)², h], [−hω², 1]]: determinant 1, trace 2 − (hω)². Above hω = 2
    // the eigenvalues are real and negative, and the larger in magnitude,
    // |λ| = ((hω)² − 2 + √(((hω)² − 2)² − 4)) / 2, is the growth per substep: 1.877 at hω = 2.1, ×12.42 per
    // step of 4 substeps (the other eigenvalue, 1/|λ|, dies out within the first step).
    let substeps = WorldSettings::default().substep_count;
    let h = f64::from(DT) / f64::from(substeps);
    let h_omega = 2.1_f64;
    let omega = h_omega / h;
    let a = h_omega * h_omega - 2.0;
    let per_step = ((a + (a * a - 4.0).sqrt()) / 2.0).powi(substeps as i32);
    assert!((per_step - 12.42).abs() < 0.01, "{per_step}");
    // A 100 m spring from a 1 mm stretch: the body swings to 51 m beyond the rest length and 27 m short of it
    // within four steps, never past the anchor (where the spring's direction would turn), and its speed at
    // the end of the fourth, 1.9·10⁴ m/s, is past the quarantine's bound (10⁴ m/s by default).
    const REST: f32 = 100.0;
    let (mut w, mass) = one_kg_without_gravity(Vec3::new(REST + 1.0e-3, 0.0, 0.0));
    let model = SpringModel::force((omega * omega) as f32, 0.0).unwrap();
    w.insert_world_joint(Joint::new(Spring::new(REST, model).unwrap()), mass)
        .unwrap();
    let max_speed = f64::from(w.settings().limits.max_speed);
    let mut predicted = (f64::from(body(&w, mass).position().x - REST), 0.0);
    let mut previous = predicted.0;
    for step in 1..=10 {
        let before = body(&w, mass).position();
        let report = w.step(DT);
        predicted = explicit_spring_substeps(predicted.0, predicted.1, h, omega, substeps);
        if predicted.1.abs() > max_speed {
            // The first step whose closed-form end speed is past the bound: the body is taken out where the
            // step found it, at rest, after three steps that grew as predicted.
            let event = Event::BodyQuarantined {
                body: mass,
                reason: rebound::QuarantineReason::Speed,
            };
            assert!(
                report.quarantined_body_count == 1 && w.events().contains(&event),
                "step {step}: predicted speed {} m/s, {report:?}",
                predicted.1
            );
            assert_eq!(step, 4);
            assert_eq!(w.is_quarantined(mass), Some(true));
            assert_eq!(body(&w, mass).position(), before);
            assert_eq!(body(&w, mass).linear_velocity(), Vec3::ZERO);
            return;
        }
        assert_eq!(report.quarantined_body_count, 0, "step {step}");
        let stretch = f64::from(body(&w, mass).position().x - REST);
        assert!(
            (stretch - predicted.0).abs() <= 0.01 * predicted.0.abs(),
            "step {step}: stretch {stretch} m, closed form {} m",
            predicted.0
        );
        if step >= 2 {
            let growth = stretch / previous;
            assert!(
                (growth - per_step).abs() <= 0.01 * per_step,
                "step {step}: growth ×{growth}, |λ|⁴ = ×{per_step}"
            );
        }
        previous = stretch;
    }
    panic!("never quarantined");
}

#[test]
fn a_stiff_soft_spring_never_diverges_and_converges() {
    let (mut w, mass) = one_kg_without_gravity(Vec3::new(1.1, 0.0, 0.0));
    w.insert_world_joint(
        spring(SpringModel::soft_stiffness(1.0e7, 0.0).unwrap()),
        mass,
    )
    .unwrap();
    let mut error = f32::INFINITY;
    for _ in 0..120 {
        w.step(1.0 / 30.0);
        let e = (body(&w, mass).position().length() - 1.0).abs();
        assert!(e <= 0.1 + 1e-6, "the stiff spring overshot: error {e} m");
        error = e;
    }
    assert!(error < 1e-4, "length error converges to 0, got {error} m");
}

#[test]
fn rope_pendulum_period_and_length() {
    let mut w = world();
    let length = 2.0f32;
    let angle = 10f32.to_radians();
    let ball = w
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(
            length * angle.sin(),
            -length * angle.cos(),
            0.0,
        )))
        .unwrap();
    w.set_body_mass_properties(
        ball,
        MassProperties::new(1.0, Vec3::ZERO, Vec3::splat(0.004)).unwrap(),
    )
    .unwrap();
    w.insert_world_joint(Joint::new(Rope::new(length).unwrap()), ball)
        .unwrap();
    let mut crossings = Vec::new();
    let mut previous = body(&w, ball).position().x;
    for step in 0..900 {
        w.step(DT);
        let p = body(&w, ball).position();
        assert!(
            p.length() <= length * 1.005,
            "rope stretched to {} m",
            p.length()
        );
        if previous > 0.0 && p.x <= 0.0 {
            crossings.push((step as f32 + previous / (previous - p.x)) * DT);
        }
        previous = p.x;
    }
    let period = (crossings[crossings.len() - 1] - crossings[0]) / (crossings.len() - 1) as f32;
    let expected = core::f32::consts::TAU * (length / G).sqrt();
    assert!(
        (period - expected).abs() < 0.015 * expected,
        "period {period} s vs {expected} s"
    );
}

#[test]
fn a_slack_rope_applies_nothing() {
    let run = |with_rope: bool| {
        let mut w = world();
        let ball = w
            .insert_body(
                BodyDesc::dynamic()
                    .with_position(Vec3::new(0.0, -0.5, 0.0))
                    .with_linear_velocity(Vec3::new(0.3, 1.0, 0.0)),
            )
            .unwrap();
        if with_rope {
            w.insert_world_joint(Joint::new(Rope::new(2.0).unwrap()), ball)
                .unwrap();
        }
        let mut path = Vec::new();
        for _ in 0..20 {
            w.step(DT);
            path.push(body(&w, ball).position());
        }
        path
    };
    assert_eq!(
        run(true),
        run(false),
        "inside its length the rope leaves the ball in exact free fall"
    );
}

#[test]
fn a_stack_of_ten_boxes_stands() {
    let mut w = world();
    add_ground(&mut w, 0.6, 0.0);
    let boxes: Vec<_> = (0..10)
        .map(|i| {
            let b = w
                .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.5 + i as f32, 0.0)))
                .unwrap();
            w.insert_collider(
                ColliderDesc::cuboid(Vec3::splat(0.5))
                    .with_density(1.0)
                    .with_friction(0.6),
                b,
            )
            .unwrap();
            b
        })
        .collect();
    for _ in 0..600 {
        w.step(DT);
    }
    let top = body(&w, boxes[9]).position();
    assert!(
        Vec3::new(top.x, 0.0, top.z).length() < 0.02,
        "top box moved {top} sideways"
    );
    assert!((top.y - 9.5).abs() < 0.05, "top box at height {}", top.y);
}

/// A column of 20 unit boxes (1 kg each) on the ground, sleep off, 10 s. Its top box's drop and the largest
/// sideways drift of any box. `resting_overlap` as given: `None` leaves the contacts unpreloaded.
fn column_of_20(resting_overlap: Option<f32>) -> (f32, f32) {
    const COUNT: usize = 20;
    let settings = WorldSettings {
        sleep_enabled: false,
        resting_overlap,
        ..WorldSettings::default()
    };
    let mut w = world_with(settings);
    add_ground(&mut w, 0.6, 0.0);
    let boxes: Vec<_> = (0..COUNT)
        .map(|i| {
            let b = w
                .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 0.5 + i as f32, 0.0)))
                .unwrap();
            w.insert_collider(ColliderDesc::cuboid(Vec3::splat(0.5)).with_density(1.0), b)
                .unwrap();
            b
        })
        .collect();
    let mut worst_sideways = 0.0_f32;
    for _ in 0..600 {
        w.step(DT);
        for &b in &boxes {
            let p = body(&w, b).position();
            worst_sideways = worst_sideways.max(Vec3::new(p.x, 0.0, p.z).length());
        }
    }
    let drop = 0.5 + (COUNT - 1) as f32 - body(&w, boxes[COUNT - 1]).position().y;
    (drop, worst_sideways)
}

/// The column of 20 boxes without preloads. With soft contacts each interface is a spring of stiffness
/// `m_eff·ω²` (`m_eff` = 0.5 kg between two boxes at 30 Hz, 1 kg against the fixed ground at the static
/// 60 Hz), so the top box sinks by `Σₖ Wₖ / (m_eff·ω²)` where `Wₖ` is the weight above interface `k`. The
/// column must also stay upright: before contacts kept their lever arms (`LEVER_ARM_TOLERANCE`), a tilt fed
/// back through the re-derived Jacobians and this column fell over within 10 s. Preloaded (0.1 mm),
/// each interface overlaps `min(ε, Wₖ / (m_eff·ω²))` instead (`docs/physics.md`, "Contacts under load").
#[test]
fn a_column_of_20_boxes_stands_and_sinks_as_the_soft_contacts_predict() {
    const COUNT: usize = 20;
    let (hz, m) = (WorldSettings::default().contact_frequency_hz, 1.0_f32);
    let omega = core::f32::consts::TAU * hz;
    let between_boxes = |cap: f32| -> f32 {
        (1..COUNT)
            .map(|k| ((COUNT - k) as f32 * m * G / (0.5 * m * omega * omega)).min(cap))
            .sum()
    };
    let on_ground =
        |cap: f32| (COUNT as f32 * m * G / (m * (2.0 * omega) * (2.0 * omega))).min(cap);
    let (drop, worst_sideways) = column_of_20(None);
    assert!(
        worst_sideways < 0.03,
        "a box moved {worst_sideways} m sideways"
    );
    let expected = between_boxes(f32::INFINITY) + on_ground(f32::INFINITY);
    assert!(
        (drop - expected).abs() < 2e-3,
        "top box sank {drop} m, soft contacts predict {expected} m"
    );
    let epsilon = 1e-4;
    let (drop, worst_sideways) = column_of_20(Some(epsilon));
    assert!(
        worst_sideways < 0.01,
        "preloaded, a box moved {worst_sideways} m sideways"
    );
    let expected = between_boxes(epsilon) + on_ground(epsilon);
    assert!(
        (drop - expected).abs() < 0.1 * expected,
        "preloaded, the top box sank {drop} m, the preloaded contacts predict {expected} m ± 10 %"
    );
}

#[test]
fn a_box_sliding_at_5_m_s_stops_after_v_squared_over_2_mu_g() {
    let mut w = world();
    add_ground(&mut w, 0.5, 0.0);
    let b = w
        .insert_body(
            BodyDesc::dynamic()
                .with_position(Vec3::new(0.0, 0.5, 0.0))
                .with_linear_velocity(Vec3::X * 5.0),
        )
        .unwrap();
    w.insert_collider(
        ColliderDesc::cuboid(Vec3::splat(0.5))
            .with_density(1.0)
            .with_friction(0.5),
        b,
    )
    .unwrap();
    for _ in 0..180 {
        w.step(DT);
    }
    let expected = 25.0 / (2.0 * 0.5 * G);
    let x = body(&w, b).position().x;
    assert!(
        body(&w, b).linear_velocity().length() < 1e-2,
        "still sliding"
    );
    assert!(
        (x - expected).abs() < 0.03 * expected,
        "stopped after {x} m, expected {expected} m ± 3 %"
    );
}

/// Friction against twist: a cube resting on its face and spinning about the vertical. Its four corner
/// contacts each carry `m·g/4` and slide at `ω·d` (`d = h·√2`, half-extent `h`), so Coulomb friction brakes it
/// with the torque `μ·m·g·d` — what per-point friction gives and what the friction patch's twist row is limited
/// to (`docs/physics.md`, Contacts, "Friction"). With `I = (2/3)·m·h²` the spin slows at `α = 3·μ·g·d/(2·h²)`,
/// stops after turning `ω₀²/(2α)` and stays stopped; no net force moves the centre.
#[test]
fn a_cube_spinning_on_its_face_stops_after_turning_omega_squared_over_2_alpha() {
    const MU: f32 = 0.5;
    const HALF: f32 = 0.5;
    const SPIN: f32 = 5.0;
    let mut w = world();
    add_ground(&mut w, MU, 0.0);
    let b = w
        .insert_body(
            BodyDesc::dynamic()
                .with_position(Vec3::new(0.0, HALF, 0.0))
                .with_angular_velocity(Vec3::Y * SPIN),
        )
        .unwrap();
    w.insert_collider(
        ColliderDesc::cuboid(Vec3::splat(HALF))
            .with_density(1.0)
            .with_friction(MU),
        b,
    )
    .unwrap();
    let d = HALF * core::f32::consts::SQRT_2;
    let alpha = 3.0 * MU * G * d / (2.0 * HALF * HALF);
    // Halfway to the stop the spin has lost α·t.
    let half_time = SPIN / alpha / 2.0;
    let steps = (half_time / DT).round() as usize;
    for _ in 0..steps {
        w.step(DT);
    }
    let t = steps as f32 * DT;
    let omega = body(&w, b).angular_velocity().y;
    let expected = SPIN - alpha * t;
    assert!(
        (omega - expected).abs() < 0.03 * SPIN,
        "spin {omega} rad/s after {t} s, expected {expected} rad/s"
    );
    for _ in steps..60 {
        w.step(DT);
    }
    let (axis, angle) = body(&w, b).rotation().to_axis_angle();
    let turned = angle * axis.y.signum();
    let expected = SPIN * SPIN / (2.0 * alpha);
    assert!(
        (turned - expected).abs() < 0.03 * expected,
        "turned {turned} rad, expected {expected} rad ± 3 %"
    );
    assert!(
        body(&w, b).angular_velocity().length() < 1e-2,
        "still spinning at {}",
        body(&w, b).angular_velocity()
    );
    let p = body(&w, b).position();
    assert!(
        p.x.hypot(p.z) < 1e-3,
        "the centre moved to {p}: twist friction pushed it"
    );
}

#[test]
fn a_torque_free_spinning_box_conserves_angular_momentum() {
    let mut w = world_with(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    });
    let b = w
        .insert_body(
            BodyDesc::dynamic()
                .with_angular_velocity(Vec3::new(0.1, 5.0, 0.1))
                .with_can_sleep(false),
        )
        .unwrap();
    w.insert_collider(
        ColliderDesc::cuboid(Vec3::new(0.1, 0.5, 1.0)).with_density(500.0),
        b,
    )
    .unwrap();
    let l0 = body(&w, b).angular_momentum(body(&w, b).center_of_mass());
    let e0 = body(&w, b).kinetic_energy();
    for _ in 0..600 {
        w.step(DT);
        let x = body(&w, b);
        let l = x.angular_momentum(x.center_of_mass());
        assert!(
            (l - l0).length() < 0.01 * l0.length(),
            "angular momentum drifted to {l} from {l0}"
        );
        assert!(
            x.kinetic_energy() <= e0 * (1.0 + 1e-4),
            "kinetic energy grew"
        );
    }
}

#[test]
fn a_pyramid_of_base_20_stands_in_its_plane_for_10_s() {
    let mut w = world();
    add_ground(&mut w, 0.6, 0.0);
    let mut boxes = Vec::new();
    for row in 0..20 {
        for j in 0..(20 - row) {
            let p = Vec3::new(
                j as f32 - (20 - row - 1) as f32 / 2.0,
                0.5 + row as f32,
                0.0,
            );
            let b = w.insert_body(BodyDesc::dynamic().with_position(p)).unwrap();
            w.insert_collider(
                ColliderDesc::cuboid(Vec3::splat(0.5))
                    .with_density(1.0)
                    .with_friction(0.6),
                b,
            )
            .unwrap();
            boxes.push((b, p));
        }
    }
    let mut out_of_plane = 0.0f32;
    for _ in 0..600 {
        w.step(DT);
        for &(b, p0) in &boxes {
            out_of_plane = out_of_plane.max((body(&w, b).position().z - p0.z).abs());
        }
    }
    let (b, p0) = *boxes.last().unwrap();
    let moved = (body(&w, b).position() - p0).length();
    assert!(moved < 0.05, "the top box moved {moved} m");
    // The one-box-deep wall must not rock out of its plane: nothing pushes along z but rounding, and the
    // contacts' overlap correction must outpace the slow sway it starts. Measured 1.4 mm with the default
    // contact damping ratio 5, 5.3 mm with Box2D's 10 (`docs/physics.md`, "Contact damping ratio").
    assert!(
        out_of_plane < 0.003,
        "a box swayed {out_of_plane} m out of the pyramid's plane"
    );
}

#[test]
fn balls_on_a_height_field_stay_above_it() {
    let mut w = world();
    let (rows, cols) = (11usize, 11usize);
    let height = |x: f32, z: f32| 0.5 * (0.6 * x).sin() * (0.4 * z).cos();
    let heights: Vec<f32> = (0..rows * cols)
        .map(|i| height((i % cols) as f32 - 5.0, (i / cols) as f32 - 5.0))
        .collect();
    let ground = w.insert_body(BodyDesc::fixed()).unwrap();
    w.insert_collider(
        ColliderDesc::heightfield(rows, cols, heights, Vec3::new(10.0, 1.0, 10.0)),
        ground,
    )
    .unwrap();
    let balls: Vec<_> = (0..25)
        .map(|i| {
            add_ball(
                &mut w,
                BodyDesc::dynamic().with_position(Vec3::new(
                    (i % 5) as f32 * 1.6 - 3.2,
                    3.0 + (i / 5) as f32,
                    (i / 5) as f32 * 1.6 - 3.2,
                )),
                0.3,
                0.0,
            )
        })
        .collect();
    for _ in 0..300 {
        w.step(DT);
        for &b in &balls {
            let p = body(&w, b).position();
            if p.x.abs() < 4.5 && p.z.abs() < 4.5 {
                // The surface between samples is piecewise linear; compare with a bound on its deviation from
                // the smooth function (≤ 0.1 m with these samples) plus the ball radius less a 2 cm overlap.
                let below = height(p.x, p.z) + 0.3 - 0.1 - 0.02 - p.y;
                assert!(
                    below <= 0.0,
                    "a ball sank {below} m into the height field at {p}"
                );
            }
        }
    }
}

#[test]
fn a_100_m_s_ball_does_not_tunnel_through_a_10_cm_wall() {
    let mut w = world_with(WorldSettings {
        gravity: Vec3::ZERO,
        ..WorldSettings::default()
    });
    let wall = w
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(10.0, 0.0, 0.0)))
        .unwrap();
    w.insert_collider(ColliderDesc::cuboid(Vec3::new(0.05, 5.0, 5.0)), wall)
        .unwrap();
    let ball = add_ball(
        &mut w,
        BodyDesc::dynamic().with_linear_velocity(Vec3::X * 100.0),
        0.1,
        0.0,
    );
    for _ in 0..60 {
        w.step(DT);
        let x = body(&w, ball).position().x;
        assert!(
            x <= 10.0 - 0.05 - 0.1 + 0.01,
            "the ball passed into or through the wall: x = {x}"
        );
    }
}

#[test]
fn newtons_cradle_hands_the_momentum_to_the_last_ball() {
    let (radius, length, gap) = (0.1f32, 1.0f32, 0.001f32);
    let mut w = world();
    let mut balls = Vec::new();
    for i in 0..5 {
        let anchor = Vec3::new(i as f32 * (2.0 * radius + gap), 0.0, 0.0);
        let angle = if i == 0 { 30f32.to_radians() } else { 0.0 };
        let start = anchor + Vec3::new(-length * angle.sin(), -length * angle.cos(), 0.0);
        let b = add_ball(
            &mut w,
            BodyDesc::dynamic().with_position(start),
            radius,
            1.0,
        );
        let rope = Joint::new(Rope::new(length).unwrap())
            .with_local_anchors(anchor, Vec3::ZERO)
            .unwrap();
        w.insert_world_joint(rope, b).unwrap();
        balls.push(b);
    }
    let v = |w: &PhysicsWorld, i: usize| body(w, balls[i]).linear_velocity().x;
    let v0 = (2.0 * G * length * (1.0 - 30f32.to_radians().cos())).sqrt();
    let mut struck = false;
    for _ in 0..120 {
        let before = v(&w, 0);
        w.step(DT);
        if before > 0.5 * v0 && v(&w, 0) < 0.5 * before {
            struck = true;
            break;
        }
    }
    assert!(struck, "the first ball never struck the row");
    let total: f32 = (0..5).map(|i| v(&w, i)).sum();
    assert!(
        v(&w, 4) / total >= 0.9,
        "the last ball carries {:.1} %",
        100.0 * v(&w, 4) / total
    );
    assert!(
        (v(&w, 0) / total).abs() <= 0.1,
        "the first ball keeps {:.1} %",
        100.0 * v(&w, 0) / total
    );
}
