//! `springs`: 1,000 damped spring pairs in zero gravity (docs/scenes.md).
//!
//! Pairs on a 10 × 10 × 10 grid of 4 m spacing, pair centre `c = 4·(i, j, k)`, ball A at `c − (0.75, 0, 0)`
//! and ball B at `c + (0.75, 0, 0)` (initial length 1.5). Balls of radius 0.25 and mass 1 kg: the colliders
//! have density 0 and each body carries `MassProperties::new(1, 0, 0.025·(1, 1, 1))`, a solid 1 kg ball of
//! radius 0.25 (what rapier's `ColliderBuilder::mass(1.0)` gives). The spring is Rebound's implicit soft
//! spring (`SpringModel::Soft` with `SoftSpring::Stiffness`): rest length 1, k = 1e4 N/m, c = 10 N·s/m,
//! anchored at the centres. Undamped this oscillator has ω = √(k/μ) = 141 rad/s (period ≈ 2.7 steps) and
//! ζ = 0.07, so the quality mostly measures how much numerical damping the integrator adds.

use rebound::RigidBody;
use rebound::prelude::*;

use super::metrics::max_speed;
use super::{Scene, SceneOptions, Value, joint_error};

/// Pairs per side of the grid.
pub const GRID: usize = 10;
/// Grid spacing (m).
pub const SPACING: f32 = 4.0;
/// Half the initial length (m).
pub const HALF_LENGTH: f32 = 0.75;
/// Ball radius (m).
pub const RADIUS: f32 = 0.25;
/// Ball mass (kg).
pub const MASS: f32 = 1.0;
/// Spring rest length (m).
pub const REST: f32 = 1.0;
/// Spring stiffness (N/m).
pub const STIFFNESS: f32 = 1.0e4;
/// Spring damping (N·s/m).
pub const DAMPING: f32 = 10.0;
/// The energy threshold of `steps_to_E<1e-3E0`, relative to E0.
pub const ENERGY_THRESHOLD: f64 = 1.0e-3;

/// The `springs` scene.
#[derive(Debug)]
pub struct Springs {
    world: PhysicsWorld,
    /// Ball A and ball B of every pair.
    pairs: Vec<(BodyHandle, BodyHandle)>,
    /// Oscillator energy of the initial state (J; 1,250 J per pair).
    energy0: f64,
    /// Energy after step 10 (J).
    energy10: Option<f64>,
    /// First step after which the energy is below 1e-3·E0.
    steps_to_threshold: Option<usize>,
    /// Shortest spring seen over the run (m).
    min_len_run: f64,
}

impl Springs {
    /// Builds the scene.
    ///
    /// # Errors
    /// Whatever Rebound refuses while building (a bug).
    pub fn new(options: SceneOptions) -> Result<Self, Error> {
        let mut world = PhysicsWorld::new(options.settings(Vec3::ZERO))?;
        // A solid ball: I = 2/5·m·r².
        let inertia = 0.4 * MASS * RADIUS * RADIUS;
        let mass = MassProperties::new(MASS, Vec3::ZERO, Vec3::splat(inertia))?;
        let spring = Spring::new(
            REST,
            SpringModel::Soft(SoftSpring::stiffness(STIFFNESS, DAMPING).map_err(joint_error)?),
        )
        .map_err(joint_error)?;
        let mut pairs = Vec::with_capacity(GRID * GRID * GRID);
        for i in 0..GRID {
            for j in 0..GRID {
                for k in 0..GRID {
                    let c = SPACING * Vec3::new(i as f32, j as f32, k as f32);
                    let offset = Vec3::new(HALF_LENGTH, 0.0, 0.0);
                    let mut ball = |p| -> Result<BodyHandle, Error> {
                        let body =
                            world.insert_body(options.dynamic(p).with_mass_properties(mass))?;
                        world
                            .insert_collider(ColliderDesc::ball(RADIUS).with_density(0.0), body)?;
                        Ok(body)
                    };
                    let a = ball(c - offset)?;
                    let b = ball(c + offset)?;
                    world.insert_joint(Joint::new(spring), a, b)?;
                    pairs.push((a, b));
                }
            }
        }
        let mut scene = Self {
            world,
            pairs,
            energy0: 0.0,
            energy10: None,
            steps_to_threshold: None,
            min_len_run: f64::INFINITY,
        };
        scene.energy0 = scene.energy();
        scene.min_len_run = scene.lengths().fold(f64::INFINITY, f64::min);
        Ok(scene)
    }

