//! The body components: [`Body`] (type, damping, gravity scale, sleep settings), [`Velocity`], [`Sleeping`],
//! [`MassOverride`] and [`KinematicTarget`]. Read by the prepare systems (insertion and edits), written by the
//! writeback systems (velocity and sleep state after each step).
//!
//! A body entity's [`Transform`] is its pose in world space: give bodies no parent (a body's `Transform`
//! is not composed with an ancestor's). Its scale is left alone and does not scale the colliders.

use bevy_ecs::component::Component;
use bevy_transform::components::Transform;
use rebound::prelude::{BodyDesc, BodyType, MassProperties, Pose, Quat, Vec3};

/// A rigid body. The entity's [`Transform`] (translation and rotation) is the body's pose in world space
/// (m); editing it teleports the body, and each step writes the new pose back.
///
/// ```
/// use rebound_bevy::Body;
/// let crate_box = Body::dynamic().with_linear_damping(0.1).with_gravity_scale(0.5);
/// let ground = Body::fixed();
/// assert_eq!(crate_box.gravity_scale, 0.5);
/// assert!(!ground.is_dynamic());
/// ```
#[derive(Component, Debug, Clone, Copy, PartialEq)]
#[require(Transform, Velocity, Sleeping)]
pub struct Body {
    /// Dynamic, fixed or kinematic. Default: dynamic.
    pub body_type: BodyType,
    /// Multiplier on the world's gravity (dimensionless; may be negative or 0). Default: 1.0.
    pub gravity_scale: f32,
    /// Linear damping coefficient (1/s, ≥ 0): `v ← v / (1 + c·h)` each substep. Default: 0.0.
    pub linear_damping: f32,
    /// Angular damping coefficient (1/s, ≥ 0). Default: 0.0.
    pub angular_damping: f32,
    /// Whether the body may fall asleep when it comes to rest. Default: true.
    pub can_sleep: bool,
    /// Whether the gyroscopic term `ω × I·ω` is integrated. Default: true.
    pub gyroscopic: bool,
}

impl Default for Body {
    fn default() -> Self {
        Self::dynamic()
    }
}

impl Body {
    /// A dynamic body: moved by gravity, forces, contacts and joints.
    #[must_use]
    pub const fn dynamic() -> Self {
        Self::of_type(BodyType::Dynamic)
    }

    /// A fixed body: never moves (ground, walls).
    #[must_use]
    pub const fn fixed() -> Self {
        Self::of_type(BodyType::Fixed)
    }

    /// A kinematic body: moved by its [`Velocity`] or a [`KinematicTarget`], pushes dynamic bodies.
    #[must_use]
    pub const fn kinematic() -> Self {
        Self::of_type(BodyType::Kinematic)
    }

    const fn of_type(body_type: BodyType) -> Self {
        Self {
            body_type,
            gravity_scale: 1.0,
            linear_damping: 0.0,
            angular_damping: 0.0,
            can_sleep: true,
            gyroscopic: true,
        }
    }

    /// Whether this is a dynamic body.
    #[must_use]
    pub fn is_dynamic(&self) -> bool {
        self.body_type == BodyType::Dynamic
    }

    /// Sets the gravity scale (dimensionless).
    #[must_use]
    pub const fn with_gravity_scale(mut self, gravity_scale: f32) -> Self {
        self.gravity_scale = gravity_scale;
        self
    }

    /// Sets the linear damping (1/s).
    #[must_use]
    pub const fn with_linear_damping(mut self, damping: f32) -> Self {
        self.linear_damping = damping;
        self
    }

    /// Sets the angular damping (1/s).
    #[must_use]
    pub const fn with_angular_damping(mut self, damping: f32) -> Self {
        self.angular_damping = damping;
        self
    }

    /// Sets whether the body may fall asleep.
    #[must_use]
    pub const fn with_can_sleep(mut self, can_sleep: bool) -> Self {
        self.can_sleep = can_sleep;
        self
    }

    /// The engine's description of this body at `pose`, moving at `velocity`.
    pub(crate) fn desc(
        &self,
        pose: Pose,
        velocity: Velocity,
        sleeping: bool,
        mass: Option<MassProperties>,
    ) -> BodyDesc {
        let mut desc = BodyDesc {
            body_type: self.body_type,
            position: pose.position,
            rotation: pose.rotation,
            linear_velocity: velocity.linear,
            angular_velocity: velocity.angular,
            gravity_scale: self.gravity_scale,
            linear_damping: self.linear_damping,
            angular_damping: self.angular_damping,
            gyroscopic: self.gyroscopic,
            sleeping,
            can_sleep: self.can_sleep,
            ..BodyDesc::default()
        };
        if let Some(mass) = mass {
            desc.mass_properties = mass;
        }
        desc
    }
}

/// A body's velocity: of its centre of mass (m/s) and angular (rad/s, world space). Written after every step;
/// a value set by the user is given to the body at the next step. Default: at rest.
#[derive(Component, Debug, Clone, Copy, PartialEq, Default)]
pub struct Velocity {
    /// Velocity of the centre of mass (m/s).
    pub linear: Vec3,
    /// Angular velocity (rad/s, world space).
    pub angular: Vec3,
}

impl Velocity {
    /// A velocity from its linear (m/s) and angular (rad/s) parts.
    #[must_use]
    pub const fn new(linear: Vec3, angular: Vec3) -> Self {
        Self { linear, angular }
    }

    /// A linear velocity (m/s) without rotation.
    #[must_use]
    pub const fn linear(linear: Vec3) -> Self {
        Self {
            linear,
            angular: Vec3::ZERO,
        }
    }
}

/// Whether a body is asleep. Written after every step; setting it to `false` wakes the body (and its
/// island), setting it to `true` puts the body to sleep. Inserted with `true`, the body starts asleep.
/// Default: awake.
#[derive(Component, Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct Sleeping(pub bool);

/// Mass properties that replace the ones a body's colliders would give it (mass in kg, centre of mass in
/// the body frame in m, inertia in kg·m²). Without this component a body's mass is the sum of its colliders'
/// (each `density` × volume), or 1 kg when they add none.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct MassOverride(pub MassProperties);

/// Where a kinematic body must be at the end of the next step: the step gives it the velocity that takes
/// it there. Applied at every step while the component is present (a body at its target stays there, awake).
/// Only kinematic bodies follow it; on dynamic and fixed bodies it does nothing.
#[derive(Component, Debug, Clone, Copy, PartialEq)]
pub struct KinematicTarget {
    /// Target position of the body origin (m, world space).
    pub position: Vec3,
    /// Target orientation (unit quaternion).
    pub rotation: Quat,
}

impl KinematicTarget {
    /// A target pose.
    #[must_use]
    pub const fn new(position: Vec3, rotation: Quat) -> Self {
        Self { position, rotation }
    }

    /// The target as a pose.
    #[must_use]
    pub const fn pose(&self) -> Pose {
        Pose::new(self.position, self.rotation)
    }
}

/// The pose a [`Transform`] describes (its scale is not part of a pose).
pub(crate) fn pose_of(transform: &Transform) -> Pose {
    Pose::new(transform.translation, transform.rotation)
}
