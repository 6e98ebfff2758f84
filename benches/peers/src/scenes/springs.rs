//! `springs`: 1,000 damped spring pairs in zero gravity.
//!
//! Pairs on a 10 × 10 × 10 grid of 4 m spacing, pair centre `c = 4·(i, j, k)`, ball A at `c − (0.75, 0, 0)`
//! and ball B at `c + (0.75, 0, 0)` (initial length 1.5). Balls of radius 0.25 and mass 1 kg
//! (`ColliderBuilder::mass(1.0)`), joined by `SpringJointBuilder::new(1.0, 1e4, 10.0)` (rest length 1, k = 1e4
//! N/m, c = 10 N·s/m: a force-based motor on the distance) anchored at the centres. Undamped this oscillator
//! has ω = √(k/μ) = 141 rad/s (period ≈ 2.7 steps) and ζ = 0.07, so the quality mostly measures how much
//! numerical damping the integrator adds.

use rapier3d::prelude::*;

use super::{Scene, SceneOptions};
use crate::metrics::{Quality, max_speed};
use crate::world::World;

/// Pairs per side of the grid.
const GRID: usize = 10;
/// Grid spacing.
const SPACING: f32 = 4.0;
/// Half the initial length.
const HALF_LENGTH: f32 = 0.75;
/// Ball radius.
const RADIUS: f32 = 0.25;
/// Ball mass.
const MASS: f32 = 1.0;
/// Spring rest length.
const REST: f32 = 1.0;
/// Spring stiffness.
const STIFFNESS: f32 = 1.0e4;
/// Spring damping.
const DAMPING: f32 = 10.0;
/// The energy threshold of `steps_to_E<1e-3E0`, relative to E0.
const ENERGY_THRESHOLD: f64 = 1.0e-3;

/// The `springs` scene.
pub struct Springs {
    world: World,
    /// Ball A and ball B of every pair.
    pairs: Vec<(RigidBodyHandle, RigidBodyHandle)>,
    /// Oscillator energy of the initial state (1,250 J per pair).
    energy0: f64,
    /// Energy after step 10.
    energy10: Option<f64>,
    /// First step after which the energy is below 1e-3·E0.
    steps_to_threshold: Option<usize>,
    /// Smallest spring length seen over the run.
    min_len_run: f64,
}

impl Springs {
    /// Builds the scene.
    pub fn new(options: SceneOptions) -> Self {
        let mut world = World::new(Vector::ZERO);
        let mut pairs = Vec::with_capacity(GRID * GRID * GRID);
        for i in 0..GRID {
            for j in 0..GRID {
                for k in 0..GRID {
                    let c = SPACING * Vector::new(i as f32, j as f32, k as f32);
                    let offset = Vector::new(HALF_LENGTH, 0.0, 0.0);
                    let ball = || Some(ColliderBuilder::ball(RADIUS).mass(MASS).build());
                    let a = world.add_body(options.dynamic(c - offset), ball());
                    let b = world.add_body(options.dynamic(c + offset), ball());
                    world.add_joint(a, b, SpringJointBuilder::new(REST, STIFFNESS, DAMPING));
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
        scene
    }

    /// Length of every spring (centre to centre).
    fn lengths(&self) -> impl Iterator<Item = f64> + '_ {
        self.pairs
            .iter()
            .map(|&(a, b)| f64::from(self.world.pos(a).distance(self.world.pos(b))))
    }

    /// Oscillator energy summed over the pairs: `½k(L − 1)² + ½μ|v_B − v_A|²`, μ the reduced mass (the
    /// pair's internal energy; its centre-of-mass motion is not part of the oscillator).
    fn energy(&self) -> f64 {
        self.pairs
            .iter()
            .map(|&(a, b)| {
                let (ba, bb) = (&self.world.bodies[a], &self.world.bodies[b]);
                let len = f64::from(ba.translation().distance(bb.translation()));
                let (ma, mb) = (f64::from(ba.mass()), f64::from(bb.mass()));
                let mu = ma * mb / (ma + mb);
                let dv = f64::from((bb.linvel() - ba.linvel()).length());
                0.5 * f64::from(STIFFNESS) * (len - f64::from(REST)).powi(2) + 0.5 * mu * dv * dv
            })
            .sum()
    }
}

impl Scene for Springs {
    fn world(&self) -> &World {
        &self.world
    }

    fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    fn observe(&mut self, step: usize, _total: usize) {
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
    fn quality(&self) -> Quality {
        let errors: Vec<f64> = self
            .lengths()
            .map(|len| (len - f64::from(REST)).abs())
            .collect();
        let err_max = errors.iter().copied().fold(0.0, f64::max);
        let err_mean = errors.iter().sum::<f64>() / errors.len() as f64;
        let mut q = Quality::new();
        match self.energy10 {
            Some(e10) => q.num("E10/E0", e10 / self.energy0),
            None => q.optional_count("E10/E0", None),
        };
        q.optional_count("steps_to_E<1e-3E0", self.steps_to_threshold)
            .num("min_len_run", self.min_len_run)
            .num("len_err_end_max", err_max)
            .num("len_err_end_mean", err_mean)
            .num("max_speed_end", max_speed(&self.world));
        q
    }
}

#[cfg(test)]
mod tests {
    use super::Springs;
    use crate::scenes::{Scene, SceneOptions};

    #[test]
    fn initial_energy_is_1250_joules_per_pair() {
        let scene = Springs::new(SceneOptions::default());
        assert_eq!(scene.world().dynamic_body_count(), 2000);
        assert_eq!(scene.world().joint_count(), 1000);
        assert!((scene.energy0 - 1000.0 * 1250.0).abs() < 1e-3 * scene.energy0);
        assert!((scene.min_len_run - 1.5).abs() < 1e-5);
    }
}
