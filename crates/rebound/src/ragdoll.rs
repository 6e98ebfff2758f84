//! A ragdoll: a 15-part humanoid of capsules joined by swing–twist ball joints at the neck, spine,
//! shoulders, wrists, hips and ankles and by hinges at the elbows and knees, each limited to a human range of
//! motion. Built into a [`PhysicsWorld`] by [`Ragdoll::build`]; measured by [`Ragdoll::worst_joint_gap`]
//! and [`Ragdoll::worst_limit_excess`].
//!
//! # Ranges of motion
//!
//! The limits are the average active ranges of healthy adults as the American Academy of Orthopaedic
//! Surgeons tabulates them (*Joint Motion: Method of Measuring and Recording*, AAOS 1965; the same table in
//! Norkin & White, *Measurement of Joint Motion: A Guide to Goniometry*, appendix A), in degrees:
//!
//! | joint | swing about the flexion axis | swing about the other axis | twist |
//! |---|---|---|---|
//! | neck | flexion 45, extension 45 | lateral bend 45 each way | rotation 70 each way |
//! | spine (thoracolumbar) | flexion 80, extension 25 | lateral bend 35 each way | rotation 45 each way |
//! | shoulder | flexion 180, extension 60 | abduction 180, adduction 45 | internal 70, external 90 |
//! | elbow (hinge) | flexion 0 … 150 | | |
//! | wrist | radial 20, ulnar 30 (as ±25) | flexion 80, extension 70 (as ±75) | pronation/supination 80 each way |
//! | hip | flexion 120, extension 30 | abduction 45, adduction 30 | internal 45, external 45 |
//! | knee (hinge) | flexion 0 … 135 | | |
//! | ankle | dorsiflexion 20, plantarflexion 50 | abduction/adduction 20 each way | inversion/eversion 25 each way |
//!
//! A swing–twist cone is symmetric about its axis, so each cone is centred on the middle of its range (the
//! parent's joint frame is turned by the offset, [`SwingTwistLimits`]) with half-angles of half the range;
//! the corners of the ellipse are rounder than a real shoulder's.
//!
//! The humanoid stands 1.78 m tall at scale 1, facing +z with its left side towards +x, and weighs about
//! 73 kg at the default density of 1,000 kg/m³.

use crate::{ColliderDesc, Error, PhysicsWorld};
use core::f32::consts::PI;
use rebound_constraints::part::SwingTwist;
use rebound_constraints::{
    BallJoint, HingeJoint, Joint, JointKind, SwingTwistLimits, basis_from_axis, twist_angle,
};
use rebound_dynamics::BodyDesc;
use rebound_math::{Mat3, Pose, Quat, Vec2, Vec3};
use rebound_world::{BodyHandle, JointHandle};

/// Where and how to build a ragdoll.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RagdollDesc {
    /// The point on the ground between the feet (m). Default: the origin.
    pub position: Vec3,
    /// The whole body's orientation. Default: identity (facing +z, standing up +y).
    pub rotation: Quat,
    /// Every part's initial linear velocity (m/s). Default: 0.
    pub linear_velocity: Vec3,
    /// Density of the capsules (kg/m³). Default: 1,000.
    pub density: f32,
    /// Friction coefficient of the capsules (dimensionless). Default: 0.6.
    pub friction: f32,
}

impl Default for RagdollDesc {
    fn default() -> Self {
        Self {
            position: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            linear_velocity: Vec3::ZERO,
            density: 1000.0,
            friction: 0.6,
        }
    }
}

/// The parts of a ragdoll, in [`Ragdoll::parts`] order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Part {
    /// The pelvis (the root).
    Pelvis,
    /// The chest.
    Chest,
    /// The head.
    Head,
    /// The left upper arm.
    LeftUpperArm,
    /// The left forearm.
    LeftForearm,
    /// The left hand.
    LeftHand,
    /// The right upper arm.
    RightUpperArm,
    /// The right forearm.
    RightForearm,
    /// The right hand.
    RightHand,
    /// The left thigh.
    LeftThigh,
    /// The left shin.
    LeftShin,
    /// The left foot.
    LeftFoot,
    /// The right thigh.
    RightThigh,
    /// The right shin.
    RightShin,
    /// The right foot.
    RightFoot,
}

