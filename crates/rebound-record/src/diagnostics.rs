//! The measures a frame carries besides the state (`docs/recording.md`, frame header and JOINT STATE): the
//! positional error of each joint kind and the energy of a spring joint, plus the frame's totals of energy,
//! momentum, joint error and penetration. Kinetic and potential energy and momentum come from the engine's
//! own helpers (`rebound::dynamics::momentum::totals`); the joint measures are defined here because the
//! engine does not measure them.

use crate::frame::{Diagnostics, JointSample};
use rebound::dynamics::momentum::totals;
use rebound::{
    Axis, AxisMotion, Joint, JointKind, PhysicsWorld, Quat, RigidBody, SixDofJoint, SoftSpring,
    SpringModel, Vec3,
};

/// The positional error of `joint` (m) with its anchors at the world points `anchor_a`, `anchor_b` and
/// body A's orientation `rotation_a` (identity for a world joint):
///
/// * ball, hinge, fixed: `|B − A|` (the anchors should coincide);
/// * rod: `| |B − A| − length |`; rope: `max(0, |B − A| − max_length)`;
/// * prismatic: the part of `B − A` across the slide axis (A's joint-frame X);
/// * wheel: the part of `B − A` across the suspension axis (A's joint-frame Y);
/// * 6-DOF: the part of `B − A` along its locked linear axes and past its linear limits (A's joint frame);
/// * spring: 0 — a spring stretches by design.
///
/// Angular errors (a hinge's axes out of line, a weld's twist) are not included.
#[must_use]
pub fn joint_error(joint: &Joint, anchor_a: Vec3, anchor_b: Vec3, rotation_a: Quat) -> f32 {
    let d = anchor_b - anchor_a;
    let frame_a = rotation_a * joint.local_basis_a();
    let across = |axis: Vec3| (d - axis * d.dot(axis)).length();
    match joint.kind() {
        JointKind::Ball(_) | JointKind::Hinge(_) | JointKind::Fixed(_) => d.length(),
        JointKind::Rod(rod) => (d.length() - rod.length()).abs(),
        JointKind::Rope(rope) => (d.length() - rope.max_length()).max(0.0),
        JointKind::Prismatic(_) => across(frame_a * Vec3::X),
        JointKind::Wheel(_) => across(frame_a * Vec3::Y),
        JointKind::SixDof(j) => six_dof_error(j, frame_a, d),
        JointKind::Spring(_) => 0.0,
    }
}

/// The linear error of a 6-DOF joint with anchor separation `d` (m) and A's joint frame `frame_a`.
fn six_dof_error(joint: &SixDofJoint, frame_a: Quat, d: Vec3) -> f32 {
    let axes = [Axis::LinearX, Axis::LinearY, Axis::LinearZ];
    let squared: f32 = axes
        .iter()
        .zip([Vec3::X, Vec3::Y, Vec3::Z])
        .map(|(&axis, local)| {
            let x = d.dot(frame_a * local);
            let past = match joint.axis(axis).motion {
                AxisMotion::Free => 0.0,
                AxisMotion::Locked => x,
                AxisMotion::Limited(l) => x - x.clamp(l.lower(), l.upper()),
            };
            past * past
        })
        .sum();
    squared.sqrt()
}

/// The elastic energy of a `Spring` joint (J): `½·k·(|B − A| − L)²`, `L` the rest length. For a soft spring
/// given by frequency, `k = μ·(2π·f)²` with `μ = 1/(1/m_A + 1/m_B)` from the inverse masses `inv_mass_a`,
/// `inv_mass_b` (1/kg; 0 for a fixed body or the world) — the translational effective mass, as the spring's
/// own stiffness law `k = m_eff·ω²` uses it. 0 for other kinds and for an infinitely stiff spring.
#[must_use]
pub fn spring_energy(
    joint: &Joint,
    anchor_a: Vec3,
    anchor_b: Vec3,
    inv_mass_a: f32,
    inv_mass_b: f32,
) -> f32 {
    let JointKind::Spring(spring) = joint.kind() else {
        return 0.0;
    };
    let stiffness = match spring.model() {
        SpringModel::Force { stiffness, .. }
        | SpringModel::Soft(SoftSpring::Stiffness { stiffness, .. }) => stiffness,
        SpringModel::Soft(SoftSpring::Frequency { frequency_hz, .. }) => {
            let omega = std::f32::consts::TAU * frequency_hz;
            omega * omega / (inv_mass_a + inv_mass_b)
        }
    };
    if !stiffness.is_finite() {
        return 0.0;
    }
    let stretch = anchor_b.distance(anchor_a) - spring.rest_length();
    0.5 * stiffness * stretch * stretch
}

/// The frame's totals: energies and momenta of the world's bodies (the engine's helpers), spring energy, and
/// the worst error of the frame's joint samples. The deepest penetration is left 0: it is found while the
/// contacts are written (`crate::contacts::write_contacts`).
pub(crate) fn diagnostics(
    world: &PhysicsWorld,
    spring_energy: f32,
    joints: &[JointSample],
) -> Diagnostics {
    let bodies = world.bodies().iter().map(|(_, body)| body);
    let sums = totals(bodies, world.settings().gravity, Vec3::ZERO);
    Diagnostics {
        kinetic_energy: sums.kinetic_energy,
        potential_energy: sums.gravitational_potential_energy,
        spring_energy,
        linear_momentum: sums.linear_momentum,
        angular_momentum: sums.angular_momentum,
        worst_joint_error: joints
            .iter()
            .filter(|j| j.present && !j.broken)
            .map(|j| j.error)
            .fold(0.0, f32::max),
        deepest_penetration: 0.0,
    }
}

/// The inverse mass of an optional body (0 for the world).
pub(crate) fn inv_mass(body: Option<&RigidBody>) -> f32 {
    body.map_or(0.0, RigidBody::inv_mass)
}
