//! The contact solve four manifolds at a time (Box2D v3's graph-coloured wide solver; Catto, "Solver2D",
//! 2024).
//!
//! One manifold's rows form a chain of dependent arithmetic: each row reads the velocities the row before
//! it wrote. Solved one manifold after another, a pass waits on that chain; four manifolds that share no
//! moving body are independent, so they are solved side by side in the four lanes of a `Vec4` — the
//! equations of the scalar solve (`super::scalar::solve`), lane by lane.
//!
//! *Colouring*: manifolds are given, in order, the first of `COLORS` colours in which neither of their
//! moving bodies appears yet (fixed and kinematic bodies are never changed by a contact, so any number of
//! lanes may read them); each colour's manifolds are grouped four by four into batches. Manifolds that fit
//! no colour, and those the wide path does not handle (restitution, rolling resistance), are solved by the
//! scalar path after the batches. The grouping is a function of the manifold order alone: deterministic.
//!
//! A batch has as many point slots as its largest manifold; the slots a smaller manifold leaves empty, and
//! the empty lanes of a colour's last batch, carry zero masses and so apply zero impulses.
//!
//! Files: `coloring.rs` (which manifolds go into which batch), `batch.rs` (a batch: its preparation, warm
//! start and passes), `fill.rs` (the batches prepared over the thread pool), `results.rs` (its impulses read
//! back per manifold), `groups.rs` (a pass over the batches, a colour group's on several threads), `lanes.rs`
//! (the lane arithmetic and transposes).

mod batch;
mod coloring;
mod fill;
mod groups;
mod lanes;
mod results;
#[cfg(test)]
mod tests;

pub(crate) use batch::Batches;
pub(crate) use coloring::Coloring;
pub(crate) use groups::{BATCHES_PER_CHUNK, SharedRows, solve_batches, warm_start_batches};
