//! Generational handles for the objects a world stores (rapier's `RigidBodyHandle`, Box2D's ids, Jolt's
//! `BodyID`). A handle is an index plus the generation of its slot, so a handle to a removed object never
//! reaches a later one: lookups return `None` and setters return [`crate::WorldError::StaleHandle`].

use crate::arena::Index;

/// Refers to a body in a [`crate::World`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(transparent)]
pub struct BodyHandle(pub(crate) Index);

/// Refers to a joint (spring, rope, hinge, …) in a [`crate::World`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(transparent)]
pub struct JointHandle(pub(crate) Index);

macro_rules! handle_methods {
    ($name:ident) => {
        impl $name {
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
    };
}

handle_methods!(BodyHandle);
handle_methods!(JointHandle);
