//! `ragdolls` (supplementary, not in the default list): ten 15-part ragdolls dropped onto a pile of 48 boxes.
//!
//! The ground of docs/scenes.md; a pile of 4 × 4 × 3 cubes of side 0.5 m (density 200) centred on the origin,
//! top at y = 1.5; ten ragdolls standing in two layers of five along x (x = −1.4 + 0.7·i, feet at y = 1.6 and
//! 3.6), each tipped about x by ±0.3 rad. A ragdoll is Rebound's `rebound::ragdoll` humanoid rebuilt here
//! part for part: the same 15 capsules (density 1000, friction 0.6) and 14 joints at the same pivots with
//! the same ranges — rapier `SphericalJoint`s for the neck, spine, shoulders, wrists, hips and ankles, with
//! the twist as the limit on `AngX` and the two swings as limits on `AngY` and `AngZ` about a frame turned to
//! the middle of each range (rapier limits each angle on its own, where Rebound limits the swing with an
//! elliptical cone), and `RevoluteJoint`s with limits for the elbows and knees. Contacts between jointed parts
//! are disabled. Impulse joints (not multibody), rapier's defaults otherwise.
//!
//! Metrics: `max_joint_gap_end` and `max_joint_gap_run` (the largest distance between a joint's two anchors at
//! the last step and over the run, m) and `lowest_part_y_run` (the lowest part centre over the run, m).

use rapier3d::math::{Pose, Rotation};
use rapier3d::prelude::*;

use super::{Scene, SceneOptions, add_ground};
use crate::metrics::Quality;
use crate::world::{GRAVITY, World};

/// The ragdolls in the scene.
pub const RAGDOLLS: usize = 10;

/// A capsule between two points of the standing pose (m, feet's midpoint at the origin) and its radius.
type Segment = (Vector, Vector, f32);

fn v(x: f32, y: f32, z: f32) -> Vector {
    Vector::new(x, y, z)
}

/// The 15 parts: pelvis, chest, head, left arm (upper, fore, hand), right arm, left leg (thigh, shin, foot),
/// right leg — Rebound's table.
fn segments() -> Vec<Segment> {
    let mut s = vec![
        (v(-0.18, 0.98, 0.0), v(0.18, 0.98, 0.0), 0.11),
        (v(0.0, 1.08, 0.0), v(0.0, 1.50, 0.0), 0.14),
        (v(0.0, 1.52, 0.0), v(0.0, 1.78, 0.0), 0.1),
    ];
    for side in [1.0f32, -1.0] {
        let x = 0.24 * side;
        s.push((v(x, 1.45, 0.0), v(x, 1.17, 0.0), 0.05));
        s.push((v(x, 1.17, 0.0), v(x, 0.92, 0.0), 0.045));
        s.push((v(x, 0.92, 0.0), v(x, 0.76, 0.0), 0.04));
    }
    for side in [1.0f32, -1.0] {
        let x = 0.09 * side;
        s.push((v(x, 0.92, 0.0), v(x, 0.50, 0.0), 0.07));
        s.push((v(x, 0.50, 0.0), v(x, 0.08, 0.0), 0.05));
        s.push((v(x, 0.04, -0.05), v(x, 0.04, 0.17), 0.04));
    }
    s
}

/// A joint: parent, child, pivot and kind, with ranges in degrees (Rebound's table and sign conventions).
enum Kind {
    /// Limb axis, flexion axis, (lower, upper) about the flexion axis, about `axis × flexion`, and the twist.
    Ball(Vector, Vector, (f32, f32), (f32, f32), (f32, f32)),
    /// Hinge axis and (lower, upper).
    Hinge(Vector, (f32, f32)),
}

/// A joint of the table: parent, child, pivot and kind.
type JointRow = (usize, usize, Vector, Kind);

