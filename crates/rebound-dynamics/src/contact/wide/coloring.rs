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
/// the other, so a body may have one colour in each. On one thread *prepare* makes a chunk's headers, colours
/// them and builds their batches before the next chunk's, in one buffer of a chunk's length that stays in
/// cache, instead of a list as long as the contacts written and read once a step.
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
    /// Manifold indices per colour, in manifold order, for the chunk being coloured (see [`CHUNK`]): into
    /// the chunk, or on a pool into every manifold prepared.
    pub(crate) members: [Vec<usize>; COLORS],
    /// The end (one past the last index into the batches) of each colour of each chunk, in batch order: the
    /// batches of one such group share no moving body (`super::groups` solves them on several threads).
    pub(crate) group_ends: Vec<usize>,
    /// Leave every manifold to the scalar path (tests compare the two paths).
    pub(crate) scalar_only: bool,
    /// Whether the batches are named by the chunks and prepared over the pool at the end (`super::fill`).
    on_pool: bool,
    /// On a pool of several threads, the batches named before they are prepared (`super::fill`): each
    /// batch's range of `pool_members` (its manifolds, in lane order), and scratch.
    pool_groups: Vec<(u32, u32)>,
    pool_members: Vec<usize>,
    pool_places: Vec<(u32, u32)>,
}

impl Coloring {
    /// Colours the wide-eligible manifolds of `contacts` and groups them into `batches`, chunk by chunk; the
    /// others (and those that fit no colour) are copied to `scalar`, in manifold order. On a pool the batches
    /// are named here and prepared over it at the end.
    pub(crate) fn build(
        &mut self,
        contacts: &[PreparedContact],
        input: &PrepareInput<'_>,
        batches: &mut Batches,
        scalar: &mut Vec<PreparedContact>,
    ) {
        let on_pool = par::is_parallel() && contacts.len() >= MIN_CONTACTS_ON_POOL;
        self.begin(input.params.len(), on_pool, batches);
        for start in (0..contacts.len()).step_by(CHUNK) {
            let chunk = &contacts[start..contacts.len().min(start + CHUNK)];
            self.color_chunk(chunk, start, input, batches, scalar);
        }
        self.finish(contacts, input, batches);
    }

    /// Starts a colouring between `body_count` bodies: empties `batches`; `on_pool`: the batches are named
    /// by [`Coloring::color_chunk`] and prepared over the pool by [`Coloring::finish`].
    pub(crate) fn begin(&mut self, body_count: usize, on_pool: bool, batches: &mut Batches) {
        self.on_pool = on_pool;
        batches.clear();
        self.pool_groups.clear();
        self.pool_members.clear();
        self.group_ends.clear();
        // Each chunk's end clears every bit its manifolds set (`flush`): between colourings the array is all
        // zero, so it only grows, and a step writes no more of it than its manifolds' bodies.
        debug_assert!(self.used.iter().all(|&used| used == 0));
        if self.used.len() < body_count {
            self.used.resize(body_count, 0);
        }
        for members in &mut self.members {
            members.clear();
        }
    }

    /// Colours one chunk (at most [`CHUNK`] manifolds, the one starting at `first` of those prepared) and
    /// makes its batches, or names them on a pool; the manifolds the scalar path solves are copied to
    /// `scalar`. Its batches read `chunk`; on a pool, [`Coloring::finish`] reads the manifolds the chunks
    /// together make, whose indices start at 0.
    pub(crate) fn color_chunk(
        &mut self,
        chunk: &[PreparedContact],
        first: usize,
        input: &PrepareInput<'_>,
        batches: &mut Batches,
        scalar: &mut Vec<PreparedContact>,
    ) {
        let params = input.params;
        // Batches read the manifolds by their index in `chunk`; on a pool, in every manifold prepared.
        let offset = if self.on_pool { first } else { 0 };
        for (index, c) in chunk.iter().enumerate() {
            if !is_wide(c) || self.scalar_only {
                scalar.push(*c);
                continue;
            }
            // Fixed and kinematic bodies take no colour: any number of lanes may read them.
            let moves = |body: usize| params[body].is_dynamic();
            let used = |body: usize| if moves(body) { self.used[body] } else { 0 };
            // The first colour neither body is in.
            let color = (!(used(c.body_a) | used(c.body_b))).trailing_zeros() as usize;
            if color >= COLORS {
                scalar.push(*c);
                continue;
            }
            for body in [c.body_a, c.body_b] {
                if moves(body) {
                    self.used[body] |= 1 << color;
                }
            }
            self.members[color].push(offset + index);
        }
        self.flush(chunk, input, batches);
    }

    /// Ends the colouring: on a pool, the batches named, each prepared over it from `contacts` (every
    /// manifold the chunks held, in order).
    pub(crate) fn finish(
        &mut self,
        contacts: &[PreparedContact],
        input: &PrepareInput<'_>,
        batches: &mut Batches,
    ) {
        if self.on_pool {
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
    fn flush(
        &mut self,
        chunk: &[PreparedContact],
        input: &PrepareInput<'_>,
        batches: &mut Batches,
    ) {
        for members in &mut self.members {
            if self.on_pool {
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
                batches.push(group, chunk, input);
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
