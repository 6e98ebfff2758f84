//! The JSON part of a recording: the [`Manifest`] written once at the start (the world's settings, bodies
//! with their colliders, joints) and the [`Changes`] a frame carries when objects are inserted or edited.
//! Field by field in `docs/recording.md`; these types are that description in serde form.

use crate::format::FORMAT_NAME;
use rebound::{BodyType, ColliderShape, JointKind, Pose, Quat, Vec3};
use serde::{Deserialize, Serialize};

/// What a recording starts with: the engine, the world's settings and the bodies and joints present when
/// recording started.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Manifest {
    /// Always `"rebound-recording"` ([`crate::FORMAT_NAME`]).
    pub format: String,
    /// Always `"rebound"`.
    pub engine: String,
    /// The version of the `rebound` crate that wrote the file.
    pub engine_version: String,
    /// The world's fixed time step when recording started (s).
    pub dt: f32,
    /// The world's substep count.
    pub substeps: u32,
    /// The world's gravity (m/s²).
    pub gravity: Vec3,
    /// The bodies present when recording started; entry `i` has index `i`.
    pub bodies: Vec<BodyEntry>,
    /// The joints present when recording started; entry `i` has index `i`.
    pub joints: Vec<JointEntry>,
}

impl Manifest {
    /// An empty manifest with the engine's name and version and the given world settings.
    #[must_use]
    pub fn new(dt: f32, substeps: u32, gravity: Vec3) -> Self {
        Self {
            format: FORMAT_NAME.to_owned(),
            engine: "rebound".to_owned(),
            engine_version: ENGINE_VERSION.to_owned(),
            dt,
            substeps,
            gravity,
            bodies: Vec::new(),
            joints: Vec::new(),
        }
    }
}

/// The version written into manifests: this crate's, which the workspace keeps equal to the facade's.
const ENGINE_VERSION: &str = env!("CARGO_PKG_VERSION");

/// How a body takes part in the simulation, as the format names it (`"dynamic"`, `"fixed"`,
/// `"kinematic"`; in frames the codes 0, 1, 2).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum BodyKind {
    /// Moved by forces and contacts. Code 0.
    #[default]
    Dynamic,
    /// Never moves. Code 1.
    Fixed,
    /// Moved by its velocity, not pushed. Code 2.
    Kinematic,
}

impl BodyKind {
    /// The two-bit code of the frame's body flags.
    #[must_use]
    pub const fn code(self) -> u8 {
        match self {
            Self::Dynamic => 0,
            Self::Fixed => 1,
            Self::Kinematic => 2,
        }
    }

    /// The kind of a code, `None` for 3 (or anything above).
    #[must_use]
    pub const fn from_code(code: u8) -> Option<Self> {
        match code {
            0 => Some(Self::Dynamic),
            1 => Some(Self::Fixed),
            2 => Some(Self::Kinematic),
            _ => None,
        }
    }
}

impl From<BodyType> for BodyKind {
    fn from(value: BodyType) -> Self {
        match value {
            BodyType::Dynamic => Self::Dynamic,
            BodyType::Fixed => Self::Fixed,
            BodyType::Kinematic => Self::Kinematic,
        }
    }
}

impl From<BodyKind> for BodyType {
    fn from(value: BodyKind) -> Self {
        match value {
            BodyKind::Dynamic => Self::Dynamic,
            BodyKind::Fixed => Self::Fixed,
            BodyKind::Kinematic => Self::Kinematic,
        }
    }
}

/// A body's description.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BodyEntry {
    /// The body's recording index.
    pub index: u32,
    /// The engine's handle as `[slot, generation]` (`BodyHandle::into_raw_parts`) when it was recorded.
    pub handle: [u32; 2],
    /// Its kind when the entry was written (frames carry the current kind).
    pub kind: BodyKind,
    /// Mass (kg).
    pub mass: f32,
    /// Centre of mass in the body frame (m).
    pub local_center_of_mass: Vec3,
    /// Inertia tensor about the centre of mass in the body frame (kg·m²), row by row.
    pub inertia: [[f32; 3]; 3],
    /// Multiplier of the world's gravity (dimensionless).
    pub gravity_scale: f32,
    /// The body's colliders: in the manifest and in a new body's entry, all of them; in an entry that
    /// replaces a known body's description, none (colliders change through [`Changes::colliders`]).
    #[serde(default)]
    pub colliders: Vec<ColliderEntry>,
}

/// A collider's description.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ColliderEntry {
    /// The collider's recording index (numbered across all bodies).
    pub index: u32,
    /// Its body's recording index.
    pub body: u32,
    /// The geometry, as the facade describes it.
    pub shape: ColliderShape,
    /// Its pose in the body frame.
    pub local_pose: Pose,
    /// Density (kg/m³).
    pub density: f32,
    /// Coulomb friction coefficient (dimensionless).
    pub friction: f32,
    /// Coefficient of restitution (dimensionless).
    pub restitution: f32,
    /// Rolling resistance lever arm (m).
    pub rolling_friction: f32,
    /// Whether it is a sensor.
    pub sensor: bool,
    /// Whether it takes part in collisions.
    pub enabled: bool,
}

