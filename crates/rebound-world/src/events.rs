//! Stage *events*, last in the step: the events a step produces, drained by the user after it. Contact
//! begin and end come from this step's touching pairs against last step's; broken joints (stage *store*)
//! and bodies falling asleep (stage *islands and sleep*) are already in the list; the bodies woken since
//! the last events stage close it. Produced in a deterministic order: contact events in body-pair order,
//! then quarantined bodies, broken joints, then contact forces (manifold order, pushed after write-back),
//! then sleep changes, each sorted by handle.

use crate::handles::{BodyHandle, JointHandle};
use crate::limits::QuarantineReason;
use crate::prepare::Solver;
use crate::sorted_walk::walk_to;
use crate::state::WorldState;
use rebound_math::{Vec3, par};

/// Something that happened during the last step.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Event {
    /// Two bodies started touching.
    ContactBegan {
        /// Body A of the pair (the lower handle).
        body_a: BodyHandle,
        /// Body B of the pair.
        body_b: BodyHandle,
        /// How fast they approached along the normal when they met (m/s, ≥ 0).
        approach_speed: f32,
    },
    /// Two bodies stopped touching (or one was removed).
    ContactEnded {
        /// Body A of the pair.
        body_a: BodyHandle,
        /// Body B of the pair.
        body_b: BodyHandle,
    },
    /// A contact whose colliders opted in pushed with at least their threshold force this step
    /// ([`crate::ContactManifold::force_event_threshold`]).
    ContactForce(ContactForce),
    /// A joint's impulse exceeded its break force or torque; it is now disabled.
    JointBroken {
        /// The joint.
        joint: JointHandle,
    },
    /// A body fell asleep with its island.
    BodyFellAsleep {
        /// The body.
        body: BodyHandle,
    },
    /// A sleeping body woke up.
    BodyWoke {
        /// The body.
        body: BodyHandle,
    },
    /// A body left the bounds of [`crate::StepLimits`] (or its solver result was not finite) and was taken
    /// out of the steps until [`crate::World::release_quarantine`]; see [`crate::QuarantineReason`].
    BodyQuarantined {
        /// The body.
        body: BodyHandle,
        /// What was out of bounds.
        reason: QuarantineReason,
    },
}

/// What one contact manifold pushed with over a step ([`Event::ContactForce`]).
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactForce {
    /// Body A of the manifold.
    pub body_a: BodyHandle,
    /// Body B of the manifold.
    pub body_b: BodyHandle,
    /// The manifold's backend key ([`crate::ContactManifold::key`]).
    pub key: u64,
    /// The manifold's unit normal, world axes, from A to B; B was pushed along it, A against it.
    pub normal: Vec3,
    /// The normal impulse the contact applied over the step, summed over its points and substeps (N·s).
    pub total_impulse: f32,
    /// The mean normal force over the step, `total_impulse / dt` (N).
    pub total_force: f32,
    /// The point that applied the largest impulse, in world space at the end of the step (m).
    pub max_impulse_point: Vec3,
    /// That point's impulse over the step (N·s).
    pub max_impulse: f32,
}

/// Stage *finalize*, after write-back: an [`Event::ContactForce`] for each solved manifold with a force
/// event threshold whose mean normal force over the step (`s.step_impulses`, summed by the substeps) reached
/// it, in manifold order. `state.manifolds` are this step's.
pub(crate) fn push_force_events(state: &WorldState, s: &Solver, dt: f32, events: &mut Vec<Event>) {
    for (sums, &source) in s.step_impulses.iter().zip(&s.contact_sources) {
        let Some(m) = state.manifolds.get(source) else {
            continue;
        };
        let Some(threshold) = m.force_event_threshold else {
            continue;
        };
        let sums = &sums[..m.points().len()];
        let total_impulse: f32 = sums.iter().sum();
        let total_force = total_impulse / dt;
        if total_force < threshold {
            continue;
        }
        let (mut max_point, mut max_impulse) = (0, f32::NEG_INFINITY);
        for (k, &impulse) in sums.iter().enumerate() {
            if impulse > max_impulse {
                (max_point, max_impulse) = (k, impulse);
            }
        }
        let (Some(a), Some(b), Some(point)) = (
            state.bodies.get(m.body_a),
            state.bodies.get(m.body_b),
            m.points().get(max_point),
        ) else {
            continue;
        };
        events.push(Event::ContactForce(ContactForce {
            body_a: m.body_a,
            body_b: m.body_b,
            key: m.key,
            normal: m.normal,
            total_impulse,
            total_force,
            max_impulse_point: point.world_point(a.pose(), b.pose()),
            max_impulse,
        }));
    }
}

