//! The quarantine: a moving body whose state leaves the bounds of [`crate::StepLimits`] (or is not finite)
//! is taken out of the step, so that one bad body cannot poison the solver for the others.
//!
//! Two checks. **At the start of the step** (after the kinematic targets became velocities, before
//! *collide*) every awake moving body's position, speed and angular speed are compared with the limits; a body
//! beyond them never reaches the collision backend or the solver. The bodies the last step wrote back were
//! compared with the limits as they were written ([`StartCheck`]), so this check runs only when something
//! could have changed them since: a body inserted, removed or edited (`World::body_mut`, a restore, a release
//! from quarantine — each moves [`crate::BodySet::revision`] on), other limits, a kinematic target that gives
//! its body a velocity beyond them, or a body the write-back (or an earlier check) found beyond them. **After
//! the solver passes** (before
//! *store*) every solved body's velocities and pose deltas: a body the solve drove beyond the limits or to a
//! non-finite value — a mass so large that its effective masses overflow, a motor at `f32::MAX`, an explicit
//! spring past its stability limit — is quarantined and the step's *prepare* and solver passes run again
//! without it, from the same start state, so nothing it did in the failed pass reaches the others.
//!
//! A bad body poisons what it touches within the pass (a contact with a non-finite velocity gives a
//! non-finite impulse), so the bodies found bad after a pass are suspects, not culprits: the passes run again
//! without all of them (and without any new ones that run finds), then with each suspect let back in turn,
//! in solver order; a suspect whose return leaves every result in bounds is innocent and stays in. Only the
//! guilty are quarantined. With more than [`MAX_TRIED_SUSPECTS`] suspects all are quarantined untried (the
//! passes are the step's cost, each).
//!
//! A quarantined body keeps its pose, its velocities are zeroed, its forces and kinematic target cleared, the
//! impulses of its joints zeroed and its contacts dropped; until [`crate::World::release_quarantine`] it is
//! in no step (no contact, no joint row, no sleep island), as if it were not in the world. Each quarantine is
//! reported once, by [`crate::Event::BodyQuarantined`] and the step report's count.
//!
//! Each rerun's joint paths build their rows anew: the rows a failed pass left to be carried
//! (`rebound_constraints::KeptRows`) may hold its non-finite values, and the rows kept from the last step are
//! gone by then. So bodies on a directly solved path move as without the bad body to the solver's tolerance
//! rather than bit for bit.

use crate::body_set::BodyEntry;
use crate::events::Event;
use crate::handles::BodyHandle;
use crate::limits::{QuarantineReason, StepLimits};
use crate::prepare::Solver;
use crate::state::WorldState;
use rebound_constraints::JointState;
use rebound_dynamics::{BodyType, SolverBody};
use rebound_math::glam::Vec3A;
use rebound_math::{Vec3, Vec4};

/// The most suspects of one step let back in one by one (see the module docs).
pub(crate) const MAX_TRIED_SUSPECTS: usize = 8;

/// The squares of the speed limits, computed once per check (the limits are at most 10¹⁵, so they are
/// finite).
pub(crate) struct Bounds {
    speed_sq: f32,
    angular_speed_sq: f32,
    position: f32,
}

impl Bounds {
    pub(crate) fn new(limits: &StepLimits) -> Self {
        Self {
            speed_sq: limits.max_speed * limits.max_speed,
            angular_speed_sq: limits.max_angular_speed * limits.max_angular_speed,
            position: limits.max_position,
        }
    }

    /// Whether a body at `position` moving at `v`, `w` is within every bound (a NaN fails every comparison;
    /// a squared length that overflows to ∞ exceeds every bound, as it should). Every body, every step: the
    /// comparisons side by side and one branch for the answer.
    #[inline]
    pub(crate) fn within(&self, position: Vec3, v: Vec3, w: Vec3) -> bool {
        let speeds = Vec3A::new(v.length_squared(), w.length_squared(), 0.0).cmple(Vec3A::new(
            self.speed_sq,
            self.angular_speed_sq,
            0.0,
        ));
        let place = Vec3A::from(position)
            .abs()
            .cmple(Vec3A::splat(self.position));
        (speeds & place).all()
    }

    /// Which bound a body outside them breaks, if any.
    #[cold]
    fn reason(&self, position: Vec3, v: Vec3, w: Vec3) -> Option<QuarantineReason> {
        if !(position.is_finite() && v.is_finite() && w.is_finite()) {
            Some(QuarantineReason::NotFinite)
        } else if v.length_squared() > self.speed_sq {
            Some(QuarantineReason::Speed)
        } else if w.length_squared() > self.angular_speed_sq {
            Some(QuarantineReason::AngularSpeed)
        } else if position.abs().max_element() > self.position {
            Some(QuarantineReason::Position)
        } else {
            None
        }
    }
}

