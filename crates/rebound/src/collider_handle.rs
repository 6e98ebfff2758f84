//! `ColliderHandle`: a generational handle to a collider of a [`crate::PhysicsWorld`] (rapier's
//! `ColliderHandle`, Box2D's shape id). A handle to a removed collider never reaches a later one: lookups
//! return `None`, setters return [`crate::Error::StaleCollider`].

use rebound_world::arena::Index;
use serde::{Deserialize, Serialize};

/// Refers to a collider in a [`crate::PhysicsWorld`]. Ordered by slot, then generation: the order the
/// broad phase sorts pairs in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[repr(transparent)]
pub struct ColliderHandle(pub(crate) Index);

impl ColliderHandle {
    /// A handle that refers to nothing in any world.
    #[must_use]
    pub const fn invalid() -> Self {
        Self(Index::INVALID)
    }

    /// The slot index and generation, e.g. for a user's own side tables.
    #[must_use]
    pub const fn into_raw_parts(self) -> (u32, u32) {
        (self.0.index, self.0.generation)
    }

    /// Rebuilds a handle from [`Self::into_raw_parts`]. A made-up pair is simply stale.
    #[must_use]
    pub const fn from_raw_parts(index: u32, generation: u32) -> Self {
        Self(Index { index, generation })
    }
}
