//! Stage *prepare*, after *collide* and waking: the dense solver arrays and the constraints on them.
//!
//! Solver indices: the awake moving bodies first, in handle order; then each fixed body when a contact or a
//! joint first needs it; last the world anchor (a fixed body at the origin), if a world joint exists. Then
//! the contacts between an awake body and anything it can push, and the joints whose bodies are awake (or
//! fixed), each handed to its solver's preparation.

use crate::body_set::BodySet;
use crate::handles::{BodyHandle, JointHandle};
use crate::manifold::ContactManifold;
use crate::report::StepReport;
use crate::state::WorldState;
use rebound_constraints::{JointBodies, JointSolver};
#[cfg(feature = "parallel")]
use rebound_dynamics::Support;
use rebound_dynamics::{
    BodyParams, BodyType, Contact, ContactPoint, ContactSolver, MAX_CONTACT_POINTS, SolverBody,
    StackLoads, StepContext,
};
use rebound_math::par::{self, MIN_ITEMS_PER_TASK};

/// The solver index of a body that has none (a sleeping body, or a fixed one no constraint needs).
const NO_INDEX: u32 = u32::MAX;

/// The solver of a step: the dense body arrays, the constraints on them and the contact and joint solvers.
/// Built by *prepare*, solved by the solver passes, read back by *store*, *finalize* and *islands and sleep*;
/// the buffers are reused from step to step. The joint solver also keeps the rows of its directly solved
/// joint paths across the step boundary, which snapshots save.
#[derive(Debug, Default)]
pub(crate) struct Solver {
    /// Body slot → solver index, or [`NO_INDEX`].
    pub(crate) solver_index: Vec<u32>,
    /// Solver index → body handle (`None` for the world anchor entry).
    pub(crate) solver_handles: Vec<Option<BodyHandle>>,
    /// Solver index → the body's solver state (velocities, pose deltas).
    pub(crate) states: Vec<SolverBody>,
    /// Solver index → the body's constant parameters for the step (mass, inertia, gravity, damping).
    pub(crate) params: Vec<BodyParams>,
    /// Solver contacts and, for each, the manifold it came from.
    pub(crate) contacts: Vec<Contact>,
    pub(crate) contact_sources: Vec<usize>,
    /// Solver index → how many overlapping manifolds the dynamic body has this step (the push-out share).
    overlaps: Vec<u32>,
    /// Over the pool: each solver contact's bodies (solver indices), found before the contacts are written,
    /// and, found as they are written, whether a point of its manifold overlaps and whether it is a support
    /// of the load propagation.
    #[cfg(feature = "parallel")]
    contact_bodies: Vec<(u32, u32)>,
    #[cfg(feature = "parallel")]
    contact_facts: Vec<(bool, Option<Support>)>,
    /// Joints handed to the solver: their bodies and the handles they came from (the joint solver reads
    /// each joint and its state where the world keeps them, and writes the state back there).
    pub(crate) joint_bodies: Vec<JointBodies>,
    pub(crate) joint_handles: Vec<JointHandle>,
    /// Indices (into `joint_handles`) of the joints that broke this step (written by *store*).
    pub(crate) broken: Vec<usize>,
    pub(crate) contact_solver: ContactSolver,
    /// The weight each resting manifold carries (what its soft rows hold at rest).
    pub(crate) stack_loads: StackLoads,
    pub(crate) joint_solver: JointSolver,
    /// Solver contact → each point's normal impulse summed over the step (N·s), kept only when a contact
    /// reports forces (empty otherwise: nothing is summed).
    pub(crate) step_impulses: Vec<[f32; MAX_CONTACT_POINTS]>,
    /// Solver indices of the bodies with locked axes (the substeps lock them after every pass).
    pub(crate) locked: Vec<usize>,
    /// The substeps' phases on a team of threads (`solve_team`).
    #[cfg(feature = "parallel")]
    pub(crate) plan: crate::solve_team::Plan,
}

