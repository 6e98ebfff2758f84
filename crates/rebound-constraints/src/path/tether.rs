//! Long-range tethers (Kim, Chentanez and Müller, "Long Range Attachments — A Method to Simulate
//! Inextensible Clothing in Computer Games", SCA 2012) and the joint graph they are found in. Built at
//! *prepare*, solved with the joints in *warm start*, *solve* and *relax*.
//!
//! A body hanging from a fixed body through a chain of ropes, rods, ball, hinge or fixed joints can never be
//! farther from the chain's fixed anchor point than the length of the chain — the sum of the rope and rod
//! lengths plus the distances between the two anchors on each intermediate body. That bound is a rope of its
//! own, from the fixed anchor straight to the body: a **tether**. It is redundant with the chain: it applies
//! nothing while the chain is bent or slack, and only what the chain itself would once the chain is straight
//! and taut — but it carries that load in one row instead of through every link, so Gauss–Seidel no longer has to
//! propagate a heavy end mass up a long chain one link per iteration (the mass-ratio problem). With it a
//! 100-link chain with a 10× end mass holds its length (tests/chain.rs); without it the soft step lets it
//! stretch by the load over the joint stiffness.
//!
//! ```text
//! C = |p_body − p_anchor| − L_path ≤ 0,    L_path = Σ link lengths + Σ |r_out − r_in| over the bodies between
//! ```
//!
//! The tether is the distance row of a rope ([`crate::Rope`], `crate::part::DistanceRow` at most its length):
//! speculative while slack, joint softness in the bias pass, rigid in the relax pass. Its impulse is stored in the
//! [`crate::JointState::tether_impulse`] of the joint through which the body was reached, for warm starting.
//!
//! **Paths solved directly.** A body whose every joint back to the root belongs to one path solved directly
//! ([`crate::path`]) — a rope chain hanging from a fixed body, a deck hung between two anchors — gets no
//! tether. The tether exists to carry the load below a link in one row instead of one link per Gauss–Seidel
//! iteration; the direct solve already gives each of the path's rows the effective mass of the whole chain
//! behind it, and the tether's bound is implied by the path's rows (it is the sum of their lengths), so it
//! would only cost a row per body and per pass. The condition is checked joint by joint in the search: the
//! first joint (at the root) is on a path, and each later joint is on the same path as the joint before it.
//! A body reached through a joint solved by Gauss–Seidel (a fixed joint, a closed loop, direct chains off)
//! or across a branching body (where two paths meet, coupled only by Gauss–Seidel) keeps its tether.
//!
//! The graph search is breadth-first from every fixed or kinematic body (inverse mass 0) over the prepared
//! joints; each body gets its distance in joints and, when the path to it is made only of tetherable joints and
//! at least two joints long, a tether. A body reached through two paths keeps the first (fewest joints; ties
//! by joint order), so the result is deterministic.

use crate::pair::BodyPair;
use crate::part::{AxisPart, Bound, DistanceRow};
use crate::stage::Stage;
use rebound_dynamics::SolverBody;
use rebound_math::{Mat3, Vec3};

/// One joint as the graph search sees it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Edge {
    // Only what the search reads of the joint's `BodyPair`: copying whole pairs (two inertia matrices, two
    // bases, …) for every joint and step was most of the search's memory traffic.
    /// The joint's body A (index into the solver bodies).
    pub index_a: usize,
    /// The joint's body B.
    pub index_b: usize,
    /// Body A's inverse mass (1/kg): 0 makes it a root of the search.
    pub inv_mass_a: f32,
    /// Body B's inverse mass (1/kg).
    pub inv_mass_b: f32,
    /// The joint's anchor on body A (m, from its centre of mass, world axes at the start of the step).
    pub anchor_a: Vec3,
    /// The joint's anchor on body B.
    pub anchor_b: Vec3,
    /// The distance the joint allows between its anchors (m): a rope's or rod's length, 0 for a point
    /// joint; `None` for joints that do not bound the distance (springs, prismatic, wheel).
    pub length: Option<f32>,
    /// The path solved directly ([`crate::path`]) the joint belongs to, if any.
    pub path: Option<usize>,
}

/// Whether a body of inverse mass `inv_mass` (1/kg) is a root of the search: fixed or kinematic.
#[inline]
fn is_root(inv_mass: f32) -> bool {
    inv_mass == 0.0
}

