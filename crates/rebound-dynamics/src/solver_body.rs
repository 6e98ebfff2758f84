//! The solver's dense per-body arrays: the hot [`SolverBody`] (velocities and position deltas, touched by
//! every constraint in every iteration) and the colder [`BodyParams`] (mass, forces, damping — read by
//! *prepare* and *integrate velocities* only). Built from [`RigidBody`]s at the start of a step, written back
//! by [`BodyParams::write_back`] at the end.
//!
//! Why deltas: constraints measure their current error from the position change since the step began
//! (`Δp`, `Δq`) rather than from absolute positions, which keeps the error free of the round-off of large
//! coordinates (Box2D v3's `b2BodyState`).

use crate::{BodyType, Integrator, LockedAxes, RigidBody};
use rebound_math::glam::Mat3A;
use rebound_math::{Mat3, Pose, Quat, Vec3, inertia, rotate};

/// The hot state of one body in the solver: 64 bytes, one cache line (`Quat` is 16-byte aligned; the three
/// `Vec3`s take 36 bytes and 12 pad). `#[repr(C)]`: the contact lanes read `[v, ω.x]` and `[ω.y, ω.z, Δp.x,
/// Δp.y]` as 16 contiguous bytes each, in this field order.
///
/// Fixed bodies appear with zero velocity and zero deltas, so the constraint code needs no branch for them.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub struct SolverBody {
    /// Rotation since the start of the step: current orientation = `delta_rotation · rotation₀`.
    pub delta_rotation: Quat,
    /// Velocity of the centre of mass (m/s).
    pub linear_velocity: Vec3,
    /// Angular velocity, world space (rad/s).
    pub angular_velocity: Vec3,
    /// Displacement of the centre of mass since the start of the step (m).
    pub delta_position: Vec3,
}

impl SolverBody {
    /// A body at rest with no displacement (what fixed bodies look like).
    pub const STATIC: Self = Self {
        delta_rotation: Quat::IDENTITY,
        linear_velocity: Vec3::ZERO,
        angular_velocity: Vec3::ZERO,
        delta_position: Vec3::ZERO,
    };

    /// The solver state of `body` at the start of a step.
    ///
    /// A kinematic body's velocity components of −0 enter as +0 (`v + 0`, every other value unchanged). A
    /// contact lane adds `0·λ` to a kinematic body's velocity, which turns −0 into +0 or not depending on the
    /// sign of `λ`; with no −0 to start from, every lane leaves it as it was, so the batches of one colour that
    /// share a kinematic body give the same bits solved one after another or side by side on threads.
    #[must_use]
    pub fn from_body(body: &RigidBody) -> Self {
        let (linear_velocity, angular_velocity) = if body.body_type() == BodyType::Kinematic {
            (
                body.linear_velocity() + Vec3::ZERO,
                body.angular_velocity() + Vec3::ZERO,
            )
        } else {
            (body.linear_velocity(), body.angular_velocity())
        };
        Self {
            delta_rotation: Quat::IDENTITY,
            linear_velocity,
            angular_velocity,
            delta_position: Vec3::ZERO,
        }
    }

    /// Velocity of the material point at `anchor` (relative to the centre of mass): `v + ω × r` (m/s).
    #[inline]
    #[must_use]
    pub fn velocity_at(&self, anchor: Vec3) -> Vec3 {
        self.linear_velocity + self.angular_velocity.cross(anchor)
    }
}

/// How a body moves in the solver, derived from its type and integrator.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Motion {
    /// Does not move.
    Fixed,
    /// Moves with its own velocity; no forces.
    Kinematic,
    /// Forces, gravity and constraints; semi-implicit Euler.
    Dynamic,
    /// Dynamic, integrated with the course's explicit Euler.
    DynamicExplicit,
}

/// The per-step constants of one body that the integrator and the constraint preparation read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BodyParams {
    /// Inverse mass (1/kg); 0 unless dynamic.
    pub inv_mass: f32,
    /// Inverse inertia in world space at the start of the step (1/(kg·m²)); 0 unless dynamic.
    pub inv_inertia_world: Mat3,
    /// Inertia in the body frame (kg·m²), for the gyroscopic term.
    pub local_inertia: Mat3,
    /// Inverse inertia in the body frame (1/(kg·m²)); 0 unless dynamic.
    pub local_inv_inertia: Mat3,
    /// Orientation at the start of the step.
    pub rotation: Quat,
    /// Centre of mass at the start of the step (m).
    pub center_of_mass: Vec3,
    /// Centre of mass in the body frame (m).
    pub local_center_of_mass: Vec3,
    /// Applied force (N).
    pub force: Vec3,
    /// Applied torque (N·m).
    pub torque: Vec3,
    /// Whether `torque` is not zero: integration skips the product with a zero torque.
    pub has_torque: bool,
    /// Gravity scale.
    pub gravity_scale: f32,
    /// Linear damping (1/s).
    pub linear_damping: f32,
    /// Angular damping (1/s).
    pub angular_damping: f32,
    /// How the body moves.
    pub motion: Motion,
    /// Whether the gyroscopic term is integrated.
    pub gyroscopic: bool,
    /// The Frobenius norm of `local_inv_inertia` (1/(kg·m²)), read by the gyroscopic solve to choose its
    /// method; computed only for a body with `gyroscopic` set, 0 otherwise.
    pub inv_inertia_norm: f32,
    /// The world axes the body may not move along or turn about ([`LockedAxes`]).
    pub locks: LockedAxes,
}

