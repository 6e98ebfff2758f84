//! `ColliderSet`: the colliders of a world behind [`ColliderHandle`]s, with the list of colliders of each
//! body. Read by the collide stage, sensors and queries; written only by the [`crate::PhysicsWorld`] API.

use crate::{Collider, ColliderHandle};
use rebound_world::BodyHandle;
use rebound_world::arena::Arena;
use std::collections::BTreeMap;

/// The colliders of a world. Iteration is in handle-slot order (deterministic).
#[derive(Debug, Clone)]
pub struct ColliderSet {
    pub(crate) arena: Arena<Collider>,
    /// Each body's colliders, in insertion order.
    pub(crate) by_body: BTreeMap<BodyHandle, Vec<ColliderHandle>>,
    /// Bumped by every insertion, edit and removal, and by a restore (see [`ColliderSet::revision`]).
    revision: u64,
}

impl Default for ColliderSet {
    fn default() -> Self {
        Self::with_generation_base(0)
    }
}

impl ColliderSet {
    pub(crate) fn with_generation_base(base: u32) -> Self {
        Self {
            arena: Arena::with_generation_base(base),
            by_body: BTreeMap::new(),
            revision: 0,
        }
    }

    /// Rebuilds the per-body lists from the arena (after a restore); the revision moves on from
    /// `revision`, the replaced set's.
    pub(crate) fn from_arena(arena: Arena<Collider>, revision: u64) -> Self {
        let mut by_body: BTreeMap<BodyHandle, Vec<ColliderHandle>> = BTreeMap::new();
        for (index, collider) in arena.iter() {
            by_body
                .entry(collider.body)
                .or_default()
                .push(ColliderHandle(index));
        }
        Self {
            arena,
            by_body,
            revision: revision.wrapping_add(1),
        }
    }

    /// A count that changes with every insertion, edit and removal of a collider, and with a snapshot
    /// restore: if two reads of the same set give the same revision, it holds the same colliders with the
    /// same descriptions. Stepping does not change it. Lets an observer (a recording) notice edits without
    /// comparing every description.
    #[must_use]
    pub const fn revision(&self) -> u64 {
        self.revision
    }

    /// The collider behind `handle`.
    #[must_use]
    pub fn get(&self, handle: ColliderHandle) -> Option<&Collider> {
        self.arena.get(handle.0)
    }

    /// The collider behind `handle`, to edit: counts as an edit in [`ColliderSet::revision`].
    pub(crate) fn get_mut(&mut self, handle: ColliderHandle) -> Option<&mut Collider> {
        self.revision = self.revision.wrapping_add(1);
        self.arena.get_mut(handle.0)
    }

    /// Whether `handle` refers to a collider of this set.
    #[must_use]
    pub fn contains(&self, handle: ColliderHandle) -> bool {
        self.get(handle).is_some()
    }

    /// The number of colliders.
    #[must_use]
    pub fn len(&self) -> usize {
        self.arena.len()
    }

    /// Whether there are no colliders.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.arena.len() == 0
    }

    /// Colliders with their handles, in handle-slot order.
    pub fn iter(&self) -> impl Iterator<Item = (ColliderHandle, &Collider)> {
        self.arena.iter().map(|(i, c)| (ColliderHandle(i), c))
    }

    /// The colliders attached to `body`, in insertion order (empty for a body without colliders or a stale
    /// handle).
    #[must_use]
    pub fn of_body(&self, body: BodyHandle) -> &[ColliderHandle] {
        self.by_body.get(&body).map_or(&[], Vec::as_slice)
    }

    /// The collider in slot `slot` (a BVH leaf id).
    pub(crate) fn at_slot(&self, slot: u32) -> Option<(ColliderHandle, &Collider)> {
        self.arena
            .get_slot(slot)
            .map(|(i, c)| (ColliderHandle(i), c))
    }

    pub(crate) fn insert(&mut self, collider: Collider) -> Option<ColliderHandle> {
        let body = collider.body;
        let handle = ColliderHandle(self.arena.insert(collider)?);
        self.revision = self.revision.wrapping_add(1);
        self.by_body.entry(body).or_default().push(handle);
        Some(handle)
    }

    pub(crate) fn remove(&mut self, handle: ColliderHandle) -> Option<Collider> {
        let collider = self.arena.remove(handle.0)?;
        self.revision = self.revision.wrapping_add(1);
        if let Some(list) = self.by_body.get_mut(&collider.body) {
            list.retain(|h| *h != handle);
            if list.is_empty() {
                self.by_body.remove(&collider.body);
            }
        }
        Some(collider)
    }
}
