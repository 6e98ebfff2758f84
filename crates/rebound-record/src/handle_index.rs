//! [`HandleIndex`]: the recorder's map from an engine handle (slot, generation) to the recording index it
//! gave the object. The current generation of each slot is found by slot in O(1), as the frame's thousands
//! of contact lookups need; a handle whose slot has since been reused is kept in a side table, so that a
//! late event naming a removed body still finds its index.

use std::collections::BTreeMap;

/// Recording indices by handle raw parts.
#[derive(Debug, Default, Clone)]
pub(crate) struct HandleIndex {
    /// By slot: the generation seen last in that slot and its index.
    latest: Vec<Option<(u32, u32)>>,
    /// Handles whose slot has since held a newer generation.
    retired: BTreeMap<(u32, u32), u32>,
}

impl HandleIndex {
    /// The index of the handle `(slot, generation)`, if it was ever inserted.
    pub(crate) fn get(&self, (slot, generation): (u32, u32)) -> Option<u32> {
        match self.latest.get(slot as usize).copied().flatten() {
            Some((g, index)) if g == generation => Some(index),
            _ => self.retired.get(&(slot, generation)).copied(),
        }
    }

    /// Records that `(slot, generation)` has `index`; an older handle of the same slot is retired.
    pub(crate) fn insert(&mut self, (slot, generation): (u32, u32), index: u32) {
        let slot_index = slot as usize;
        if self.latest.len() <= slot_index {
            self.latest.resize(slot_index + 1, None);
        }
        if let Some(old) = self.latest[slot_index].replace((generation, index)) {
            self.retired.insert((slot, old.0), old.1);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::HandleIndex;

    #[test]
    fn a_reused_slot_keeps_the_old_handle_findable() {
        let mut map = HandleIndex::default();
        map.insert((3, 1), 0);
        map.insert((0, 1), 1);
        assert_eq!(map.get((3, 1)), Some(0));
        map.insert((3, 2), 2);
        assert_eq!(map.get((3, 2)), Some(2));
        assert_eq!(map.get((3, 1)), Some(0));
        assert_eq!(map.get((3, 3)), None);
        assert_eq!(map.get((9, 1)), None);
    }
}
