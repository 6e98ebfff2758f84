//! `WorldState`: everything a simulation needs to continue, and what a snapshot holds — the settings, the
//! bodies, the joints, last step's contacts, the touching pairs and the sleeping islands. Read and written by
//! every stage of the step; the API in `world.rs` reads and edits it between steps.

use crate::arena::Arena;
use crate::body_set::BodySet;
use crate::handles::BodyHandle;
use crate::manifold::ContactManifold;
use crate::settings::WorldSettings;
use rebound_constraints::{Joint, JointState};
use std::collections::BTreeMap;

/// A joint and the world's bookkeeping for it.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct JointEntry {
    pub(crate) joint: Joint,
    /// `None`: anchor A is a fixed point of the world (`joint`'s local anchor A is then a world point).
    pub(crate) body_a: Option<BodyHandle>,
    pub(crate) body_b: BodyHandle,
    pub(crate) state: JointState,
}

/// Everything needed to continue a simulation: what a snapshot holds. Scratch buffers and the collision
/// backend are not part of it.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub(crate) struct WorldState {
    pub(crate) settings: WorldSettings,
    pub(crate) bodies: BodySet,
    pub(crate) joints: Arena<JointEntry>,
    /// Last step's manifolds with their impulses, sorted by order key (warm starting, events, queries).
    pub(crate) manifolds: Vec<ContactManifold>,
    /// Body pairs that touched at the end of last step, sorted (contact begin/end events).
    pub(crate) touching: Vec<(BodyHandle, BodyHandle)>,
    /// Sleeping islands: id → bodies, in handle order.
    pub(crate) islands: BTreeMap<u32, Vec<BodyHandle>>,
    pub(crate) next_island: u32,
    /// Time [`crate::World::advance`] has not yet stepped (s).
    pub(crate) accumulator: f32,
    /// Steps taken.
    pub(crate) step_count: u64,
}
