//! Rigid bodies: the body types, their description (`BodyDesc`) and state (`RigidBody`), force and impulse
//! application. Bodies are read into the solver at *prepare* and written back after the substeps.

use crate::{DynamicsError, LockedAxes, MassProperties};
use rebound_math::validity::{check_finite, check_finite_vec3, check_non_negative, check_rotation};
use rebound_math::{Mat3, Pose, Quat, Vec3, inertia};

/// How a body takes part in the simulation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum BodyType {
    /// Moved by forces, gravity, contacts and constraints. Default.
    #[default]
    Dynamic,
    /// Never moves: infinite mass (inverse mass 0), zero velocity. Ground, walls.
    Fixed,
    /// Moved by the user through its velocity; pushes dynamic bodies and is not pushed back (inverse mass 0).
    Kinematic,
}

/// How a body's state is advanced over a substep of length `h`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Integrator {
    /// Semi-implicit (symplectic) Euler: `v ← v + a·h`, then `x ← x + v·h` with the new velocity, after the
    /// constraints have corrected it. Energy stays bounded; the engine's default.
    #[default]
    SemiImplicitEuler,
    /// The course's explicit Euler: `x ← x + v·h` with the old velocity, then `v ← v + a·h`. Gains energy
    /// every step (a free orbit spirals out); it is here to teach and to compare. Constraint corrections
    /// reach the position only in the next substep.
    ExplicitEuler,
}

/// A body's settings: public fields with [`Default`], plus `with_*` sugar.
///
/// ```
/// use rebound_dynamics::{BodyDesc, RigidBody};
/// use rebound_math::Vec3;
/// let desc = BodyDesc::dynamic().with_position(Vec3::new(0.0, 4.0, 0.0)).with_linear_damping(0.1);
/// let body = RigidBody::new(&desc)?;
/// assert_eq!(body.position(), Vec3::new(0.0, 4.0, 0.0));
/// # Ok::<(), rebound_dynamics::DynamicsError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(
    feature = "serde",
    derive(serde::Serialize, serde::Deserialize),
    serde(remote = "Self")
)]
// Missing fields take their defaults, so a scene file names only what differs.
#[cfg_attr(feature = "serde", serde(default))]
pub struct BodyDesc {
    /// Dynamic, fixed or kinematic. Default: dynamic.
    pub body_type: BodyType,
    /// Position of the body origin in world space (m). Default: origin.
    pub position: Vec3,
    /// Orientation, a unit quaternion. Default: identity.
    pub rotation: Quat,
    /// Velocity of the centre of mass (m/s). Default: zero.
    pub linear_velocity: Vec3,
    /// Angular velocity in world space (rad/s). Default: zero.
    pub angular_velocity: Vec3,
    /// Mass, centre of mass and inertia. Default: [`MassProperties::default`] (1 kg ball of radius 0.5 m).
    /// Ignored by the solver for fixed and kinematic bodies, which have infinite mass.
    pub mass_properties: MassProperties,
    /// Multiplier on the world's gravity (dimensionless; may be negative or 0). Default: 1.0.
    pub gravity_scale: f32,
    /// Linear damping coefficient c (1/s): `v ← v / (1 + c·h)` each substep. Default: 0.0.
    pub linear_damping: f32,
    /// Angular damping coefficient (1/s), as `linear_damping` for ω. Default: 0.0.
    pub angular_damping: f32,
    /// The integrator. Default: semi-implicit Euler.
    pub integrator: Integrator,
    /// Whether the gyroscopic term `ω × I·ω` is integrated (implicitly). Without it a spinning asymmetric
    /// body does not conserve angular momentum. Default: true.
    pub gyroscopic: bool,
    /// Whether the body starts asleep. Default: false.
    pub sleeping: bool,
    /// Whether the body may fall asleep when it comes to rest. Default: true.
    pub can_sleep: bool,
    /// World axes along which the body may not translate or about which it may not turn; their velocity
    /// components stay exactly zero ([`LockedAxes`]). Default: none.
    pub locked_axes: LockedAxes,
}

impl Default for BodyDesc {
    fn default() -> Self {
        Self {
            body_type: BodyType::Dynamic,
            position: Vec3::ZERO,
            rotation: Quat::IDENTITY,
            linear_velocity: Vec3::ZERO,
            angular_velocity: Vec3::ZERO,
            mass_properties: MassProperties::default(),
            gravity_scale: 1.0,
            linear_damping: 0.0,
            angular_damping: 0.0,
            integrator: Integrator::SemiImplicitEuler,
            gyroscopic: true,
            sleeping: false,
            can_sleep: true,
            locked_axes: LockedAxes::NONE,
        }
    }
}

