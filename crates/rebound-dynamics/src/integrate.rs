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
//! by fixed-point iteration where the map contracts fast (its derivative is about `½·h·|I⁻¹|·|L|`, `h·|ω|`
//! times the inertia's anisotropy; two iterations leave an error of order its square of the change), and by
//! Newton's method with a backtracking line search where it does not (a fast spin, a thin rod turning about
//! a skew axis: the plain iteration diverges from about 2 rad per substep). A torque-free body then carries
//! exactly the angular momentum it started the substep with, whatever its spin, and kinetic energy can only
//! fall: for any root, with `E(L) = ½·L·I⁻¹·L` convex and `L_b' = Δ*·L_b·Δ` a turn about `ω' = I⁻¹·L_b'`
//! (which keeps `ω'·L` fixed), `E(L_b) ≥ E(L_b') + ω'·(L_b − L_b') = E(L_b')`. Should the solve stop
//! short of the root, the energy is capped at the substep's start. The dissipation grows with the turn per
//! substep: at 2 rad per substep a middle-axis spin settles onto the major axis (energy falls to
//! `I_mid/I_max` of its start) instead of flipping. (An implicit treatment in the spirit of Catto, "Numerical Methods", GDC 2015, and Jolt, which
//! also keep |L| from growing; writing it on the group rather than on ω in the body frame removes the 4 %
//! drift in |L| over 10 s that a body-frame backward-Euler step showed on the `rotation` test.)
//!
//! Without it, ω stays fixed in world space while the inertia turns, so `L` is not conserved (the `rotation`
//! test shows it).

use crate::solver_body::inverse_inertia_norm;
use crate::{BodyParams, LockedAxes, Motion, SolverBody, StepContext};
use rebound_math::glam::{Mat3A, Vec3A};
use rebound_math::quat::{RotationIntegrator, integrate_rotation};
use rebound_math::{Mat3, Quat, Vec3, par};

/// Stage *integrate velocities* of one substep: gravity, applied forces and torques, damping and the
/// gyroscopic term. Explicit-Euler bodies also advance their positions here, with the velocity from before
/// the update.
pub fn integrate_velocities(bodies: &mut [SolverBody], params: &[BodyParams], ctx: &StepContext) {
    debug_assert_eq!(bodies.len(), params.len());
    par::for_each_zip_mut(bodies, params, par::MIN_ITEMS_PER_TASK, |state, p| {
        integrate_velocity(state, p, ctx);
    });
}

/// [`integrate_velocities`] of one body (`state`, with its `p`), for a caller that splits the bodies itself.
#[inline(always)]
pub fn integrate_velocity(state: &mut SolverBody, p: &BodyParams, ctx: &StepContext) {
    let h = ctx.h;
    match p.motion {
        Motion::Fixed | Motion::Kinematic => return,
        Motion::DynamicExplicit => advance_position(state, h),
        Motion::Dynamic => {}
    }
    // Undamped bodies and bodies under no torque skip the division by 1 and the product with zero: the
    // same bits (`v/1 = v`; `h·(I⁻¹·0)` is +0, which is what the addition of zero adds). In 16-byte vectors,
    // each lane the same operation as alone, and each velocity written once.
    let linear_acceleration =
        Vec3A::from(p.force) * p.inv_mass + Vec3A::from(ctx.gravity) * p.gravity_scale;
    let mut v = Vec3A::from(state.linear_velocity);
    if p.linear_damping != 0.0 {
        v /= 1.0 + h * p.linear_damping;
    }
    let v = v + h * linear_acceleration;

    let mut omega = Vec3A::from(if p.gyroscopic {
        let rotation = state.delta_rotation * p.rotation;
        gyroscopic_iterations_with_norm(
            state.angular_velocity,
            rotation,
            (&p.local_inertia, &p.local_inv_inertia),
            p.inv_inertia_norm,
            h,
            GYROSCOPIC_ITERATIONS,
            true,
        )
    } else {
        state.angular_velocity
    });
    if p.angular_damping != 0.0 {
        omega /= 1.0 + h * p.angular_damping;
    }
    let omega = omega
        + if p.has_torque {
            Vec3A::from(h * (p.inv_inertia_world * p.torque))
        } else {
            Vec3A::ZERO
        };
    state.linear_velocity = flush_tiny(v).into();
    state.angular_velocity = flush_tiny(omega).into();
}

