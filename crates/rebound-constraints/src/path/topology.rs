//! Stage *prepare*, path discovery: which joints form the paths the direct solve takes, in path order
//! ([`Topology::find_paths`]), how consecutive members share a body ([`Topology::shared_with_next`]), and
//! which paths are *closed* — solved entirely by the direct solve, with nothing else acting on their dynamic
//! bodies ([`Topology::find_closed`]). It sees joints only as body pairs, their direct row counts and two
//! flags given by the solver: whether a joint's rows can join a path, and whether all of them do; it keeps
//! its last search while those are unchanged ([`Topology::keeps`]).

use super::graph::DirectGraph;
use crate::pair::{BodyPair, dynamic_bodies};
use core::ops::Range;

/// The paths of one step and the scratch of their search, reused from step to step.
#[derive(Debug, Clone, Default)]
pub(crate) struct Topology {
    /// Paths of joints solved directly, as ranges into `path_joints` (joint indices in path order).
    pub paths: Vec<Range<usize>>,
    pub path_joints: Vec<usize>,
    /// Per path, whether it is closed ([`Topology::find_closed`]).
    pub closed: Vec<bool>,
    /// Per entry of `paths`, the graph it is (an index into `graphs`), `None` for a path
    /// ([`Topology::find_paths_and_graphs`]).
    pub graph_of: Vec<Option<usize>>,
    /// The graphs solved directly (the first as many as `graph_of` names; the rest kept for their buffers).
    pub graphs: Vec<DirectGraph>,
    /// Scratch of the graph search ([`Topology::find_paths_and_graphs`]): the graphs' members and their
    /// ranges, per joint whether a graph took it and its path, per body its union-find parent and whether
    /// a joint closed a loop of dynamic bodies there, the capable joints by group and each group's first
    /// joint and range, a group's bodies.
    pub(super) graph_members: Vec<usize>,
    pub(super) graph_ranges: Vec<Range<usize>>,
    pub(super) in_graph: Vec<bool>,
    pub(super) joint_path: Vec<usize>,
    pub(super) parent: Vec<usize>,
    pub(super) closes_loop: Vec<bool>,
    pub(super) grouped: Vec<(usize, usize)>,
    pub(super) group_starts: Vec<(usize, Range<usize>)>,
    pub(super) scratch_bodies: Vec<usize>,
    /// Whether the last [`Topology::find_paths`] left a group of joints that is not one path: a body with
    /// three joints or more, two paths on one body, joints on no path. Only then can there be graphs.
    pub(super) split: bool,
    /// Scratch of the path search: per body, its number of path-capable joints and the first two of them;
    /// per joint, whether a path has taken it.
    degree: Vec<u32>,
    incident: Vec<[usize; 2]>,
    visited: Vec<bool>,
    /// Scratch of [`Topology::find_closed`]: per body, the joints and tethers acting on it.
    touches: Vec<u32>,
    /// What the last search read of the joints ([`Topology::keeps`]).
    inputs: SearchInputs,
    /// The searches made so far ([`Topology::find_paths`] calls), for the tests of what is kept.
    #[cfg(test)]
    pub(crate) searches: usize,
}

/// What the path and graph search and [`Topology::find_closed`] read of one joint: its bodies, which of them
/// move ([`dynamic_bodies`]), whether its rows can join the direct solve and how many they are, and whether
/// all of them do.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) struct JointShape {
    bodies: [usize; 2],
    moves: [bool; 2],
    capable: bool,
    rows: usize,
    whole: bool,
}

impl JointShape {
    /// The shape of a joint between the bodies of `pair`, able to join a path if `capable`, with `rows`
    /// direct rows, all of them in the direct solve if `whole`.
    #[inline]
    pub fn new(pair: &BodyPair, capable: bool, rows: usize, whole: bool) -> Self {
        let [a, b] = dynamic_bodies(pair);
        Self {
            bodies: [pair.index_a, pair.index_b],
            moves: [a.is_some(), b.is_some()],
            capable,
            rows,
            whole,
        }
    }
}

/// The joints' shapes and the body count the paths were last searched for, and whether the closed paths
/// were last counted without tethers: a step whose joints have the same shapes finds the same paths, graphs
/// and closed paths (the searches read nothing else), so it keeps them ([`Topology::keeps`]).
#[derive(Debug, Clone, Default)]
struct SearchInputs {
    shapes: Vec<JointShape>,
    body_count: usize,
    /// Whether `shapes` are those the current paths were found for.
    found: bool,
    /// Whether the current closed paths were counted for these paths with no tether acting.
    closed_alone: bool,
}