rebound_math::checked_serde!(remote_self BodyDesc, BodyDesc::validated);

impl BodyDesc {
    /// Returns `self` if [`RigidBody::new`] accepts it (the check of a deserialised description).
    ///
    /// # Errors
    /// As [`RigidBody::new`].
    pub fn validated(self) -> Result<Self, DynamicsError> {
        RigidBody::new(&self)?;
        Ok(self)
    }

    /// A dynamic body with the defaults.
    #[must_use]
    pub fn dynamic() -> Self {
        Self::default()
    }

    /// A fixed (immovable) body.
    #[must_use]
    pub fn fixed() -> Self {
        Self {
            body_type: BodyType::Fixed,
            ..Self::default()
        }
    }

    /// A kinematic body, moved by its velocity.
    #[must_use]
    pub fn kinematic() -> Self {
        Self {
            body_type: BodyType::Kinematic,
            ..Self::default()
        }
    }

    /// Sets the position (m).
    #[must_use]
    pub const fn with_position(mut self, position: Vec3) -> Self {
        self.position = position;
        self
    }

    /// Sets the orientation (unit quaternion).
    #[must_use]
    pub const fn with_rotation(mut self, rotation: Quat) -> Self {
        self.rotation = rotation;
        self
    }

    /// Sets the linear velocity (m/s).
    #[must_use]
    pub const fn with_linear_velocity(mut self, velocity: Vec3) -> Self {
        self.linear_velocity = velocity;
        self
    }

    /// Sets the angular velocity (rad/s, world space).
    #[must_use]
    pub const fn with_angular_velocity(mut self, velocity: Vec3) -> Self {
        self.angular_velocity = velocity;
        self
    }

    /// Sets the mass properties.
    #[must_use]
    pub const fn with_mass_properties(mut self, mass_properties: MassProperties) -> Self {
        self.mass_properties = mass_properties;
        self
    }

    /// Sets the gravity scale.
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

    /// Sets the integrator.
    #[must_use]
    pub const fn with_integrator(mut self, integrator: Integrator) -> Self {
        self.integrator = integrator;
        self
    }

    /// Turns the gyroscopic term on or off.
    #[must_use]
    pub const fn with_gyroscopic(mut self, gyroscopic: bool) -> Self {
        self.gyroscopic = gyroscopic;
        self
    }

    /// Sets whether the body may sleep.
    #[must_use]
    pub const fn with_can_sleep(mut self, can_sleep: bool) -> Self {
        self.can_sleep = can_sleep;
        self
    }

    /// Sets the locked axes.
    #[must_use]
    pub const fn with_locked_axes(mut self, locked_axes: LockedAxes) -> Self {
        self.locked_axes = locked_axes;
        self
    }
}

rebound_math::checked_serde! { "RigidBody", RigidBody::validated;
/// A rigid body's state. Built from a [`BodyDesc`] by [`RigidBody::new`], which checks every field; every
/// setter checks its input and changes nothing on error; a deserialised body passes
/// [`RigidBody::validated`].
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct RigidBody {
    body_type: BodyType,
    pose: Pose,
    linear_velocity: Vec3,
    angular_velocity: Vec3,
    force: Vec3,
    torque: Vec3,
    mass_properties: MassProperties,
    gravity_scale: f32,
    linear_damping: f32,
    angular_damping: f32,
    integrator: Integrator,
    gyroscopic: bool,
    sleeping: bool,
    can_sleep: bool,
    #[cfg_attr(feature = "serde", serde(default))]
    locked_axes: LockedAxes,
}
}

/// `accumulated + added`, if finite.
fn checked_sum(field: &'static str, accumulated: Vec3, added: Vec3) -> Result<Vec3, DynamicsError> {
    let sum = accumulated + added;
    if sum.is_finite() {
        Ok(sum)
    } else {
        Err(DynamicsError::AccumulatedNotFinite {
            field,
            accumulated,
            added,
        })
    }
}