/// The number of parts.
pub const PART_COUNT: usize = 15;
/// The number of joints.
pub const JOINT_COUNT: usize = 14;

/// A capsule between two points of the standing pose (m, at scale 1, the feet's midpoint at the origin).
struct Segment {
    from: Vec3,
    to: Vec3,
    radius: f32,
}

/// The parts' capsules, in [`Part`] order; `side` = +1 for the left, −1 for the right.
fn segments() -> [Segment; PART_COUNT] {
    let seg = |from: Vec3, to: Vec3, radius: f32| Segment { from, to, radius };
    let arm = |side: f32| {
        let x = 0.24 * side;
        [
            seg(Vec3::new(x, 1.45, 0.0), Vec3::new(x, 1.17, 0.0), 0.05),
            seg(Vec3::new(x, 1.17, 0.0), Vec3::new(x, 0.92, 0.0), 0.045),
            seg(Vec3::new(x, 0.92, 0.0), Vec3::new(x, 0.76, 0.0), 0.04),
        ]
    };
    let leg = |side: f32| {
        let x = 0.09 * side;
        [
            seg(Vec3::new(x, 0.92, 0.0), Vec3::new(x, 0.50, 0.0), 0.07),
            seg(Vec3::new(x, 0.50, 0.0), Vec3::new(x, 0.08, 0.0), 0.05),
            seg(Vec3::new(x, 0.04, -0.05), Vec3::new(x, 0.04, 0.17), 0.04),
        ]
    };
    let [lu, lf, lh] = arm(1.0);
    let [ru, rf, rh] = arm(-1.0);
    let [lt, ls, lfo] = leg(1.0);
    let [rt, rs, rfo] = leg(-1.0);
    [
        seg(
            Vec3::new(-0.18, 0.98, 0.0),
            Vec3::new(0.18, 0.98, 0.0),
            0.11,
        ),
        seg(Vec3::new(0.0, 1.08, 0.0), Vec3::new(0.0, 1.50, 0.0), 0.14),
        seg(Vec3::new(0.0, 1.52, 0.0), Vec3::new(0.0, 1.78, 0.0), 0.1),
        lu,
        lf,
        lh,
        ru,
        rf,
        rh,
        lt,
        ls,
        lfo,
        rt,
        rs,
        rfo,
    ]
}

/// One joint of the standing pose: parent and child part indices, the pivot (m), and its kind.
struct JointSpec {
    parent: usize,
    child: usize,
    pivot: Vec3,
    kind: Spec,
}

/// A joint's kind and range (degrees, see the module docs).
enum Spec {
    /// A swing–twist ball joint: `axis` along the child (world, standing pose), `flexion_axis` the swing
    /// axis of the first range, the ranges (lower, upper) about it and about `axis × flexion_axis`, and the
    /// twist range.
    Ball {
        axis: Vec3,
        flexion_axis: Vec3,
        flexion: (f32, f32),
        other: (f32, f32),
        twist: (f32, f32),
    },
    /// A hinge about `axis` (world) with the range (lower, upper).
    Hinge { axis: Vec3, range: (f32, f32) },
}

