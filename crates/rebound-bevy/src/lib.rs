#![doc = include_str!("../README.md")]
// Bevy systems take their parameters (`Res`, `Query`) by value and spell out their queries' types: the two
// lints Bevy itself allows for the same reason.
#![allow(
    clippy::needless_pass_by_value,
    reason = "Bevy system parameters are passed by value"
)]
#![allow(
    clippy::type_complexity,
    reason = "Bevy queries are spelled out in system signatures"
)]

mod body;
mod collider;
mod debug_render;
mod error;
mod events;
mod forces;
mod interpolation;
mod joint;
mod physics;
mod plugin;
mod prepare;
mod query;
mod settings;
mod snapshot;
mod writeback;

/// The engine this plugin drives, re-exported so users name the same version.
pub use rebound;
/// The debug-draw description the [`PhysicsDebugRender`] resource holds.
pub use rebound_debug;

pub use body::{Body, KinematicTarget, MassOverride, Sleeping, Velocity};
pub use collider::Collider;
pub use debug_render::PhysicsDebugRender;
pub use error::PhysicsError;
pub use events::PhysicsEvent;
pub use forces::{ExternalForce, ExternalImpulse};
pub use interpolation::{TransformInterpolation, interpolate_pose};
pub use joint::PhysicsJoint;
pub use physics::Physics;
pub use plugin::{PhysicsSystems, ReboundPlugin};
pub use query::{
    EntityHit, EntityPickHit, EntityPointHit, EntityRayHit, EntityShapeHit, SpatialQuery,
    SpatialQueryFilter,
};
pub use settings::PhysicsSettings;
pub use snapshot::PhysicsState;

/// What most Bevy programs need: `use rebound_bevy::prelude::*;`.
pub mod prelude {
    pub use crate::{
        Body, Collider, ExternalForce, ExternalImpulse, KinematicTarget, MassOverride, Physics,
        PhysicsDebugRender, PhysicsError, PhysicsEvent, PhysicsJoint, PhysicsSettings,
        PhysicsState, PhysicsSystems, ReboundPlugin, Sleeping, SpatialQuery, SpatialQueryFilter,
        TransformInterpolation, Velocity,
    };
    pub use rebound::prelude::{
        BallJoint, BodyDesc, BodyType, ColliderDesc, ColliderShape, CollisionGroups, CombineRule,
        FixedJoint, HingeJoint, Joint, Limits, MassProperties, Motor, Pose, PrismaticJoint, Quat,
        Rod, Rope, Spring, Vec3, WheelJoint, WorldSettings,
    };
}