/// The kind of a joint, as the format names it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum JointKindName {
    /// A spring with a rest length.
    Spring,
    /// A maximum distance.
    Rope,
    /// A fixed distance.
    Rod,
    /// A spherical joint.
    Ball,
    /// A revolute joint.
    Hinge,
    /// A weld.
    Fixed,
    /// A slider.
    Prismatic,
    /// A suspended, driven wheel.
    Wheel,
    /// A generic joint, each axis free, locked, limited or driven.
    #[serde(rename = "six_dof")]
    SixDof,
}

impl From<&JointKind> for JointKindName {
    fn from(value: &JointKind) -> Self {
        match value {
            JointKind::Spring(_) => Self::Spring,
            JointKind::Rope(_) => Self::Rope,
            JointKind::Rod(_) => Self::Rod,
            JointKind::Ball(_) => Self::Ball,
            JointKind::Hinge(_) => Self::Hinge,
            JointKind::Fixed(_) => Self::Fixed,
            JointKind::Prismatic(_) => Self::Prismatic,
            JointKind::Wheel(_) => Self::Wheel,
            JointKind::SixDof(_) => Self::SixDof,
        }
    }
}

/// A joint coordinate's limits (rad for a hinge, m for a slide or a suspension).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LimitsEntry {
    /// Lower bound.
    pub lower: f32,
    /// Upper bound.
    pub upper: f32,
}

/// A joint's description.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct JointEntry {
    /// The joint's recording index.
    pub index: u32,
    /// Its kind.
    pub kind: JointKindName,
    /// Body A's recording index; `None` for a world joint (A is the world).
    pub body_a: Option<u32>,
    /// Body B's recording index.
    pub body_b: u32,
    /// Anchor on A in A's frame, relative to its origin (m); a world point for a world joint.
    pub local_anchor_a: Vec3,
    /// Anchor on B in B's frame (m).
    pub local_anchor_b: Vec3,
    /// The joint frame in A's frame (world frame for a world joint).
    pub local_basis_a: Quat,
    /// The joint frame in B's frame.
    pub local_basis_b: Quat,
    /// The X axis of `local_basis_a`: the hinge axis, slide axis or wheel axle (unit).
    pub local_axis_a: Vec3,
    /// The X axis of `local_basis_b` (unit).
    pub local_axis_b: Vec3,
    /// Hinge (rad), prismatic (m) or wheel suspension (m) limits, if any.
    pub limits: Option<LimitsEntry>,
    /// Spring rest length, rope maximum length or rod length (m), for those kinds.
    pub length: Option<f32>,
    /// Break force (N); +∞ (`null` in JSON) = unbreakable.
    #[serde(with = "unbounded")]
    pub break_force: f32,
    /// Break torque (N·m); +∞ (`null` in JSON) = unbreakable.
    #[serde(with = "unbounded")]
    pub break_torque: f32,
    /// The engine's `JointKind` as serde JSON (motors, springs, restitution, …), for display. An infinite
    /// value in it is `null`.
    pub params: serde_json::Value,
}

/// What a frame adds or replaces (`docs/recording.md`, "Changes after recording starts"). Every list is
/// optional in JSON.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct Changes {
    /// New bodies (with their colliders) and replaced body descriptions (without colliders).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<BodyEntry>,
    /// New colliders on known bodies and replaced collider descriptions.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub colliders: Vec<ColliderEntry>,
    /// New joints and replaced joint descriptions.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<JointEntry>,
    /// Indices of colliders removed since the previous frame.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub removed_colliders: Vec<u32>,
}

impl Changes {
    /// Whether there is nothing in any list.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.bodies.is_empty()
            && self.colliders.is_empty()
            && self.joints.is_empty()
            && self.removed_colliders.is_empty()
    }
}

/// `f32` fields where +∞ is written as JSON `null` (JSON has no infinity) and read back as +∞.
mod unbounded {
    use serde::{Deserialize, Deserializer, Serialize, Serializer};

    // serde's `with` hands the field by reference.
    pub(super) fn serialize<S: Serializer>(value: &f32, serializer: S) -> Result<S::Ok, S::Error> {
        value.is_finite().then_some(*value).serialize(serializer)
    }

    pub(super) fn deserialize<'de, D: Deserializer<'de>>(deserializer: D) -> Result<f32, D::Error> {
        Ok(Option::<f32>::deserialize(deserializer)?.unwrap_or(f32::INFINITY))
    }
}