impl Solver {
    /// The arrays the substeps' team reads and writes, borrowed apart (`solve_team`).
    #[cfg(feature = "parallel")]
    pub(crate) fn team_arrays(&mut self) -> crate::solve_team::Arrays<'_> {
        crate::solve_team::Arrays {
            plan: &mut self.plan,
            states: &mut self.states,
            params: &self.params,
            contact_solver: &mut self.contact_solver,
            joint_solver: &mut self.joint_solver,
            step_impulses: &mut self.step_impulses,
            locked: &self.locked,
        }
    }
}

/// Stage *prepare*, part 1: the dense solver arrays. Awake moving bodies in handle order get indices
/// first; fixed bodies are added when a contact or joint needs them; the world anchor (a fixed body at the
/// origin) last, if a world joint exists. Quarantined bodies get none, so their joints are skipped.
pub(crate) fn build_solver_bodies(bodies: &BodySet, s: &mut Solver) {
    s.solver_index.clear();
    s.solver_index.resize(bodies.slot_count(), NO_INDEX);
    s.solver_handles.clear();
    s.states.clear();
    s.params.clear();
    s.locked.clear();
    // On one thread each body's solver state and parameters are built as it is met; with a pool, after
    // the walk, over the pool.
    let serial = !par::is_parallel();
    for (index, entry) in bodies.arena.iter() {
        let body = &entry.body;
        if body.is_sleeping() || body.body_type() == BodyType::Fixed || entry.quarantined {
            continue;
        }
        if body.locked_axes().is_any() && body.is_dynamic() {
            s.locked.push(s.solver_handles.len());
        }
        s.solver_index[index.index as usize] = s.solver_handles.len() as u32;
        s.solver_handles.push(Some(BodyHandle(index)));
        if serial {
            s.states.push(SolverBody::from_body(body));
            s.params.push(BodyParams::from_body(body));
        }
    }
    if serial {
        return;
    }
    // Each body's solver state and parameters read that body alone: over the pool, kept in index order.
    let body = |handle: &Option<BodyHandle>| handle.and_then(|h| bodies.get(h));
    // Both in one section: every entry is written.
    let n = s.solver_handles.len();
    s.states.resize(n, SolverBody::STATIC);
    s.params.resize(n, BodyParams::WORLD);
    let handles = &s.solver_handles;
    par::for_each_indexed_zip_both_mut(
        &mut s.states,
        &mut s.params,
        MIN_ITEMS_PER_TASK,
        |i, state, params| {
            if let Some(b) = handles.get(i).and_then(body) {
                *state = SolverBody::from_body(b);
                *params = BodyParams::from_body(b);
            }
        },
    );
}

/// The solver index of `handle`, adding a fixed body on first use. `None` for sleeping bodies (whose
/// constraints wait) and stale handles.
#[inline]
fn solver_index_of(s: &mut Solver, bodies: &BodySet, handle: BodyHandle) -> Option<usize> {
    let slot = BodySet::slot(handle);
    let existing = *s.solver_index.get(slot)?;
    if existing != NO_INDEX {
        return Some(existing as usize);
    }
    add_fixed(s, bodies, handle, slot)
}

/// The solver indices of `manifold`'s two bodies, when both have one ([`solver_index_of`]) and at least one
/// of them is dynamic: the pairs that become solver contacts.
#[inline]
fn contact_pair(
    s: &mut Solver,
    bodies: &BodySet,
    manifold: &ContactManifold,
) -> Option<(usize, usize)> {
    // Both looked up first: the second may number a fixed body even when the first has no index.
    let ia = solver_index_of(s, bodies, manifold.body_a);
    let ib = solver_index_of(s, bodies, manifold.body_b);
    let (ia, ib) = (ia?, ib?);
    (s.params[ia].is_dynamic() || s.params[ib].is_dynamic()).then_some((ia, ib))
}

