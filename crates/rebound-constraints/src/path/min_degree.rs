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

/// The minimum degree order of the graph of `nodes` nodes whose edges are `adjacency(i)` (each node's
/// neighbours, both ways, no self-loops), written into `order`; returns the fill of the elimination, the sum
/// over the nodes of their degree when eliminated (the block entries of `L`). `sets` is scratch.
pub(crate) fn minimum_degree_order<'n>(
    nodes: usize,
    adjacency: impl Fn(usize) -> &'n [usize],
    sets: &mut Vec<Vec<usize>>,
    order: &mut Vec<usize>,
) -> usize {
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
    let mut eliminated = vec![false; nodes];
    let mut fill = 0;
    let mut clique = Vec::new();
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
        for &i in &clique {
            let set = &mut sets[i];
            set.retain(|&j| j != pivot);
            for &j in &clique {
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