/// The six joints of one side — shoulder, elbow, wrist, hip, knee, ankle — for `side` = +1 (the left, parts
/// 3–5 and 9–11) or −1 (the right, parts 6–8 and 12–14).
fn limb_joints(side: f32) -> [JointRow; 6] {
    let (down, forward, x) = (-Vector::Y, Vector::Z, Vector::X);
    // Abduction (outwards) is a negative swing on the left, a positive one on the right.
    let abduct = |out: f32, inward: f32| {
        if side > 0.0 {
            (-out, inward)
        } else {
            (-inward, out)
        }
    };
    let k = usize::from(side < 0.0);
    let (upper, fore, hand) = (3 + 3 * k, 4 + 3 * k, 5 + 3 * k);
    let (thigh, shin, foot) = (9 + 3 * k, 10 + 3 * k, 11 + 3 * k);
    let (xa, xl) = (0.24 * side, 0.09 * side);
    [
        (
            1,
            upper,
            v(xa, 1.45, 0.0),
            Kind::Ball(down, -x, (-60.0, 180.0), abduct(180.0, 45.0), (-70.0, 90.0)),
        ),
        (upper, fore, v(xa, 1.17, 0.0), Kind::Hinge(-x, (0.0, 150.0))),
        (
            fore,
            hand,
            v(xa, 0.92, 0.0),
            Kind::Ball(down, -x, (-25.0, 25.0), (-75.0, 75.0), (-80.0, 80.0)),
        ),
        (
            0,
            thigh,
            v(xl, 0.92, 0.0),
            Kind::Ball(down, -x, (-30.0, 120.0), abduct(45.0, 30.0), (-45.0, 45.0)),
        ),
        (thigh, shin, v(xl, 0.50, 0.0), Kind::Hinge(x, (0.0, 135.0))),
        (
            shin,
            foot,
            v(xl, 0.08, 0.0),
            Kind::Ball(forward, x, (-20.0, 50.0), (-20.0, 20.0), (-25.0, 25.0)),
        ),
    ]
}

/// The 14 joints in Rebound's order: spine, neck, then the left arm, the right arm, the left leg and the
/// right leg (shoulder, elbow, wrist; hip, knee, ankle).
fn joints() -> Vec<JointRow> {
    let (up, x) = (Vector::Y, Vector::X);
    let mut j = vec![
        (
            0,
            1,
            v(0.0, 1.08, 0.0),
            Kind::Ball(up, x, (-25.0, 80.0), (-35.0, 35.0), (-45.0, 45.0)),
        ),
        (
            1,
            2,
            v(0.0, 1.52, 0.0),
            Kind::Ball(up, x, (-45.0, 45.0), (-45.0, 45.0), (-70.0, 70.0)),
        ),
    ];
    let [left, right] = [1.0, -1.0].map(limb_joints);
    let ([ls, le, lw, lh, lk, la], [rs, re, rw, rh, rk, ra]) = (left, right);
    j.extend([ls, le, lw, rs, re, rw, lh, lk, la, rh, rk, ra]);
    j
}

/// The `ragdolls` scene.
pub struct Ragdolls {
    world: World,
    /// Every joint: its two bodies and its anchors in each body's frame.
    anchors: Vec<(RigidBodyHandle, RigidBodyHandle, Vector, Vector)>,
    /// Every ragdoll part.
    parts: Vec<RigidBodyHandle>,
    max_gap_run: f32,
    lowest_run: f32,
}

impl Ragdolls {
    /// Builds the scene.
    pub fn new(options: SceneOptions) -> Self {
        let mut world = World::new(GRAVITY);
        add_ground(&mut world);
        for layer in 0..3 {
            for i in 0..4 {
                for k in 0..4 {
                    let p = v(
                        -0.75 + 0.5 * i as f32,
                        0.25 + 0.5 * layer as f32,
                        -0.75 + 0.5 * k as f32,
                    );
                    let collider = ColliderBuilder::cuboid(0.25, 0.25, 0.25)
                        .density(200.0)
                        .build();
                    world.add_body(options.dynamic(p), Some(collider));
                }
            }
        }
        let mut scene = Self {
            world,
            anchors: Vec::new(),
            parts: Vec::new(),
            max_gap_run: 0.0,
            lowest_run: f32::INFINITY,
        };
        for r in 0..RAGDOLLS {
            let (i, layer) = (r % 5, r / 5);
            let tilt = if r % 2 == 0 { 0.3 } else { -0.3 };
            let origin = Pose::from_parts(
                v(-1.4 + 0.7 * i as f32, 1.6 + 2.0 * layer as f32, 0.0),
                Rotation::from_rotation_x(tilt),
            );
            scene.add_ragdoll(options, origin);
        }
        scene
    }

