//! The scalar path: one manifold at a time, every row kind included — the normal rows with the bounce
//! (restitution), the friction patch ([`Patch`]) and rolling resistance ([`Rolling`]). It solves the
//! manifolds the wide path leaves out (a bounce or a rolling block, or no colour left for them), after the
//! wide batches. Stages *prepare* (the points), *warm start*, *solve* and *relax*.

use super::bias::Bias;
use super::manifold::ContactPoint;
use super::patch::Patch;
use super::prepared::{PrepareInput, PreparedContact};
use crate::{BodyParams, SolverBody, StepContext};
use rebound_math::{Mat3, Vec3, rotate_inverse};

/// A point closer than this (m) counts as touching for restitution: a speculative contact closes its gap to
/// rounding error, not always to exactly zero.
const BOUNCE_SLOP: f32 = 5e-3;

/// A prepared contact point: anchors, effective masses, the angular Jacobian terms and the accumulated
/// impulses. The angular terms `r × d` and `I⁻¹·(r × d)` are computed once at prepare so that the solve loop
/// does no matrix products.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct PreparedPoint {
    pub(crate) anchor_a: Vec3,
    pub(crate) anchor_b: Vec3,
    pub(crate) separation: f32,
    /// The most negative normal relative velocity seen before an impulse in any pass of the step since the
    /// point last bounced (m/s); negative when approaching. Restitution reverses it. A bounce resets it to
    /// the velocity it leaves, so the contact is then an ordinary one until the bodies approach again: a
    /// bounce is one event per approach (otherwise a ball that handed its momentum on would be pushed again),
    /// and a second approach in the same step — the next ball of a row arriving — bounces again.
    pub(crate) relative_velocity: f32,
    pub(crate) normal_impulse: f32,
    pub(crate) max_normal_impulse: f32,
    /// What the point pushed with at its bounce beyond its accumulated impulse (N·s; 0 until it bounces): the
    /// bounce's impulse plus the warm-start impulse the bounce forgot (both kept out of `normal_impulse`).
    pub(crate) bounce_impulse: f32,
    pub(crate) normal_mass: f32,
    /// The point's distance from its manifold's patch centre (m): its lever against twist.
    pub(crate) twist_radius: f32,
    pub(crate) rn_a: Vec3,
    pub(crate) rn_b: Vec3,
    pub(crate) wn_a: Vec3,
    pub(crate) wn_b: Vec3,
}

impl PreparedPoint {
    /// The prepared form of `point`, a point of manifold `c` whose patch centre is `center_a`: anchors, angular
    /// Jacobian terms, effective mass, twist lever, the warm-start normal impulse and the separation, less
    /// the load's shift of the rest point. The pre-step normal
    /// velocity, which only a bounce reads, is left at 0 (see [`PreparedPoint::with_approach`]).
    #[inline]
    pub(crate) fn new(
        input: &PrepareInput<'_>,
        c: &PreparedContact,
        point: &ContactPoint,
        center_a: Vec3,
    ) -> Self {
        let (pa, pb) = (&input.params[c.body_a], &input.params[c.body_b]);
        let normal = c.normal;
        let (ra, rb) = (point.anchor_a, point.anchor_b);
        let rn_a = ra.cross(normal);
        let rn_b = rb.cross(normal);
        let wn_a = pa.inv_inertia_world * rn_a;
        let wn_b = pb.inv_inertia_world * rn_b;
        let k_normal = pa.inv_mass + pb.inv_mass + rn_a.dot(wn_a) + rn_b.dot(wn_b);
        let rho = ra - center_a;
        let normal_mass = if k_normal > 0.0 { 1.0 / k_normal } else { 0.0 };
        Self {
            anchor_a: ra,
            anchor_b: rb,
            // A loaded point's rest point moved into the overlap ([`PreparedContact::load_shift`]).
            separation: point.separation - c.load_shift(k_normal, input.ctx),
            relative_velocity: 0.0,
            normal_impulse: if input.ctx.warm_starting {
                point.normal_impulse
            } else {
                0.0
            },
            max_normal_impulse: 0.0,
            bounce_impulse: 0.0,
            normal_mass,
            twist_radius: rho.dot(rho).sqrt(),
            rn_a,
            rn_b,
            wn_a,
            wn_b,
        }
    }

    /// [`PreparedPoint::new`] with the pre-step normal velocity, for the scalar path (which bounces).
    #[inline]
    pub(crate) fn with_approach(
        input: &PrepareInput<'_>,
        c: &PreparedContact,
        point: &ContactPoint,
        center_a: Vec3,
    ) -> Self {
        let (sa, sb) = (&input.bodies[c.body_a], &input.bodies[c.body_b]);
        let dv = sb.velocity_at(point.anchor_b) - sa.velocity_at(point.anchor_a);
        Self {
            relative_velocity: dv.dot(c.normal),
            ..Self::new(input, c, point, center_a)
        }
    }
}

