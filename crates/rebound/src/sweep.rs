//! The rotational sweep, around the world's step (facade): a body that turns far within one step is swept
//! along its turning path against what lies near it, and stopped where it first touches.
//!
//! Speculative contacts (`crate::prediction`) are found at the start of a step and linearised there: they stop
//! what the bodies close along the contact normal, which is right while a body turns by a small angle in the
//! step. A thin plank spinning at 150 rad/s turns by 2.5 rad per step at 60 Hz: the closest points at the
//! start say nothing about the face that sweeps into a ball a quarter turn later, and the plank passes
//! through it. So, as conservative advancement does (Mirtich 1996; parry's nonlinear shape cast), each body
//! that turns by more than [`crate::prediction::SWEPT_TURN`] in a step is cast along its motion of the step — its start pose
//! carried by its end-of-step velocities, linear and angular — against the colliders in reach, at their
//! end-of-step poses. At the first time of impact `t* < dt` with a collider it did not already push in the
//! step, the body is put back on its path at `t*`, touching, with its velocities unchanged: the next step's
//! contacts see the touch and the solver handles the impact. The body loses `dt − t*` of motion; kinetic
//! energy is untouched (no velocity is changed) and the impact that follows removes energy or keeps it, as
//! its restitution says. A body jointed to another dynamic body is not swept: put back alone while its
//! partner moves on, it would open the joint by their relative motion over `dt − t*`; the joint keeps it
//! with its partner, and the next step's contacts take what it touches.

use crate::backend::ParryBackend;
use crate::shape::{from_parry_pose, to_parry_pose};
use crate::{Collider, ColliderHandle};
use parry3d::bounding_volume::{Aabb, BoundingVolume};
use parry3d::query::{NonlinearRigidMotion, ShapeCastStatus};
use rebound_dynamics::RigidBody;
use rebound_math::Pose;
use rebound_world::{BodyHandle, BodySet, ContactManifold};

/// The sweep's buffers, reused from step to step (a step that sweeps nothing touches none of them).
#[derive(Debug, Default)]
pub(crate) struct SweepScratch {
    /// The bodies held by a joint to another dynamic body ([`tied_bodies`]).
    tied: Vec<BodyHandle>,
    /// The bodies to sweep this step and their start poses (the broad phase's list).
    spinning: Vec<(BodyHandle, Pose)>,
    /// Bodies a swept body pushed in the step (their contacts handle them).
    pushed: Vec<BodyHandle>,
    /// Colliders whose boxes meet a swept box.
    candidates: Vec<ColliderHandle>,
}

/// The length of the cast's time interval (in the cast's own time unit). Parry's nonlinear cast advances by
/// at least its time tolerance (`10 · f32::EPSILON` ≈ 1.2·10⁻⁶) per round or stops, and bisects a time
/// range down to that tolerance, both in absolute time; over `[0, dt]` its rounds are bounded only by
/// `dt / 1.2·10⁻⁶` (10⁵ rounds, each a GJK query, for one pair in a step of 0.1 s). So the step's motion
/// is cast over `[0, CAST_SPAN]` with its velocities scaled by `dt / CAST_SPAN`: the same path, at most
/// about 1,000 rounds per pair, and a time of impact resolved to 0.1 % of the step.
const CAST_SPAN: f32 = 1.2e-3;

/// The most rounds parry's nonlinear cast may take to look past a touch at the start (see `first_impact`).
const MAX_TOUCHING_ROUNDS: f32 = 1_000.0;

/// The motion of `collider` on `body` from the body's start pose `start` at its current velocities, with
/// time scaled by `time_scale` (a velocity of the motion is the body's times `time_scale`).
fn collider_motion(
    collider: &Collider,
    body: &RigidBody,
    start: Pose,
    time_scale: f32,
) -> NonlinearRigidMotion {
    let local = collider.desc.local_pose;
    // The body's centre of mass in the collider's frame: the point the rotation turns about.
    let center = local.inverse_transform_point(body.mass_properties().local_center_of_mass());
    NonlinearRigidMotion::new(
        to_parry_pose(collider.world_pose(start)),
        center,
        body.linear_velocity() * time_scale,
        body.angular_velocity() * time_scale,
    )
}