    fn add_ragdoll(&mut self, options: SceneOptions, origin: Pose) {
        let mut bodies = Vec::new();
        for (from, to, radius) in segments() {
            let along = to - from;
            let length = along.length();
            let half_height = (0.5 * length - radius).max(0.01);
            let centre = origin.transform_point(0.5 * (from + to));
            let body = options
                .dynamic(centre)
                .rotation(origin.rotation.to_scaled_axis());
            let collider = ColliderBuilder::capsule_y(half_height, radius)
                .position(Pose::from_rotation(Rotation::from_rotation_arc(
                    Vector::Y,
                    along / length,
                )))
                .density(1000.0)
                .friction(0.6)
                .build();
            bodies.push(self.world.add_body(body, Some(collider)));
        }
        let centres: Vec<Vector> = segments().iter().map(|(a, b, _)| 0.5 * (*a + *b)).collect();
        let rad = |d: f32| d.to_radians();
        for (parent, child, pivot, kind) in joints() {
            // Bodies are turned by `origin.rotation` alike, so joint frames in body coordinates are the
            // standing pose's, relative to each part's centre.
            let (anchor1, anchor2) = (pivot - centres[parent], pivot - centres[child]);
            let joint: GenericJoint = match kind {
                Kind::Ball(axis, flexion_axis, flexion, other, twist) => {
                    let other_axis = axis.cross(flexion_axis);
                    let rest =
                        Rotation::from_mat3(&Mat3::from_cols(axis, flexion_axis, other_axis));
                    let mid = |(a, b): (f32, f32)| rad(0.5 * (a + b));
                    let half = |(a, b): (f32, f32)| rad(0.5 * (b - a));
                    let centre = Rotation::from_axis_angle(other_axis, mid(other))
                        * Rotation::from_axis_angle(flexion_axis, mid(flexion))
                        * rest;
                    SphericalJointBuilder::new()
                        .local_frame1(Pose::from_parts(anchor1, centre.normalize()))
                        .local_frame2(Pose::from_parts(anchor2, rest.normalize()))
                        .limits(JointAxis::AngX, [rad(twist.0), rad(twist.1)])
                        .limits(JointAxis::AngY, [-half(flexion), half(flexion)])
                        .limits(JointAxis::AngZ, [-half(other), half(other)])
                        .contacts_enabled(false)
                        .build()
                        .into()
                }
                Kind::Hinge(axis, (lower, upper)) => RevoluteJointBuilder::new(axis)
                    .local_anchor1(anchor1)
                    .local_anchor2(anchor2)
                    .limits([rad(lower), rad(upper)])
                    .contacts_enabled(false)
                    .build()
                    .into(),
            };
            self.world.add_joint(bodies[parent], bodies[child], joint);
            self.anchors
                .push((bodies[parent], bodies[child], anchor1, anchor2));
        }
        self.parts.extend(bodies);
    }

    /// The largest distance between a joint's anchors now (m).
    fn max_gap(&self) -> f32 {
        self.anchors
            .iter()
            .map(|&(a, b, ra, rb)| {
                let pa = self.world.bodies[a].position().transform_point(ra);
                let pb = self.world.bodies[b].position().transform_point(rb);
                (pb - pa).length()
            })
            .fold(0.0, f32::max)
    }
}

impl Scene for Ragdolls {
    fn world(&self) -> &World {
        &self.world
    }

    fn world_mut(&mut self) -> &mut World {
        &mut self.world
    }

    fn observe(&mut self, _step: usize, _total: usize) {
        self.max_gap_run = self.max_gap_run.max(self.max_gap());
        for &p in &self.parts {
            self.lowest_run = self.lowest_run.min(self.world.pos(p).y);
        }
    }

    fn quality(&self) -> Quality {
        let mut q = Quality::new();
        q.num("max_joint_gap_end", self.max_gap())
            .num("max_joint_gap_run", self.max_gap_run)
            .num("lowest_part_y_run", self.lowest_run);
        q
    }
}

#[cfg(test)]
mod tests {
    use super::{RAGDOLLS, Ragdolls};
    use crate::scenes::{Scene, SceneOptions};

    #[test]
    fn ten_ragdolls_of_15_parts_and_48_boxes_start_with_their_joints_closed() {
        let scene = Ragdolls::new(SceneOptions::default());
        assert_eq!(scene.world().dynamic_body_count(), 48 + 15 * RAGDOLLS);
        assert_eq!(scene.world().joint_count(), 14 * RAGDOLLS);
        assert!(scene.max_gap() < 1e-5, "{}", scene.max_gap());
    }
}