/// What the start-of-step check needs to know of the bodies as the last step left them: whether every body
/// it would look at was within the limits then, and under which revision of the body set and which limits.
/// Not part of the world's state: a restore moves the revision on, so the next step checks every body.
#[derive(Debug, Default)]
pub(crate) struct StartCheck {
    /// The body set's revision and the limits after the last write-back, if every body written back was
    /// within those limits (and no sleeping body was found beyond them).
    clean: Option<(u64, StepLimits)>,
    /// Whether the last full check saw a sleeping body beyond the bounds: it is skipped while it sleeps, but
    /// wakes without an edit, so every step checks again until it is gone or quarantined.
    sleeping_beyond: bool,
}

impl StartCheck {
    /// After the write-back: `within` says whether every body written back is within the limits (its
    /// velocities as solved, its position as written).
    pub(crate) fn written(&mut self, state: &WorldState, within: bool) {
        self.clean = (within && !self.sleeping_beyond)
            .then_some((state.bodies.revision(), state.settings.limits));
    }

    /// Whether the bodies may have changed (or the limits) since the last write-back found them all within.
    fn is_needed(&self, state: &WorldState) -> bool {
        self.clean != Some((state.bodies.revision(), state.settings.limits))
    }
}

/// The check at the start of the step: every awake moving body out of bounds is quarantined. Returns how
/// many were. Skipped when nothing could have changed the bodies since the last write-back found them all
/// within the limits (see [`StartCheck`]); `targets_within` says whether the kinematic targets of this step
/// gave their bodies velocities within them.
pub(crate) fn check_bodies(
    state: &mut WorldState,
    start: &mut StartCheck,
    targets_within: bool,
    events: &mut Vec<Event>,
) -> usize {
    if targets_within && !start.is_needed(state) {
        return 0;
    }
    let bounds = Bounds::new(&state.settings.limits);
    let mut found = Vec::new();
    let mut sleeping_beyond = false;
    for (index, entry) in state.bodies.arena.iter() {
        let body = &entry.body;
        let (v, w) = (body.linear_velocity(), body.angular_velocity());
        // The bounds first, whatever the body: almost every body is within them, and one branch says so.
        if bounds.within(body.position(), v, w)
            || entry.quarantined
            || body.body_type() == BodyType::Fixed
        {
            continue;
        }
        if body.is_sleeping() {
            sleeping_beyond = true;
            continue;
        }
        if let Some(reason) = bounds.reason(body.position(), v, w) {
            found.push((BodyHandle(index), reason));
        }
    }
    start.sleeping_beyond = sleeping_beyond;
    quarantine(state, &found, events);
    found.len()
}

/// The check after the solver passes: the solved dynamic bodies (kinematic ones keep the velocities the
/// first check passed) whose velocities or pose deltas are out of bounds or not finite, into `found`
/// (cleared first) in solver order. Changes nothing: the step decides which of them to quarantine.
pub(crate) fn find_bad_results(
    state: &WorldState,
    s: &Solver,
    found: &mut Vec<(BodyHandle, QuarantineReason)>,
) {
    found.clear();
    let bounds = Bounds::new(&state.settings.limits);
    // Every solved body at once first (the fixed ones are at rest, the kinematic ones were checked): almost
    // always all are within, and the search below, body by body, is skipped.
    if all_solved_within(&bounds, &s.states) {
        return;
    }
    for ((handle, solved), params) in s.solver_handles.iter().zip(&s.states).zip(&s.params) {
        let Some(handle) = handle else { continue };
        if !params.is_dynamic() {
            continue;
        }
        if let Some(reason) = check_solved(&bounds, solved) {
            found.push((*handle, reason));
        }
    }
}

/// Marks a body as out of the step (`true`) or back in it, for a trial pass of the solver: *prepare* skips
/// a marked body and its contacts and joints.
pub(crate) fn set_excluded(state: &mut WorldState, body: BodyHandle, excluded: bool) {
    if let Some(entry) = state.bodies.entry_mut(body) {
        entry.quarantined = excluded;
    }
}

/// Quarantines `bodies`: each isolated (at rest, no force, no target), its contacts and joint impulses
/// cleared, an event each.
pub(crate) fn quarantine(
    state: &mut WorldState,
    bodies: &[(BodyHandle, QuarantineReason)],
    events: &mut Vec<Event>,
) {
    if bodies.is_empty() {
        return;
    }
    for &(body, reason) in bodies {
        if let Some(entry) = state.bodies.entry_mut(body) {
            isolate(entry);
            events.push(Event::BodyQuarantined { body, reason });
        }
    }
    forget(state, bodies);
}

