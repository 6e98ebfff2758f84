//! Integration stages of the substep loop: *integrate velocities* (gravity, forces, damping, the gyroscopic
//! term) and *integrate positions*.
//!
//! Semi-implicit (symplectic) Euler per substep `h`:
//!
//! ```text
//! v ← v / (1 + c·h) + h·(F/m + s·g)          damping: implicit, so it never reverses v (Box2D)
//! ω ← gyroscopic(ω) ;  ω ← ω / (1 + c_ω·h) + h·I⁻¹·τ
//! … constraints correct v and ω …
//! Δp ← Δp + h·v ;  Δq ← normalise(Δq + ½·h·(ω, 0)·Δq)
//! ```
//!
//! The gyroscopic term of Euler's equations, `I·ω̇ + ω × I·ω = τ`, is what makes a free body's angular
//! momentum `L = I_w·ω` constant in world space while ω wanders. Rebound integrates it implicitly on the
//! rotation group: with `L = I_w(q)·ω` at the start of the substep and the same first-order rotation update
//! the position stage will apply, it solves
//!
//! ```text
//! ω' = I_w(q')⁻¹·L,    q' = normalise(q + ½·h·(ω', 0)·q)
//! ```
//!
//! by fixed-point iteration (the map contracts by about `h·|ω|`, so two iterations leave an error of order
//! `(h·|ω|)²` of the change). A torque-free body then carries exactly the angular momentum it started the
//! substep with, whatever its spin; backward Euler's small numerical dissipation means kinetic energy can
//! only fall. (An implicit treatment in the spirit of Catto, "Numerical Methods", GDC 2015, and Jolt, which
//! also keep |L| from growing; writing it on the group rather than on ω in the body frame removes the 4 %
//! drift in |L| over 10 s that a body-frame backward-Euler step showed on the `rotation` test.)
//!
//! Without it, ω stays fixed in world space while the inertia turns, so `L` is not conserved (the `rotation`
//! test shows it).

use crate::{BodyParams, Motion, SolverBody, StepContext};
use rebound_math::quat::{RotationIntegrator, integrate_rotation};
use rebound_math::{Mat3, Quat, Vec3};

/// Stage *integrate velocities* of one substep: gravity, applied forces and torques, damping and the
/// gyroscopic term. Explicit-Euler bodies also advance their positions here, with the velocity from before
/// the update.
pub fn integrate_velocities(bodies: &mut [SolverBody], params: &[BodyParams], ctx: &StepContext) {
    debug_assert_eq!(bodies.len(), params.len());
    let h = ctx.h;
    for (state, p) in bodies.iter_mut().zip(params) {
        match p.motion {
            Motion::Fixed | Motion::Kinematic => continue,
            Motion::DynamicExplicit => advance_position(state, h),
            Motion::Dynamic => {}
        }
        let linear_acceleration = p.force * p.inv_mass + ctx.gravity * p.gravity_scale;
        state.linear_velocity =
            state.linear_velocity / (1.0 + h * p.linear_damping) + h * linear_acceleration;

        let mut omega = state.angular_velocity;
        if p.gyroscopic {
            let rotation = state.delta_rotation * p.rotation;
            omega = solve_gyroscopic(omega, rotation, &p.local_inertia, &p.local_inv_inertia, h);
        }
        state.angular_velocity =
            omega / (1.0 + h * p.angular_damping) + h * (p.inv_inertia_world * p.torque);
    }
}

/// Stage *integrate positions* of one substep: `Δp += h·v`, `Δq` by ω (first order). Fixed bodies and
/// explicit-Euler bodies (advanced in [`integrate_velocities`]) are skipped.
pub fn integrate_positions(bodies: &mut [SolverBody], params: &[BodyParams], ctx: &StepContext) {
    debug_assert_eq!(bodies.len(), params.len());
    for (state, p) in bodies.iter_mut().zip(params) {
        if matches!(p.motion, Motion::Dynamic | Motion::Kinematic) {
            advance_position(state, ctx.h);
        }
    }
}

#[inline]
fn advance_position(state: &mut SolverBody, h: f32) {
    state.delta_position += h * state.linear_velocity;
    state.delta_rotation = integrate_rotation(
        state.delta_rotation,
        state.angular_velocity,
        h,
        RotationIntegrator::FirstOrder,
    );
}

/// Fixed-point iterations of the implicit gyroscopic solve.
const GYROSCOPIC_ITERATIONS: usize = 2;

/// The implicit gyroscopic update of one substep (see the module docs): the angular velocity `ω'` that
/// carries the body's angular momentum `L = I_w(q)·ω` unchanged through the rotation the next position
/// update will make. `local_inertia` and `local_inv_inertia` are the body-frame tensors (kg·m² and inverse);
/// a zero inverse along an axis keeps that axis locked.
#[must_use]
pub fn solve_gyroscopic(
    angular_velocity: Vec3,
    rotation: Quat,
    local_inertia: &Mat3,
    local_inv_inertia: &Mat3,
    h: f32,
) -> Vec3 {
    let momentum = rotation * (*local_inertia * (rotation.conjugate() * angular_velocity));
    let mut omega = angular_velocity;
    for _ in 0..GYROSCOPIC_ITERATIONS {
        let next = integrate_rotation(rotation, omega, h, RotationIntegrator::FirstOrder);
        omega = next * (*local_inv_inertia * (next.conjugate() * momentum));
    }
    omega
}