/// Whether a joint that allows its anchors `length` apart (`None`: no bound, [`Edge::length`]), between
/// bodies of inverse masses `inv_masses` (1/kg), can be the first joint of a tether: it bounds the distance
/// and one of its bodies is a root. Every tether starts with one, so without one the search makes none.
#[inline]
pub(crate) fn starts_a_tether(length: Option<f32>, (inv_mass_a, inv_mass_b): (f32, f32)) -> bool {
    length.is_some() && (is_root(inv_mass_a) || is_root(inv_mass_b))
}

/// What the search found about one body.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Node {
    /// Joints between it and the nearest fixed body; `u32::MAX` if unreachable.
    depth: u32,
    /// Whether a tether path reaches it (only tetherable joints on the way).
    tethered: bool,
    /// Whether every joint between it and the root belongs to one directly solved path: its tether would be
    /// redundant.
    direct: bool,
    /// The fixed body at the root of its path.
    root: usize,
    /// The root joint's anchor on the fixed body (relative to its centre of mass, world axes, m).
    root_anchor: Vec3,
    /// The anchor of the incoming joint on this body (relative to its centre of mass, world axes, m).
    in_anchor: Vec3,
    /// Index of the incoming joint (into the prepared joints).
    in_joint: usize,
    /// Path length from the root anchor to `in_anchor` (m).
    length: f32,
}

const UNREACHED: Node = Node {
    depth: u32::MAX,
    tethered: false,
    direct: false,
    root: 0,
    root_anchor: Vec3::ZERO,
    in_anchor: Vec3::ZERO,
    in_joint: usize::MAX,
    length: 0.0,
};

/// Scratch buffers of the graph search, reused from step to step.
#[derive(Debug, Clone, Default)]
pub(crate) struct JointGraph {
    /// Neighbours of body `i`: `edges[start[i]..start[i + 1]]`, as (joint index, other body, this is side A).
    start: Vec<usize>,
    edges: Vec<(usize, usize, bool)>,
    queue: Vec<usize>,
    nodes: Vec<Node>,
}

impl JointGraph {
    /// Breadth-first search from the fixed bodies over `joints`, for `body_count` bodies.
    pub(crate) fn analyse(&mut self, joints: &[Edge], body_count: usize) {
        self.start.clear();
        self.start.resize(body_count + 1, 0);
        for e in joints {
            self.start[e.index_a + 1] += 1;
            self.start[e.index_b + 1] += 1;
        }
        for i in 0..body_count {
            self.start[i + 1] += self.start[i];
        }
        self.edges.clear();
        self.edges.resize(self.start[body_count], (0, 0, false));
        // `queue` is the fill cursor per body first.
        self.queue.clear();
        self.queue.extend_from_slice(&self.start[..body_count]);
        for (j, e) in joints.iter().enumerate() {
            let (a, b) = (e.index_a, e.index_b);
            self.edges[self.queue[a]] = (j, b, true);
            self.queue[a] += 1;
            self.edges[self.queue[b]] = (j, a, false);
            self.queue[b] += 1;
        }
        self.nodes.clear();
        self.nodes.resize(body_count, UNREACHED);
        self.queue.clear();
        for e in joints {
            for (index, inv_mass) in [(e.index_a, e.inv_mass_a), (e.index_b, e.inv_mass_b)] {
                if is_root(inv_mass) && self.nodes[index].depth != 0 {
                    self.nodes[index] = Node {
                        depth: 0,
                        root: index,
                        ..UNREACHED
                    };
                    self.queue.push(index);
                }
            }
        }
        let mut head = 0;
        while let Some(&body) = self.queue.get(head) {
            head += 1;
            let node = self.nodes[body];
            for k in self.start[body]..self.start[body + 1] {
                let (j, other, body_is_a) = self.edges[k];
                if self.nodes[other].depth != u32::MAX {
                    continue;
                }
                let e = &joints[j];
                let (here, there) = if body_is_a {
                    (e.anchor_a, e.anchor_b)
                } else {
                    (e.anchor_b, e.anchor_a)
                };
                let mut next = Node {
                    depth: node.depth.saturating_add(1),
                    root: node.root,
                    in_anchor: there,
                    in_joint: j,
                    ..UNREACHED
                };
                if let Some(length) = e.length {
                    if node.depth == 0 {
                        next.tethered = true;
                        next.direct = e.path.is_some();
                        next.root_anchor = here;
                        next.length = length;
                    } else if node.tethered {
                        next.direct = node.direct
                            && e.path.is_some()
                            && joints.get(node.in_joint).map(|p| p.path) == Some(e.path);
                        next.tethered = true;
                        next.root_anchor = node.root_anchor;
                        next.length = node.length + (here - node.in_anchor).length() + length;
                    }
                }
                self.nodes[other] = next;
                self.queue.push(other);
            }
        }
    }

