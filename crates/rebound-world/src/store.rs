//! Stage *store*, after the solver passes: the solver's results back into the world. Each manifold keeps its
//! points' impulses for the next step's warm start and whether it pushed (for the touching test of the
//! events); each joint keeps its state; joints past their break limits are reported broken. Then (stage
//! *finalize*) the poses and velocities of the solved bodies, each compared with the quarantine's bounds as
//! it is written (so that the next step's start need not look at them again).

use crate::arena::Arena;
use crate::body_set::BodySet;
use crate::collide::Collision;
use crate::events::Event;
use crate::handles::JointHandle;
use crate::manifold::ContactManifold;
use crate::prepare::Solver;
use crate::report::StepReport;
use crate::state::{JointEntry, WorldState};
use core::sync::atomic::{AtomicBool, Ordering};
use rebound_constraints::{JointState, JointStates};
use rebound_dynamics::{BodyParams, ContactSolver, Motion, RigidBody, SolverBody};
#[cfg(feature = "parallel")]
use rebound_math::Disjoint;
use rebound_math::glam::Vec3A;
use rebound_math::{Vec3, par};

/// The world's joints as the joint solver writes their states back: joint `i` of the step is the one of
/// handle `handles[i]`.
struct StoredJoints<'a> {
    joints: &'a mut Arena<JointEntry>,
    handles: &'a [JointHandle],
}

impl JointStates for StoredJoints<'_> {
    fn state_mut(&mut self, i: usize) -> Option<&mut JointState> {
        let handle = self.handles.get(i)?;
        self.joints.get_mut(handle.0).map(|entry| &mut entry.state)
    }
}

/// Stage *store impulses*: manifolds keep theirs for the next step; joint states likewise; joints that
/// exceeded their break limits are marked broken and reported.
pub(crate) fn store_impulses(
    state: &mut WorldState,
    c: &mut Collision,
    s: &mut Solver,
    events: &mut Vec<Event>,
    report: &mut StepReport,
) {
    // Straight into the manifolds (the solver's contacts are not read again): impulses for the next
    // step's warm start, and whether each manifold pushed (for the touching test of the events).
    // `pushed` holds collide's verdict for each manifold (a carried resting contact keeps its touching).
    c.pushed.resize(c.manifolds.len(), false);
    let (manifolds, pushed, sources) = (&mut c.manifolds, &mut c.pushed, &s.contact_sources);
    // Never a non-finite impulse into the state (the next step would warm start from it): the quarantine
    // reruns a step whose bodies went non-finite, so this guards a fault only.
    if !read_back_impulses(&s.contact_solver, sources, manifolds, pushed) {
        zero_non_finite_impulses(manifolds);
    }
    s.broken.clear();
    let mut stored = StoredJoints {
        joints: &mut state.joints,
        handles: &s.joint_handles,
    };
    // The joint solver stores no non-finite impulse either.
    s.joint_solver.store_impulses_to(&mut stored, &mut s.broken);
    report.broken_joint_count = s.broken.len();
    for &i in &s.broken {
        if let Some(handle) = s.joint_handles.get(i) {
            events.push(Event::JointBroken { joint: *handle });
        }
    }
    core::mem::swap(&mut state.manifolds, &mut c.manifolds);
}

/// The solver's impulses into the manifolds they came from (solver contact `i` is manifold `sources[i]`),
/// and into `pushed` whether each pushed; returns whether every impulse stored is finite.
fn read_back_impulses(
    solver: &ContactSolver,
    sources: &[usize],
    manifolds: &mut [ContactManifold],
    pushed: &mut [bool],
) -> bool {
    #[cfg(feature = "parallel")]
    if par::is_parallel() && sources.len() >= MIN_CONTACTS_ON_POOL {
        return read_back_on_pool(solver, sources, manifolds, pushed);
    }
    let mut finite = true;
    solver.for_each_point_result(|contact, k, normal, tangent, max| {
        let Some(&source) = sources.get(contact) else {
            return;
        };
        finite &= store_point(manifolds.get_mut(source), k, normal, tangent);
        if let Some(was_pushed) = pushed.get_mut(source) {
            *was_pushed |= max > 0.0;
        }
    });
    finite
}

