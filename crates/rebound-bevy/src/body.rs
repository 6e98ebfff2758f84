//! The body components: [`Body`] (a [`BodyDesc`]: type, damping, gravity scale, sleep settings), [`Velocity`], [`Sleeping`],
//! [`MassOverride`] and [`KinematicTarget`]. Read by the prepare systems (insertion and edits), written by the
//! writeback systems (velocity and sleep state after each step).
//!
//! A body entity's [`Transform`] is its pose in world space: give bodies no parent (a body's `Transform`
//! is not composed with an ancestor's). Its scale is left alone and does not scale the colliders.

use bevy_ecs::component::Component;
use bevy_transform::components::Transform;
use rebound::prelude::{BodyDesc, BodyType, MassProperties, Pose, Quat, Vec3};

/// A rigid body: a [`BodyDesc`] on an entity. The entity's [`Transform`] (translation and rotation) is the
/// body's pose in world space (m); editing it teleports the body, and each step writes the new pose back.
///
/// The description gives the body type, gravity scale, damping, integrator, gyroscopic term, sleep setting
/// and locked axes, each with the engine's default; build it with [`BodyDesc`]'s `with_*` setters. Its
/// pose, velocities, `sleeping` and mass properties belong to other components ([`Transform`],
/// [`Velocity`], [`Sleeping`], [`MassOverride`]) and must stay at their defaults: a body that sets one is
/// refused with a [`crate::PhysicsError::BodyField`] naming it, as an invalid value is refused with a
/// [`crate::PhysicsError::Refused`]. Editing the component applies the new description, all of it or none.
///
/// ```
/// use rebound_bevy::prelude::*;
/// let crate_box = Body::new(BodyDesc::dynamic().with_linear_damping(0.1).with_gravity_scale(0.5));
/// let ground = Body::fixed();
/// assert_eq!(crate_box.desc.gravity_scale, 0.5);
/// assert!(!ground.is_dynamic());
/// ```
#[derive(Component, Debug, Clone, Copy, PartialEq)]
#[require(Transform, Velocity, Sleeping)]
pub struct Body {
    /// The engine's description of the body (see the type's documentation for the fields it may set).
    pub desc: BodyDesc,
}

impl Default for Body {
    fn default() -> Self {
        Self::dynamic()
    }
}

impl From<BodyDesc> for Body {
    fn from(desc: BodyDesc) -> Self {
        Self::new(desc)
    }
}

impl Body {
    /// A body from a full description.
    #[must_use]
    pub const fn new(desc: BodyDesc) -> Self {
        Self { desc }
    }

    /// A dynamic body: moved by gravity, forces, contacts and joints.
    #[must_use]
    pub fn dynamic() -> Self {
        Self::new(BodyDesc::dynamic())
    }

    /// A fixed body: never moves (ground, walls).
    #[must_use]
    pub fn fixed() -> Self {
        Self::new(BodyDesc::fixed())
    }

    /// A kinematic body: moved by its [`Velocity`] or a [`KinematicTarget`], pushes dynamic bodies.
    #[must_use]
    pub fn kinematic() -> Self {
        Self::new(BodyDesc::kinematic())
    }

    /// Whether this is a dynamic body.
    #[must_use]
    pub fn is_dynamic(&self) -> bool {
        self.desc.body_type == BodyType::Dynamic
    }

    /// The first field of the description that another component gives, with its value and that
    /// component's name: `(field, value, component)`; `None` if all of them are at their defaults.
    pub(crate) fn foreign_field(&self) -> Option<(&'static str, String, &'static str)> {
        let (d, e) = (&self.desc, BodyDesc::default());
        type Check<'a> = (&'static str, &'static str, bool, &'a dyn Fn() -> String);
        let checks: [Check<'_>; 6] = [
            ("position", "Transform", d.position != e.position, &|| {
                d.position.to_string()
            }),
            ("rotation", "Transform", d.rotation != e.rotation, &|| {
                d.rotation.to_string()
            }),
            (
                "linear_velocity",
                "Velocity",
                d.linear_velocity != e.linear_velocity,
                &|| d.linear_velocity.to_string(),
            ),
            (
                "angular_velocity",
                "Velocity",
                d.angular_velocity != e.angular_velocity,
                &|| d.angular_velocity.to_string(),
            ),
            ("sleeping", "Sleeping", d.sleeping != e.sleeping, &|| {
                d.sleeping.to_string()
            }),
            (
                "mass_properties",
                "MassOverride",
                d.mass_properties != e.mass_properties,
                &|| format!("{:?}", d.mass_properties),
            ),
        ];
        checks
            .into_iter()
            .find(|&(_, _, differs, _)| differs)
            .map(|(field, component, _, value)| (field, value(), component))
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
            position: pose.position,
            rotation: pose.rotation,
            linear_velocity: velocity.linear,
            angular_velocity: velocity.angular,
            sleeping,
            ..self.desc
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