/// What is wrong with a solved body, if anything: its velocities against the bounds, its pose deltas
/// finite (its position is checked at the start of the next step).
#[inline]
fn check_solved(bounds: &Bounds, solved: &SolverBody) -> Option<QuarantineReason> {
    if solved_within(bounds, solved) {
        None
    } else if !deltas_are_finite(solved) {
        Some(QuarantineReason::NotFinite)
    } else {
        bounds.reason(Vec3::ZERO, solved.linear_velocity, solved.angular_velocity)
    }
}

/// Whether every solved body of `states` certainly has velocities within the bounds and finite pose deltas,
/// in one pass with no branch per body. The bounds are checked on the largest square of each velocity
/// component over all bodies: a body's `v.x² + v.y² + v.z²`, added in the order [`Bounds::within`] adds it,
/// is no larger than the sum of the three largest squares (rounding keeps order), and the largest squares do
/// not grow with the number of bodies as a sum of them would. Finiteness is checked on sums of the squares of
/// every component: a NaN or an infinity anywhere makes its sum NaN or infinite (a maximum would lose a
/// NaN). The components go in the 16-byte groups a [`SolverBody`] keeps them in (`[v, ω.x]`,
/// `[ω.y, ω.z, Δp.x, Δp.y]`, `Δq`, `Δp.z`). `false` sends the caller to the body-by-body check, which finds
/// the answer (also when different bodies have the largest squares of one vector's components, or a sum
/// overflows, with every body within).
fn all_solved_within(bounds: &Bounds, states: &[SolverBody]) -> bool {
    let sums = (Vec4::ZERO, Vec4::ZERO, Vec4::ZERO, 0.0_f32);
    let ((first, second, rotation, last), (largest_first, largest_second)) = states.iter().fold(
        (sums, (Vec4::ZERO, Vec4::ZERO)),
        |((first, second, rotation, last), (largest_first, largest_second)), solved| {
            let (v, w, dp) = (
                solved.linear_velocity,
                solved.angular_velocity,
                solved.delta_position,
            );
            let a = Vec4::new(v.x, v.y, v.z, w.x);
            let b = Vec4::new(w.y, w.z, dp.x, dp.y);
            let q = Vec4::from(solved.delta_rotation);
            let (aa, bb) = (a * a, b * b);
            (
                (
                    first + aa,
                    second + bb,
                    rotation + q * q,
                    last + dp.z * dp.z,
                ),
                (largest_first.max(aa), largest_second.max(bb)),
            )
        },
    );
    let speed_sq = largest_first.x + largest_first.y + largest_first.z;
    let angular_speed_sq = largest_first.w + largest_second.x + largest_second.y;
    let finite =
        (first.element_sum() + second.element_sum() + rotation.element_sum() + last).is_finite();
    speed_sq <= bounds.speed_sq && angular_speed_sq <= bounds.angular_speed_sq && finite
}

/// Whether a solved body's velocities are within the bounds and its pose deltas finite.
#[inline]
fn solved_within(bounds: &Bounds, solved: &SolverBody) -> bool {
    deltas_are_finite(solved)
        & bounds.within(Vec3::ZERO, solved.linear_velocity, solved.angular_velocity)
}

/// Whether a solved body's pose deltas are finite: `x·0` is 0 for a finite `x` and NaN otherwise, so one
/// comparison covers the seven numbers.
#[inline]
fn deltas_are_finite(solved: &SolverBody) -> bool {
    let deltas = Vec3A::from(solved.delta_position) * 0.0
        + Vec3A::splat(solved.delta_rotation.length_squared() * 0.0);
    deltas.cmpeq(Vec3A::ZERO).all()
}

/// Takes a body out of the steps: at rest where it is, no force, no kinematic target.
fn isolate(entry: &mut BodyEntry) {
    entry.quarantined = true;
    entry.kinematic_target = None;
    entry.sleep_time = 0.0;
    entry.body.clear_forces();
    // Zero is finite: both setters accept it.
    let _ = entry.body.set_linear_velocity(Vec3::ZERO);
    let _ = entry.body.set_angular_velocity(Vec3::ZERO);
}