/// Point `k`'s impulses `normal` (N·s) and `tangent` into `manifold`; returns whether both are finite (true
/// when there is no such point).
#[inline(always)]
fn store_point(
    manifold: Option<&mut ContactManifold>,
    k: usize,
    normal: f32,
    tangent: Vec3,
) -> bool {
    let Some(point) = manifold.and_then(|m| m.points.get_mut(k)) else {
        return true;
    };
    point.normal_impulse = normal;
    point.tangent_impulse = tangent;
    normal.is_finite() & tangent.is_finite()
}

/// Solver contacts below which the impulses are read back on one thread even on a pool.
#[cfg(feature = "parallel")]
const MIN_CONTACTS_ON_POOL: usize = 256;

/// [`read_back_impulses`] over the pool: each manifold is written by the one call that reads back its
/// solver contact's points, the same values as on one thread. A non-finite impulse is rare: one flag,
/// written only then.
#[cfg(feature = "parallel")]
#[expect(
    unsafe_code,
    reason = "each manifold written by the one task that reads back its contact (rebound_math::Disjoint)"
)]
fn read_back_on_pool(
    solver: &ContactSolver,
    sources: &[usize],
    manifolds: &mut [ContactManifold],
    pushed: &mut [bool],
) -> bool {
    let finite = AtomicBool::new(true);
    let (manifolds, pushed) = (Disjoint::new(manifolds), Disjoint::new(pushed));
    solver.for_each_point_result_on_pool(|contact, k, normal, tangent, max| {
        let Some(&source) = sources.get(contact) else {
            return;
        };
        // SAFETY: solver contacts come from distinct manifolds (`sources` is strictly increasing), and all
        // calls for one contact are made one after the other on one thread
        // (`ContactSolver::for_each_point_result_on_pool`): no two threads hold one manifold or flag.
        let (manifold, was_pushed) = unsafe { (manifolds.get_mut(source), pushed.get_mut(source)) };
        if !store_point(manifold, k, normal, tangent) {
            finite.store(false, Ordering::Relaxed);
        }
        if let Some(was_pushed) = was_pushed {
            *was_pushed |= max > 0.0;
        }
    });
    finite.into_inner()
}

/// Stage *finalize*: poses and velocities back into the bodies. Returns whether every moving body written
/// is within `max_position` (m) of the origin along each axis (the quarantine's position bound; the solver's
/// velocities were compared with their bounds before).
pub(crate) fn write_back(bodies: &mut BodySet, s: &Solver, max_position: f32) -> bool {
    // A refused (non-finite) result leaves the body where it was; the finite-state tests guard that this
    // never happens. Fixed bodies do not move, and the quarantine does not look at them.
    let write = |params: &BodyParams, state: &SolverBody, body: &mut RigidBody| {
        let _accepted = params.write_back(state, body);
        if params.motion == Motion::Fixed {
            Vec3A::ZERO
        } else {
            Vec3A::from(body.position()).abs()
        }
    };
    let bound = Vec3A::splat(max_position);
    if par::is_parallel() {
        // Each body reads its own solver entry: every slot over the pool, the same writes as below. A body
        // beyond the bound is rare: one flag, written only then.
        let within = AtomicBool::new(true);
        bodies.arena.for_each_value_mut(|slot, entry| {
            let Some(&i) = s.solver_index.get(slot as usize) else {
                return;
            };
            let i = i as usize;
            if let (Some(state), Some(params)) = (s.states.get(i), s.params.get(i))
                && !write(params, state, &mut entry.body).cmple(bound).all()
            {
                within.store(false, Ordering::Relaxed);
            }
        });
        return within.into_inner();
    }
    // The farthest coordinate of all, compared once (positions are finite: a refused result is not
    // written).
    let mut farthest = Vec3A::ZERO;
    for ((handle, state), params) in s.solver_handles.iter().zip(&s.states).zip(&s.params) {
        let Some(handle) = handle else { continue };
        if let Some(entry) = bodies.entry_mut(*handle) {
            farthest = farthest.max(write(params, state, &mut entry.body));
        }
    }
    farthest.cmple(bound).all()
}

/// Sets the impulses of every point whose normal or friction impulse is not finite to zero.
#[cold]
fn zero_non_finite_impulses(manifolds: &mut [ContactManifold]) {
    for point in manifolds.iter_mut().flat_map(|m| m.points.iter_mut()) {
        if !(point.normal_impulse.is_finite() && point.tangent_impulse.is_finite()) {
            point.normal_impulse = 0.0;
            point.tangent_impulse = Vec3::ZERO;
        }
    }
}