/// [`solver_index_of`] for a body without a solver index yet (in slot `slot`): a fixed body gets the next
/// one; `None` for any other.
#[inline(never)]
fn add_fixed(s: &mut Solver, bodies: &BodySet, handle: BodyHandle, slot: usize) -> Option<usize> {
    let body = bodies.get(handle)?;
    if body.body_type() != BodyType::Fixed {
        return None;
    }
    let index = s.states.len();
    s.solver_index[slot] = index as u32;
    s.solver_handles.push(Some(handle));
    s.states.push(SolverBody::STATIC);
    s.params.push(BodyParams::from_body(body));
    Some(index)
}

/// Stage *prepare*, part 2: a solver contact for each manifold between an awake body and anything it can
/// push (anchors relative to the centres of mass: the lever arms the *collide* stage chose), with its bodies'
/// solver indices; then the contact solver's preparation.
pub(crate) fn build_contacts(
    bodies: &BodySet,
    manifolds: &[ContactManifold],
    s: &mut Solver,
    ctx: &StepContext,
    report: &mut StepReport,
) {
    #[cfg(feature = "parallel")]
    if par::is_parallel() && manifolds.len() >= MIN_MANIFOLDS_ON_POOL {
        build_contacts_on_pool(bodies, manifolds, s, ctx, report);
        return;
    }
    // Last step's contacts are written over in place (their points' storage kept), the rest cut off.
    let mut count = 0;
    // The points handed to the solver, added to the report at the end.
    let mut point_count = 0;
    s.contact_sources.clear();
    let mut reports_forces = false;
    // Only the awake moving bodies, which have the first solver indices, are counted.
    s.overlaps.clear();
    s.overlaps.resize(s.states.len(), 0);
    // Whether some dynamic body overlaps more than one other: then the push-out speed is shared out.
    let mut crowded = false;
    // The manifolds go to the load propagation as they are built: it keeps the resting supports.
    let loads = ctx.resting_overlap.is_some();
    if loads {
        s.stack_loads.begin(ctx.gravity);
    }
    for (source, manifold) in manifolds.iter().enumerate() {
        let Some((ia, ib)) = contact_pair(s, bodies, manifold) else {
            continue;
        };
        // Written in place in the list, point by point (not built aside and moved in); a new one is pushed
        // first while the list is short.
        if count == s.contacts.len() {
            s.contacts.push(Contact::new(
                ia,
                ib,
                manifold.normal,
                manifold.friction,
                manifold.restitution,
            ));
        }
        let Some(contact) = s.contacts.get_mut(count) else {
            continue;
        };
        count += 1;
        reports_forces |= manifold.force_event_threshold.is_some();
        let overlapping = write_contact(contact, ia, ib, manifold);
        point_count += contact.point_count;
        if loads {
            s.stack_loads
                .add(s.contact_sources.len(), contact, &s.params);
        }
        s.contact_sources.push(source);
        if overlapping {
            crowded |= count_overlap(s, ia) | count_overlap(s, ib);
        }
    }
    s.contacts.truncate(count);
    report.contact_point_count += point_count;
    finish_contacts(s, ctx, report, crowded, reports_forces);
}

/// The end of [`build_contacts`] once every solver contact is written: the push-out shares if some body
/// overlaps more than one other (`crowded`), the force sums if a contact reports forces, the stack loads,
/// the contact solver's preparation.
fn finish_contacts(
    s: &mut Solver,
    ctx: &StepContext,
    report: &mut StepReport,
    crowded: bool,
    reports_forces: bool,
) {
    if crowded {
        share_push_out(s, ctx.max_push_out_speed);
    }
    report.contact_count = s.contacts.len();
    s.step_impulses.clear();
    if reports_forces {
        s.step_impulses
            .resize(s.contacts.len(), [0.0; MAX_CONTACT_POINTS]);
    }
    if ctx.resting_overlap.is_some() {
        s.stack_loads.finish(&mut s.contacts, &s.params, ctx.h);
    }
    report.rejected_contact_count +=
        s.contact_solver
            .prepare(&s.contacts, &s.states, &s.params, ctx);
}