impl RigidBody {
    /// A body from its description.
    ///
    /// # Errors
    /// Non-finite position, velocities or gravity scale; a non-unit rotation; negative or non-finite damping;
    /// invalid mass properties ([`MassProperties::validated`]) — each as a [`DynamicsError`] naming the field.
    pub fn new(desc: &BodyDesc) -> Result<Self, DynamicsError> {
        desc.mass_properties.validated()?;
        check_finite_vec3("position", desc.position)?;
        check_rotation("rotation", desc.rotation)?;
        check_finite_vec3("linear_velocity", desc.linear_velocity)?;
        check_finite_vec3("angular_velocity", desc.angular_velocity)?;
        check_finite("gravity_scale", desc.gravity_scale)?;
        check_non_negative("linear_damping", desc.linear_damping)?;
        check_non_negative("angular_damping", desc.angular_damping)?;
        let moves = desc.body_type != BodyType::Fixed;
        let locks = desc.locked_axes;
        Ok(Self {
            body_type: desc.body_type,
            pose: Pose::new(desc.position, desc.rotation.normalize()),
            linear_velocity: if moves {
                locks.lock_linear(desc.linear_velocity)
            } else {
                Vec3::ZERO
            },
            angular_velocity: if moves {
                locks.lock_angular(desc.angular_velocity)
            } else {
                Vec3::ZERO
            },
            force: Vec3::ZERO,
            torque: Vec3::ZERO,
            mass_properties: desc.mass_properties,
            gravity_scale: desc.gravity_scale,
            linear_damping: desc.linear_damping,
            angular_damping: desc.angular_damping,
            integrator: desc.integrator,
            gyroscopic: desc.gyroscopic,
            sleeping: desc.sleeping,
            can_sleep: desc.can_sleep,
            locked_axes: locks,
        })
    }

    /// Returns `self` if every field passes the checks of [`RigidBody::new`] and the setters — a finite pose
    /// with a unit rotation, finite velocities, force and torque, valid mass properties, a finite gravity
    /// scale, finite non-negative damping: the one check of a body from outside the constructors
    /// (deserialised, or a snapshot being restored).
    ///
    /// # Errors
    /// The first invalid field, by name.
    pub fn validated(self) -> Result<Self, DynamicsError> {
        self.mass_properties.validated()?;
        check_finite_vec3("position", self.pose.position)?;
        check_rotation("rotation", self.pose.rotation)?;
        check_finite_vec3("linear_velocity", self.linear_velocity)?;
        check_finite_vec3("angular_velocity", self.angular_velocity)?;
        check_finite_vec3("force", self.force)?;
        check_finite_vec3("torque", self.torque)?;
        check_finite("gravity_scale", self.gravity_scale)?;
        check_non_negative("linear_damping", self.linear_damping)?;
        check_non_negative("angular_damping", self.angular_damping)?;
        Ok(self)
    }

    /// The body type.
    #[must_use]
    pub const fn body_type(&self) -> BodyType {
        self.body_type
    }

    /// Whether forces, gravity and impulses move this body (dynamic bodies only).
    #[must_use]
    pub fn is_dynamic(&self) -> bool {
        self.body_type == BodyType::Dynamic
    }

    /// The pose of the body origin.
    #[must_use]
    pub const fn pose(&self) -> Pose {
        self.pose
    }

    /// Position of the body origin (m).
    #[must_use]
    pub const fn position(&self) -> Vec3 {
        self.pose.position
    }

    /// Orientation (unit quaternion).
    #[must_use]
    pub const fn rotation(&self) -> Quat {
        self.pose.rotation
    }

    /// Centre of mass in world space (m).
    #[must_use]
    pub fn center_of_mass(&self) -> Vec3 {
        let local = self.mass_properties.local_center_of_mass();
        // Most bodies are centred on their centre of mass (every primitive shape is): no rotation to do.
        if local == Vec3::ZERO {
            return self.pose.position;
        }
        self.pose.transform_point(local)
    }

    /// Velocity of the centre of mass (m/s).
    #[must_use]
    pub const fn linear_velocity(&self) -> Vec3 {
        self.linear_velocity
    }

    /// Angular velocity, world space (rad/s).
    #[must_use]
    pub const fn angular_velocity(&self) -> Vec3 {
        self.angular_velocity
    }

    /// Velocity of the material point at `world_point` (m/s): `v + ω × (p − c)`.
    #[must_use]
    pub fn velocity_at_point(&self, world_point: Vec3) -> Vec3 {
        self.velocity_at_offset(world_point - self.center_of_mass())
    }

    /// Velocity of the material point at `offset` (m, world axes) from the centre of mass (m/s): `v + ω × r`.
    /// [`RigidBody::velocity_at_point`] without finding the centre of mass again, for a caller that reads
    /// several points of one body.
    #[must_use]
    pub fn velocity_at_offset(&self, offset: Vec3) -> Vec3 {
        self.linear_velocity + self.angular_velocity.cross(offset)
    }