impl Topology {
    /// Forgets the paths (direct chains switched off).
    pub fn clear(&mut self) {
        self.paths.clear();
        self.path_joints.clear();
        self.graph_of.clear();
        self.inputs.found = false;
    }

    /// Records the shapes of this step's joints (`shapes`, in joint order) among `body_count` bodies, and
    /// returns whether the paths found for the last step's serve this one: the same shapes, the paths found
    /// for them, and no graph among them (a graph's [`DirectGraph`] is made again with the search). If not,
    /// the caller searches again ([`Topology::find_paths_and_graphs`]) and counts the closed paths again.
    pub fn keeps(
        &mut self,
        body_count: usize,
        shapes: impl ExactSizeIterator<Item = JointShape>,
    ) -> bool {
        let inputs = &mut self.inputs;
        let mut same =
            inputs.found && inputs.body_count == body_count && inputs.shapes.len() == shapes.len();
        inputs.shapes.resize(shapes.len(), JointShape::default());
        for (kept, shape) in inputs.shapes.iter_mut().zip(shapes) {
            same &= *kept == shape;
            *kept = shape;
        }
        inputs.body_count = body_count;
        let keeps = same && self.graph_of.iter().all(Option::is_none);
        // Found for these shapes once the caller has searched (or kept the paths).
        inputs.found = true;
        if !keeps {
            inputs.closed_alone = false;
        }
        keeps
    }

    /// The graph path `path` is, if it is one ([`Topology::find_paths_and_graphs`]).
    pub fn graph(&self, path: usize) -> Option<usize> {
        self.graph_of.get(path).copied().flatten()
    }

