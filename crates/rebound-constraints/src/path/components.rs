//! Stage *prepare*, graph discovery: which connected groups of joints the direct solve takes as one graph
//! rather than as paths ([`Topology::find_graphs`]). Joints are connected through the dynamic bodies they
//! share; a group that is one path stays with the path solver (its block Thomas sweep is the cheaper
//! factorisation of the same system), any other — a ladder, a tree, a loop — of at most
//! [`MAX_GRAPH_JOINTS`] joints whose elimination fills at most [`MAX_GRAPH_FILL`] blocks is a graph, and
//! the rest is left as the paths found in it and Gauss–Seidel. A path with more rows than its bodies have
//! degrees of freedom (a door on two hinges on one axis, a grounded four-bar of hinges) is a graph too:
//! some of its rows are dependent, which the graph's factorisation finds and holds
//! ([`super::sparse_ldl`]), and a graph's projection holds it ten times closer than a path's. So is any
//! other group with more rows than degrees of freedom, but one with a loop of dynamic bodies alone (a
//! floating loop of hinges), which is left to Gauss–Seidel alone.

use super::graph::{DirectGraph, MAX_GRAPH_FILL, MAX_GRAPH_JOINTS};
use super::topology::Topology;
use crate::pair::BodyPair;
use crate::pair::dynamic_bodies;

/// The root of `body` in the union-find forest `parent` (path halving).
fn root(parent: &mut [usize], mut body: usize) -> usize {
    while parent[body] != body {
        parent[body] = parent[parent[body]];
        body = parent[body];
    }
    body
}