    /// Accumulated force this step (N, world space); cleared after each step.
    #[must_use]
    pub const fn force(&self) -> Vec3 {
        self.force
    }

    /// Accumulated torque about the centre of mass this step (N·m, world space); cleared after each step.
    #[must_use]
    pub const fn torque(&self) -> Vec3 {
        self.torque
    }

    /// Mass properties as given (also for fixed and kinematic bodies, whose solver mass is infinite).
    #[must_use]
    pub const fn mass_properties(&self) -> &MassProperties {
        &self.mass_properties
    }

    /// Inverse mass seen by the solver (1/kg): 0 for fixed and kinematic bodies.
    #[must_use]
    pub fn inv_mass(&self) -> f32 {
        if self.is_dynamic() {
            self.mass_properties.inv_mass()
        } else {
            0.0
        }
    }

    /// Inverse inertia in the body frame seen by the solver (1/(kg·m²)): 0 for fixed and kinematic bodies.
    #[must_use]
    pub fn local_inv_inertia(&self) -> Mat3 {
        if self.is_dynamic() {
            self.mass_properties.local_inv_inertia()
        } else {
            Mat3::ZERO
        }
    }

    /// Inverse inertia in world space, `R·I⁻¹·Rᵀ` (1/(kg·m²)).
    #[must_use]
    pub fn inv_inertia_world(&self) -> Mat3 {
        inertia::rotate_inertia(self.pose.rotation, self.local_inv_inertia())
    }

    /// Inertia tensor in world space about the centre of mass, `R·I·Rᵀ` (kg·m²).
    #[must_use]
    pub fn inertia_world(&self) -> Mat3 {
        inertia::rotate_inertia(self.pose.rotation, self.mass_properties.local_inertia())
    }

    /// Gravity scale (dimensionless).
    #[must_use]
    pub const fn gravity_scale(&self) -> f32 {
        self.gravity_scale
    }

    /// Linear damping (1/s).
    #[must_use]
    pub const fn linear_damping(&self) -> f32 {
        self.linear_damping
    }

    /// Angular damping (1/s).
    #[must_use]
    pub const fn angular_damping(&self) -> f32 {
        self.angular_damping
    }

    /// The integrator.
    #[must_use]
    pub const fn integrator(&self) -> Integrator {
        self.integrator
    }

    /// Whether the gyroscopic term is integrated.
    #[must_use]
    pub const fn gyroscopic(&self) -> bool {
        self.gyroscopic
    }

    /// Whether the body is asleep.
    #[must_use]
    pub const fn is_sleeping(&self) -> bool {
        self.sleeping
    }

    /// Whether the body may fall asleep.
    #[must_use]
    pub const fn can_sleep(&self) -> bool {
        self.can_sleep
    }

    /// Puts the body to sleep or wakes it. A sleeping body keeps its state; the world skips it.
    pub fn set_sleeping(&mut self, sleeping: bool) {
        self.sleeping = sleeping;
    }

    /// Sets whether the body may fall asleep.
    pub fn set_can_sleep(&mut self, can_sleep: bool) {
        self.can_sleep = can_sleep;
    }

    /// The locked world axes ([`LockedAxes`]).
    #[must_use]
    pub const fn locked_axes(&self) -> LockedAxes {
        self.locked_axes
    }

    /// Locks (or unlocks) world axes; the velocity components along newly locked axes become zero. Wakes the
    /// body.
    pub fn set_locked_axes(&mut self, locked_axes: LockedAxes) {
        self.locked_axes = locked_axes;
        self.linear_velocity = locked_axes.lock_linear(self.linear_velocity);
        self.angular_velocity = locked_axes.lock_angular(self.angular_velocity);
        self.sleeping = false;
    }

    /// Changes the body type. Becoming fixed zeroes the velocities; wakes the body.
    pub fn set_body_type(&mut self, body_type: BodyType) {
        self.body_type = body_type;
        if body_type == BodyType::Fixed {
            self.linear_velocity = Vec3::ZERO;
            self.angular_velocity = Vec3::ZERO;
        }
        self.sleeping = false;
    }

    /// Teleports the body origin to `position` (m); wakes the body.
    ///
    /// # Errors
    /// Non-finite `position`.
    pub fn set_position(&mut self, position: Vec3) -> Result<(), DynamicsError> {
        self.pose.position = check_finite_vec3("position", position)?;
        self.sleeping = false;
        Ok(())
    }