    /// The paths solved directly among `count` joints, joint `i` between the bodies of `pair(i)` and able to
    /// join a path if `capable(i)`: maximal sequences of capable joints through dynamic bodies that belong to
    /// exactly two such joints. A path ends at a fixed body, a free end or a branching body; joints on a
    /// closed loop stay with Gauss–Seidel.
    pub fn find_paths<'p>(
        &mut self,
        body_count: usize,
        count: usize,
        pair: impl Fn(usize) -> &'p BodyPair,
        capable: impl Fn(usize) -> bool,
    ) {
        #[cfg(test)]
        {
            self.searches += 1;
        }
        // The lists alone, not what the last search read ([`Topology::keeps`] records it).
        self.paths.clear();
        self.path_joints.clear();
        self.graph_of.clear();
        self.degree.clear();
        self.degree.resize(body_count, 0);
        self.incident.clear();
        self.incident.resize(body_count, [usize::MAX; 2]);
        let mut split = false;
        let mut capable_count = 0;
        for index in 0..count {
            if !capable(index) {
                continue;
            }
            capable_count += 1;
            for body in dynamic_bodies(pair(index)).into_iter().flatten() {
                let (Some(degree), Some(incident)) =
                    (self.degree.get_mut(body), self.incident.get_mut(body))
                else {
                    continue;
                };
                if let Some(slot) = incident.get_mut(*degree as usize) {
                    *slot = index;
                }
                *degree += 1;
                split |= *degree > 2;
            }
        }
        let inner = |degree: &[u32], body: Option<usize>| {
            body.is_some_and(|b| degree.get(b).copied() == Some(2))
        };
        self.visited.clear();
        self.visited.resize(count, false);
        for start in 0..count {
            if self.visited[start] || !capable(start) {
                continue;
            }
            let [body_a, body_b] = dynamic_bodies(pair(start));
            // Walk away from an end of the path; a joint with inner bodies on both sides is not an end.
            let mut toward = if !inner(&self.degree, body_a) {
                body_b
            } else if !inner(&self.degree, body_b) {
                body_a
            } else {
                continue;
            };
            let first = self.path_joints.len();
            let mut current = start;
            loop {
                self.visited[current] = true;
                self.path_joints.push(current);
                let Some(body) = toward.filter(|&b| inner(&self.degree, Some(b))) else {
                    break;
                };
                let [j0, j1] = self.incident[body];
                let next = if j0 == current { j1 } else { j0 };
                if next >= count {
                    split = true;
                    break;
                }
                let next_pair = *pair(next);
                let other = if next_pair.index_a == body {
                    next_pair.index_b
                } else {
                    next_pair.index_a
                };
                // Two joints between the same two bodies share both: not a path link.
                let here = pair(current);
                if self.visited[next] || other == here.index_a || other == here.index_b {
                    split = true;
                    break;
                }
                toward = dynamic_bodies(&next_pair)
                    .into_iter()
                    .flatten()
                    .find(|&b| b == other);
                current = next;
            }
            // A walk that comes back to the dynamic body it started from (a loop through a branching body:
            // a four-bar linkage whose ground link hangs free) is not a path: the sweep couples consecutive
            // members only, and would miss the coupling of the first and last through that body. The last
            // joint is left out (a path of its own, coupled to this one by Gauss–Seidel).
            if self.path_joints.len() - first >= 2 {
                let members = &self.path_joints[first..];
                let outer = |joint: usize, inner: usize| {
                    let [a, b] = dynamic_bodies(pair(joint));
                    let (p, q) = (pair(joint), pair(inner));
                    let shared = |body: usize| body == q.index_a || body == q.index_b;
                    if shared(p.index_a) { b } else { a }
                };
                let (n, last) = (members.len(), members[members.len() - 1]);
                let start_outer = outer(members[0], members[1]);
                let end_outer = outer(last, members[n - 2]);
                if start_outer.is_some() && start_outer == end_outer {
                    self.visited[last] = false;
                    self.path_joints.pop();
                    split = true;
                }
            }
            self.paths.push(first..self.path_joints.len());
        }
        // Joints on no path (a closed loop) are a group no path covers.
        self.split = split || self.path_joints.len() < capable_count;
    }

    /// For member `slot` of the path `members` (joint `i` between the bodies of `pair(i)`): the side of it on
    /// the body it shares with the next member and the side of the next member on it (`true` = body B);
    /// `None` for the last member.
    pub fn shared_with_next<'p>(
        members: &[usize],
        slot: usize,
        pair: impl Fn(usize) -> &'p BodyPair,
    ) -> Option<(bool, bool)> {
        members.get(slot + 1).map(|&next| {
            let (this, next) = (pair(members[slot]), pair(next));
            let shared = if this.index_a == next.index_a || this.index_a == next.index_b {
                this.index_a
            } else {
                this.index_b
            };
            (this.index_b == shared, next.index_b == shared)
        })
    }

    /// Marks each path closed or not: a path is closed when every member's rows are all in the direct solve
    /// (`whole(i)` of its joints) and each of its dynamic bodies is acted on by the path's joints alone — of
    /// all the joints `pair(0..count)` and the tethers' pairs `others`, no other acts on it. Fixed and
    /// kinematic bodies (zero inverse mass and inertia) take no impulse and may be shared. The marks of the
    /// last count stand, uncounted, for paths kept with their joints' shapes ([`Topology::keeps`]) when no
    /// tether acts now or then (the shapes hold what the count reads of the joints).
    pub fn find_closed<'p>(
        &mut self,
        body_count: usize,
        count: usize,
        pair: impl Fn(usize) -> &'p BodyPair,
        others: impl Iterator<Item = &'p BodyPair>,
        whole: impl Fn(usize) -> bool,
    ) {
        let mut others = others.peekable();
        let alone = others.peek().is_none();
        if alone && self.inputs.closed_alone && self.inputs.found {
            return;
        }
        self.inputs.closed_alone = alone;
        let Self {
            paths,
            path_joints,
            closed,
            touches,
            ..
        } = self;
        touches.clear();
        touches.resize(body_count, 0);
        for p in (0..count).map(&pair).chain(others) {
            for body in dynamic_bodies(p).into_iter().flatten() {
                if let Some(count) = touches.get_mut(body) {
                    *count += 1;
                }
            }
        }
        closed.clear();
        closed.extend(paths.iter().map(|range| {
            let members = path_joints.get(range.clone()).unwrap_or_default();
            let all_rows = members.iter().all(|&index| whole(index));
            // Each dynamic body of the path: as many joints and tethers act on it as path joints do.
            count_dynamic_bodies(touches, &pair, members, false);
            let alone = members.iter().all(|&index| {
                dynamic_bodies(pair(index))
                    .into_iter()
                    .flatten()
                    .all(|body| touches.get(body) == Some(&0))
            });
            count_dynamic_bodies(touches, &pair, members, true);
            all_rows && alone
        }));
    }
}

/// Adds (`add`) or takes off one count per joint of `members` from each of its dynamic bodies in `touches`.
fn count_dynamic_bodies<'p>(
    touches: &mut [u32],
    pair: impl Fn(usize) -> &'p BodyPair,
    members: &[usize],
    add: bool,
) {
    for &index in members {
        for body in dynamic_bodies(pair(index)).into_iter().flatten() {
            if let Some(count) = touches.get_mut(body) {
                *count = if add {
                    *count + 1
                } else {
                    count.wrapping_sub(1)
                };
            }
        }
    }
}
