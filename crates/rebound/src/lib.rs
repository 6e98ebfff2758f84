#![doc = include_str!("../README.md")]
// sin, atan2, exp… only through `rebound_math::real` (the same bits on every platform under
// `enhanced-determinism`); clippy.toml lists them.
#![warn(clippy::disallowed_methods)]

mod backend;
mod ball_ball;
mod box_box;
mod broad_phase;
mod character;
mod collider;
mod collider_handle;
mod collider_set;
mod error;
mod events;
mod hooks;
mod narrow_phase;
mod one_way;
mod pair_sort;
mod physics_world;
mod prediction;
mod query;
pub mod ragdoll;
mod recycling;
mod seam;
mod sensors;
mod shape;
mod shape_manifold;
mod snapshot;
mod sweep;

/// The collision library, re-exported so users get the same version Rebound uses.
pub use parry3d;

/// Rotations, transforms, inertia (`rebound-math`).
pub use rebound_math as math;

/// Bodies, mass, integration, impulses (`rebound-dynamics`).
pub use rebound_dynamics as dynamics;

/// Springs, ropes and joints (`rebound-constraints`).
pub use rebound_constraints as constraints;

/// The world and its step (`rebound-world`).
pub use rebound_world as world;

// Everything the layers below export, at the crate root. Items defined here (`Event`) take precedence over
// the world's of the same name, which stays reachable as `rebound::world::Event`.
pub use rebound_constraints::*;
pub use rebound_dynamics::*;
pub use rebound_math::*;
pub use rebound_world::*;

pub use backend::ParryBackend;
pub use character::{
    Autostep, CharacterCollision, CharacterController, CharacterError, CharacterMove,
    CharacterPush, CharacterSettings, Ground, MAX_SLIDE_ITERATIONS, Push,
};
pub use collider::{Collider, ColliderDesc, CollisionGroups};
pub use collider_handle::ColliderHandle;
pub use collider_set::ColliderSet;
pub use error::{Error, ShapeError};
pub use events::Event;
pub use hooks::{ContactEdit, ContactHooks, ContactPair, ContactPointEdit};
pub use one_way::OneWayPlatform;
#[cfg(feature = "parallel")]
pub use physics_world::MIN_WORK_FOR_THREADS;
pub use physics_world::PhysicsWorld;
pub use query::{PickHit, PointHit, QueryFilter, RayHit, ShapeHit};
pub use shape::{ColliderShape, MAX_SHAPE_COORDINATE};
pub use snapshot::PhysicsSnapshot;

/// What most programs need: `use rebound::prelude::*;`.
pub mod prelude {
    pub use crate::{
        Autostep, CharacterCollision, CharacterController, CharacterError, CharacterMove,
        CharacterPush, CharacterSettings, Collider, ColliderDesc, ColliderHandle, ColliderShape,
        CollisionGroups, ContactEdit, ContactHooks, ContactPair, Error, Event, Ground,
        OneWayPlatform, PhysicsSnapshot, PhysicsWorld, PickHit, PointHit, Push, QueryFilter,
        RayHit, ShapeError, ShapeHit,
    };
    pub use rebound_constraints::{
        AxisDrive, AxisMotion, BallJoint, ConstraintError, FixedJoint, HingeJoint, Joint,
        JointKind, Limits, Motor, OrientationMotor, PrismaticJoint, Rod, Rope, SixDofJoint,
        SoftSpring, Spring, SpringModel, SwingTwistLimits, WheelJoint,
    };
    pub use rebound_dynamics::{
        BodyDesc, BodyType, CombineRule, DynamicsError, LockedAxes, MassProperties,
    };
    pub use rebound_math::{MathError, Pose, Quat, Vec3};
    pub use rebound_world::{
        AdvanceReport, BodyHandle, ContactForce, ContactManifold, JointHandle, StepReport,
        WorldError, WorldSettings,
    };
}
