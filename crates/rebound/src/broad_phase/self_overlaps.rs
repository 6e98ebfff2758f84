//! The pool's traversal of the broad phase's tree against itself (the `parallel` feature): every pair of
//! overlapping leaves, found over the pool into buffers kept from step to step.
//!
//! Written here, not taken from parry: `Bvh::traverse_bvtt_single_tree_parallel` returns a new `Vec` from
//! every task it splits off and concatenates them by appending, so it allocates and reallocates in every
//! step, and parry keeps its nodes' children private, so its traversal cannot be split from outside.
//! [`SelfOverlaps::copy`] reads the tree through parry's public depth-first walk (`Bvh::traverse_indexed`)
//! into an array kept here: each node's box and its children (or, for a leaf, its slot). The top of that
//! copy is split into units of work ([`Unit`]), each traversed by one task into its own kept list.
//!
//! The pairs are those of parry's traversal (every two leaves whose boxes overlap, each pair once), in
//! another order and in one list per unit: the caller sorts them over the pool (`pair_sort::sort_parts`),
//! so the candidate pairs are the one-thread search's for any number of threads.

use parry3d::partitioning::{Bvh, TraversalAction};
use rebound_math::glam::Vec3A;
use rebound_math::par;

/// Units of work the top of the tree is split into, at least (while it has subtrees to split): rayon hands
/// them to the threads as they come free, which evens out units of unequal size.
const MIN_UNITS: usize = 64;

/// A node of the copy: its index into [`SelfOverlaps::nodes`].
type NodeId = u32;

/// One unit of the traversal: the leaf pairs within one subtree, or between two disjoint subtrees whose
/// boxes overlap.
#[derive(Debug, Clone, Copy)]
enum Unit {
    Within(NodeId),
    Between(NodeId, NodeId),
}

/// A node of the copy: its box and, for a leaf, its slot, else the index of its first child in
/// [`SelfOverlaps::nodes`] (the second follows it).
#[derive(Debug, Clone, Copy)]
struct Node {
    mins: Vec3A,
    maxs: Vec3A,
    down: u32,
    is_leaf: bool,
}

impl Node {
    /// Whether the two boxes overlap, touching included (parry's `BvhNode::intersects`, inlined here: it is
    /// the traversal's inner test, and parry's is not inlined across crates).
    #[inline(always)]
    fn overlaps(&self, other: &Self) -> bool {
        (self.mins.cmple(other.maxs) & self.maxs.cmpge(other.mins)).all()
    }
}

/// The copy of the tree's shape and the traversal's buffers, kept from step to step; `Pair` is what the
/// caller's filter makes of two leaves.
#[derive(Debug, Clone)]
pub(super) struct SelfOverlaps<Pair> {
    /// The tree's nodes in the order parry's walk checks them: the two children of a node side by side,
    /// the first pair the root's two children.
    nodes: Vec<Node>,
    /// Nodes whose children the walk has yet to reach (scratch of [`SelfOverlaps::copy`]).
    waiting: Vec<NodeId>,
    /// This step's units, and the next level's while the top is split.
    units: Vec<Unit>,
    next_units: Vec<Unit>,
    /// Per unit, the pairs it found and kept.
    found: Vec<Vec<Pair>>,
}

impl<Pair> Default for SelfOverlaps<Pair> {
    fn default() -> Self {
        Self {
            nodes: Vec::new(),
            waiting: Vec::new(),
            units: Vec::new(),
            next_units: Vec::new(),
            found: Vec::new(),
        }
    }
}

impl<Pair: Copy + Send> SelfOverlaps<Pair> {
    /// Every two leaves of `bvh` whose boxes overlap that `keep` (on their slots) makes a pair, found over
    /// the pool: the pairs of each unit of work in its own list, returned (each pair once, in no order).
    pub(super) fn find_parts(
        &mut self,
        bvh: &Bvh,
        keep: impl Fn(u32, u32) -> Option<Pair> + Sync + Send,
    ) -> &mut [Vec<Pair>] {
        if bvh.leaf_count() < 2 {
            return &mut [];
        }
        self.copy(bvh);
        self.split();
        let tree = Tree { nodes: &self.nodes };
        let units = &self.units;
        if self.found.len() < units.len() {
            self.found.resize_with(units.len(), Vec::new);
        }
        let found = &mut self.found[..units.len()];
        par::for_each_mut(found, 1, |r, out| {
            out.clear();
            let mut emit = |a: u32, b: u32| {
                if let Some(pair) = keep(a, b) {
                    out.push(pair);
                }
            };
            match units.get(r) {
                Some(&Unit::Within(id)) => tree.within(id, &mut emit),
                Some(&Unit::Between(a, b)) => tree.between(a, b, &mut emit),
                None => {}
            }
        });
        // Every list made to hold twice what the fullest held: which unit meets the most pairs moves from
        // step to step (the units follow the tree), and a list grown only by its own unit would keep
        // growing, one unit after another, long after the total has stopped.
        let widest = found.iter().map(Vec::len).max().unwrap_or(0);
        for part in found.iter_mut() {
            if part.capacity() < widest {
                part.reserve(2 * widest - part.len());
            }
        }
        found
    }

