#![doc = include_str!("../README.md")]
// sin, atan2, exp… only through `rebound_math::real` (the same bits on every platform under
// `enhanced-determinism`); clippy.toml lists them.
#![warn(clippy::disallowed_methods)]

pub mod part;

mod ball;
#[cfg(feature = "serde")]
mod bounds;
mod coordinate;
mod error;
mod fixed;
mod hinge;
mod joint;
mod limits;
mod motor;
mod orientation_motor;
mod pair;
pub mod path;
mod prismatic;
mod rod;
mod rope;
mod settings;
mod six_dof;
mod soft_spring;
mod solver;
pub mod spring;
mod stage;
mod state;
mod swing_twist;
mod wheel;

/// The dynamics layer this crate builds on.
pub use rebound_dynamics as dynamics;
/// The math layer.
pub use rebound_math as math;

pub use ball::BallJoint;
pub use error::ConstraintError;
pub use fixed::FixedJoint;
pub use hinge::{HingeJoint, twist_angle};
pub use joint::{Joint, JointBodies, JointKind, basis_from_axes, basis_from_axis};
pub use limits::Limits;
pub use motor::Motor;
pub use orientation_motor::OrientationMotor;
pub use pair::{Anchors, BodyPair, Distance, MIN_AXIS_LENGTH};
pub use prismatic::PrismaticJoint;
pub use rod::Rod;
pub use rope::Rope;
pub use settings::{JointSettings, MAX_JOINT_ITERATIONS};
pub use six_dof::{Axis, AxisDrive, AxisMotion, AxisSettings, SixDofJoint};
pub use soft_spring::{JointSpring, OscillatorStep, SoftSpring};
pub use solver::{JointSolver, JointTeam, KeptRows};
pub use spring::{Spring, SpringModel};
pub use stage::Substep;
pub use state::{JointState, JointStates};
pub use swing_twist::{MIN_SWING_HALF_ANGLE, SwingTwistLimits};
pub use wheel::WheelJoint;
