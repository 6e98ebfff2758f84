//! `bridge`: a slack rope bridge of 100 planks between two fixed anchors, with 50 balls dropped on it
//! (docs/scenes.md).
//!
//! No ground. Planks are cuboids of half-extents 0.25 × 0.1 × 1.0 (density 1): 0.5 m long along x, 2 m wide
//! along z, a 50 m deck. The two fixed anchors (no colliders) are 47.5 m apart (95 % of the deck) at y0 = 10.
//!
//! The planks start as the chords of the circular arc through both anchors, so every joint starts exactly
//! satisfied: R solves `2R·sin(100·asin(0.25/R)) = 47.5` (bisection, R ≈ 45.30), θ = 2·asin(0.25/R) per plank,
//! half-angle h = 50θ, arc centre `(0, y0 + R·cos h, 0)`, the point at angle φ is
//! `centre + (R sin φ, −R cos φ, 0)`. Plank `i` spans φ = −h + iθ to −h + (i + 1)θ, centred at the chord's
//! midpoint and rotated about z by −h + (i + ½)θ.
//!
//! Hinges about z, anchored at the plank ends (±0.25, 0, 0) and at the anchors' origins, chain left anchor →
//! plank 0 → … → plank 99 → right anchor (101 joints), with contacts between jointed bodies disabled.
//!
//! Ball `k` in `0..50` (radius 0.25, density 1): `x = −23.75 + 2 + k·43.5/49 + U(−0.2, 0.2)`,
//! `z = U(−0.3, 0.3)` (x draw then z draw, generator seeded `0x5EED_B41D_6E00_0001`),
//! `y = deck(x) + 0.1 + 0.25 + 0.2 + (k mod 5)·0.3` with `deck(x) = centre.y − √(R² − x²)`.
//!
//! The geometry is computed in f32, in the order the formulas are written, exactly as the rapier side does
//! (`benches/peers/src/scenes/bridge.rs`): where the balls end up is chaotic (a 1 µm shift moves
//! `balls_on_bridge` between 3 and 6 in rapier), so the two engines must start from the same bits.

use std::collections::VecDeque;

use rebound::prelude::*;

use super::metrics::max_joint_separation;
use super::{Scene, SceneOptions, Value, joint_error};
use crate::XorShift64Star;

/// Number of planks.
pub const PLANKS: usize = 100;
/// Plank half-extents (m).
pub const PLANK_HALF: [f32; 3] = [0.25, 0.1, 1.0];
/// Distance between the anchors (m).
pub const SPAN: f32 = 47.5;
/// Anchor height (m).
pub const Y0: f32 = 10.0;
/// Number of balls.
pub const BALLS: usize = 50;
/// Ball radius (m).
pub const BALL_RADIUS: f32 = 0.25;
/// Generator seed.
pub const SEED: u64 = 0x5EED_B41D_6E00_0001;
/// A ball counts as on the bridge while it is no more than this far (m) below the lowest plank.
pub const ON_BRIDGE_BELOW: f32 = 2.0;
/// Number of final steps `sag_mean_last60` averages over.
pub const LAST_STEPS: usize = 60;

/// The circular arc the planks start on.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Arc {
    /// Radius (m).
    pub radius: f32,
    /// Angle subtended by one plank (rad).
    pub theta: f32,
    /// Half the angle of the whole deck, 50θ (rad).
    pub half_angle: f32,
    /// Height of the arc's centre (m).
    pub centre_y: f32,
}

impl Arc {
    /// Solves `2R·sin(100·asin(0.25/R)) = 47.5` for R by bisection (200 halvings of [20, 1000], far more than
    /// f32 needs: the bracket stops shrinking at adjacent floats).
    #[must_use]
    pub fn solve() -> Self {
        let half_plank = PLANK_HALF[0];
        let planks = PLANKS as f32;
        let chord = |r: f32| 2.0 * r * (planks * (half_plank / r).asin()).sin() - SPAN;
        // chord(20) < 0 < chord(1000), and the chord length grows with R on that interval.
        let (mut lo, mut hi) = (20.0_f32, 1000.0_f32);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if chord(mid) < 0.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        let radius = 0.5 * (lo + hi);
        let theta = 2.0 * (half_plank / radius).asin();
        let half_angle = 0.5 * planks * theta;
        Self {
            radius,
            theta,
            half_angle,
            centre_y: Y0 + radius * half_angle.cos(),
        }
    }