    /// Copies the shape of `bvh` (at least two leaves) by one depth-first walk. parry's walk checks the two
    /// children of a node one after the other, then goes down into the left one if it is not a leaf (the
    /// right one waiting on its stack if it is not a leaf either), else into the right one, else into the
    /// last one that waited; the copy follows the same rule to know whose children each pair is.
    fn copy(&mut self, bvh: &Bvh) {
        let (nodes, waiting) = (&mut self.nodes, &mut self.waiting);
        nodes.clear();
        waiting.clear();
        // The node whose children the walk checks next (none for the root's).
        let mut parent: Option<NodeId> = None;
        bvh.traverse_indexed(None, |node, _| {
            let id = nodes.len() as NodeId;
            let is_leaf = node.is_leaf();
            nodes.push(Node {
                mins: node.mins().into(),
                maxs: node.maxs().into(),
                down: node.leaf_data().unwrap_or(0),
                is_leaf,
            });
            if id.is_multiple_of(2) {
                if let Some(up) = parent.and_then(|p| nodes.get_mut(p as usize)) {
                    up.down = id;
                }
                return TraversalAction::Continue;
            }
            let left_inner = nodes.get(id as usize - 1).is_some_and(|n| !n.is_leaf);
            parent = match (left_inner, !is_leaf) {
                (true, true) => {
                    waiting.push(id);
                    Some(id - 1)
                }
                (true, false) => Some(id - 1),
                (false, true) => Some(id),
                (false, false) => waiting.pop(),
            };
            TraversalAction::Continue
        });
    }

    /// Splits the traversal of the copy, level by level from the root's children, into at least
    /// [`MIN_UNITS`] units (or as many as the tree's top gives).
    fn split(&mut self) {
        let tree = Tree { nodes: &self.nodes };
        self.units.clear();
        self.units.push(Unit::Within(0));
        self.units.push(Unit::Within(1));
        if tree.overlap(0, 1) {
            self.units.push(Unit::Between(0, 1));
        }
        while self.units.len() < MIN_UNITS {
            self.next_units.clear();
            let mut split_any = false;
            for &unit in &self.units {
                split_any |= tree.split(unit, &mut self.next_units);
            }
            core::mem::swap(&mut self.units, &mut self.next_units);
            if !split_any {
                break;
            }
        }
    }
}

/// The copy read by the traversal.
#[derive(Clone, Copy)]
struct Tree<'a> {
    nodes: &'a [Node],
}