/// Manifolds below which the solver contacts are built on one thread even on a pool.
#[cfg(feature = "parallel")]
const MIN_MANIFOLDS_ON_POOL: usize = 256;

/// [`build_contacts`] over the pool, with the same contacts, loads and counts: the manifolds' solver indices
/// on this thread (a fixed body gets its index when first met, in manifold order), then each contact written
/// from its manifold over the pool (and judged a support of the load propagation or not), then, in contact
/// order on this thread, the overlaps counted and the supports linked (the propagation's lists and sums
/// follow that order).
#[cfg(feature = "parallel")]
fn build_contacts_on_pool(
    bodies: &BodySet,
    manifolds: &[ContactManifold],
    s: &mut Solver,
    ctx: &StepContext,
    report: &mut StepReport,
) {
    s.contact_sources.clear();
    s.contact_bodies.clear();
    let mut reports_forces = false;
    for (source, manifold) in manifolds.iter().enumerate() {
        let Some((ia, ib)) = contact_pair(s, bodies, manifold) else {
            continue;
        };
        reports_forces |= manifold.force_event_threshold.is_some();
        s.contact_sources.push(source);
        s.contact_bodies.push((ia as u32, ib as u32));
    }
    let count = s.contact_sources.len();
    // Every entry is written over below; last step's keep their points' storage.
    s.contacts.resize(
        count,
        Contact::new(0, 0, rebound_math::Vec3::ZERO, 0.0, 0.0),
    );
    s.contact_facts.resize(count, (false, None));
    let loads = ctx.resting_overlap.is_some();
    if loads {
        s.stack_loads.begin(ctx.gravity);
    }
    let (sources, pairs, params, stack_loads) = (
        &s.contact_sources,
        &s.contact_bodies,
        &s.params,
        &s.stack_loads,
    );
    par::for_each_indexed_zip_both_mut(
        &mut s.contacts,
        &mut s.contact_facts,
        MIN_ITEMS_PER_TASK,
        |i, contact, facts| {
            let (Some(manifold), Some(&(ia, ib))) =
                (sources.get(i).and_then(|&m| manifolds.get(m)), pairs.get(i))
            else {
                return;
            };
            let overlapping = write_contact(contact, ia as usize, ib as usize, manifold);
            *facts = (
                overlapping,
                loads
                    .then(|| stack_loads.support(contact, params))
                    .flatten(),
            );
        },
    );
    s.overlaps.clear();
    s.overlaps.resize(s.states.len(), 0);
    let (mut point_count, mut crowded) = (0, false);
    for i in 0..count {
        let (Some(contact), Some(&(overlapping, support))) =
            (s.contacts.get(i), s.contact_facts.get(i))
        else {
            continue;
        };
        point_count += contact.point_count;
        let (ia, ib) = (contact.body_a, contact.body_b);
        if let Some(support) = support {
            s.stack_loads.link(i, support, &s.params);
        }
        if overlapping {
            crowded |= count_overlap(s, ia) | count_overlap(s, ib);
        }
    }
    report.contact_point_count += point_count;
    finish_contacts(s, ctx, report, crowded, reports_forces);
}

