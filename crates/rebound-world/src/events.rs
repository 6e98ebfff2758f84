//! Stage *events*, last in the step: the events a step produces, drained by the user after it. Contact
//! begin and end come from this step's touching pairs against last step's; broken joints (stage *store*)
//! and bodies falling asleep (stage *islands and sleep*) are already in the list; the bodies woken since
//! the last events stage close it. Produced in a deterministic order: contact events in body-pair order,
//! then broken joints, then sleep changes, each sorted by handle.

use crate::handles::{BodyHandle, JointHandle};
use crate::scratch::Scratch;
use crate::sorted_walk::walk_to;
use crate::state::WorldState;

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
}

/// Stage *events*: contact begin/end from the touching pairs, woken bodies; sorted.
pub(crate) fn emit_events(
    state: &mut WorldState,
    s: &mut Scratch,
    events: &mut Vec<Event>,
    woken: &mut Vec<BodyHandle>,
) {
    // Touching pairs with their approach speeds, sorted by pair: O(m log m) for m manifolds.
    s.touching_speeds.clear();
    for ((m, &pushed), &speed) in state
        .manifolds
        .iter()
        .zip(&s.pushed)
        .zip(&s.approach_speeds)
    {
        // Touching: overlapping, or pushed this step (a speculative contact that closed its gap, a bounce).
        if m.is_touching() || pushed {
            let pair = if m.body_a <= m.body_b {
                (m.body_a, m.body_b)
            } else {
                (m.body_b, m.body_a)
            };
            s.touching_speeds.push((pair, speed));
        }
    }
    s.touching_speeds.sort_unstable_by_key(|x| x.0);
    s.touching.clear();
    let mut contact_events = core::mem::take(&mut s.contact_events);
    contact_events.clear();
    let mut last = state.touching.iter().peekable();
    let mut i = 0;
    while i < s.touching_speeds.len() {
        let pair = s.touching_speeds[i].0;
        let mut approach_speed = 0.0f32;
        while i < s.touching_speeds.len() && s.touching_speeds[i].0 == pair {
            approach_speed = approach_speed.max(s.touching_speeds[i].1);
            i += 1;
        }
        s.touching.push(pair);
        // Both lists are sorted: a forward walk through last step's.
        if walk_to(&mut last, &pair, |&old| old).is_none() {
            contact_events.push(Event::ContactBegan {
                body_a: pair.0,
                body_b: pair.1,
                approach_speed,
            });
        }
    }
    let mut now = s.touching.iter().peekable();
    for pair in &state.touching {
        if walk_to(&mut now, pair, |&new| new).is_none() {
            contact_events.push(Event::ContactEnded {
                body_a: pair.0,
                body_b: pair.1,
            });
        }
    }
    core::mem::swap(&mut state.touching, &mut s.touching);
    // Contact events first (pair order), then what the step already pushed (broken joints, sleep), then
    // wakes: `events` holds what the step already pushed; put the contact events in front of it.
    contact_events.append(events);
    core::mem::swap(events, &mut contact_events);
    s.contact_events = contact_events;
    woken.sort_unstable();
    woken.dedup();
    events.extend(woken.drain(..).map(|body| Event::BodyWoke { body }));
}