fn joint_specs() -> [JointSpec; JOINT_COUNT] {
    use Part::*;
    let (down, up, forward) = (-Vec3::Y, Vec3::Y, Vec3::Z);
    let ball = |axis, flexion_axis, flexion, other, twist| Spec::Ball {
        axis,
        flexion_axis,
        flexion,
        other,
        twist,
    };
    // Swings are positive by the right-hand rule about the flexion axis and about `axis × flexion_axis`.
    // For a limb hanging down with flexion axis −x, a positive swing is forward (flexion); the other axis is
    // `−y × −x = −z`, about which a positive swing moves the limb towards −x (the right).
    let side_joints = |side: f32, arm: [Part; 3], leg: [Part; 3]| {
        let (x_arm, x_leg) = (0.24 * side, 0.09 * side);
        // Abduction (outwards) is a negative swing on the left, a positive one on the right.
        let abduct = |out: f32, inward: f32| {
            if side > 0.0 {
                (-out, inward)
            } else {
                (-inward, out)
            }
        };
        [
            JointSpec {
                parent: Chest as usize,
                child: arm[0] as usize,
                pivot: Vec3::new(x_arm, 1.45, 0.0),
                kind: ball(
                    down,
                    -Vec3::X,
                    (-60.0, 180.0),
                    abduct(180.0, 45.0),
                    (-70.0, 90.0),
                ),
            },
            JointSpec {
                parent: arm[0] as usize,
                child: arm[1] as usize,
                pivot: Vec3::new(x_arm, 1.17, 0.0),
                kind: Spec::Hinge {
                    axis: -Vec3::X,
                    range: (0.0, 150.0),
                },
            },
            JointSpec {
                parent: arm[1] as usize,
                child: arm[2] as usize,
                pivot: Vec3::new(x_arm, 0.92, 0.0),
                kind: ball(down, -Vec3::X, (-25.0, 25.0), (-75.0, 75.0), (-80.0, 80.0)),
            },
            JointSpec {
                parent: Pelvis as usize,
                child: leg[0] as usize,
                pivot: Vec3::new(x_leg, 0.92, 0.0),
                kind: ball(
                    down,
                    -Vec3::X,
                    (-30.0, 120.0),
                    abduct(45.0, 30.0),
                    (-45.0, 45.0),
                ),
            },
            JointSpec {
                parent: leg[0] as usize,
                child: leg[1] as usize,
                pivot: Vec3::new(x_leg, 0.50, 0.0),
                kind: Spec::Hinge {
                    axis: Vec3::X,
                    range: (0.0, 135.0),
                },
            },
            JointSpec {
                parent: leg[1] as usize,
                child: leg[2] as usize,
                pivot: Vec3::new(x_leg, 0.08, 0.0),
                // Toes down (plantarflexion) is a positive swing about +x for a foot along +z.
                kind: ball(
                    forward,
                    Vec3::X,
                    (-20.0, 50.0),
                    (-20.0, 20.0),
                    (-25.0, 25.0),
                ),
            },
        ]
    };
    let [sl, el, wl, hl, kl, al] = side_joints(
        1.0,
        [LeftUpperArm, LeftForearm, LeftHand],
        [LeftThigh, LeftShin, LeftFoot],
    );
    let [sr, er, wr, hr, kr, ar] = side_joints(
        -1.0,
        [RightUpperArm, RightForearm, RightHand],
        [RightThigh, RightShin, RightFoot],
    );
    [
        JointSpec {
            parent: Pelvis as usize,
            child: Chest as usize,
            pivot: Vec3::new(0.0, 1.08, 0.0),
            // For the chest (up), flexion (forward) is a positive swing about +x.
            kind: ball(up, Vec3::X, (-25.0, 80.0), (-35.0, 35.0), (-45.0, 45.0)),
        },
        JointSpec {
            parent: Chest as usize,
            child: Head as usize,
            pivot: Vec3::new(0.0, 1.52, 0.0),
            kind: ball(up, Vec3::X, (-45.0, 45.0), (-45.0, 45.0), (-70.0, 70.0)),
        },
        sl,
        el,
        wl,
        sr,
        er,
        wr,
        hl,
        kl,
        al,
        hr,
        kr,
        ar,
    ]
}