    /// The point of the arc at angle φ (rad; φ = 0 is the bottom).
    #[must_use]
    pub fn point(&self, phi: f32) -> Vec3 {
        Vec3::new(
            self.radius * phi.sin(),
            self.centre_y - self.radius * phi.cos(),
            0.0,
        )
    }

    /// Height of the arc above `x` (its lower half): `centre.y − √(R² − x²)`.
    #[must_use]
    pub fn deck(&self, x: f32) -> f32 {
        self.centre_y - (self.radius * self.radius - x * x).sqrt()
    }
}

/// The `bridge` scene.
#[derive(Debug)]
pub struct Bridge {
    world: PhysicsWorld,
    planks: Vec<BodyHandle>,
    balls: Vec<BodyHandle>,
    joints: Vec<JointHandle>,
    /// Sag of the initial pose (m).
    sag0: f32,
    /// Largest joint separation over the run (m).
    max_sep_run: f32,
    /// The sag after each of the last (up to) 60 steps (m).
    sag_tail: VecDeque<f32>,
}

impl Bridge {
    /// Builds the scene.
    ///
    /// # Errors
    /// Whatever Rebound refuses while building (a bug).
    pub fn new(options: SceneOptions) -> Result<Self, Error> {
        let arc = Arc::solve();
        let mut world = PhysicsWorld::new(options.settings(Vec3::new(0.0, -9.81, 0.0)))?;
        let half_span = 0.5 * SPAN;
        let anchor_left =
            world.insert_body(BodyDesc::fixed().with_position(Vec3::new(-half_span, Y0, 0.0)))?;
        let anchor_right =
            world.insert_body(BodyDesc::fixed().with_position(Vec3::new(half_span, Y0, 0.0)))?;

        let mut planks = Vec::with_capacity(PLANKS);
        for i in 0..PLANKS {
            let a = arc.point(-arc.half_angle + i as f32 * arc.theta);
            let b = arc.point(-arc.half_angle + (i + 1) as f32 * arc.theta);
            let angle = -arc.half_angle + (i as f32 + 0.5) * arc.theta;
            let body = options
                .dynamic((a + b) * 0.5)
                .with_rotation(Quat::from_rotation_z(angle));
            let plank = world.insert_body(body)?;
            let [hx, hy, hz] = PLANK_HALF;
            world.insert_collider(
                ColliderDesc::cuboid(Vec3::new(hx, hy, hz)).with_density(1.0),
                plank,
            )?;
            planks.push(plank);
        }

        let end = Vec3::new(PLANK_HALF[0], 0.0, 0.0);
        let mut joints = Vec::with_capacity(PLANKS + 1);
        let mut hinge = |world: &mut PhysicsWorld,
                         a: BodyHandle,
                         b: BodyHandle,
                         anchor_a: Vec3,
                         anchor_b: Vec3|
         -> Result<(), Error> {
            let joint = Joint::new(HingeJoint::new())
                .with_local_anchors(anchor_a, anchor_b)
                .and_then(|j| j.with_local_axes(Vec3::Z, Vec3::Z))
                .map_err(joint_error)?;
            let handle = world.insert_joint(joint, a, b)?;
            world.set_joint_contacts_enabled(handle, false)?;
            joints.push(handle);
            Ok(())
        };
        hinge(&mut world, anchor_left, planks[0], Vec3::ZERO, -end)?;
        for pair in planks.windows(2) {
            hinge(&mut world, pair[0], pair[1], end, -end)?;
        }
        hinge(
            &mut world,
            planks[PLANKS - 1],
            anchor_right,
            end,
            Vec3::ZERO,
        )?;

        let mut rng = XorShift64Star::new(SEED);
        let mut balls = Vec::with_capacity(BALLS);
        for k in 0..BALLS {
            let x = -half_span + 2.0 + k as f32 * 43.5 / 49.0 + rng.uniform(-0.2, 0.2);
            let z = rng.uniform(-0.3, 0.3);
            let y = arc.deck(x) + PLANK_HALF[1] + BALL_RADIUS + 0.2 + (k % 5) as f32 * 0.3;
            let ball = world.insert_body(options.dynamic(Vec3::new(x, y, z)))?;
            world.insert_collider(ColliderDesc::ball(BALL_RADIUS).with_density(1.0), ball)?;
            balls.push(ball);
        }

        let mut scene = Self {
            world,
            planks,
            balls,
            joints,
            sag0: 0.0,
            max_sep_run: 0.0,
            sag_tail: VecDeque::with_capacity(LAST_STEPS),
        };
        scene.sag0 = scene.sag();
        Ok(scene)
    }