/// The rolling-resistance block of a manifold: an angular constraint `ω_b − ω_a = 0` whose accumulated
/// impulse is clamped to `rolling_friction × Σλ_n`. Effective mass `(I_a⁻¹ + I_b⁻¹)⁻¹`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Rolling {
    pub(crate) friction: f32,
    pub(crate) impulse: Vec3,
    pub(crate) mass: Mat3,
    pub(crate) inv_inertia_a: Mat3,
    pub(crate) inv_inertia_b: Mat3,
}

impl Rolling {
    /// Stage *prepare*: the rolling block of a manifold with lever arm `friction` (m) between bodies with
    /// parameters `pa` and `pb`, with no impulse yet.
    #[inline]
    pub(crate) fn new(friction: f32, pa: &BodyParams, pb: &BodyParams) -> Self {
        Self {
            friction,
            impulse: Vec3::ZERO,
            mass: angular_mass(pa.inv_inertia_world + pb.inv_inertia_world),
            inv_inertia_a: pa.inv_inertia_world,
            inv_inertia_b: pb.inv_inertia_world,
        }
    }
}

/// Stage *warm start* for manifold `c` with points `points`, its friction patch and its rolling block: applies
/// the accumulated impulses of the last substep (or the last step) again.
#[inline]
pub(crate) fn warm_start(
    c: &PreparedContact,
    points: &[PreparedPoint],
    patch: Option<&Patch>,
    rolling: Option<&Rolling>,
    bodies: &mut [SolverBody],
) {
    let (mut a, mut b) = (bodies[c.body_a], bodies[c.body_b]);
    // All normal impulses act along n: their sum moves the linear velocities once (as the wide path).
    let mut pushed = 0.0;
    for p in points {
        pushed += p.normal_impulse;
        a.angular_velocity -= p.wn_a * p.normal_impulse;
        b.angular_velocity += p.wn_b * p.normal_impulse;
    }
    a.linear_velocity -= c.normal * (pushed * c.inv_mass_a);
    b.linear_velocity += c.normal * (pushed * c.inv_mass_b);
    if let Some(patch) = patch {
        patch.warm_start(c, &mut a, &mut b);
    }
    if let Some(r) = rolling {
        a.angular_velocity -= r.inv_inertia_a * r.impulse;
        b.angular_velocity += r.inv_inertia_b * r.impulse;
    }
    write_pair(bodies, c.body_a, a, c.body_b, b);
}