/// The buffers of the *events* stage, reused from step to step.
#[derive(Debug, Default)]
pub(crate) struct EventBuffers {
    /// Touching body pairs of this step, sorted.
    touching: Vec<(BodyHandle, BodyHandle)>,
    /// Touching body pairs of this step with their approach speeds.
    touching_speeds: Vec<((BodyHandle, BodyHandle), f32)>,
    /// The contact events of the step.
    contact_events: Vec<Event>,
}

/// Stage *events*: contact begin/end from this step's touching pairs against last step's
/// (`state.touching`, replaced by this step's), then the bodies in `woken`; sorted.
///
/// `state.manifolds` are this step's manifolds, `pushed` and `approach_speeds` say for each whether the
/// solver pushed with it and how fast its bodies approached before the step (m/s); `events` holds what the
/// step already reported (broken joints, bodies fallen asleep).
pub(crate) fn emit_events(
    state: &mut WorldState,
    pushed: &[bool],
    approach_speeds: &[f32],
    buffers: &mut EventBuffers,
    events: &mut Vec<Event>,
    woken: &mut Vec<BodyHandle>,
) {
    // Touching pairs with their approach speeds, sorted by pair: O(m log m) for m manifolds.
    buffers.touching_speeds.clear();
    for ((m, &was_pushed), &speed) in state.manifolds.iter().zip(pushed).zip(approach_speeds) {
        // Touching: pushed this step (a speculative contact that closed its gap, a bounce), or overlapping.
        // The flag first: a manifold that pushed (most that touch) is not read past its bodies.
        if was_pushed || m.is_touching() {
            let pair = if m.body_a <= m.body_b {
                (m.body_a, m.body_b)
            } else {
                (m.body_b, m.body_a)
            };
            buffers.touching_speeds.push((pair, speed));
        }
    }
    // By pair, then by the speed's bits: no two entries that differ have one key, so the list is the same
    // whichever sort puts it in order (the pool's or one thread's).
    par::sort_unstable_by_key(&mut buffers.touching_speeds, |x| (x.0, x.1.to_bits()));
    buffers.touching.clear();
    let mut contact_events = core::mem::take(&mut buffers.contact_events);
    contact_events.clear();
    let mut last = state.touching.iter().peekable();
    let mut i = 0;
    while i < buffers.touching_speeds.len() {
        let pair = buffers.touching_speeds[i].0;
        let mut approach_speed = 0.0f32;
        while i < buffers.touching_speeds.len() && buffers.touching_speeds[i].0 == pair {
            approach_speed = approach_speed.max(buffers.touching_speeds[i].1);
            i += 1;
        }
        buffers.touching.push(pair);
        // Both lists are sorted: a forward walk through last step's.
        if walk_to(&mut last, &pair, |&old| old).is_none() {
            contact_events.push(Event::ContactBegan {
                body_a: pair.0,
                body_b: pair.1,
                approach_speed,
            });
        }
    }
    let mut now = buffers.touching.iter().peekable();
    for pair in &state.touching {
        if walk_to(&mut now, pair, |&new| new).is_none() {
            contact_events.push(Event::ContactEnded {
                body_a: pair.0,
                body_b: pair.1,
            });
        }
    }
    core::mem::swap(&mut state.touching, &mut buffers.touching);
    // Contact events first (pair order), then what the step already pushed (broken joints, sleep), then
    // wakes: `events` holds what the step already pushed; put the contact events in front of it.
    contact_events.append(events);
    core::mem::swap(events, &mut contact_events);
    buffers.contact_events = contact_events;
    woken.sort_unstable();
    woken.dedup();
    events.extend(woken.drain(..).map(|body| Event::BodyWoke { body }));
}
