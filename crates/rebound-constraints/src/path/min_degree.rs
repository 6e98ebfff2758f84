//! Stage *prepare*, the elimination order of a joint graph solved directly ([`crate::path`]): the minimum
//! degree order over its joints, which keeps the fill of the factorisation small.
//!
//! Eliminating a joint couples all the joints it is coupled with (their rows' Schur complement gains the
//! entries between them); a ladder eliminated end to end, or a tree from its leaves, gains none, a loop a
//! column along it. The greedy rule — always eliminate a joint with the fewest couplings left, ties to the
//! lowest index, so that the order is a function of the graph alone — finds those orders (Tinney and
//! Walker's scheme 2; George and Liu, "The evolution of the minimum degree ordering algorithm", SIAM Review
//! 1989). The graphs solved directly have at most [`super::graph::MAX_GRAPH_JOINTS`] joints, so the plain
//! form with explicit adjacency sets (no quotient graph, no multiple elimination) is quick enough, once a
//! step.

/// The scratch of [`minimum_degree_order`], kept from step to step so that ordering allocates nothing once
/// it has grown: each node's adjacency set, which nodes are eliminated, and the clique being formed.
#[derive(Debug, Clone, Default)]
pub(crate) struct OrderScratch {
    sets: Vec<Vec<usize>>,
    eliminated: Vec<bool>,
    clique: Vec<usize>,
}

/// The minimum degree order of the graph of `nodes` nodes whose edges are `adjacency(i)` (each node's
/// neighbours, both ways, no self-loops), written into `order`; returns the fill of the elimination, the sum
/// over the nodes of their degree when eliminated (the block entries of `L`).
pub(crate) fn minimum_degree_order<'n>(
    nodes: usize,
    adjacency: impl Fn(usize) -> &'n [usize],
    scratch: &mut OrderScratch,
    order: &mut Vec<usize>,
) -> usize {
    let OrderScratch {
        sets,
        eliminated,
        clique,
    } = scratch;
    sets.resize_with(nodes.max(sets.len()), Vec::new);
    for (i, set) in sets.iter_mut().enumerate().take(nodes) {
        set.clear();
        set.extend(
            adjacency(i)
                .iter()
                .copied()
                .filter(|&j| j != i && j < nodes),
        );
        set.sort_unstable();
        set.dedup();
    }
    order.clear();
    eliminated.clear();
    eliminated.resize(nodes, false);
    let mut fill = 0;
    for _ in 0..nodes {
        let Some(pivot) = (0..nodes)
            .filter(|&i| !eliminated[i])
            .min_by_key(|&i| (sets[i].len(), i))
        else {
            break;
        };
        eliminated[pivot] = true;
        order.push(pivot);
        clique.clear();
        clique.extend(sets[pivot].iter().copied());
        fill += clique.len();
        // The neighbours become one clique, without the pivot.
        for &i in clique.iter() {
            let set = &mut sets[i];
            set.retain(|&j| j != pivot);
            for &j in clique.iter() {
                if j != i
                    && let Err(at) = set.binary_search(&j)
                {
                    set.insert(at, j);
                }
            }
        }
        sets[pivot].clear();
    }
    fill
}

#[cfg(test)]
mod tests {
    use super::{OrderScratch, minimum_degree_order};

    /// The order and fill of the graph with `edges` on `nodes` nodes.
    fn order(nodes: usize, edges: &[(usize, usize)]) -> (Vec<usize>, usize) {
        let mut adjacency = vec![Vec::new(); nodes];
        for &(a, b) in edges {
            adjacency[a].push(b);
            adjacency[b].push(a);
        }
        let (mut scratch, mut order) = (OrderScratch::default(), Vec::new());
        let fill = minimum_degree_order(nodes, |i| &adjacency[i], &mut scratch, &mut order);
        (order, fill)
    }

    #[test]
    fn a_path_and_a_star_are_eliminated_without_fill() {
        // A path: an end first, then along it; each node has one neighbour left when eliminated.
        let (path, fill) = order(5, &[(0, 1), (1, 2), (2, 3), (3, 4)]);
        assert_eq!(path, vec![0, 1, 2, 3, 4]);
        assert_eq!(fill, 4);
        // A star (a ragdoll's torso): the leaves first; with one leaf left, the hub and it tie, and the
        // lower index goes first.
        let (star, fill) = order(5, &[(0, 1), (0, 2), (0, 3), (0, 4)]);
        assert_eq!(star, vec![1, 2, 3, 0, 4]);
        assert_eq!(fill, 4);
    }

    #[test]
    fn a_loop_fills_one_column_and_the_order_is_a_permutation() {
        let n = 8;
        let edges: Vec<(usize, usize)> = (0..n).map(|i| (i, (i + 1) % n)).collect();
        let (order, fill) = order(n, &edges);
        let mut sorted = order.clone();
        sorted.sort_unstable();
        assert_eq!(sorted, (0..n).collect::<Vec<_>>());
        // Each elimination but the last leaves two neighbours, then one: 2·(n − 2) + 1.
        assert_eq!(fill, 2 * (n - 2) + 1);
    }
}