/// Writes `contact` over as the solver contact of `manifold` between the bodies of solver indices `ia` and
/// `ib` (the points with the lever arms the collide stage chose); returns whether a point of the manifold
/// overlaps.
#[inline]
fn write_contact(contact: &mut Contact, ia: usize, ib: usize, manifold: &ContactManifold) -> bool {
    contact.renew(
        ia,
        ib,
        manifold.normal,
        manifold.friction,
        manifold.restitution,
    );
    contact.rolling_friction = manifold.rolling_friction;
    contact.surface_velocity = manifold.surface_velocity;
    let mut overlapping = false;
    for point in manifold.points() {
        overlapping |= point.separation < 0.0;
        // The collide stage chose every point's lever arms.
        let Some([anchor_a, anchor_b]) = point.solver_lever_arms else {
            continue;
        };
        contact.push_point(ContactPoint {
            anchor_a,
            anchor_b,
            separation: point.separation,
            normal_impulse: point.normal_impulse,
            tangent_impulse: point.tangent_impulse,
            feature_id: point.feature_id,
        });
    }
    overlapping
}

/// Counts an overlapping manifold of the body of solver index `i` if it is dynamic (a fixed or kinematic
/// body is not pushed); returns whether it now has more than one.
#[inline]
fn count_overlap(s: &mut Solver, i: usize) -> bool {
    if !s.params[i].is_dynamic() {
        return false;
    }
    let Some(count) = s.overlaps.get_mut(i) else {
        return false;
    };
    *count += 1;
    *count > 1
}

/// Shares the push-out speed of each dynamic body out among its overlaps: a manifold whose bodies have up to
/// `k` overlapping manifolds each pushes at most `max_push_out_speed / k` (m/s). Without it, the caps of a
/// body's overlaps add up: `n` balls created at one point push each other apart along one line (their normal
/// is +y) at up to 3 m/s a pair, and the pile flies apart at `n`·3/2 m/s.
fn share_push_out(s: &mut Solver, max_push_out_speed: f32) {
    let count = |i: usize| s.overlaps.get(i).copied().unwrap_or(0);
    for contact in &mut s.contacts {
        let k = count(contact.body_a).max(count(contact.body_b));
        if k > 1 {
            contact.push_out_speed = max_push_out_speed / k as f32;
        }
    }
}

/// Stage *prepare*, part 3: joints whose bodies are awake (or fixed), then the joint solver's preparation.
pub(crate) fn build_joints(
    state: &WorldState,
    s: &mut Solver,
    ctx: &StepContext,
    report: &mut StepReport,
) {
    s.joint_bodies.clear();
    s.joint_handles.clear();
    let mut world_anchor: Option<usize> = None;
    for (index, entry) in state.joints.iter() {
        if entry.state.broken {
            continue;
        }
        let Some(b) = solver_index_of(s, &state.bodies, entry.body_b) else {
            continue;
        };
        let a = match entry.body_a {
            Some(handle) => match solver_index_of(s, &state.bodies, handle) {
                Some(a) => a,
                None => continue,
            },
            None => *world_anchor.get_or_insert_with(|| {
                let index = s.states.len();
                s.solver_handles.push(None);
                s.states.push(SolverBody::STATIC);
                s.params.push(BodyParams::WORLD);
                index
            }),
        };
        if !s.params[a].is_dynamic() && !s.params[b].is_dynamic() {
            continue;
        }
        s.joint_bodies.push(JointBodies { a, b });
        s.joint_handles.push(JointHandle(index));
    }
    report.joint_count = s.joint_handles.len();
    if s.joint_solver.settings() != &state.settings.joints {
        // `WorldSettings` are validated whenever they are set, so this cannot fail.
        let applied = s.joint_solver.set_settings(state.settings.joints);
        debug_assert!(applied.is_ok(), "world settings are validated on entry");
    }
    let (handles, pairs) = (&s.joint_handles, &s.joint_bodies);
    let joint = |i: usize| {
        let entry = state.joints.get(handles.get(i)?.0)?;
        Some((&entry.joint, &entry.state, *pairs.get(i)?))
    };
    let skipped = s
        .joint_solver
        .prepare_from(handles.len(), joint, &s.states, &s.params, ctx);
    debug_assert_eq!(
        skipped, 0,
        "the world hands the joint solver only valid joints"
    );
}