    /// Ball A and ball B of every pair.
    #[must_use]
    pub fn pairs(&self) -> &[(BodyHandle, BodyHandle)] {
        &self.pairs
    }

    /// The bodies of a pair (`None` for stale handles, which the scene never holds).
    fn bodies(&self, (a, b): (BodyHandle, BodyHandle)) -> Option<(&RigidBody, &RigidBody)> {
        Some((self.world.body(a)?, self.world.body(b)?))
    }

    /// Length of every spring, centre to centre (m).
    pub fn lengths(&self) -> impl Iterator<Item = f64> + '_ {
        self.pairs.iter().map(|&pair| {
            self.bodies(pair).map_or(f64::NAN, |(a, b)| {
                f64::from(a.position().distance(b.position()))
            })
        })
    }

    /// Oscillator energy summed over the pairs (J): `½k(L − 1)² + ½μ|v_B − v_A|²`, μ the reduced mass (the
    /// pair's internal energy; its centre-of-mass motion is not part of the oscillator).
    #[must_use]
    pub fn energy(&self) -> f64 {
        self.pairs
            .iter()
            .map(|&pair| {
                self.bodies(pair).map_or(f64::NAN, |(a, b)| {
                    let len = f64::from(a.position().distance(b.position()));
                    // μ = m_a·m_b/(m_a + m_b) = 1/(1/m_a + 1/m_b).
                    let mu = 1.0 / f64::from(a.inv_mass() + b.inv_mass());
                    let dv = f64::from((b.linear_velocity() - a.linear_velocity()).length());
                    0.5 * f64::from(STIFFNESS) * (len - f64::from(REST)).powi(2)
                        + 0.5 * mu * dv * dv
                })
            })
            .sum()
    }

    /// The initial oscillator energy (J).
    #[must_use]
    pub fn initial_energy(&self) -> f64 {
        self.energy0
    }
}

impl Scene for Springs {
    fn world(&self) -> &PhysicsWorld {
        &self.world
    }

    fn world_mut(&mut self) -> &mut PhysicsWorld {
        &mut self.world
    }

    fn step(&mut self) -> StepReport {
        self.world.step(super::DT)
    }

    fn observe(&mut self, step: usize) {
        let energy = self.energy();
        if step == 10 {
            self.energy10 = Some(energy);
        }
        if self.steps_to_threshold.is_none() && energy < ENERGY_THRESHOLD * self.energy0 {
            self.steps_to_threshold = Some(step);
        }
        self.min_len_run = self.lengths().fold(self.min_len_run, f64::min);
    }

    /// `E10/E0` (energy after 10 steps over the initial energy; null if fewer steps ran),
    /// `steps_to_E<1e-3E0` (null if never reached), `min_len_run` (an undamped spring reaches 0.5), the end
    /// length errors `len_err_end_max` / `len_err_end_mean` (|L − 1| at the last step) and `max_speed_end`.
    fn quality(&self) -> Vec<(&'static str, Value)> {
        let errors: Vec<f64> = self
            .lengths()
            .map(|len| (len - f64::from(REST)).abs())
            .collect();
        let err_max = errors.iter().copied().fold(0.0, f64::max);
        let err_mean = errors.iter().sum::<f64>() / errors.len() as f64;
        vec![
            (
                "E10/E0",
                self.energy10
                    .map_or(Value::Missing, |e10| Value::f64(e10 / self.energy0)),
            ),
            (
                "steps_to_E<1e-3E0",
                self.steps_to_threshold.map_or(Value::Missing, Value::count),
            ),
            ("min_len_run", Value::f64(self.min_len_run)),
            ("len_err_end_max", Value::f64(err_max)),
            ("len_err_end_mean", Value::f64(err_mean)),
            ("max_speed_end", Value::f32(max_speed(&self.world))),
        ]
    }
}
