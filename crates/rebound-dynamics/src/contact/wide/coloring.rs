//! Colouring for the wide contact path: which manifolds are solved four at a time, in which batches. The
//! manifolds are given, in order, the first colour in which neither of their moving bodies appears yet, chunk
//! by chunk; each colour's manifolds become batches of four. Stage *prepare*.

use super::batch::Batches;
use super::fill::fill_on_pool;
use super::lanes::LANES;
use crate::contact::prepared::{PrepareInput, PreparedContact};
use rebound_math::par;

/// Manifolds below which the batches are prepared on one thread even on a pool (a fork costs about as much
/// as preparing a few dozen batches).
const MIN_CONTACTS_ON_POOL: usize = 256;

/// The number of colours tried before a manifold is left to the scalar path. A body touching more manifolds
/// than this overflows (Box2D v3 uses 24; a box in a pyramid touches 6, a ball in a pile about 12). At most
/// 32 (one bit each in a `u32` per body).
pub(crate) const COLORS: usize = 24;

/// Manifolds coloured together: the batches of the first `CHUNK` manifolds (colour by colour), then those of
/// the next `CHUNK`, and so on. A chunk's bodies stay in cache while its colours are solved one after the
/// other; coloured all at once, a pile of 16,384 balls swept its whole body array once per colour, in
/// *prepare* and in every solve pass. Scenes with fewer manifolds are one chunk (the solve order does not
/// change; stacks are sensitive to it). Each chunk's colours start afresh: the chunks are solved one after
/// the other, so a body may have one colour in each.
pub(crate) const CHUNK: usize = 4096;

/// Whether the wide path solves this manifold exactly as the scalar path would: no bounce (restitution 0),
/// no rolling block and no surface velocity.
pub(crate) fn is_wide(c: &PreparedContact) -> bool {
    c.restitution == 0.0 && c.rolling.is_none() && !c.moving_surface && c.point_count > 0
}

/// The colouring's scratch.
#[derive(Debug, Clone, Default)]
pub(crate) struct Coloring {
    /// Per body, bit `c` set when a manifold of colour `c` moves it.
    pub(crate) used: Vec<u32>,
    /// Manifold indices per colour, in manifold order, for the chunk being coloured (see [`CHUNK`]).
    pub(crate) members: [Vec<usize>; COLORS],
    /// The end (one past the last index into the batches) of each colour of each chunk, in batch order: the
    /// batches of one such group share no moving body (`super::groups` solves them on several threads).
    pub(crate) group_ends: Vec<usize>,
    /// Leave every manifold to the scalar path (tests compare the two paths).
    pub(crate) scalar_only: bool,
    /// On a pool of several threads, the batches named before they are prepared (`super::fill`): each
    /// batch's range of `pool_members` (its manifolds, in lane order), and scratch.
    pool_groups: Vec<(u32, u32)>,
    pool_members: Vec<usize>,
    pool_places: Vec<(u32, u32)>,
}

impl Coloring {
    /// Colours the wide-eligible manifolds of `contacts` and groups them into `batches`; the others (and those
    /// that fit no colour) go to `scalar`, in manifold order.
    pub(crate) fn build(
        &mut self,
        contacts: &[PreparedContact],
        input: &PrepareInput<'_>,
        batches: &mut Batches,
        scalar: &mut Vec<usize>,
    ) {
        let params = input.params;
        // On a pool the batches are named here and prepared over the pool at the end.
        let on_pool = par::is_parallel() && contacts.len() >= MIN_CONTACTS_ON_POOL;
        batches.clear();
        self.pool_groups.clear();
        self.pool_members.clear();
        scalar.clear();
        self.group_ends.clear();
        self.used.clear();
        self.used.resize(params.len(), 0);
        for members in &mut self.members {
            members.clear();
        }
        for (chunk_index, chunk) in contacts.chunks(CHUNK).enumerate() {
            for (offset, c) in chunk.iter().enumerate() {
                let index = chunk_index * CHUNK + offset;
                if !is_wide(c) || self.scalar_only {
                    scalar.push(index);
                    continue;
                }
                // Fixed and kinematic bodies take no colour: any number of lanes may read them.
                let moves = |body: usize| params[body].is_dynamic();
                let used = |body: usize| if moves(body) { self.used[body] } else { 0 };
                // The first colour neither body is in.
                let color = (!(used(c.body_a) | used(c.body_b))).trailing_zeros() as usize;
                if color >= COLORS {
                    scalar.push(index);
                    continue;
                }
                for body in [c.body_a, c.body_b] {
                    if moves(body) {
                        self.used[body] |= 1 << color;
                    }
                }
                self.members[color].push(index);
            }
            self.flush(chunk, contacts, input, batches, on_pool);
        }
        if on_pool {
            fill_on_pool(
                batches,
                &self.pool_groups,
                &self.pool_members,
                &mut self.pool_places,
                contacts,
                input,
            );
        }
    }

    /// Ends a chunk: its batches, colour by colour (each colour's manifolds four at a time, in manifold
    /// order), then the colours of its bodies are freed for the next chunk.
    pub(crate) fn flush(
        &mut self,
        chunk: &[PreparedContact],
        contacts: &[PreparedContact],
        input: &PrepareInput<'_>,
        batches: &mut Batches,
        on_pool: bool,
    ) {
        for members in &mut self.members {
            if on_pool {
                for group in members.chunks(LANES) {
                    let start = self.pool_members.len() as u32;
                    self.pool_members.extend_from_slice(group);
                    self.pool_groups
                        .push((start, self.pool_members.len() as u32));
                }
                if !members.is_empty() {
                    self.group_ends.push(self.pool_groups.len());
                }
                members.clear();
                continue;
            }
            for group in members.chunks(LANES) {
                batches.push(group, contacts, input);
            }
            if !members.is_empty() {
                self.group_ends.push(batches.batches.len());
            }
            members.clear();
        }
        for c in chunk {
            for body in [c.body_a, c.body_b] {
                if let Some(used) = self.used.get_mut(body) {
                    *used = 0;
                }
            }
        }
    }
}
