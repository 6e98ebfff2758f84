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
#[derive(Debug, Clone, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct BodySet {
    pub(crate) arena: Arena<BodyEntry>,
}

impl BodySet {
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
