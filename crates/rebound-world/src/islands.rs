//! Stage *islands and sleep*: which bodies sleep and which wake.
//!
//! Awake islands are rebuilt every step, after write-back, with a union-find over the awake bodies, linked
//! by contacts and joints, in handle order (deterministic). An island falls asleep when every body in it has
//! rested — speed below the thresholds — for `time_to_sleep`; its bodies then keep a persistent island id, so
//! waking any one of them wakes them all. Waking runs before the solver arrays are built: a body whose own
//! flag a setter, a force or an impulse cleared wakes its island before *collide*, and an awake body that
//! touches or is about to hit a sleeping one, or is jointed to it, wakes it after *collide*.

use crate::body_set::{BodyEntry, BodySet, NO_ISLAND};
use crate::collide::Collision;
use crate::events::Event;
use crate::handles::BodyHandle;
use crate::prepare::Solver;
use crate::state::WorldState;
use crate::union_find::UnionFind;
use rebound_dynamics::{BodyParams, BodyType, Motion};
use rebound_math::Vec3;

/// The buffers of the waking and sleep stages, reused from step to step.
#[derive(Debug, Default)]
pub(crate) struct SleepBuffers {
    union_find: UnionFind,
    /// Solver index → whether the body has rested long enough to sleep.
    can_rest: Vec<bool>,
    /// Island root → whether every member may sleep.
    island_ok: Vec<bool>,
    /// Pairs of solver indices in the same island.
    links: Vec<(u32, u32)>,
    /// (island root, body) of the bodies falling asleep.
    sleepers: Vec<(u32, BodyHandle)>,
    /// Bodies to wake.
    to_wake: Vec<BodyHandle>,
}

/// A fresh sleeping-island id.
pub(crate) fn new_island(state: &mut WorldState) -> u32 {
    let id = state.next_island;
    state.next_island = state.next_island.wrapping_add(1);
    id
}

/// Wakes the sleeping island of `handle` (if any), recording each of its bodies in `woken` (reported as
/// `BodyWoke` by the *events* stage).
pub(crate) fn wake_island_of(
    state: &mut WorldState,
    woken: &mut Vec<BodyHandle>,
    handle: BodyHandle,
) {
    let island = match state.bodies.entry(handle) {
        Some(entry) if entry.island != NO_ISLAND => entry.island,
        Some(_) => {
            if let Some(entry) = state.bodies.entry_mut(handle) {
                entry.sleep_time = 0.0;
                entry.body.set_sleeping(false);
            }
            return;
        }
        None => return,
    };
    let members = state.islands.remove(&island).unwrap_or_default();
    for member in members {
        if let Some(entry) = state.bodies.entry_mut(member) {
            entry.island = NO_ISLAND;
            entry.sleep_time = 0.0;
            entry.body.set_sleeping(false);
            woken.push(member);
        }
    }
}

/// Bodies in a sleeping island whose own flag was cleared (by a setter, a force, an impulse) wake their
/// whole island.
pub(crate) fn wake_changed_bodies(
    state: &mut WorldState,
    woken: &mut Vec<BodyHandle>,
    buffers: &mut SleepBuffers,
) {
    // Reuses the wake buffer of the touch test: no allocation per step.
    let mut changed = core::mem::take(&mut buffers.to_wake);
    changed.clear();
    changed.extend(
        state
            .bodies
            .arena
            .iter()
            .filter(|(_, e)| e.island != NO_ISLAND && !e.body.is_sleeping())
            .map(|(i, _)| BodyHandle(i)),
    );
    for &handle in &changed {
        wake_island_of(state, woken, handle);
    }
    buffers.to_wake = changed;
}

/// Waking by touch and by joints, after *collide*: an awake moving body that touches a sleeping one, or
/// closes the gap to it within this step (`s.manifolds` and their approach speeds), or is jointed to it,
/// wakes its island; repeated until nothing changes (a woken island may touch another sleeping one).
pub(crate) fn wake_touched(
    state: &mut WorldState,
    woken: &mut Vec<BodyHandle>,
    c: &Collision,
    buffers: &mut SleepBuffers,
    dt: f32,
) {
    // Nothing to do when no body sleeps (always so with sleeping off): one scan of the bodies instead of a
    // look at every manifold and joint.
    if !state.bodies.iter().any(|(_, body)| body.is_sleeping()) {
        return;
    }
    let mut to_wake = core::mem::take(&mut buffers.to_wake);
    loop {
        to_wake.clear();
        for (m, &speed) in c.manifolds.iter().zip(&c.approach_speeds) {
            // Touching, or closing the gap within this step: a sleeping body about to be hit must be in
            // the solver when the hit comes.
            let gap = m
                .points()
                .iter()
                .map(|p| p.separation)
                .fold(f32::INFINITY, f32::min);
            if gap <= speed * dt {
                collect_wake(&state.bodies, m.body_a, m.body_b, &mut to_wake);
            }
        }
        for (_, joint) in state.joints.iter() {
            if joint.state.broken {
                continue;
            }
            if let Some(a) = joint.body_a {
                collect_wake(&state.bodies, a, joint.body_b, &mut to_wake);
            }
        }
        if to_wake.is_empty() {
            break;
        }
        for &handle in &to_wake {
            wake_island_of(state, woken, handle);
        }
    }
    buffers.to_wake = to_wake;
}