/// Sets the velocity components and the displacement along `locks`' axes to zero (the caller does it after
/// integration and after each constraint pass for the bodies with locks, see [`LockedAxes`]; not done here,
/// so that bodies without locks pay nothing).
#[inline]
pub fn lock_axes(state: &mut SolverBody, locks: LockedAxes) {
    state.linear_velocity = locks.lock_linear(state.linear_velocity);
    state.angular_velocity = locks.lock_angular(state.angular_velocity);
    state.delta_position = locks.lock_linear(state.delta_position);
}

/// Velocity components smaller than this are set to exactly zero (m/s, rad/s): 1e-15 m/s is 3e-8 m a year.
///
/// A body whose motion decays exponentially (damping, a damped spring, friction) with sleeping off would
/// otherwise reach subnormal floats — below 1.2e-38, and their squares and products long before that — where
/// every arithmetic operation on x86 takes a slow microcode path: the springs scene's solve ran twice as long
/// once its springs had settled. Rust gives no safe way to set the processor's flush-to-zero mode.
pub const TINY_SPEED: f32 = 1e-15;

/// `v` with the components smaller than [`TINY_SPEED`] in magnitude set to zero.
#[inline]
fn flush_tiny(v: Vec3A) -> Vec3A {
    Vec3A::select(v.abs().cmplt(Vec3A::splat(TINY_SPEED)), Vec3A::ZERO, v)
}

/// Stage *integrate positions* of one substep: `Δp += h·v`, `Δq` by ω (first order). Fixed bodies and
/// explicit-Euler bodies (advanced in [`integrate_velocities`]) are skipped.
pub fn integrate_positions(bodies: &mut [SolverBody], params: &[BodyParams], ctx: &StepContext) {
    debug_assert_eq!(bodies.len(), params.len());
    par::for_each_zip_mut(bodies, params, par::MIN_ITEMS_PER_TASK, |state, p| {
        integrate_position(state, p, ctx);
    });
}

