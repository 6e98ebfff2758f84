//! Limited hinges and fixed joints in the direct solve of paths (`rebound_constraints::path`): a chain of
//! five hinged bars falling from the horizontal into their limits keeps every hinge within 0.5° of its
//! limits; a cantilever of eight boxes welded to a wall drops its tip by at most 1 mm (a rigid beam does not
//! drop at all); a welded bar of four boxes swinging on a ball joint follows the one rigid box of the same
//! mass and inertia to 1 mm. Each checks that the joints are solved directly, every row, at every step.

#![allow(
    clippy::unwrap_used,
    reason = "helpers outside #[test] functions build known-valid inputs; a failure is a test failure"
)]

mod support;

use rebound_constraints::{BallJoint, FixedJoint, HingeJoint, Joint, JointSettings, twist_angle};
use rebound_dynamics::{BodyDesc, MassProperties, SolverSettings};
use rebound_math::Vec3;
use support::Harness;

const DT: f32 = 1.0 / 60.0;

/// A box of `mass` (kg) and half extents `half` (m): principal inertia `m/3·(b² + c²)`, ….
fn cuboid(mass: f32, half: Vec3) -> MassProperties {
    let h2 = half * half;
    let inertia = Vec3::new(h2.y + h2.z, h2.x + h2.z, h2.x + h2.y) * (mass / 3.0);
    MassProperties::new(mass, Vec3::ZERO, inertia).unwrap()
}

/// The half extents of every bar and box (m): 0.5 m long along x.
const HALF: Vec3 = Vec3::new(0.25, 0.05, 0.05);

/// `count` boxes of 1 kg laid end to end along +x from a fixed body at the origin, box `i` joined to the one
/// before (the first to the fixed body) by `joint(i)` with anchors at their touching faces: the harness, the
/// boxes and the joints.
fn row_of_boxes(
    settings: JointSettings,
    count: usize,
    joint: impl Fn(usize) -> Joint,
) -> (Harness, Vec<usize>, Vec<usize>) {
    let mut h = Harness::new(SolverSettings::default()).with_joint_settings(settings);
    let wall = h.world_anchor();
    let (mut boxes, mut joints) = (Vec::new(), Vec::new());
    let mut previous = (wall, Vec3::ZERO);
    for i in 0..count {
        let centre = Vec3::new(HALF.x * (2 * i + 1) as f32, 0.0, 0.0);
        let b = h.add(
            &BodyDesc::dynamic()
                .with_mass_properties(cuboid(1.0, HALF))
                .with_position(centre),
        );
        let j = joint(i)
            .with_local_anchors(previous.1, Vec3::new(-HALF.x, 0.0, 0.0))
            .unwrap();
        joints.push(h.join(j, previous.0, b));
        boxes.push(b);
        previous = (b, Vec3::new(HALF.x, 0.0, 0.0));
    }
    (h, boxes, joints)
}

/// Whether every joint of `joints` had all its rows in the direct solve in the last step.
fn all_direct(h: &Harness, joints: &[usize]) -> bool {
    joints.iter().all(|&j| h.solver.is_solved_directly(j))
}

const LIMIT: f32 = 0.5;

/// The largest hinge angle's magnitude (rad) among `joints`.
fn largest_angle(h: &Harness, joints: &[usize]) -> f32 {
    joints
        .iter()
        .map(|&j| {
            let pair = h.pairs[j];
            let joint = &h.joints[j];
            let frame_a = h.bodies[pair.a].rotation() * joint.local_basis_a();
            let frame_b = h.bodies[pair.b].rotation() * joint.local_basis_b();
            twist_angle(frame_a, frame_b).abs()
        })
        .fold(0.0, f32::max)
}

/// Five hinged bars about z, limited to ±0.5 rad, falling from the horizontal: each hinge bends until its
/// limit stops it, the first (at the fixed body) with the whole chain's weight and swing on it. The worst
/// hinge angle's magnitude over 4 s (its excess past `LIMIT` is the worst excess) and whether every hinge
/// was solved directly throughout.
fn falling_hinge_chain(settings: JointSettings) -> (f32, bool) {
    let hinge = |_| {
        Joint::new(HingeJoint::new().with_limits(-LIMIT, LIMIT).unwrap())
            .with_local_axes(Vec3::Z, Vec3::Z)
            .unwrap()
    };
    let (mut h, _, joints) = row_of_boxes(settings, 5, hinge);
    let (mut worst, mut direct) = (0.0f32, true);
    for _ in 0..240 {
        h.step(DT);
        worst = worst.max(largest_angle(&h, &joints));
        direct &= all_direct(&h, &joints);
    }
    (worst, direct)
}

#[test]
fn a_chain_of_limited_hinges_falling_into_its_limits_holds_each_within_half_a_degree() {
    let (largest, direct) = falling_hinge_chain(JointSettings::default());
    let (iterated, _) = falling_hinge_chain(JointSettings {
        direct_chains: false,
        ..JointSettings::default()
    });
    let (worst, iterated) = (largest - LIMIT, iterated - LIMIT);
    println!(
        "falling hinge chain: worst limit excess {worst:.3e} rad solved directly, {iterated:.3e} rad joint \
         by joint"
    );
    assert!(
        direct,
        "a limited hinge left rows to the Gauss–Seidel passes"
    );
    // Driven into its limits: some hinge reaches one (to 0.01 rad).
    assert!(
        worst > -0.01,
        "no hinge reached its limit: {largest} rad at most"
    );
    assert!(
        worst < 0.5f32.to_radians(),
        "a hinge passed its limit by {worst} rad"
    );
}