impl Tree<'_> {
    /// Whether nodes `a` and `b` overlap.
    #[inline(always)]
    fn overlap(&self, a: NodeId, b: NodeId) -> bool {
        self.nodes[a as usize].overlaps(&self.nodes[b as usize])
    }

    /// The pairs of children to visit under two overlapping nodes `a` and `b`: each child of an inner node
    /// against the other node or its children.
    #[inline(always)]
    fn child_pairs(&self, a: NodeId, b: NodeId) -> ([(NodeId, NodeId); 4], usize) {
        let (na, nb) = (&self.nodes[a as usize], &self.nodes[b as usize]);
        match (na.is_leaf, nb.is_leaf) {
            (true, true) => ([(a, b); 4], 0),
            (true, false) => ([(a, nb.down), (a, nb.down + 1), (0, 0), (0, 0)], 2),
            (false, true) => ([(na.down, b), (na.down + 1, b), (0, 0), (0, 0)], 2),
            (false, false) => {
                let (ca, cb) = (na.down, nb.down);
                ([(ca, cb), (ca, cb + 1), (ca + 1, cb), (ca + 1, cb + 1)], 4)
            }
        }
    }

    /// `unit`'s parts one level down into `out` (a unit between two leaves as it is, parts whose boxes do
    /// not overlap left out); whether it was split.
    fn split(&self, unit: Unit, out: &mut Vec<Unit>) -> bool {
        match unit {
            Unit::Within(id) => {
                let node = &self.nodes[id as usize];
                if node.is_leaf {
                    return false;
                }
                let c = node.down;
                out.push(Unit::Within(c));
                out.push(Unit::Within(c + 1));
                if self.overlap(c, c + 1) {
                    out.push(Unit::Between(c, c + 1));
                }
                true
            }
            Unit::Between(a, b) => {
                let (pairs, count) = self.child_pairs(a, b);
                if count == 0 {
                    out.push(unit);
                    return false;
                }
                for &(x, y) in pairs.iter().take(count) {
                    if self.overlap(x, y) {
                        out.push(Unit::Between(x, y));
                    }
                }
                true
            }
        }
    }

    /// Every pair of overlapping leaves within the subtree of `id`, as slots, to `emit`.
    fn within(&self, id: NodeId, emit: &mut impl FnMut(u32, u32)) {
        let node = &self.nodes[id as usize];
        if node.is_leaf {
            return;
        }
        let c = node.down;
        self.within(c, emit);
        self.within(c + 1, emit);
        if self.overlap(c, c + 1) {
            self.between(c, c + 1, emit);
        }
    }

    /// Every pair of overlapping leaves, one under `a` and one under `b` (disjoint subtrees whose boxes
    /// overlap), to `emit`.
    fn between(&self, a: NodeId, b: NodeId, emit: &mut impl FnMut(u32, u32)) {
        let (na, nb) = (&self.nodes[a as usize], &self.nodes[b as usize]);
        match (na.is_leaf, nb.is_leaf) {
            (true, true) => emit(na.down, nb.down),
            (true, false) => self.leaf_against(na, nb.down, emit),
            (false, true) => self.leaf_against(nb, na.down, emit),
            (false, false) => {
                let (ca, cb) = (na.down, nb.down);
                for (x, y) in [(ca, cb), (ca, cb + 1), (ca + 1, cb), (ca + 1, cb + 1)] {
                    if self.overlap(x, y) {
                        self.between(x, y, emit);
                    }
                }
            }
        }
    }

    /// Every leaf under the two children `first`, `first + 1` of a node that overlaps `leaf`, against it.
    fn leaf_against(&self, leaf: &Node, first: NodeId, emit: &mut impl FnMut(u32, u32)) {
        for child in [first, first + 1] {
            let node = &self.nodes[child as usize];
            if leaf.overlaps(node) {
                if node.is_leaf {
                    emit(leaf.down, node.down);
                } else {
                    self.leaf_against(leaf, node.down, emit);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use parry3d::bounding_volume::Aabb;
    use parry3d::math::Vector;

    /// A tree of `count` boxes scattered by a fixed linear congruential sequence, grown by insertion,
    /// moved, refitted and optimised as the broad phase does it.
    fn scattered(count: u32, seed: u64) -> Bvh {
        let mut state = seed;
        let mut next = move || {
            state = state
                .wrapping_mul(6_364_136_223_846_793_005)
                .wrapping_add(1_442_695_040_888_963_407);
            (state >> 40) as f32 / (1_u64 << 24) as f32
        };
        let mut random_box = || {
            let centre = Vector::new(next() * 20.0, next() * 20.0, next() * 20.0);
            let half = Vector::splat(0.2 + next());
            Aabb::new(centre - half, centre + half)
        };
        let mut bvh = Bvh::new();
        for slot in 0..count {
            bvh.insert(random_box(), slot);
        }
        let mut workspace = parry3d::partitioning::BvhWorkspace::default();
        for slot in (0..count).step_by(3) {
            let _ = bvh.insert_or_update_partially(random_box(), slot, 0.0);
        }
        bvh.refit(&mut workspace);
        bvh.optimize_incremental(&mut workspace);
        bvh
    }

    /// The pairs of parry's one-thread traversal, each lower slot first, sorted.
    fn parry_pairs(bvh: &Bvh) -> Vec<(u32, u32)> {
        let mut pairs = Vec::new();
        let mut workspace = parry3d::partitioning::BvhWorkspace::default();
        bvh.traverse_bvtt_single_tree::<false>(&mut workspace, &mut |a, b| {
            pairs.push((a.min(b), a.max(b)));
        });
        pairs.sort_unstable();
        pairs
    }

    /// On a pool of two threads (and on one), over trees of 0 to 3,000 boxes: the pairs parry's traversal
    /// finds, each once, and the caller's filter applied to each.
    #[test]
    fn finds_the_pairs_of_parrys_traversal() {
        let pools = [1, 2].map(|threads| {
            par::rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .expect("the test machine starts threads")
        });
        let mut traversal = SelfOverlaps::default();
        for (count, seed) in [
            (0, 1),
            (1, 2),
            (2, 3),
            (7, 4),
            (100, 5),
            (1_000, 6),
            (3_000, 7),
        ] {
            let bvh = scattered(count, seed);
            let expected = parry_pairs(&bvh);
            if count >= 1_000 {
                assert!(
                    expected.len() > count as usize,
                    "{count} boxes: too few pairs to test"
                );
            }
            for pool in &pools {
                let mut found: Vec<_> = pool.install(|| {
                    traversal
                        .find_parts(&bvh, |a, b| Some((a.min(b), a.max(b))))
                        .concat()
                });
                let all = found.len();
                found.sort_unstable();
                found.dedup();
                assert_eq!(found.len(), all, "{count} boxes: a pair found twice");
                assert_eq!(found, expected, "{count} boxes: other pairs than parry's");
                // The filter's verdict is applied: only the pairs of even slots kept.
                let mut even: Vec<_> = pool.install(|| {
                    traversal
                        .find_parts(&bvh, |a, b| {
                            (a % 2 == 0 && b % 2 == 0).then_some((a.min(b), a.max(b)))
                        })
                        .concat()
                });
                even.sort_unstable();
                let expected_even: Vec<_> = expected
                    .iter()
                    .copied()
                    .filter(|&(a, b)| a % 2 == 0 && b % 2 == 0)
                    .collect();
                assert_eq!(even, expected_even, "{count} boxes: the filter not applied");
            }
        }
    }
}
