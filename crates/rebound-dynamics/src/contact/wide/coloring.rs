//! Colouring for the wide contact path: which manifolds are solved four at a time, in which batches. The
//! manifolds are given, in order, the first colour in which neither of their moving bodies appears yet, chunk
//! by chunk; each colour's manifolds become batches of four. Stage *prepare*.

use super::batch::Batches;
use super::lanes::LANES;
use crate::BodyParams;
use crate::contact::manifold::Contact;
use crate::contact::prepared::PrepareInput;
use rebound_math::Vec3;

/// The number of colours tried before a manifold is left to the scalar path. A body touching more manifolds
/// than this overflows (Box2D v3 uses 24; a box in a pyramid touches 6, a ball in a pile about 12). At most
/// 32 (one bit each in a `u32` per body).
pub(crate) const COLORS: usize = 24;

/// Manifolds coloured together: the batches of the first `CHUNK` prepared manifolds (colour by colour, those
/// of the scalar path counted too), then those of
/// the next `CHUNK`, and so on. A chunk's bodies stay in cache while its colours are solved one after the
/// other; coloured all at once, a pile of 16,384 balls swept its whole body array once per colour, in
/// *prepare* and in every solve pass. Scenes with fewer manifolds are one chunk (the solve order does not
/// change; stacks are sensitive to it). Each chunk's colours start afresh: the chunks are solved one after
/// the other, so a body may have one colour in each.
pub(crate) const CHUNK: usize = 4096;

/// Whether the wide path solves this contact exactly as the scalar path would: no bounce (restitution 0),
/// no rolling block, no surface velocity, and some point.
pub(crate) fn is_wide(c: &Contact) -> bool {
    let rolls = c.rolling_friction > 0.0;
    c.restitution == 0.0
        && !rolls
        && c.surface_velocity == Vec3::ZERO
        && !c.points().is_empty()
}

/// The colouring's scratch. Stage *prepare* hands it the wide-eligible manifolds one by one, in manifold
/// order ([`Coloring::add`]), and ends each chunk ([`Coloring::flush`]); the batches are built at each
/// flush, from the contacts themselves, so no prepared header of a batched manifold is stored.
#[derive(Debug, Clone, Default)]
pub(crate) struct Coloring {
    /// Per body, bit `c` set when a manifold of colour `c` moves it.
    pub(crate) used: Vec<u32>,
    /// Manifold indices (into the contacts given to *prepare*) per colour, in manifold order, for the chunk
    /// being coloured (see [`CHUNK`]).
    pub(crate) members: [Vec<usize>; COLORS],
    /// The end (one past the last index into the batches) of each colour of each chunk, in batch order: the
    /// batches of one such group share no moving body (`super::groups` solves them on several threads).
    pub(crate) group_ends: Vec<usize>,
    /// Leave every manifold to the scalar path (tests compare the two paths).
    pub(crate) scalar_only: bool,
}

impl Coloring {
    /// Starts a colouring of manifolds between `body_count` bodies: no batch, no colour used.
    pub(crate) fn begin(&mut self, body_count: usize, batches: &mut Batches) {
        batches.clear();
        self.group_ends.clear();
        self.used.clear();
        self.used.resize(body_count, 0);
        for members in &mut self.members {
            members.clear();
        }
    }

    /// Gives manifold `source` (`contact`, wide-eligible, its bodies in range) the first colour in which
    /// neither of its moving bodies appears yet; `false` when none is left (it goes to the scalar path).
    pub(crate) fn add(&mut self, source: usize, contact: &Contact, params: &[BodyParams]) -> bool {
        if self.scalar_only {
            return false;
        }
        // Fixed and kinematic bodies take no colour: any number of lanes may read them.
        let moves = |body: usize| params[body].is_dynamic();
        let used = |body: usize| if moves(body) { self.used[body] } else { 0 };
        let color = (!(used(contact.body_a) | used(contact.body_b))).trailing_zeros() as usize;
        if color >= COLORS {
            return false;
        }
        for body in [contact.body_a, contact.body_b] {
            if moves(body) {
                self.used[body] |= 1 << color;
            }
        }
        self.members[color].push(source);
        true
    }

    /// Ends a chunk: its batches, colour by colour (each colour's manifolds four at a time, in manifold
    /// order), then the colours of its bodies are freed for the next chunk.
    pub(crate) fn flush(&mut self, input: &PrepareInput<'_>, batches: &mut Batches) {
        for members in &mut self.members {
            for group in members.chunks(LANES) {
                batches.push(group, input);
            }
            if !members.is_empty() {
                self.group_ends.push(batches.batches.len());
            }
            for &source in members.iter() {
                let c = &input.contacts[source];
                for body in [c.body_a, c.body_b] {
                    if let Some(used) = self.used.get_mut(body) {
                        *used = 0;
                    }
                }
            }
            members.clear();
        }
    }
}
