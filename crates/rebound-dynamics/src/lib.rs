#![doc = include_str!("../README.md")]
// sin, atan2, exp… only through `rebound_math::real` (the same bits on every platform under
// `enhanced-determinism`); clippy.toml lists them.
#![warn(clippy::disallowed_methods)]

pub mod contact;
pub mod impulse;
pub mod integrate;
pub mod material;
pub mod momentum;

mod body;
mod error;
mod locks;
mod mass;
mod softness;
mod solver_body;
mod step_context;

/// The math layer this crate builds on.
pub use rebound_math as math;

pub use body::{BodyDesc, BodyType, Integrator, RigidBody};
pub use contact::{
    Bias, Contact, ContactPoint, ContactSolver, ContactTeam, MAX_CONTACT_POINTS, StackLoads,
    Support,
};
pub use error::DynamicsError;
pub use locks::LockedAxes;
pub use mass::MassProperties;
pub use material::CombineRule;
pub use softness::Softness;
pub use solver_body::{BodyParams, Motion, SolverBody};
pub use step_context::{SolverSettings, StepContext};