/// Eight 1 kg boxes welded end to end to a wall, 4 m of beam sticking out along +x under gravity: the
/// largest drop of the tip box's far end below its start over 3 s (m), and whether every weld was solved
/// directly throughout.
fn cantilever_tip_drop(settings: JointSettings) -> (f32, bool) {
    let (mut h, boxes, joints) = row_of_boxes(settings, 8, |_| Joint::new(FixedJoint::new()));
    let tip = *boxes.last().unwrap();
    let far_end = Vec3::new(HALF.x, 0.0, 0.0);
    let start = h.world_point(tip, far_end);
    let (mut drop, mut direct) = (0.0f32, true);
    for _ in 0..180 {
        h.step(DT);
        drop = drop.max(start.y - h.world_point(tip, far_end).y);
        direct &= all_direct(&h, &joints);
    }
    (drop, direct)
}

#[test]
fn a_cantilever_of_eight_welded_boxes_drops_its_tip_by_at_most_a_millimetre() {
    let (drop, direct) = cantilever_tip_drop(JointSettings::default());
    let (iterated, _) = cantilever_tip_drop(JointSettings {
        direct_chains: false,
        ..JointSettings::default()
    });
    println!(
        "welded cantilever: worst tip drop {:.4} mm solved directly, {:.1} mm joint by joint",
        drop * 1e3,
        iterated * 1e3
    );
    assert!(direct, "a weld left rows to the Gauss–Seidel passes");
    assert!(drop <= 1e-3, "the tip dropped by {} mm", drop * 1e3);
}

#[test]
fn a_welded_bar_swings_on_a_ball_joint_as_the_one_rigid_box_of_its_mass() {
    // Four boxes welded end to end, hung by a ball joint at the near end of the first from a fixed body at
    // the origin, released horizontal at rest: a compound pendulum swinging down through 3 m of arc.
    const COUNT: usize = 4;
    let joint = |i: usize| {
        if i == 0 {
            Joint::new(BallJoint::new())
        } else {
            Joint::new(FixedJoint::new())
        }
    };
    let (mut welded, boxes, joints) = row_of_boxes(JointSettings::default(), COUNT, joint);
    // The same bar as one box: 4 kg, half extents (1, 0.05, 0.05) — the same mass distribution.
    let mut rigid = Harness::new(SolverSettings::default());
    let pivot = rigid.world_anchor();
    let bar_half = Vec3::new(HALF.x * COUNT as f32, HALF.y, HALF.z);
    let bar = rigid.add(
        &BodyDesc::dynamic()
            .with_mass_properties(cuboid(COUNT as f32, bar_half))
            .with_position(Vec3::new(bar_half.x, 0.0, 0.0)),
    );
    rigid.join(
        Joint::new(BallJoint::new())
            .with_local_anchors(Vec3::ZERO, Vec3::new(-bar_half.x, 0.0, 0.0))
            .unwrap(),
        pivot,
        bar,
    );
    let tip = *boxes.last().unwrap();
    let tip_welded = |h: &Harness| h.world_point(tip, Vec3::new(HALF.x, 0.0, 0.0));
    let tip_rigid = |h: &Harness| h.world_point(bar, Vec3::new(bar_half.x, 0.0, 0.0));
    let (mut apart, mut gap, mut turn, mut direct) = (0.0f32, 0.0f32, 0.0f32, true);
    for _ in 0..120 {
        welded.step(DT);
        rigid.step(DT);
        apart = apart.max(tip_welded(&welded).distance(tip_rigid(&rigid)));
        for &j in &joints[1..] {
            let (pair, weld) = (welded.pairs[j], &welded.joints[j]);
            let anchor_a = welded.world_point(pair.a, weld.local_anchor_a());
            gap = gap.max(anchor_a.distance(welded.world_point(pair.b, weld.local_anchor_b())));
            let frame_a = welded.bodies[pair.a].rotation() * weld.local_basis_a();
            let frame_b = welded.bodies[pair.b].rotation() * weld.local_basis_b();
            turn = turn.max(2.0 * (frame_b * frame_a.conjugate()).xyz().length());
        }
        direct &= all_direct(&welded, &joints);
    }
    let swing = tip_rigid(&rigid).distance(Vec3::new(2.0 * bar_half.x, 0.0, 0.0));
    println!(
        "welded bar against one rigid box over 2 s (the tip moved {swing:.2} m): tips {:.3} mm apart, welds \
         open by {:.3} mm and turned by {turn:.1e} rad at worst",
        apart * 1e3,
        gap * 1e3,
    );
    assert!(
        direct,
        "a weld or the ball joint left rows to the Gauss–Seidel passes"
    );
    assert!(swing > 1.0, "the bar hardly moved: {swing} m");
    // Each weld holds its relative pose: the anchors together to the projection's tolerance (0.1 mm) and
    // what the swing's load opens between projections, the frames to 0.1 mrad.
    assert!(gap <= 5e-4, "a weld opened by {} mm", gap * 1e3);
    assert!(turn <= 1e-4, "a weld turned by {turn} rad");
    // The bar swings as the one box: the two differ by the joints' soft step and those gaps, not by a
    // weld's give (0.3 % of the tip's path).
    assert!(
        apart <= 1e-2,
        "the welded bar's tip strayed {} mm",
        apart * 1e3
    );
}
