//! Stage *project positions*, the velocities after it. The projection moves a path's bodies by position
//! impulses `p` along its rows, `Δx = M⁻¹·Jᵀ·p`. Left alone, the velocities would be those of bodies that
//! never moved: a bob pulled in towards the other end of its rope would keep its speed across the rope
//! instead of its angular momentum about that end, and lose the work of the centripetal force over the
//! shortening, `m·|v⊥|²·δ/L`. The soft rows stretch the rope again in the next step and the projection
//! pulls it in again: a rope pendulum released from 80° lost 2.5 % of its energy every period that way.
//!
//! Moving the bodies by `Δx` takes forces along the rows, and the rows turn with the bodies while they act.
//! A push out and back that starts and ends with the velocities along the rows unchanged (`∫f dt = 0`) and
//! displaces by `Δx` has the second moment `∫t·f dt = −p`, so it changes the velocities by
//! `Δv = M⁻¹·∫J(t)ᵀ·f dt = −M⁻¹·J̇ᵀ·p`, `J̇` the rows' rate of turn at the current velocities. This file
//! applies that change for the rope and rod rows (their `J̇` below): for a bob on a rope it is `v⊥·δ/L`
//! across the rope, its angular momentum about the other end kept to first order (`docs/physics.md`,
//! "Energy of constrained motion"). The forces are internal, so linear and angular momentum are kept too.
//!
//! ```text
//! d = c_b + r_b − c_a − r_a,  n = d/|d|,  ḋ = v_b + ω_b × r_b − v_a − ω_a × r_a,  ṅ = (ḋ − (ḋ·n)·n)/|d|
//! J = [ −n  −(r_a × n)  n  r_b × n ],   J̇ = [ −ṅ  −(ṙ_a × n + r_a × ṅ)  ṅ  ṙ_b × n + r_b × ṅ ],  ṙ = ω × r
//! ```

use super::dispatch::PreparedJoint;
use crate::pair::MIN_AXIS_LENGTH;
use rebound_dynamics::SolverBody;
use rebound_math::Vec3;

/// The largest change of a link's relative velocity across it that the turning of its row may make, as a
/// fraction of that velocity: 1 %. The first-order change above holds while the link turns little during
/// the push, i.e. while the projection's displacement is small against the link (`δ/L`); a swinging
/// pendulum's projection stays below 0.1 % of it. Beyond, the projection is taking back the drift of a link
/// that turned by a large angle within one substep (the whip of a falling chain: centimetres on a 0.25 m
/// link), an error of the velocity passes that no push made, and scaling the velocity by it fed the whip:
/// the 100-link chain released horizontally (`tests/chain.rs`) blew up without the cap.
pub(super) const MAX_TURN_CHANGE: f32 = 0.01;

/// Changes the velocities of each rope and rod of `members` (joint indices, in path order) by `−M⁻¹·J̇ᵀ·p`,
/// `p` its distance row's position impulse in the projection just made (`impulses`, one per member, N·s·s;
/// 0 for joints that are no rope or rod and for links the projection did not move: those are left alone,
/// bit for bit), scaled down to at most [`MAX_TURN_CHANGE`] of the link's velocity across it.
pub(super) fn apply_turning_rows(
    joints: &[PreparedJoint],
    members: &[usize],
    impulses: &[f32],
    solver_bodies: &mut [SolverBody],
) {
    for (&index, &p) in members.iter().zip(impulses) {
        let j = &joints[index];
        if p == 0.0 || j.kind.link_length().is_none() {
            continue;
        }
        let Some([a, b]) = j.pair.bodies_mut(solver_bodies) else {
            continue;
        };
        let dist = j.pair.distance(a, b, Vec3::X);
        if dist.length <= MIN_AXIS_LENGTH {
            continue;
        }
        let (n, r_a, r_b) = (dist.axis, dist.anchors.r_a, dist.anchors.r_b);
        let turn_a = a.angular_velocity.cross(r_a);
        let turn_b = b.angular_velocity.cross(r_b);
        let rate = b.linear_velocity + turn_b - a.linear_velocity - turn_a;
        let n_dot = (rate - n * rate.dot(n)) / dist.length;
        let pair = &j.pair;
        // |Δv across| / |v across| of the centres' part: (1/m_a + 1/m_b)·|p|/|d|.
        let change = (pair.inv_mass_a + pair.inv_mass_b) * p.abs() / dist.length;
        let p = if change > MAX_TURN_CHANGE {
            p * (MAX_TURN_CHANGE / change)
        } else {
            p
        };
        a.linear_velocity += n_dot * (pair.inv_mass_a * p);
        a.angular_velocity += pair.inv_inertia_a * (turn_a.cross(n) + r_a.cross(n_dot)) * p;
        b.linear_velocity -= n_dot * (pair.inv_mass_b * p);
        b.angular_velocity -= pair.inv_inertia_b * (turn_b.cross(n) + r_b.cross(n_dot)) * p;
    }
}
