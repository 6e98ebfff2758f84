//! One recorded step as plain data ([`Frame`]): per-body samples, contacts, joint states, events and the
//! step's energy and momentum. The writer fills one from a world; the reader gives the same numbers back.

use crate::manifest::{BodyKind, Changes};
use rebound::{Quat, Vec3};

/// One frame of a recording: the world's state after one step (or before the first).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Frame {
    /// The world's `step_count()` when the frame was taken (0 = before the first step).
    pub step: u64,
    /// Simulated time of the frame (s): the sum of the recorded steps' `dt`.
    pub time: f64,
    /// Bodies, colliders and joints inserted or edited since the previous frame, if any (they apply before
    /// this frame's numbers are read).
    pub changes: Option<Changes>,
    /// One sample per body index assigned so far, in index order (removed bodies have `present == false`).
    pub bodies: Vec<BodySample>,
    /// The contact points of the step, one per manifold point, in the engine's manifold order.
    pub contacts: Vec<ContactSample>,
    /// One sample per joint index assigned so far, in index order.
    pub joints: Vec<JointSample>,
    /// The events of the step, in the engine's order.
    pub events: Vec<RecordedEvent>,
    /// Energy, momentum and error measures of the frame.
    pub diagnostics: Diagnostics,
}

/// A body's state in a frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodySample {
    /// Position of the body origin in world space (m); zero for a removed body.
    pub position: Vec3,
    /// Orientation (unit quaternion); identity for a removed body.
    pub rotation: Quat,
    /// Linear velocity (m/s).
    pub linear_velocity: Vec3,
    /// Angular velocity, world axes (rad/s).
    pub angular_velocity: Vec3,
    /// Whether the body exists at this frame.
    pub present: bool,
    /// Whether the body is asleep.
    pub sleeping: bool,
    /// Dynamic, fixed or kinematic at this frame.
    pub kind: BodyKind,
}

impl BodySample {
    /// The sample of a body that no longer exists: every number zero, identity rotation, `present == false`.
    pub const REMOVED: Self = Self {
        position: Vec3::ZERO,
        rotation: Quat::IDENTITY,
        linear_velocity: Vec3::ZERO,
        angular_velocity: Vec3::ZERO,
        present: false,
        sleeping: false,
        kind: BodyKind::Dynamic,
    };
}

impl Default for BodySample {
    /// [`BodySample::REMOVED`].
    fn default() -> Self {
        Self::REMOVED
    }
}

/// One contact point of a step.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactSample {
    /// Body A's index.
    pub body_a: u32,
    /// Body B's index.
    pub body_b: u32,
    /// The contact point in world space (m): the midpoint of the point's anchors on A and on B.
    pub point: Vec3,
    /// Unit normal in world space, from A to B.
    pub normal: Vec3,
    /// Normal impulse of the step's last substep (N·s, ≥ 0): about `m·g·h` on a resting contact, `h` the
    /// substep.
    pub normal_impulse: f32,
    /// Signed distance between the surfaces (m): negative when overlapping, positive for a speculative point;
    /// as the step measured it before solving.
    pub separation: f32,
}

/// A joint's state in a frame.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct JointSample {
    /// Anchor A in world space (m).
    pub anchor_a: Vec3,
    /// Anchor B in world space (m).
    pub anchor_b: Vec3,
    /// Positional joint error (m); see `docs/recording.md` for each kind's measure.
    pub error: f32,
    /// Magnitude of the constraint force of the last substep (N).
    pub reaction_force: f32,
    /// Magnitude of the constraint torque of the last substep (N·m).
    pub reaction_torque: f32,
    /// Whether the joint exists at this frame.
    pub present: bool,
    /// Whether it has broken.
    pub broken: bool,
}

/// An event of a step, with bodies, colliders and joints as recording indices (`None`: a handle the
/// recorder never saw).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum RecordedEvent {
    /// Two bodies started touching.
    ContactBegan {
        /// Body A.
        body_a: Option<u32>,
        /// Body B.
        body_b: Option<u32>,
        /// Approach speed along the normal (m/s, ≥ 0).
        approach_speed: f32,
    },
    /// Two bodies stopped touching.
    ContactEnded {
        /// Body A.
        body_a: Option<u32>,
        /// Body B.
        body_b: Option<u32>,
    },
    /// A joint broke.
    JointBroken {
        /// The joint.
        joint: Option<u32>,
    },
    /// A body fell asleep.
    BodyFellAsleep {
        /// The body.
        body: Option<u32>,
    },
    /// A body woke up.
    BodyWoke {
        /// The body.
        body: Option<u32>,
    },
    /// A contact pushed with at least a collider's force event threshold over the step (the engine's
    /// `Event::ContactForce`).
    ContactForce {
        /// Body A of the manifold.
        body_a: Option<u32>,
        /// Body B of the manifold.
        body_b: Option<u32>,
        /// The pair's collider on body A (`None`: not named by the engine, or never seen).
        collider_a: Option<u32>,
        /// The pair's collider on body B.
        collider_b: Option<u32>,
        /// The manifold's unit normal, world axes, from A to B.
        normal: Vec3,
        /// The normal impulse of the step, summed over its points and substeps (N·s).
        total_impulse: f32,
        /// The mean normal force of the step, `total_impulse / dt` (N).
        total_force: f32,
        /// The point that applied the largest impulse, world space at the end of the step (m).
        max_impulse_point: Vec3,
        /// That point's impulse over the step (N·s).
        max_impulse: f32,
    },
    /// A collider started overlapping a sensor.
    SensorEntered {
        /// The sensor collider.
        sensor: Option<u32>,
        /// The collider that entered.
        collider: Option<u32>,
    },
    /// A collider stopped overlapping a sensor.
    SensorExited {
        /// The sensor collider.
        sensor: Option<u32>,
        /// The collider that left.
        collider: Option<u32>,
    },
}

/// Energy, momentum and error measures of a frame (`docs/recording.md`, frame header).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Diagnostics {
    /// Kinetic energy of the dynamic bodies (J).
    pub kinetic_energy: f32,
    /// Gravitational potential energy of the dynamic bodies, zero at the world origin's height (J).
    pub potential_energy: f32,
    /// Energy stored in unbroken `Spring` joints (J).
    pub spring_energy: f32,
    /// Total linear momentum of the dynamic bodies (kg·m/s).
    pub linear_momentum: Vec3,
    /// Total angular momentum of the dynamic bodies about the world origin (kg·m²/s).
    pub angular_momentum: Vec3,
    /// The largest joint error of the frame (m), 0 without joints.
    pub worst_joint_error: f32,
    /// The largest overlap of the frame's contacts (m, ≥ 0).
    pub deepest_penetration: f32,
}

impl Diagnostics {
    /// Kinetic + potential + spring energy (J).
    #[must_use]
    pub fn total_energy(&self) -> f32 {
        self.kinetic_energy + self.potential_energy + self.spring_energy
    }
}