/// [`integrate_positions`] of one body (`state`, with its `p`), for a caller that splits the bodies itself.
#[inline(always)]
pub fn integrate_position(state: &mut SolverBody, p: &BodyParams, ctx: &StepContext) {
    if matches!(p.motion, Motion::Dynamic | Motion::Kinematic) {
        advance_position(state, ctx.h);
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
    gyroscopic_iterations(
        angular_velocity,
        rotation,
        (local_inertia, local_inv_inertia),
        h,
        GYROSCOPIC_ITERATIONS,
        true,
    )
}

/// [`solve_gyroscopic`] with up to `iterations` fixed-point iterations, stopping after the first once the
/// next could not move ω by an `f32` ulp if `stop_early`.
fn gyroscopic_iterations(
    angular_velocity: Vec3,
    rotation: Quat,
    tensors: (&Mat3, &Mat3),
    h: f32,
    iterations: usize,
    stop_early: bool,
) -> Vec3 {
    gyroscopic_iterations_with_norm(
        angular_velocity,
        rotation,
        tensors,
        inverse_inertia_norm(tensors.1),
        h,
        iterations,
        stop_early,
    )
}

/// [`gyroscopic_iterations`] given the inverse inertia's norm ([`inverse_inertia_norm`]: a cheap upper
/// bound on its largest eigenvalue).
#[inline]
fn gyroscopic_iterations_with_norm(
    angular_velocity: Vec3,
    rotation: Quat,
    (local_inertia, local_inv_inertia): (&Mat3, &Mat3),
    inv_inertia_norm: f32,
    h: f32,
    iterations: usize,
    stop_early: bool,
) -> Vec3 {
    // In the body frame of `q` (vectors `x_b = q*·x·q`): the update `q' = normalise(q + ½·h·(ω, 0)·q)` is
    // `q' = q·Δ` with `Δ = normalise(1, ½·h·ω_b)`, so `I_w(q')⁻¹·L` is `q·(Δ·I⁻¹·(Δ*·L_b·Δ)·Δ*)·q*` — the
    // same iteration with one rotation by `q` in and one out, and only `Δ` to turn by within it.
    // In 16-byte vectors (`Vec3A`, `Mat3A`, each built from three defined components, see
    // [`rebound_math::rotate`]): one SIMD instruction per product where `Vec3` takes three.
    let (inertia, inv_inertia) = (Mat3A::from(*local_inertia), Mat3A::from(*local_inv_inertia));
    let mut omega = rotation.conjugate() * Vec3A::from(angular_velocity);
    let momentum = inertia * omega;
    let half_h = 0.5 * h;
    // The fixed-point map's derivative is about `½·h·|I⁻¹|·|L|` (`h·|ω|` times the inertia's anisotropy):
    // where that is small, plain iterations converge fast; elsewhere (a fast spin, or a thin rod turning
    // about a skew axis) they stop contracting or diverge, and Newton's method takes over.
    let stiffness = half_h * momentum.length() * inv_inertia_norm;
    if stiffness < NEWTON_FROM_STIFFNESS {
        for iteration in 0..iterations {
            let FixedPointIterate { next, x } =
                fixed_point_iteration(omega, momentum, &inv_inertia, half_h);
            // With the anisotropy factor taken as 20, once the next iteration cannot move ω by 6e-8·|ω|
            // (half an f32 ulp of |ω| or less) the first is kept — a body turning slowly (under about
            // 0.01 rad per substep) skips the second, half the solve's dependency chain.
            let change = (next - omega).length_squared();
            omega = next;
            if stop_early
                && iteration == 0
                && change * (4.0 * x) * 400.0 < omega.length_squared() * 3.6e-15
            {
                break;
            }
        }
        return Vec3::from(rotation * omega);
    }
    Vec3::from(rotation * newton_solve(omega, momentum, (&inertia, &inv_inertia), half_h))
}

/// The gyroscopic solve where the fixed-point map does not contract (see
/// [`gyroscopic_iterations_with_norm`]): the body-frame ω' from the substep's `omega` and `momentum` (`L_b`),
/// with the body-frame `inertia` and its inverse. Rare (a fast spin, a thin rod turning about a skew axis):
/// kept out of the common path, which then needs fewer registers.
#[inline(never)]
fn newton_solve(
    mut omega: Vec3A,
    momentum: Vec3A,
    (inertia, inv_inertia): (&Mat3A, &Mat3A),
    half_h: f32,
) -> Vec3A {
    let omega_start_energy = omega.dot(momentum);
    // Newton's method on `F(ω) = ω − I⁻¹·g(ω) = 0`, `g(ω) = Δ(ω)*·L_b·Δ(ω)`, from the substep's ω.
    let mut residual = momentum_residual(omega, momentum, inertia, half_h);
    for _ in 0..NEWTON_ITERATIONS {
        let step = newton_step(omega, momentum, inv_inertia, half_h);
        // Backtracking: a full step far from the root can overshoot where the map is stiff (a thin rod's
        // inertia ratio multiplies `h·|ω|`); halve it until the momentum residual falls.
        let mut scale = 1.0;
        let mut accepted = false;
        for _ in 0..BACKTRACKS {
            let trial = omega - step * scale;
            let r = momentum_residual(trial, momentum, inertia, half_h);
            if r < residual {
                omega = trial;
                residual = r;
                accepted = true;
                break;
            }
            scale *= 0.5;
        }
        if !accepted || (step * scale).length_squared() <= omega.length_squared() * 1e-13 {
            break;
        }
    }
    let next = fixed_point_iteration(omega, momentum, inv_inertia, half_h).next;
    // The exact root never gains kinetic energy (module docs); should the solve stop short of it, the
    // energy is capped at the substep's start (`½·ω·I·ω` in the body frame: the turn `Δ(ω')` is about ω'
    // itself, so the frame of `q` and of `q'` see the same vector).
    let energy_before = omega_start_energy;
    let energy_after = next.dot(*inertia * next);
    if energy_after > energy_before {
        next * (energy_before / energy_after).sqrt()
    } else {
        next
    }
}

/// Estimated derivative of the fixed-point map (dimensionless) from which the gyroscopic solve uses Newton's
/// method: below it two fixed-point iterations leave an error under 0.1² of the first change.
const NEWTON_FROM_STIFFNESS: f32 = 0.1;

/// Most Newton iterations of the gyroscopic solve; it stops once a step moves ω by under 3e-7·|ω|
/// (a few f32 ulps; each step squares the relative error).
const NEWTON_ITERATIONS: usize = 12;

/// Halvings of a Newton step tried before the gyroscopic solve stops.
const BACKTRACKS: usize = 12;

/// `|I·ω − g(ω)|²` (kg²·m⁴/s²), `g(ω) = Δ(ω)*·L_b·Δ(ω)`: zero at the root of the gyroscopic solve.
#[inline]
fn momentum_residual(omega: Vec3A, momentum: Vec3A, inertia: &Mat3A, half_h: f32) -> f32 {
    let u = omega * half_h;
    let k = 2.0 / (1.0 + u.length_squared());
    let c = u.cross(momentum);
    (*inertia * omega - (momentum + k * (u.cross(c) - c))).length_squared()
}

/// One fixed-point iterate of the gyroscopic solve and `x = |½·h·ω|²` of the ω it started from.
struct FixedPointIterate {
    next: Vec3A,
    x: f32,
}

/// `Δ·I⁻¹·(Δ*·L_b·Δ)·Δ*` with `Δ = normalise(1, ½·h·ω_b)`: the angular velocity that carries `L_b` after the
/// turn by `ω` (body frame of the substep's start).
#[inline]
fn fixed_point_iteration(
    omega: Vec3A,
    momentum: Vec3A,
    inv_inertia: &Mat3A,
    half_h: f32,
) -> FixedPointIterate {
    // `Δ = (u, 1)/√s` with `u = ½·h·ω_b`, `s = 1 + |u|²`: turning by the unit quaternion `(u', w')` is
    // `v + 2w'·(u' × v) + 2u' × (u' × v)`, which with `u' = u/√s`, `w' = 1/√s` is
    // `v + (2/s)·(u × v + u × (u × v))` — the normalisation's square root drops out (one division is left,
    // shared by both turns), and `Δ*` only flips the sign of the first cross product.
    // In 16-byte vectors (`Vec3A`, `Mat3A`, each built from three defined components, see
    // [`rebound_math::rotate`]): one SIMD instruction per product where `Vec3` takes three.
    let u = omega * half_h;
    let x = u.length_squared();
    let k = 2.0 / (1.0 + x);
    let turned_back = {
        let c = u.cross(momentum);
        momentum + k * (u.cross(c) - c)
    };
    let next = {
        let v = *inv_inertia * turned_back;
        let c = u.cross(v);
        v + k * (c + u.cross(c))
    };
    FixedPointIterate { next, x }
}

/// The Newton step `J⁻¹·F(ω)` for `F(ω) = ω − I⁻¹·g(ω)`, `g(ω) = L + k·(u × (u × L) − u × L)` (`L` turned
/// back by `Δ(ω)`), `u = ½·h·ω`, `k = 2/(1 + |u|²)`. With `c = u × L`:
/// `∂g/∂u = −k²·(u × c − c)·uᵀ + k·([L]× − [c]× − [u]×·[L]×)`, and `J = 1 − ½·h·I⁻¹·∂g/∂u`. Zero where
/// `J` is singular (the step then keeps the last iterate).
fn newton_step(omega: Vec3A, momentum: Vec3A, inv_inertia: &Mat3A, half_h: f32) -> Vec3A {
    let u = omega * half_h;
    let k = 2.0 / (1.0 + u.length_squared());
    let c = u.cross(momentum);
    let g = momentum + k * (u.cross(c) - c);
    let residual = omega - *inv_inertia * g;
    let skew = |a: Vec3A| {
        Mat3A::from_cols(
            Vec3A::new(0.0, a.z, -a.y),
            Vec3A::new(-a.z, 0.0, a.x),
            Vec3A::new(a.y, -a.x, 0.0),
        )
    };
    let a = (u.cross(c) - c) * (-k * k);
    let outer = Mat3A::from_cols(a * u.x, a * u.y, a * u.z);
    let skew_l = skew(momentum);
    let dg_du = outer + (skew_l - skew(c) - skew(u) * skew_l) * k;
    let jacobian = Mat3A::IDENTITY - (*inv_inertia * dg_du) * half_h;
    let det = jacobian.determinant();
    if !det.is_finite() || det.abs() <= 1e-12 {
        return Vec3A::ZERO;
    }
    jacobian.inverse() * residual
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{BodyDesc, RigidBody, SolverSettings};

    /// The early stop keeps the first iteration only where the second would not move ω: over spins from 1e-4
    /// to 20 rad/s about skew axes of a slab whose moments differ 20-fold, the solve's result is within 2
    /// ulps of |ω| of two full iterations' (and, where it stopped early, of the converged fixed point).
    #[test]
    fn stopping_after_one_gyroscopic_iteration_stays_at_the_fixed_point() {
        let mass =
            crate::MassProperties::cuboid(1.0, Vec3::new(1.0, 0.05, 0.3)).expect("valid box");
        let local_inertia = mass.local_inertia();
        let local_inv_inertia = mass.local_inv_inertia();
        let tensors = (&local_inertia, &local_inv_inertia);
        let rotation = Quat::from_axis_angle(Vec3::new(1.0, 2.0, -0.5).normalize(), 0.7);
        let h = 1.0 / 240.0;
        let mut stopped_early = 0;
        for axis in [
            Vec3::new(0.3, 1.0, 0.2),
            Vec3::new(-1.0, 0.1, 0.4),
            Vec3::new(0.2, -0.3, 1.0),
        ] {
            let mut speed = 1e-4_f32;
            while speed < 20.0 {
                let omega = axis.normalize() * speed;
                let fast = solve_gyroscopic(omega, rotation, &local_inertia, &local_inv_inertia, h);
                let reference = gyroscopic_iterations(omega, rotation, tensors, h, 12, false);
                let two = gyroscopic_iterations(omega, rotation, tensors, h, 2, false);
                let ulps = |other: Vec3| (fast - other).length() / (speed * f32::EPSILON);
                assert!(
                    ulps(two) <= 2.0,
                    "|ω| = {speed}: {} ulps from two iterations",
                    ulps(two)
                );
                if fast != two {
                    stopped_early += 1;
                    let off = ulps(reference);
                    assert!(
                        off <= 2.0,
                        "|ω| = {speed}: stopped {off} ulps from the fixed point"
                    );
                }
                speed *= 1.5;
            }
        }
        // The test must exercise the early stop (slow spins) as well as the second iteration (fast ones).
        assert!(stopped_early > 0, "no spin stopped after one iteration");
        let fast = Vec3::new(0.3, 1.0, 0.2).normalize() * 4.0;
        assert_ne!(
            solve_gyroscopic(fast, rotation, &local_inertia, &local_inv_inertia, h),
            gyroscopic_iterations(fast, rotation, tensors, h, 1, false),
            "a fast spin must take the second iteration"
        );
    }

    /// A damped body coasting with no gravity: its speed decays by `1/(1 + h·c)` per substep. It must reach
    /// exactly zero without ever holding a subnormal component (which costs a microcode assist per operation).
    #[test]
    fn a_decaying_velocity_reaches_zero_without_subnormals() {
        let mut body = RigidBody::new(
            &BodyDesc::dynamic()
                .with_linear_velocity(Vec3::new(1.0, -2.0, 0.5))
                .with_angular_velocity(Vec3::new(0.3, 0.0, -1.0)),
        )
        .expect("valid body");
        body.set_linear_damping(30.0).expect("valid damping");
        body.set_angular_damping(30.0).expect("valid damping");
        let settings = SolverSettings {
            gravity: Vec3::ZERO,
            ..SolverSettings::default()
        };
        let ctx = StepContext::new(1.0 / 60.0, &settings);
        let params = [BodyParams::from_body(&body)];
        let mut states = [SolverBody::from_body(&body)];
        let decay = 1.0 / (1.0 + ctx.h * 30.0);
        // 2.0 m/s · decay^n < 1e-15 m/s after this many substeps; run twice as long.
        let needed = (rebound_math::real::ln(1e-15_f32 / 2.0) / rebound_math::real::ln(decay))
            .ceil() as usize;
        for substep in 0..2 * needed {
            let before = states[0].linear_velocity;
            integrate_velocities(&mut states, &params, &ctx);
            let (v, w) = (states[0].linear_velocity, states[0].angular_velocity);
            for c in v.to_array().into_iter().chain(w.to_array()) {
                assert!(
                    !c.is_subnormal(),
                    "substep {substep}: subnormal component {c:e}"
                );
                assert!(
                    c == 0.0 || c.abs() >= TINY_SPEED,
                    "substep {substep}: {c:e}"
                );
            }
            // Until it is flushed, each component follows the damping law.
            for (now, was) in v.to_array().into_iter().zip(before.to_array()) {
                if now != 0.0 {
                    assert!(
                        (now - was * decay).abs() <= 1e-6 * was.abs(),
                        "{now:e} vs {was:e}"
                    );
                }
            }
        }
        assert_eq!(states[0].linear_velocity, Vec3::ZERO);
        assert_eq!(states[0].angular_velocity, Vec3::ZERO);
    }
}