    /// Sets the orientation; wakes the body.
    ///
    /// # Errors
    /// A non-finite or non-unit `rotation`.
    pub fn set_rotation(&mut self, rotation: Quat) -> Result<(), DynamicsError> {
        self.pose.rotation = check_rotation("rotation", rotation)?.normalize();
        self.sleeping = false;
        Ok(())
    }

    /// Sets the pose; wakes the body.
    ///
    /// # Errors
    /// As [`RigidBody::set_position`] and [`RigidBody::set_rotation`]; nothing changes on error.
    pub fn set_pose(&mut self, pose: Pose) -> Result<(), DynamicsError> {
        self.pose = Pose::try_new(pose.position, pose.rotation)?;
        self.sleeping = false;
        Ok(())
    }

    /// Sets the velocity of the centre of mass (m/s); ignored (kept zero) for fixed bodies; wakes the body.
    ///
    /// # Errors
    /// Non-finite `velocity`.
    pub fn set_linear_velocity(&mut self, velocity: Vec3) -> Result<(), DynamicsError> {
        check_finite_vec3("linear_velocity", velocity)?;
        if self.body_type != BodyType::Fixed {
            self.linear_velocity = self.locked_axes.lock_linear(velocity);
            self.sleeping = false;
        }
        Ok(())
    }

    /// Sets the angular velocity (rad/s, world space); ignored for fixed bodies; wakes the body.
    ///
    /// # Errors
    /// Non-finite `velocity`.
    pub fn set_angular_velocity(&mut self, velocity: Vec3) -> Result<(), DynamicsError> {
        check_finite_vec3("angular_velocity", velocity)?;
        if self.body_type != BodyType::Fixed {
            self.angular_velocity = self.locked_axes.lock_angular(velocity);
            self.sleeping = false;
        }
        Ok(())
    }

    /// Replaces the mass properties, keeping the body origin in place.
    pub fn set_mass_properties(&mut self, mass_properties: MassProperties) {
        self.mass_properties = mass_properties;
        self.sleeping = false;
    }

    /// Sets the gravity scale.
    ///
    /// # Errors
    /// Non-finite `gravity_scale`.
    pub fn set_gravity_scale(&mut self, gravity_scale: f32) -> Result<(), DynamicsError> {
        self.gravity_scale = check_finite("gravity_scale", gravity_scale)?;
        self.sleeping = false;
        Ok(())
    }

    /// Sets the linear damping (1/s).
    ///
    /// # Errors
    /// Negative or non-finite `linear_damping`.
    pub fn set_linear_damping(&mut self, damping: f32) -> Result<(), DynamicsError> {
        self.linear_damping = check_non_negative("linear_damping", damping)?;
        Ok(())
    }

    /// Sets the angular damping (1/s).
    ///
    /// # Errors
    /// Negative or non-finite `angular_damping`.
    pub fn set_angular_damping(&mut self, damping: f32) -> Result<(), DynamicsError> {
        self.angular_damping = check_non_negative("angular_damping", damping)?;
        Ok(())
    }

    /// Sets the integrator.
    pub fn set_integrator(&mut self, integrator: Integrator) {
        self.integrator = integrator;
    }

    /// Turns the gyroscopic term on or off.
    pub fn set_gyroscopic(&mut self, gyroscopic: bool) {
        self.gyroscopic = gyroscopic;
    }

    /// Adds a force (N) through the centre of mass for the next step (course item 8: `F = m·a`); wakes the
    /// body. Only dynamic bodies respond.
    ///
    /// # Errors
    /// Non-finite `force`; a sum with the force accumulated so far that is not finite
    /// ([`DynamicsError::AccumulatedNotFinite`]). Nothing is added on error.
    pub fn apply_force(&mut self, force: Vec3) -> Result<(), DynamicsError> {
        check_finite_vec3("force", force)?;
        self.force = checked_sum("force", self.force, force)?;
        self.sleeping = false;
        Ok(())
    }

    /// Adds a force (N) applied at `world_point` (m): the force plus the torque `τ = (p − c) × F`.
    ///
    /// # Errors
    /// Non-finite `force` or `world_point`; a torque `(p − c) × F` or a sum with what was accumulated so far
    /// that is not finite ([`DynamicsError::AccumulatedNotFinite`]). Nothing is added on error.
    pub fn apply_force_at_point(
        &mut self,
        force: Vec3,
        world_point: Vec3,
    ) -> Result<(), DynamicsError> {
        check_finite_vec3("force", force)?;
        check_finite_vec3("world_point", world_point)?;
        let torque = (world_point - self.center_of_mass()).cross(force);
        let total_force = checked_sum("force", self.force, force)?;
        let total_torque = checked_sum("torque", self.torque, torque)?;
        (self.force, self.torque) = (total_force, total_torque);
        self.sleeping = false;
        Ok(())
    }