    /// The tethers: one per body two or more joints away from a fixed body along tetherable joints, in body
    /// order — except bodies whose whole way to the fixed body is one directly solved path (see the module
    /// documentation). `params` gives the bodies' masses and centres (inverse masses and inertias, start-of-step
    /// centres of mass).
    pub(crate) fn tethers<'a>(
        &'a self,
        inv_mass: impl Fn(usize) -> (f32, Mat3, Vec3) + 'a,
    ) -> impl Iterator<Item = Tether> + 'a {
        self.nodes
            .iter()
            .enumerate()
            .filter(|(_, n)| n.tethered && !n.direct && n.depth >= 2)
            .map(move |(body, n)| {
                let (inv_mass_a, inv_inertia_a, center_a) = inv_mass(n.root);
                let (inv_mass_b, inv_inertia_b, center_b) = inv_mass(body);
                Tether {
                    pair: BodyPair {
                        index_a: n.root,
                        index_b: body,
                        inv_mass_a,
                        inv_mass_b,
                        inv_inertia_a,
                        inv_inertia_b,
                        anchor_a: n.root_anchor,
                        anchor_b: n.in_anchor,
                        basis_a: rebound_math::Quat::IDENTITY,
                        basis_b: rebound_math::Quat::IDENTITY,
                        delta_center: center_b - center_a,
                    },
                    max_length: n.length,
                    joint: n.in_joint,
                    impulse: 0.0,
                }
            })
    }
}

/// A tether: an implicit rope from a fixed anchor to a body, as long as the chain between them.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Tether {
    pub pair: BodyPair,
    pub max_length: f32,
    /// The prepared joint whose state stores the impulse.
    pub joint: usize,
    /// Accumulated impulse (N·s, ≤ 0).
    pub impulse: f32,
}

impl Tether {
    pub(crate) fn warm_start(&self, a: &mut SolverBody, b: &mut SolverBody) {
        if self.impulse == 0.0 {
            return;
        }
        let dist = self.pair.distance(a, b, Vec3::X);
        AxisPart::along(&self.pair, &dist).apply(&self.pair, a, b, self.impulse);
    }

    pub(crate) fn solve(&mut self, a: &mut SolverBody, b: &mut SolverBody, stage: &Stage) {
        let bodies = (&*a, &*b);
        let row = DistanceRow::measure(&self.pair, bodies, Vec3::X, self.max_length, Bound::AtMost);
        row.solve(&self.pair, a, b, stage, &mut self.impulse);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rope of 1 m between bodies `a` and `b` (body 0 fixed, the others 1 kg), on direct path `path`.
    fn rope(a: usize, b: usize, path: Option<usize>) -> Edge {
        let inv_mass = |i: usize| if i == 0 { 0.0 } else { 1.0 };
        Edge {
            index_a: a,
            index_b: b,
            inv_mass_a: inv_mass(a),
            inv_mass_b: inv_mass(b),
            anchor_a: Vec3::ZERO,
            anchor_b: Vec3::ZERO,
            length: Some(1.0),
            path,
        }
    }

    /// The bodies that get a tether, for a chain 0 (fixed) – 1 – 2 – 3 – 4 whose joints are on `paths`.
    fn tethered(paths: [Option<usize>; 4]) -> Vec<usize> {
        let edges: Vec<Edge> = (0..4).map(|i| rope(i, i + 1, paths[i])).collect();
        let mut graph = JointGraph::default();
        graph.analyse(&edges, 5);
        graph
            .tethers(|_| (1.0, Mat3::ZERO, Vec3::ZERO))
            .map(|t| t.pair.index_b)
            .collect()
    }

    #[test]
    fn a_chain_solved_as_one_path_from_its_fixed_body_gets_no_tethers() {
        assert_eq!(tethered([Some(0); 4]), Vec::<usize>::new());
    }

    #[test]
    fn bodies_reached_past_the_end_of_a_path_keep_their_tethers() {
        // Joint by joint: every body two or more joints away.
        assert_eq!(tethered([None; 4]), vec![2, 3, 4]);
        // The path stops at body 2 (another path, or Gauss–Seidel, beyond it).
        assert_eq!(tethered([Some(0), Some(0), Some(1), Some(1)]), vec![3, 4]);
        assert_eq!(tethered([Some(0), Some(0), None, Some(1)]), vec![3, 4]);
        // The path does not start at the fixed body.
        assert_eq!(tethered([None, Some(0), Some(0), Some(0)]), vec![2, 3, 4]);
    }
}
