//! `BodySet`: the bodies of a world behind [`BodyHandle`]s, with the per-body data the world keeps beside
//! each [`RigidBody`] (sleep timer, sleeping island, kinematic target). Read by every stage; written by the
//! finalize and sleep stages.

use crate::BodyHandle;
use crate::arena::{Arena, Index};
use rebound_dynamics::RigidBody;
use rebound_math::Pose;

/// No sleeping island.
pub(crate) const NO_ISLAND: u32 = u32::MAX;

/// A body and the world's bookkeeping for it.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct BodyEntry {
    pub(crate) body: RigidBody,
    /// How long the body has been resting (s).
    pub(crate) sleep_time: f32,
    /// The sleeping island the body belongs to, or [`NO_ISLAND`].
    pub(crate) island: u32,
    /// Where a kinematic body should be at the end of the next step.
    pub(crate) kinematic_target: Option<Pose>,
    /// Whether the body is quarantined: out of every step until released (see `quarantine.rs`).
    #[cfg_attr(feature = "serde", serde(default))]
    pub(crate) quarantined: bool,
}

/// The bodies of a world. Iteration is in handle-slot order, which is deterministic.
///
/// Two sets are equal when they hold the same bodies under the same handles; their
/// [`BodySet::revision`]s, a count of the edits that led there, are not compared.
#[derive(Debug, Clone, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodySet {
    pub(crate) arena: Arena<BodyEntry>,
    /// Bumped by every insertion, removal and mutable access from outside the step, and by a restore (see
    /// [`BodySet::revision`]). Not saved in a snapshot: a restore moves it on from the replaced set's.
    #[cfg_attr(feature = "serde", serde(skip))]
    pub(crate) revision: u64,
}

impl PartialEq for BodySet {
    fn eq(&self, other: &Self) -> bool {
        self.arena == other.arena
    }
}

impl BodySet {
    /// A number that moves on with every body inserted or removed, every mutable access to a body through
    /// the world's API (`body_mut`, which every setter of a [`RigidBody`] is reached through: its mass
    /// properties, gravity scale, type, pose, velocities, forces), every release from quarantine and every
    /// restore. A step changes only what every step changes (poses, velocities, sleep) and leaves it alone,
    /// unless continuous collision detection puts a fast body back along its path (an edit through
    /// `body_mut`). If two reads of the same set give the same revision, no body was inserted, removed or
    /// edited in between, so an observer (a recorder, the quarantine's start-of-step check) that compares
    /// what it saw of the bodies can skip the comparison.
    #[must_use]
    pub const fn revision(&self) -> u64 {
        self.revision
    }

    /// Counts an insertion, removal, edit or restore in [`BodySet::revision`].
    pub(crate) const fn bump_revision(&mut self) {
        self.revision = self.revision.wrapping_add(1);
    }

    /// The body behind `handle`, if it exists.
    #[must_use]
    #[inline]
    pub fn get(&self, handle: BodyHandle) -> Option<&RigidBody> {
        self.arena.get(handle.0).map(|e| &e.body)
    }

    /// Whether `handle` refers to a body of this set.
    #[must_use]
    pub fn contains(&self, handle: BodyHandle) -> bool {
        self.arena.contains(handle.0)
    }

    /// Whether the body behind `handle` is quarantined (taken out of every step after its state left the
    /// bounds of [`crate::StepLimits`]); `false` for a stale handle. A collision backend skips such bodies.
    #[must_use]
    #[inline]
    pub fn is_quarantined(&self, handle: BodyHandle) -> bool {
        self.arena.get(handle.0).is_some_and(|e| e.quarantined)
    }

    /// The number of bodies.
    #[must_use]
    pub fn len(&self) -> usize {
        self.arena.len()
    }

    /// Whether there are no bodies.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.arena.is_empty()
    }

    /// Bodies with their handles, in handle-slot order.
    pub fn iter(&self) -> impl Iterator<Item = (BodyHandle, &RigidBody)> {
        self.arena.iter().map(|(i, e)| (BodyHandle(i), &e.body))
    }

    /// The number of slots a side table indexed by `handle.into_raw_parts().0` needs.
    #[must_use]
    pub fn slot_count(&self) -> usize {
        self.arena.capacity()
    }

    #[inline]
    pub(crate) fn entry(&self, handle: BodyHandle) -> Option<&BodyEntry> {
        self.arena.get(handle.0)
    }

    #[inline]
    pub(crate) fn entry_mut(&mut self, handle: BodyHandle) -> Option<&mut BodyEntry> {
        self.arena.get_mut(handle.0)
    }

    pub(crate) fn slot(handle: BodyHandle) -> usize {
        let Index { index, .. } = handle.0;
        index as usize
    }
}