/// The motion of `body`'s own frame from `start` at its current velocities.
fn body_motion(body: &RigidBody, start: Pose) -> NonlinearRigidMotion {
    NonlinearRigidMotion::new(
        to_parry_pose(start),
        body.mass_properties().local_center_of_mass(),
        body.linear_velocity(),
        body.angular_velocity(),
    )
}

/// Whether both corners of `aabb` are finite.
fn is_finite(aabb: &Aabb) -> bool {
    aabb.mins.is_finite() && aabb.maxs.is_finite()
}

/// The bodies `handle` pushed in the step (a point with a normal impulse), into `out`.
fn pushed_partners(handle: BodyHandle, manifolds: &[ContactManifold], out: &mut Vec<BodyHandle>) {
    out.clear();
    for m in manifolds {
        if (m.body_a == handle || m.body_b == handle)
            && m.points().iter().any(|p| p.normal_impulse > 0.0)
        {
            out.push(if m.body_a == handle {
                m.body_b
            } else {
                m.body_a
            });
        }
    }
}

/// The dynamic bodies joined by a joint that is not broken to another dynamic body, into `out` (sorted).
///
/// The sweep leaves them where the step put them: a body put back on its path at `t*` alone, its partner
/// carried on for the rest of the step, would open the joint by their anchors' relative speed times
/// `dt − t*` (a ragdoll's hand whipped round at 34 rad/s into a stair, 18 mm at the wrist); the joint's
/// solve keeps it with its partner, and the next step's contacts take the impact. A body jointed to fixed
/// bodies only (a propeller on its hinge) is still swept: its anchor there barely moves in `dt − t*`.
fn tied_bodies(world: &rebound_world::World<ParryBackend>, out: &mut Vec<BodyHandle>) {
    out.clear();
    let dynamic = |h: Option<BodyHandle>| {
        h.and_then(|h| world.body(h))
            .is_some_and(RigidBody::is_dynamic)
    };
    for (handle, _) in world.joints() {
        let (Some((a, b)), Some(state)) = (world.joint_bodies(handle), world.joint_state(handle))
        else {
            continue;
        };
        if !state.broken && dynamic(a) && dynamic(Some(b)) {
            out.extend(a);
            out.push(b);
        }
    }
    out.sort_unstable();
    out.dedup();
}