/// A ragdoll built in a world: its bodies in [`Part`] order and its joints.
#[derive(Debug, Clone, PartialEq)]
pub struct Ragdoll {
    /// The parts' bodies, in [`Part`] order.
    pub parts: [BodyHandle; PART_COUNT],
    /// The joints: spine, neck, then for the left and the right arm shoulder, elbow, wrist, then for the
    /// left and the right leg hip, knee, ankle.
    pub joints: [JointHandle; JOINT_COUNT],
}

impl Ragdoll {
    /// Builds a ragdoll into `world` as `desc` says: 15 dynamic capsule bodies and 14 limited joints, the
    /// joined parts not colliding with each other.
    ///
    /// # Errors
    /// An invalid `desc` (non-finite position or velocity, a non-unit rotation, a density or friction the
    /// collider refuses). On error, the parts inserted so far stay in the world.
    pub fn build(world: &mut PhysicsWorld, desc: &RagdollDesc) -> Result<Self, Error> {
        let pose = Pose::try_new(desc.position, desc.rotation)?;
        let segments = segments();
        let mut parts = Vec::with_capacity(PART_COUNT);
        for segment in &segments {
            let along = segment.to - segment.from;
            let length = along.length();
            let half_height = (0.5 * length - segment.radius).max(0.01);
            let centre = pose.transform_point(0.5 * (segment.from + segment.to));
            let body = world.insert_body(
                BodyDesc::dynamic()
                    .with_position(centre)
                    .with_rotation(pose.rotation)
                    .with_linear_velocity(desc.linear_velocity),
            )?;
            let capsule = ColliderDesc::capsule(segment.radius, half_height)
                .with_rotation(Quat::from_rotation_arc(Vec3::Y, along / length))
                .with_density(desc.density)
                .with_friction(desc.friction);
            world.insert_collider(capsule, body)?;
            parts.push(body);
        }
        let mut joints = Vec::with_capacity(JOINT_COUNT);
        for spec in joint_specs() {
            let (a, b) = (parts[spec.parent], parts[spec.child]);
            let pose_of = |h: BodyHandle| {
                world
                    .body(h)
                    .map_or(Pose::IDENTITY, rebound_dynamics::RigidBody::pose)
            };
            let (pose_a, pose_b) = (pose_of(a), pose_of(b));
            let pivot = pose.transform_point(spec.pivot);
            let (kind, rest, centre) = joint_kind(&spec.kind);
            let rest = (pose.rotation * rest).normalize();
            let centre = (pose.rotation * centre).normalize();
            let mut joint = Joint::from_world(kind, pose_a, pose_b, pivot, pivot, rest)?;
            joint.set_local_bases(
                (pose_a.rotation.conjugate() * centre).normalize(),
                (pose_b.rotation.conjugate() * rest).normalize(),
            )?;
            let handle = world.insert_joint(joint, a, b)?;
            world.set_joint_contacts_enabled(handle, false)?;
            joints.push(handle);
        }
        Ok(Self {
            parts: parts.try_into().map_err(|_| Error::Full)?,
            joints: joints.try_into().map_err(|_| Error::Full)?,
        })
    }

    /// The body of `part`.
    #[must_use]
    pub fn part(&self, part: Part) -> BodyHandle {
        self.parts[part as usize]
    }

    /// The largest distance between a joint's two anchors (m): 0 for a joint held exactly.
    #[must_use]
    pub fn worst_joint_gap(&self, world: &PhysicsWorld) -> f32 {
        self.joints
            .iter()
            .filter_map(|&j| {
                let joint = world.joint(j)?;
                let (a, b) = world.joint_bodies(j)?;
                let pose_a = a
                    .and_then(|a| world.body(a))
                    .map_or(Pose::IDENTITY, rebound_dynamics::RigidBody::pose);
                let pose_b = world.body(b)?.pose();
                Some(
                    (pose_b.transform_point(joint.local_anchor_b())
                        - pose_a.transform_point(joint.local_anchor_a()))
                    .length(),
                )
            })
            .fold(0.0, f32::max)
    }

