#![doc = include_str!("../README.md")]
// sin, atan2, exp… only through `rebound_math::real` (the same bits on every platform under
// `enhanced-determinism`); clippy.toml lists them.
#![warn(clippy::disallowed_methods)]

pub mod arena;
mod body_set;
mod collide;
mod error;
mod events;
mod handles;
mod islands;
mod kinematic;
mod limits;
mod manifold;
mod prepare;
mod quarantine;
mod report;
mod scratch;
mod settings;
mod snapshot_check;
mod solve;
mod solve_parts;
#[cfg(feature = "parallel")]
mod solve_team;
mod sorted_walk;
mod state;
mod step;
mod store;
mod union_find;
mod world;

pub mod testing;

/// The constraints layer this crate builds on.
pub use rebound_constraints as constraints;
/// The dynamics layer.
pub use rebound_dynamics as dynamics;
/// The math layer.
pub use rebound_math as math;

pub use body_set::BodySet;
pub use error::WorldError;
pub use events::{ContactForce, Event};
pub use handles::{BodyHandle, JointHandle};
pub use limits::{MAX_BOUND, QuarantineReason, StepLimits};
pub use manifold::{
    CollisionBackend, ContactBasis, ContactManifold, LEVER_ARM_RELATIVE_TOLERANCE,
    LEVER_ARM_TOLERANCE, MAX_MANIFOLD_POINTS, ManifoldPoint, ManifoldWriter, NoCollision,
};
pub use report::{AdvanceReport, Profile, StepReport, StepSkipped};
pub use settings::{MAX_STEPS_PER_ADVANCE, MAX_SUBSTEPS, MIN_STEP_DT, WorldSettings};
pub use world::{RemovedBody, World, WorldSnapshot};