/// The earliest time of impact in `(0, dt)` of `body` (handle `handle`, at `start` when the step began) with a
/// collider of another body, among those whose box meets the body's swept box; `None` if it touches nothing
/// new on its path.
fn first_impact(
    (handle, start): (BodyHandle, Pose),
    backend: &ParryBackend,
    bodies: &BodySet,
    (pushed, candidates): (&[BodyHandle], &mut Vec<ColliderHandle>),
    dt: f32,
) -> Option<f32> {
    let body = bodies.get(handle)?;
    let colliders = &backend.colliders;
    let mut best: Option<f32> = None;
    for &own in colliders.of_body(handle) {
        let collider = colliders.get(own)?;
        if !collider.desc.enabled || collider.desc.is_sensor {
            continue;
        }
        // The step's motion over the cast's span: the cast's time `s` is the step's `s · dt / CAST_SPAN`.
        let motion = collider_motion(collider, body, start, dt / CAST_SPAN);
        // The swept box: the boxes at the start and the end of the step, loosened by what rotation can
        // bulge the path out between them.
        let at = |s: f32| collider.shape.compute_aabb(&motion.position_at_time(s));
        let start_box = at(0.0);
        let reach = crate::prediction::rotation_reach(body, &start_box) * dt;
        // A box or a reach beyond the floats (an unbounded shape, or a turn over a step of 10³⁰ s makes the
        // reach NaN) bounds nothing a cast could use: such a collider is left to the contacts and the
        // quarantine.
        let end_box = at(CAST_SPAN);
        if !(reach.is_finite() && is_finite(&start_box) && is_finite(&end_box)) {
            continue;
        }
        let swept: Aabb = start_box.merged(&end_box).loosened(reach);
        // For a pair touching at the start, parry looks for the later impact a turn would bring (a plank
        // lying on a step, turning its far end into it) by walking the span in rounds of the pair's
        // thinnest thickness over its speed, or of a quarter turn or more: a flat box (half-thickness
        // 10⁻²⁰ m) made that walk endless. Where it would take more than `MAX_TOUCHING_ROUNDS` rounds (the
        // collider's own thickness bounds the pair's from below), a pair touching at the start is left to
        // the contacts.
        let rounds = (body.linear_velocity().length() * dt / collider.shape.ccd_thickness())
            .max(body.angular_velocity().length() * dt / core::f32::consts::FRAC_PI_2);
        // A body at rest with a zero thickness gives 0/0 = NaN, which `max` passes over for the turn's count
        // (parry's walk is then one round); a NaN left over bounds nothing.
        let stop_at_penetration = rounds.is_nan() || rounds > MAX_TOUCHING_ROUNDS;
        backend.broad_phase.candidates(
            colliders,
            bodies,
            |aabb| aabb.intersects(&swept),
            candidates,
        );
        for &other_handle in candidates.iter() {
            let Some(other) = colliders.get(other_handle) else {
                continue;
            };
            let other_body_handle = other.body;
            if other_body_handle == handle
                || !other.desc.enabled
                || other.desc.is_sensor
                || !collider.desc.groups.interacts_with(other.desc.groups)
                || backend
                    .disabled_pairs
                    .contains(&crate::broad_phase::ordered(handle, other_body_handle))
                || pushed.contains(&other_body_handle)
            {
                continue;
            }
            let Some(other_body) = bodies.get(other_body_handle) else {
                continue;
            };
            let other_motion = NonlinearRigidMotion::constant_position(to_parry_pose(
                other.world_pose(other_body.pose()),
            ));
            let Ok(Some(hit)) = parry3d::query::cast_shapes_nonlinear(
                &motion,
                collider.shape.as_ref(),
                &other_motion,
                other.shape.as_ref(),
                0.0,
                CAST_SPAN,
                stop_at_penetration,
            ) else {
                continue;
            };
            let t = hit.time_of_impact * (dt / CAST_SPAN);
            if hit.status == ShapeCastStatus::PenetratingOrWithinTargetDist || !(t > 0.0 && t < dt)
            {
                continue;
            }
            if best.is_none_or(|b| t < b) {
                best = Some(t);
            }
        }
    }
    best
}

/// After the step: each body the broad phase listed as swept ([`crate::prediction::is_swept`]) that met a new collider on its
/// turning path is put back on the path at the first time of impact, velocities unchanged. Returns how many
/// were.
pub(crate) fn sweep(
    scratch: &mut SweepScratch,
    world: &mut rebound_world::World<ParryBackend>,
    dt: f32,
) -> usize {
    let mut clamped = 0;
    scratch.spinning.clear();
    scratch
        .spinning
        .extend_from_slice(world.backend().broad_phase.swept());
    let SweepScratch {
        tied,
        spinning,
        pushed,
        candidates,
    } = scratch;
    // The joints are looked through once, and only in a step that sweeps some body; a tied body is not
    // cast, since it would not be put back.
    if !spinning.is_empty() {
        tied_bodies(world, tied);
    }
    for &(handle, start) in spinning.iter() {
        if tied.binary_search(&handle).is_ok() {
            continue;
        }
        pushed_partners(handle, world.contacts(), pushed);
        let Some(t) = first_impact(
            (handle, start),
            world.backend(),
            world.bodies(),
            (pushed, candidates),
            dt,
        ) else {
            continue;
        };
        let Some(body) = world.body_mut(handle) else {
            continue;
        };
        let pose = from_parry_pose(&body_motion(body, start).position_at_time(t));
        if body.set_pose(pose).is_ok() {
            clamped += 1;
        }
    }
    if clamped > 0 {
        // The query index follows the poses it was refreshed at; these moved.
        let mut backend = core::mem::take(world.backend_mut());
        backend
            .broad_phase
            .refresh(&backend.colliders, world.bodies());
        *world.backend_mut() = backend;
    }
    clamped
}
