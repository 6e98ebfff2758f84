//! `ParryBackend`: the world's [`CollisionBackend`] on parry3d (stage 2 of the step, *collide*). It owns the
//! colliders, the broad phase (BVH), the narrow-phase pair cache and the set of body pairs whose contacts a
//! joint disabled. The world calls [`CollisionBackend::collide`] once per step; everything else is driven by
//! [`crate::PhysicsWorld`].

use crate::broad_phase::BroadPhase;
use crate::hooks::ContactHooks;
use crate::narrow_phase::NarrowPhase;
use crate::{Collider, ColliderHandle, ColliderSet};
use rebound_world::{
    BodyHandle, BodySet, CollisionBackend, ContactManifold, ManifoldWriter, WorldSettings,
};
use std::collections::BTreeSet;
use std::sync::Arc;

/// Colliders on parry3d shapes, a BVH broad phase and parry's persistent contact manifolds. Reach it through
/// [`crate::PhysicsWorld::world`]`().backend()` to read the colliders and counters.
#[derive(Debug, Clone, Default)]
pub struct ParryBackend {
    pub(crate) colliders: ColliderSet,
    pub(crate) broad_phase: BroadPhase,
    pub(crate) narrow_phase: NarrowPhase,
    /// Body pairs (lower handle first) whose contacts a joint disabled.
    pub(crate) disabled_pairs: BTreeSet<(BodyHandle, BodyHandle)>,
    /// The contact hooks, if set ([`crate::PhysicsWorld::set_contact_hooks`]).
    pub(crate) hooks: Option<SharedHooks>,
    /// Hook calls that failed during the last collide stage (panicked or returned an edit out of range).
    pub(crate) hook_failures: usize,
}

/// The contact hooks as the backend holds them: shared, so that the backend (and a world) stays `Clone`.
#[derive(Clone)]
pub(crate) struct SharedHooks(pub(crate) Arc<dyn ContactHooks>);

impl core::fmt::Debug for SharedHooks {
    fn fmt(&self, f: &mut core::fmt::Formatter<'_>) -> core::fmt::Result {
        f.write_str("ContactHooks")
    }
}

impl ParryBackend {
    pub(crate) fn with_generation_base(base: u32) -> Self {
        Self {
            colliders: ColliderSet::with_generation_base(base),
            ..Self::default()
        }
    }

    /// The colliders.
    #[must_use]
    pub fn colliders(&self) -> &ColliderSet {
        &self.colliders
    }

    /// The collider behind `handle`.
    #[must_use]
    pub fn collider(&self, handle: ColliderHandle) -> Option<&Collider> {
        self.colliders.get(handle)
    }

    /// The candidate pairs of the last step (sorted, lower handle first): overlapping fat boxes that pass the
    /// filters, less pairs of balls too far apart to touch this step (see the broad phase).
    #[must_use]
    pub fn candidate_pairs(&self) -> &[(ColliderHandle, ColliderHandle)] {
        &self.broad_phase.pairs
    }

    /// The number of collider pairs the narrow phase keeps a cache for.
    #[must_use]
    pub fn cached_pair_count(&self) -> usize {
        self.narrow_phase.pair_count()
    }

    /// Body pairs (lower handle first) whose contacts are disabled by a joint.
    #[must_use]
    pub fn disabled_body_pairs(&self) -> &BTreeSet<(BodyHandle, BodyHandle)> {
        &self.disabled_pairs
    }
}

impl CollisionBackend for ParryBackend {
    fn collide(
        &mut self,
        bodies: &BodySet,
        settings: &WorldSettings,
        dt: f32,
        previous: &[ContactManifold],
        out: &mut ManifoldWriter<'_>,
    ) {
        self.broad_phase.find_pairs(
            &self.colliders,
            bodies,
            &self.disabled_pairs,
            settings.speculative_margin,
            dt,
            settings.limits.max_candidate_pairs as usize,
        );
        let broad_phase = &self.broad_phase;
        self.hook_failures = 0;
        self.narrow_phase.collide(
            &broad_phase.pairs,
            |handle| broad_phase.rotation_reach(handle),
            &self.colliders,
            bodies,
            settings.speculative_margin,
            dt,
            previous,
            self.hooks.as_ref().map(|h| &*h.0),
            &mut self.hook_failures,
            out,
        );
    }

    fn capped_pair_count(&self) -> usize {
        self.broad_phase.capped_pair_count()
    }
}