/// Stages *solve* (`Bias::On`) and *relax* (`Bias::Off`) for manifold `c` with points `points`, its friction
/// patch and its rolling block: one Gauss–Seidel pass of its normal rows (a point that hits fast enough
/// bounces instead, once per approach), then the patch, limited by this pass's normal impulses, then the rolling
/// block, limited likewise.
#[inline]
pub(crate) fn solve(
    c: &PreparedContact,
    points: &mut [PreparedPoint],
    patch: Option<&mut Patch>,
    rolling: Option<&mut Rolling>,
    bodies: &mut [SolverBody],
    ctx: &StepContext,
    bias: Bias,
) {
    let (mut a, mut b) = (bodies[c.body_a], bodies[c.body_b]);
    let normal = c.normal;
    let shift = normal.dot(b.delta_position - a.delta_position);
    let turn_a = rotate_inverse(a.delta_rotation, normal) - normal;
    let turn_b = rotate_inverse(b.delta_rotation, normal) - normal;
    // Σλ_n and Σλ_n·|ρ| after the normal rows: the friction patch's limits.
    let (mut total, mut twist_total) = (0.0, 0.0);
    // The normal rows change the linear velocities only along n: carry `u = n·(v_b − v_a)` and the
    // sum of the applied impulses, applied to the velocities once after the rows (as the wide path).
    let mut u = normal.dot(b.linear_velocity - a.linear_velocity);
    let u_gain = (c.inv_mass_a + c.inv_mass_b) * normal.dot(normal);
    let mut pushed = 0.0;
    for p in points.iter_mut() {
        let s = p.separation + shift + turn_b.dot(p.anchor_b) - turn_a.dot(p.anchor_a);
        let vn = u + b.angular_velocity.dot(p.rn_b) - a.angular_velocity.dot(p.rn_a);
        // The approach speed restitution reverses is the fastest seen before an impulse acted, in any
        // pass: a falling body keeps accelerating after the step began, and a ball struck by its
        // neighbour in a row approaches the next only once struck.
        p.relative_velocity = p.relative_velocity.min(vn);
        let approach = -p.relative_velocity;
        let bounce = if c.restitution > 0.0 && approach > ctx.restitution_threshold {
            c.restitution * approach
        } else {
            0.0
        };
        // A bounce starts when the bodies touch. Between two moving bodies it starts already in the
        // substep that will close the gap: a speculative impulse there would share momentum
        // inelastically before the bounce, and a row of balls (Newton's cradle) would move as one.
        // The price is a bounce up to |v|·h early, under 1 cm at 2 m/s and 4 substeps.
        let closes_now = c.both_dynamic && s + vn * ctx.h <= 0.0;
        if bounce > 0.0 && (s <= BOUNCE_SLOP || closes_now) {
            // The bounce: one impulse that sets the normal velocity to +C_r·approach. It is kept out
            // of the accumulated impulse (which restarts at 0), so the later passes of the step —
            // relax, the next substeps' warm start — see a separating contact and leave it alone
            // instead of taking the bounce back; and the approach is measured afresh from the velocity
            // the bounce leaves. What was accumulated before it joins the step's bounce impulse.
            p.relative_velocity = bounce;
            p.bounce_impulse += p.normal_impulse;
            p.normal_impulse = 0.0;
            let impulse = (-p.normal_mass * (vn - bounce)).max(0.0);
            p.max_normal_impulse = p.max_normal_impulse.max(impulse);
            p.bounce_impulse += impulse;
            pushed += impulse;
            u += impulse * u_gain;
            a.angular_velocity -= p.wn_a * impulse;
            b.angular_velocity += p.wn_b * impulse;
            continue;
        }
        let (velocity_bias, mass_scale, impulse_scale) = if s > 0.0 {
            (s * ctx.inv_h, 1.0, 0.0)
        } else if bias == Bias::On {
            (
                (c.softness.bias_rate * s).max(-c.max_push_out_speed),
                c.softness.mass_scale,
                c.softness.impulse_scale,
            )
        } else {
            (0.0, 1.0, 0.0)
        };
        let delta =
            -p.normal_mass * mass_scale * (vn + velocity_bias) - impulse_scale * p.normal_impulse;
        let accumulated = (p.normal_impulse + delta).max(0.0);
        let applied = accumulated - p.normal_impulse;
        p.normal_impulse = accumulated;
        total += accumulated;
        twist_total += accumulated * p.twist_radius;
        p.max_normal_impulse = p.max_normal_impulse.max(applied);
        pushed += applied;
        u += applied * u_gain;
        a.angular_velocity -= p.wn_a * applied;
        b.angular_velocity += p.wn_b * applied;
    }
    a.linear_velocity -= normal * (pushed * c.inv_mass_a);
    b.linear_velocity += normal * (pushed * c.inv_mass_b);
    if let Some(patch) = patch {
        patch.solve(c, &mut a, &mut b, total, twist_total);
    }
    if let Some(r) = rolling {
        let total_normal = total;
        let candidate = r.impulse - r.mass * (b.angular_velocity - a.angular_velocity);
        let accumulated = candidate.clamp_length_max(r.friction * total_normal);
        let applied = accumulated - r.impulse;
        r.impulse = accumulated;
        a.angular_velocity -= r.inv_inertia_a * applied;
        b.angular_velocity += r.inv_inertia_b * applied;
    }
    write_pair(bodies, c.body_a, a, c.body_b, b);
}

/// The effective mass of an angular constraint, `K⁻¹`; a singular `K` (both bodies unable to turn about some
/// axis) inverts per axis with zero for the locked directions.
fn angular_mass(k: Mat3) -> Mat3 {
    let det = k.determinant();
    if det > f32::MIN_POSITIVE && det.is_finite() {
        return k.inverse();
    }
    let invert = |v: f32| if v > 0.0 { 1.0 / v } else { 0.0 };
    Mat3::from_diagonal(Vec3::new(
        invert(k.x_axis.x),
        invert(k.y_axis.y),
        invert(k.z_axis.z),
    ))
}

/// Writes two solver bodies back. A fixed body's copy is written too, unchanged (its inverse mass and inertia
/// are zero, so nothing was added); when both indices are equal the second write wins, which is only
/// reachable with a malformed contact.
#[inline]
fn write_pair(bodies: &mut [SolverBody], ia: usize, a: SolverBody, ib: usize, b: SolverBody) {
    bodies[ia] = a;
    bodies[ib] = b;
}