impl Topology {
    /// How many distinct dynamic bodies the joints between `pairs` move (`bodies`: scratch).
    fn dynamic_body_count<'p>(
        bodies: &mut Vec<usize>,
        pairs: impl Iterator<Item = &'p BodyPair>,
    ) -> usize {
        bodies.clear();
        for p in pairs {
            bodies.extend(dynamic_bodies(p).into_iter().flatten());
        }
        bodies.sort_unstable();
        bodies.dedup();
        bodies.len()
    }

    /// Finds the paths and the graphs solved directly among `count` joints (joint `i` between the bodies of
    /// `pair(i)`, able to join if `capable(i)`): [`Topology::find_paths`], then each connected group of
    /// capable joints that is not one path and is small enough becomes a graph, and the paths are found
    /// again among the joints left. The graphs follow the paths in `paths`, their members in joint order;
    /// `graph_of` tells which entries are graphs.
    pub fn find_paths_and_graphs<'p>(
        &mut self,
        body_count: usize,
        count: usize,
        pair: impl Fn(usize) -> &'p BodyPair + Copy,
        capable: impl Fn(usize) -> bool + Copy,
        rows: impl Fn(usize) -> usize,
    ) {
        self.find_paths(body_count, count, pair, capable);
        // Every group one path (a chain, a deck) with no more rows than degrees of freedom: nothing more to
        // find.
        let graphs = if self.split || self.has_over_constrained_path(pair, &rows) {
            self.find_graphs(body_count, count, pair, capable, rows)
        } else {
            self.in_graph.clear();
            0
        };
        if self.in_graph.contains(&true) {
            let in_graph = core::mem::take(&mut self.in_graph);
            self.find_paths(body_count, count, pair, |i| {
                capable(i) && !in_graph.get(i).copied().unwrap_or(false)
            });
            self.in_graph = in_graph;
        }
        self.graph_of.clear();
        self.graph_of.resize(self.paths.len(), None);
        for g in 0..graphs {
            let range = self.graph_ranges[g].clone();
            let first = self.path_joints.len();
            self.path_joints
                .extend_from_slice(&self.graph_members[range.clone()]);
            self.paths.push(first..self.path_joints.len());
            self.graph_of.push(Some(g));
        }
    }

    /// Whether a path found by [`Topology::find_paths`] has more rows than its dynamic bodies have degrees
    /// of freedom. An open path of `k` joints moves `k − 1` bodies between its ends and each end that is
    /// dynamic, so the dynamic sides of its joints number `2·(k − 1)` plus those ends: it moves that many
    /// sides less `k − 1` bodies.
    fn has_over_constrained_path<'p>(
        &self,
        pair: impl Fn(usize) -> &'p BodyPair,
        rows: impl Fn(usize) -> usize,
    ) -> bool {
        self.paths.iter().any(|range| {
            let joints = &self.path_joints[range.clone()];
            // `k` joints move at least `k − 1` bodies: a path with no more rows than `6·(k − 1)` is not
            // over-constrained, whichever of its ends are dynamic (a rope chain ends here).
            let row_count: usize = joints.iter().map(|&index| rows(index)).sum();
            if row_count <= 6 * joints.len().saturating_sub(1) {
                return false;
            }
            let sides: usize = joints
                .iter()
                .map(|&index| dynamic_bodies(pair(index)).iter().flatten().count())
                .sum();
            row_count > 6 * (sides + 1).saturating_sub(joints.len())
        })
    }

    /// The groups of capable joints that are graphs (see the module doc), after [`Topology::find_paths`]
    /// found the paths among all of them: their members into `graph_members` (ranges `graph_ranges`),
    /// `in_graph` per joint (set too for the joints of a group left to Gauss–Seidel alone), each one's
    /// [`DirectGraph`] built. Returns how many there are.
    fn find_graphs<'p>(
        &mut self,
        body_count: usize,
        count: usize,
        pair: impl Fn(usize) -> &'p BodyPair + Copy,
        capable: impl Fn(usize) -> bool,
        rows: impl Fn(usize) -> usize,
    ) -> usize {
        self.in_graph.clear();
        self.in_graph.resize(count, false);
        self.graph_members.clear();
        self.graph_ranges.clear();
        // Which path each joint is on (`usize::MAX`: none).
        self.joint_path.clear();
        self.joint_path.resize(count, usize::MAX);
        for (path, range) in self.paths.iter().enumerate() {
            for &index in &self.path_joints[range.clone()] {
                if let Some(slot) = self.joint_path.get_mut(index) {
                    *slot = path;
                }
            }
        }
        let parent = &mut self.parent;
        parent.clear();
        parent.extend(0..body_count);
        let closes_loop = &mut self.closes_loop;
        closes_loop.clear();
        closes_loop.resize(body_count, false);
        for index in (0..count).filter(|&i| capable(i)) {
            if let [Some(a), Some(b)] = dynamic_bodies(pair(index))
                && a < body_count
                && b < body_count
            {
                let (ra, rb) = (root(parent, a), root(parent, b));
                // A joint between two bodies already joined closes a loop of dynamic bodies.
                closes_loop[a] |= ra == rb;
                // Union by lower index: the forest, and so the groups, depend on the joints alone.
                parent[ra.max(rb)] = ra.min(rb);
            }
        }
        // Each loop marked at its group's root.
        for body in 0..body_count {
            if closes_loop[body] {
                let group = root(parent, body);
                closes_loop[group] = true;
            }
        }
        // (group, joint) for every capable joint with a dynamic body, sorted: each run is one group.
        self.grouped.clear();
        for index in (0..count).filter(|&i| capable(i)) {
            let Some(body) = dynamic_bodies(pair(index))
                .into_iter()
                .flatten()
                .find(|&b| b < body_count)
            else {
                continue;
            };
            self.grouped.push((root(parent, body), index));
        }
        self.grouped.sort_unstable();
        // Groups in the order of their first joint, so that the graphs are numbered by the joints alone.
        self.group_starts.clear();
        let mut run = 0;
        while run < self.grouped.len() {
            let group = self.grouped[run].0;
            let end = run
                + self.grouped[run..]
                    .iter()
                    .take_while(|g| g.0 == group)
                    .count();
            self.group_starts.push((self.grouped[run].1, run..end));
            run = end;
        }
        self.group_starts.sort_unstable_by_key(|g| g.0);
        let mut graphs = 0;
        for g in 0..self.group_starts.len() {
            let range = self.group_starts[g].1.clone();
            let members = &self.grouped[range];
            let first_path = self.joint_path[members[0].1];
            let one_path = first_path != usize::MAX
                && members.iter().all(|m| self.joint_path[m.1] == first_path)
                && self.paths[first_path].len() == members.len();
            if members.len() < 2 || members.len() > MAX_GRAPH_JOINTS {
                continue;
            }
            let row_count: usize = members.iter().map(|m| rows(m.1)).sum();
            let moved = Self::dynamic_body_count(
                &mut self.scratch_bodies,
                members.iter().map(|m| pair(m.1)),
            );
            let over_constrained = row_count > 6 * moved;
            // One path stays a path unless it has more rows than its bodies have degrees of freedom:
            // dependent rows, which the graph's factorisation finds (see the module doc).
            if one_path && !over_constrained {
                continue;
            }
            // More rows than degrees of freedom on a loop of dynamic bodies alone — a floating loop of
            // hinges — is left to Gauss–Seidel alone, see `docs/physics.md`, "Joint graphs": its exact
            // solve tears it apart.
            if over_constrained && self.closes_loop[members[0].0] {
                // Nor as paths: a path's exact solve beside the loop's other joints fights them.
                for m in members {
                    self.in_graph[m.1] = true;
                }
                continue;
            }
            let start = self.graph_members.len();
            self.graph_members.extend(members.iter().map(|m| m.1));
            if self.graphs.len() <= graphs {
                self.graphs.push(DirectGraph::default());
            }
            let fill = self.graphs[graphs].build(&self.graph_members[start..], pair);
            if fill > MAX_GRAPH_FILL {
                self.graph_members.truncate(start);
                continue;
            }
            for &index in &self.graph_members[start..] {
                self.in_graph[index] = true;
            }
            self.graph_ranges.push(start..self.graph_members.len());
            graphs += 1;
        }
        graphs
    }
}