/// The Frobenius norm of a body-frame inverse inertia (1/(kg·m²)), in 16-byte columns: a cheap upper bound
/// on its largest eigenvalue, which the gyroscopic solve (`crate::integrate`) reads to choose its method.
/// [`BodyParams::inv_inertia_norm`] is this, computed once per step.
#[inline]
#[must_use]
pub(crate) fn inverse_inertia_norm(local_inv_inertia: &Mat3) -> f32 {
    let m = Mat3A::from(*local_inv_inertia);
    (m.x_axis.length_squared() + m.y_axis.length_squared() + m.z_axis.length_squared()).sqrt()
}

/// The world inverse inertia of a dynamic `body` that may not turn about `locks`' rotation axes: the inverse
/// of its world inertia restricted to the free axes ([`LockedAxes::inv_inertia`]); `None` for other bodies
/// and without rotation locks. Kept out of [`BodyParams::from_body`]'s common path, which it would slow.
#[cold]
#[inline(never)]
fn locked_inv_inertia(body: &RigidBody, locks: LockedAxes) -> Option<Mat3> {
    if !body.is_dynamic() {
        return None;
    }
    // R·I·Rᵀ written out here: a second call site of `rotate_inertia` would keep it from being inlined in the
    // common path.
    let rotation = Mat3::from_quat(body.rotation());
    locks.inv_inertia(rotation * body.mass_properties().local_inertia() * rotation.transpose())
}

impl BodyParams {
    /// A fixed body at the origin with identity rotation: the anchor of constraints attached to a world point.
    pub const WORLD: Self = Self {
        inv_mass: 0.0,
        inv_inertia_world: Mat3::ZERO,
        local_inertia: Mat3::ZERO,
        local_inv_inertia: Mat3::ZERO,
        rotation: Quat::IDENTITY,
        center_of_mass: Vec3::ZERO,
        local_center_of_mass: Vec3::ZERO,
        force: Vec3::ZERO,
        torque: Vec3::ZERO,
        has_torque: false,
        gravity_scale: 0.0,
        linear_damping: 0.0,
        angular_damping: 0.0,
        motion: Motion::Fixed,
        gyroscopic: false,
        inv_inertia_norm: 0.0,
        locks: LockedAxes::NONE,
    };

    /// The constants of `body` for the step about to run.
    #[must_use]
    pub fn from_body(body: &RigidBody) -> Self {
        let motion = match (body.body_type(), body.integrator()) {
            (BodyType::Fixed, _) => Motion::Fixed,
            (BodyType::Kinematic, _) => Motion::Kinematic,
            (BodyType::Dynamic, Integrator::SemiImplicitEuler) => Motion::Dynamic,
            (BodyType::Dynamic, Integrator::ExplicitEuler) => Motion::DynamicExplicit,
        };
        let mass = body.mass_properties();
        // Inverted once (it is not stored): `RigidBody::inv_inertia_world` would invert it again.
        let local_inv_inertia = body.local_inv_inertia();
        let locks = body.locked_axes();
        // An isotropic tensor (a ball, a cube) has an isotropic inverse, the same in every frame: what
        // `rotate_inertia` gives back unchanged, without its test.
        let isotropic = mass.is_isotropic();
        let mut inv_inertia_world = if isotropic {
            local_inv_inertia
        } else {
            inertia::rotate_inertia(body.rotation(), local_inv_inertia)
        };
        if locks.is_any()
            && let Some(locked) = locked_inv_inertia(body, locks)
        {
            inv_inertia_world = locked;
        }
        // ω × I·ω vanishes for an isotropic tensor (balls, cubes): skip the solve, not just the result.
        let gyroscopic = body.gyroscopic() && !isotropic;
        Self {
            inv_mass: body.inv_mass(),
            inv_inertia_world,
            local_inertia: mass.local_inertia(),
            local_inv_inertia,
            rotation: body.rotation(),
            center_of_mass: body.center_of_mass(),
            local_center_of_mass: mass.local_center_of_mass(),
            force: body.force(),
            torque: body.torque(),
            has_torque: body.torque() != Vec3::ZERO,
            gravity_scale: body.gravity_scale(),
            linear_damping: body.linear_damping(),
            angular_damping: body.angular_damping(),
            motion,
            gyroscopic,
            inv_inertia_norm: if gyroscopic {
                inverse_inertia_norm(&local_inv_inertia)
            } else {
                0.0
            },
            locks,
        }
    }

    /// Whether this body is moved by forces and constraints.
    #[inline]
    #[must_use]
    pub fn is_dynamic(&self) -> bool {
        matches!(self.motion, Motion::Dynamic | Motion::DynamicExplicit)
    }

    /// Writes the solver's result into `body`: pose from the deltas, velocities; clears the force
    /// accumulators (the *finalize* stage). Returns `false`, leaving the pose and velocities as they were,
    /// if the result is not finite — which only a solver fault produces; the world reports it.
    #[inline]
    pub fn write_back(&self, state: &SolverBody, body: &mut RigidBody) -> bool {
        body.clear_forces();
        if self.motion == Motion::Fixed {
            return true;
        }
        let rotation = (state.delta_rotation * self.rotation).normalize();
        let center = self.center_of_mass + state.delta_position;
        let position = center - rotate(rotation, self.local_center_of_mass);
        body.set_solver_state(
            Pose::new(position, rotation),
            state.linear_velocity,
            state.angular_velocity,
        )
        .is_ok()
    }
}