    /// The planks, left to right.
    #[must_use]
    pub fn planks(&self) -> &[BodyHandle] {
        &self.planks
    }

    /// The balls, in construction order.
    #[must_use]
    pub fn balls(&self) -> &[BodyHandle] {
        &self.balls
    }

    /// The 101 hinges, left to right.
    #[must_use]
    pub fn joints(&self) -> &[JointHandle] {
        &self.joints
    }

    /// The largest distance between a hinge's two world anchor points now (m).
    #[must_use]
    pub fn max_joint_separation(&self) -> f32 {
        max_joint_separation(&self.world, &self.joints)
    }

    /// The initial sag (m).
    #[must_use]
    pub fn initial_sag(&self) -> f32 {
        self.sag0
    }

    /// Height of the lowest plank centre (m).
    fn lowest_plank_y(&self) -> f32 {
        self.planks
            .iter()
            .map(|&h| self.world.body(h).map_or(f32::NAN, |b| b.position().y))
            .fold(f32::INFINITY, f32::min)
    }

    /// Anchor height minus the lowest plank centre (m).
    fn sag(&self) -> f32 {
        Y0 - self.lowest_plank_y()
    }
}

impl Scene for Bridge {
    fn world(&self) -> &PhysicsWorld {
        &self.world
    }

    fn world_mut(&mut self) -> &mut PhysicsWorld {
        &mut self.world
    }

    fn step(&mut self) -> StepReport {
        self.world.step(super::DT)
    }

    fn observe(&mut self, _step: usize) {
        self.max_sep_run = self.max_sep_run.max(self.max_joint_separation());
        if self.sag_tail.len() == LAST_STEPS {
            self.sag_tail.pop_front();
        }
        self.sag_tail.push_back(self.sag());
    }

    /// `sag0` (initial sag), `sag_end`, `sag_mean_last60` (sag = anchor height minus the lowest plank
    /// centre), `max_joint_sep_end` / `max_joint_sep_run` (largest distance between a joint's two world anchor
    /// points, at the end / over the run) and `balls_on_bridge` (balls no more than 2 m below the lowest
    /// plank at the end).
    fn quality(&self) -> Vec<(&'static str, Value)> {
        let lowest = self.lowest_plank_y();
        let on_bridge = self
            .balls
            .iter()
            .filter_map(|&h| self.world.body(h))
            .filter(|b| b.position().y >= lowest - ON_BRIDGE_BELOW)
            .count();
        let sag_mean = if self.sag_tail.is_empty() {
            f64::NAN
        } else {
            self.sag_tail.iter().copied().map(f64::from).sum::<f64>() / self.sag_tail.len() as f64
        };
        vec![
            ("sag0", Value::f32(self.sag0)),
            ("sag_end", Value::f32(self.sag())),
            ("sag_mean_last60", Value::f64(sag_mean)),
            ("max_joint_sep_end", Value::f32(self.max_joint_separation())),
            ("max_joint_sep_run", Value::f32(self.max_sep_run)),
            ("balls_on_bridge", Value::count(on_bridge)),
        ]
    }
}