    /// Adds a torque (N·m, world space) for the next step.
    ///
    /// # Errors
    /// Non-finite `torque`; a sum with the torque accumulated so far that is not finite
    /// ([`DynamicsError::AccumulatedNotFinite`]). Nothing is added on error.
    pub fn apply_torque(&mut self, torque: Vec3) -> Result<(), DynamicsError> {
        check_finite_vec3("torque", torque)?;
        self.torque = checked_sum("torque", self.torque, torque)?;
        self.sleeping = false;
        Ok(())
    }

    /// Clears the force and torque accumulators (done after every step).
    pub fn clear_forces(&mut self) {
        self.force = Vec3::ZERO;
        self.torque = Vec3::ZERO;
    }

    /// Applies a linear impulse `J` (N·s) through the centre of mass: `Δv = J/m` at once (course item 8).
    /// Only dynamic bodies respond.
    ///
    /// # Errors
    /// Non-finite `impulse`, or an impulse that would make the velocity non-finite (a huge impulse on a tiny
    /// mass: `linear_velocity` is named); nothing is changed.
    pub fn apply_impulse(&mut self, impulse: Vec3) -> Result<(), DynamicsError> {
        check_finite_vec3("impulse", impulse)?;
        self.linear_velocity = check_finite_vec3(
            "linear_velocity",
            self.linear_velocity + impulse * self.inv_mass(),
        )?;
        self.sleeping = false;
        Ok(())
    }

    /// Applies a linear impulse `J` (N·s) at `world_point` (m): `Δv = J/m`, `Δω = I⁻¹·((p − c) × J)`.
    ///
    /// # Errors
    /// Non-finite `impulse` or `world_point`, or an impulse that would make a velocity non-finite
    /// (`linear_velocity` or `angular_velocity` is named); nothing is changed.
    pub fn apply_impulse_at_point(
        &mut self,
        impulse: Vec3,
        world_point: Vec3,
    ) -> Result<(), DynamicsError> {
        check_finite_vec3("impulse", impulse)?;
        check_finite_vec3("world_point", world_point)?;
        let r = world_point - self.center_of_mass();
        let linear = check_finite_vec3(
            "linear_velocity",
            self.linear_velocity + impulse * self.inv_mass(),
        )?;
        let angular = check_finite_vec3(
            "angular_velocity",
            self.angular_velocity + self.inv_inertia_world() * r.cross(impulse),
        )?;
        (self.linear_velocity, self.angular_velocity) = (linear, angular);
        self.sleeping = false;
        Ok(())
    }

    /// Applies an angular impulse (N·m·s, world space): `Δω = I⁻¹·L`.
    ///
    /// # Errors
    /// Non-finite `impulse`, or one that would make the angular velocity non-finite (`angular_velocity` is
    /// named); nothing is changed.
    pub fn apply_angular_impulse(&mut self, impulse: Vec3) -> Result<(), DynamicsError> {
        check_finite_vec3("angular_impulse", impulse)?;
        self.angular_velocity = check_finite_vec3(
            "angular_velocity",
            self.angular_velocity + self.inv_inertia_world() * impulse,
        )?;
        self.sleeping = false;
        Ok(())
    }

    /// Writes a solver result back: the new pose and velocities. Refuses (and changes nothing) if any of them
    /// is not finite or the rotation is not unit, so a solver fault can never put NaN into a body.
    ///
    /// # Errors
    /// As [`RigidBody::set_pose`], [`RigidBody::set_linear_velocity`], [`RigidBody::set_angular_velocity`].
    #[inline]
    pub fn set_solver_state(
        &mut self,
        pose: Pose,
        linear_velocity: Vec3,
        angular_velocity: Vec3,
    ) -> Result<(), DynamicsError> {
        let pose = Pose::try_new(pose.position, pose.rotation)?;
        check_finite_vec3("linear_velocity", linear_velocity)?;
        check_finite_vec3("angular_velocity", angular_velocity)?;
        self.pose = pose;
        self.linear_velocity = linear_velocity;
        self.angular_velocity = angular_velocity;
        Ok(())
    }
}