/// Clears what the world keeps of the quarantined bodies' interactions: last step's manifolds with them
/// (no warm start from them) and the impulses of their joints (kept: whether a joint broke).
fn forget(state: &mut WorldState, bodies: &[(BodyHandle, QuarantineReason)]) {
    let is_bad = |h: BodyHandle| bodies.iter().any(|&(b, _)| b == h);
    let involves = |a: BodyHandle, b: BodyHandle| is_bad(a) || is_bad(b);
    state.manifolds.retain(|m| !involves(m.body_a, m.body_b));
    for (_, joint) in state.joints.iter_mut() {
        let a = joint.body_a.unwrap_or(joint.body_b);
        if involves(a, joint.body_b) {
            joint.state = JointState {
                broken: joint.state.broken,
                ..JointState::default()
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Bounds of 100 m/s and 50 rad/s (the position bound is not read after the solve).
    fn bounds() -> Bounds {
        Bounds {
            speed_sq: 1.0e4,
            angular_speed_sq: 2.5e3,
            position: 1.0e4,
        }
    }

    /// A component anywhere from tiny to beyond the bounds, or not finite.
    fn component() -> impl Strategy<Value = f32> {
        prop_oneof![
            8 => -120.0_f32..120.0,
            1 => Just(f32::NAN),
            1 => Just(f32::INFINITY),
            1 => Just(-3.0e38_f32),
        ]
    }

    fn vector() -> impl Strategy<Value = Vec3> {
        (component(), component(), component()).prop_map(|(x, y, z)| Vec3::new(x, y, z))
    }

    fn solved() -> impl Strategy<Value = SolverBody> {
        (vector(), vector(), vector(), vector(), component()).prop_map(|(v, w, dp, q, qw)| {
            SolverBody {
                delta_rotation: rebound_math::Quat::from_xyzw(q.x, q.y, q.z, qw),
                linear_velocity: v,
                angular_velocity: w,
                delta_position: dp,
            }
        })
    }

    proptest! {
        /// The check over all bodies never passes a set with a body the body-by-body check finds out of
        /// bounds or not finite.
        #[test]
        fn all_within_only_when_each_is(states in prop::collection::vec(solved(), 0..6)) {
            let bounds = bounds();
            if all_solved_within(&bounds, &states) {
                for solved in &states {
                    prop_assert!(solved_within(&bounds, solved), "{solved:?}");
                }
            }
        }

        /// Bodies well within the bounds, in any number, pass it: the body-by-body search is skipped.
        #[test]
        fn bodies_at_moderate_speeds_pass(
            states in prop::collection::vec(
                (-1.0_f32..1.0, -1.0_f32..1.0, -1.0_f32..1.0).prop_map(|(x, y, z)| SolverBody {
                    delta_rotation: rebound_math::Quat::from_rotation_y(x),
                    linear_velocity: Vec3::new(x, y, z) * 5.0,
                    angular_velocity: Vec3::new(z, x, y) * 2.0,
                    delta_position: Vec3::new(y, z, x) * 0.1,
                }),
                0..64,
            )
        ) {
            // Each body at most √75 m/s and √12 rad/s: 64 of them sum to at most 4,800 and 768.
            prop_assert!(all_solved_within(&bounds(), &states));
        }
    }

    /// Many bodies each near the bounds pass the check over all (a sum of their squares would exceed the
    /// bounds and send every step to the body-by-body search), and one NaN or infinity among them fails it.
    #[test]
    fn many_bodies_near_the_bounds_pass_and_one_not_finite_fails() {
        let near = SolverBody {
            linear_velocity: Vec3::new(0.0, 99.0, 10.0),
            angular_velocity: Vec3::new(49.0, 0.0, 5.0),
            delta_position: Vec3::new(1.0e3, -1.0e3, 1.0e3),
            ..SolverBody::STATIC
        };
        let bounds = bounds();
        let mut states = vec![near; 100_000];
        assert!(solved_within(&bounds, &near));
        assert!(all_solved_within(&bounds, &states));
        for bad in [f32::NAN, f32::INFINITY] {
            let mut broken = near;
            broken.delta_position.z = bad;
            states[50_000] = broken;
            assert!(!all_solved_within(&bounds, &states), "{bad}");
            broken = near;
            broken.angular_velocity.y = bad;
            states[50_000] = broken;
            assert!(!all_solved_within(&bounds, &states), "{bad}");
        }
    }

    #[test]
    fn one_fast_body_among_slow_ones_fails_the_check_over_all() {
        let slow = SolverBody {
            linear_velocity: Vec3::new(1.0, 0.0, 0.0),
            ..SolverBody::STATIC
        };
        let fast = SolverBody {
            linear_velocity: Vec3::new(0.0, 100.5, 0.0),
            ..SolverBody::STATIC
        };
        let spinning = SolverBody {
            angular_velocity: Vec3::new(0.0, 0.0, 50.5),
            ..SolverBody::STATIC
        };
        let bounds = bounds();
        assert!(all_solved_within(&bounds, &[slow, slow]));
        assert!(!all_solved_within(&bounds, &[slow, fast, slow]));
        assert!(!all_solved_within(&bounds, &[spinning, slow]));
    }
}