    /// The largest angle by which a joint is past its limits (rad); see [`Ragdoll::limit_excesses`].
    #[must_use]
    pub fn worst_limit_excess(&self, world: &PhysicsWorld) -> f32 {
        self.limit_excesses(world).into_iter().fold(0.0, f32::max)
    }

    /// The angle by which each joint is past its limits (rad), in [`Ragdoll::joints`] order: the swing past a
    /// cone (along the cone's normal), a twist or hinge angle past its range; 0 within the limits.
    #[must_use]
    pub fn limit_excesses(&self, world: &PhysicsWorld) -> [f32; JOINT_COUNT] {
        self.joints.map(|j| {
            let (Some(joint), Some((a, b))) = (world.joint(j), world.joint_bodies(j)) else {
                return 0.0;
            };
            let rotation_a = a
                .and_then(|a| world.body(a))
                .map_or(Quat::IDENTITY, rebound_dynamics::RigidBody::rotation);
            let Some(body_b) = world.body(b) else {
                return 0.0;
            };
            let frame_a = rotation_a * joint.local_basis_a();
            let frame_b = body_b.rotation() * joint.local_basis_b();
            limit_excess(joint.kind(), frame_a, frame_b)
        })
    }
}

/// How far (rad) frames `frame_a`, `frame_b` are past the limits of `kind`.
fn limit_excess(kind: &JointKind, frame_a: Quat, frame_b: Quat) -> f32 {
    let past = |x: f32, lower: f32, upper: f32| (lower - x).max(x - upper).max(0.0);
    match kind {
        JointKind::Ball(ball) => {
            let Some(limits) = ball.limits() else {
                return 0.0;
            };
            let st = SwingTwist::new(frame_a, frame_b);
            let cone = limits.cone().map_or(0.0, |(y, z)| {
                st.cone_error(frame_a, Vec2::new(y, z)).0.max(0.0)
            });
            let twist = limits
                .twist()
                .map_or(0.0, |t| past(st.twist, t.lower(), t.upper()));
            cone.max(twist)
        }
        JointKind::Hinge(hinge) => hinge.limits().map_or(0.0, |l| {
            past(twist_angle(frame_a, frame_b), l.lower(), l.upper())
        }),
        _ => 0.0,
    }
}

/// The kind of `spec`, the joint frame at rest (both bodies', world, standing pose) and the parent's frame
/// turned to the middle of the ranges.
fn joint_kind(spec: &Spec) -> (JointKind, Quat, Quat) {
    let rad = |d: f32| d * PI / 180.0;
    match *spec {
        Spec::Ball {
            axis,
            flexion_axis,
            flexion,
            other,
            twist,
        } => {
            let other_axis = axis.cross(flexion_axis);
            let rest =
                Quat::from_mat3(&Mat3::from_cols(axis, flexion_axis, other_axis)).normalize();
            let half = |(lower, upper): (f32, f32)| rad(0.5 * (upper - lower));
            let mid = |(lower, upper): (f32, f32)| rad(0.5 * (upper + lower));
            let centre = (Quat::from_axis_angle(other_axis, mid(other))
                * Quat::from_axis_angle(flexion_axis, mid(flexion))
                * rest)
                .normalize();
            // The ranges in the table are valid by construction: half-angles in (0, π], twists in [−π, π].
            let limits = SwingTwistLimits::new()
                .with_cone(half(flexion).min(PI), half(other).min(PI))
                .and_then(|l| l.with_twist(rad(twist.0), rad(twist.1)))
                .unwrap_or_default();
            (BallJoint::new().with_limits(limits).into(), rest, centre)
        }
        Spec::Hinge { axis, range } => {
            let rest = basis_from_axis(axis).unwrap_or(Quat::IDENTITY);
            let hinge = HingeJoint::new()
                .with_limits(rad(range.0), rad(range.1))
                .unwrap_or_default();
            (hinge.into(), rest, rest)
        }
    }
}