/// Stage *islands and sleep*, after write-back: rest timers of the solved bodies, then islands of awake
/// bodies linked by contacts and joints (the solver's, `s`); an island whose bodies have all rested long
/// enough falls asleep, and each of its bodies is reported (`BodyFellAsleep`).
pub(crate) fn update_sleep(
    state: &mut WorldState,
    s: &Solver,
    buffers: &mut SleepBuffers,
    events: &mut Vec<Event>,
    dt: f32,
) {
    let settings = state.settings;
    let n = s.solver_handles.len();
    // Rest timers of the awake moving bodies; `can_rest[i]` is false for bodies that keep an island awake.
    let mut can_rest = core::mem::take(&mut buffers.can_rest);
    can_rest.clear();
    can_rest.resize(n, false);
    for (i, handle) in s.solver_handles.iter().enumerate() {
        let Some(handle) = handle else { continue };
        let Some(entry) = state.bodies.entry_mut(*handle) else {
            continue;
        };
        let body = &entry.body;
        if body.body_type() == BodyType::Fixed {
            continue;
        }
        let resting = body.linear_velocity().length() < settings.linear_sleep_threshold
            && body.angular_velocity().length() < settings.angular_sleep_threshold;
        entry.sleep_time = if resting { entry.sleep_time + dt } else { 0.0 };
        can_rest[i] = settings.sleep_enabled
            && body.can_sleep()
            && body.body_type() == BodyType::Dynamic
            && entry.sleep_time >= settings.time_to_sleep;
    }
    if !can_rest.contains(&true) {
        // No island can fall asleep (sleeping off, or everything moving): no islands to build.
        buffers.can_rest = can_rest;
        return;
    }
    buffers.union_find.reset(n);
    // Only dynamic bodies link islands: fixed and kinematic bodies are shared by many islands.
    let moving = |i: usize| s.params.get(i).is_some_and(BodyParams::is_dynamic);
    let mut links = core::mem::take(&mut buffers.links);
    links.clear();
    // Every manifold links its bodies, speculative ones too: bodies within the speculative margin of
    // each other can meet within a step, so they sleep and wake together (a row of balls 1 mm apart
    // must all be awake when the first is struck).
    for contact in &s.contacts {
        if moving(contact.body_a) && moving(contact.body_b) {
            links.push((contact.body_a as u32, contact.body_b as u32));
        }
    }
    for bodies in &s.joint_bodies {
        if moving(bodies.a) && moving(bodies.b) {
            links.push((bodies.a as u32, bodies.b as u32));
        }
    }
    for &(a, b) in &links {
        buffers.union_find.union(a, b);
    }
    buffers.links = links;
    // An island may sleep only if every member may.
    let mut island_ok = core::mem::take(&mut buffers.island_ok);
    island_ok.clear();
    island_ok.resize(n, true);
    for (i, &rest) in can_rest.iter().enumerate() {
        if s.params.get(i).is_some_and(|p| p.motion != Motion::Fixed) {
            let root = buffers.union_find.find(i as u32) as usize;
            island_ok[root] &= rest;
        }
    }
    buffers.can_rest = can_rest;
    let mut sleepers = core::mem::take(&mut buffers.sleepers);
    sleepers.clear();
    for i in 0..n {
        let Some(handle) = s.solver_handles[i] else {
            continue;
        };
        if s.params[i].motion == Motion::Fixed {
            continue;
        }
        let root = buffers.union_find.find(i as u32);
        if island_ok[root as usize] {
            sleepers.push((root, handle));
        }
    }
    buffers.island_ok = island_ok;
    // Roots are the lowest solver index of each island, handles are in handle order: deterministic.
    sleepers.sort_unstable();
    let mut current_root = None;
    let mut island_id = 0;
    for &(root, handle) in &sleepers {
        if current_root != Some(root) {
            current_root = Some(root);
            island_id = new_island(state);
            state.islands.insert(island_id, Vec::new());
        }
        if let Some(entry) = state.bodies.entry_mut(handle) {
            entry.island = island_id;
            // A sleeping body is at rest: clear the residual velocity so that it wakes exactly as it slept
            // (the velocity setters wake a body, so the flag is set after them).
            let _ = entry.body.set_linear_velocity(Vec3::ZERO);
            let _ = entry.body.set_angular_velocity(Vec3::ZERO);
            entry.body.set_sleeping(true);
        }
        if let Some(members) = state.islands.get_mut(&island_id) {
            members.push(handle);
        }
        events.push(Event::BodyFellAsleep { body: handle });
    }
    buffers.sleepers = sleepers;
}

/// If exactly one of two bodies is awake and moving and the other asleep, the sleeper must wake.
fn collect_wake(bodies: &BodySet, a: BodyHandle, b: BodyHandle, out: &mut Vec<BodyHandle>) {
    let (Some(ea), Some(eb)) = (bodies.entry(a), bodies.entry(b)) else {
        return;
    };
    let active = |e: &BodyEntry| !e.body.is_sleeping() && e.body.body_type() != BodyType::Fixed;
    let asleep = |e: &BodyEntry| e.body.is_sleeping();
    if active(ea) && asleep(eb) {
        out.push(b);
    } else if active(eb) && asleep(ea) {
        out.push(a);
    }
}
