//! A small generational arena: the storage behind [`crate::ColliderHandle`] (the same idea as
//! `rebound-world`'s body and joint arenas, rapier's `Arena`). Not a step stage.
//!
//! A slot is reused after removal with a higher generation, so a handle to a removed collider never reaches a
//! later one. Free slots are kept in a LIFO list that is part of the snapshot, so a restored world hands out
//! the same handles as the one that never stopped. Each arena starts its generations at its own base, so a
//! handle from another world is refused rather than resolved to the wrong collider.

use serde::{Deserialize, Serialize};

/// A slot index and the generation it was issued with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub(crate) struct Index {
    /// Slot in the arena.
    pub(crate) index: u32,
    /// Generation of the slot when the index was issued.
    pub(crate) generation: u32,
}

impl Index {
    /// An index that no arena ever issues.
    pub(crate) const INVALID: Self = Self {
        index: u32::MAX,
        generation: u32::MAX,
    };
}

#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
enum Slot<T> {
    Occupied { generation: u32, value: T },
    Free { generation: u32 },
}

/// Values behind generational indices, iterated in slot order (deterministic).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub(crate) struct Arena<T> {
    slots: Vec<Slot<T>>,
    free: Vec<u32>,
    len: usize,
    generation_base: u32,
}

impl<T> Arena<T> {
    /// An empty arena whose new slots start at `generation_base`.
    pub(crate) const fn with_generation_base(generation_base: u32) -> Self {
        Self {
            slots: Vec::new(),
            free: Vec::new(),
            len: 0,
            generation_base,
        }
    }

    /// Stores `value`; `None` only when 2³² − 1 slots are in use.
    pub(crate) fn insert(&mut self, value: T) -> Option<Index> {
        if let Some(slot) = self.free.pop() {
            if let Some(entry) = self.slots.get_mut(slot as usize)
                && let Slot::Free { generation } = *entry
            {
                *entry = Slot::Occupied { generation, value };
                self.len += 1;
                return Some(Index {
                    index: slot,
                    generation,
                });
            }
            // The free list only names free slots (checked on restore); a bad entry is dropped.
            debug_assert!(false, "invariant: the free list names only free slots");
        }
        let index = u32::try_from(self.slots.len())
            .ok()
            .filter(|i| *i != u32::MAX)?;
        let generation = self.generation_base;
        self.slots.push(Slot::Occupied { generation, value });
        self.len += 1;
        Some(Index { index, generation })
    }

    /// Removes and returns the value at `index`, if `index` is current.
    pub(crate) fn remove(&mut self, index: Index) -> Option<T> {
        let entry = self.slots.get_mut(index.index as usize)?;
        match entry {
            Slot::Occupied { generation, .. } if *generation == index.generation => {
                let next = Slot::Free {
                    generation: generation.wrapping_add(1),
                };
                let Slot::Occupied { value, .. } = core::mem::replace(entry, next) else {
                    return None;
                };
                self.free.push(index.index);
                self.len -= 1;
                Some(value)
            }
            _ => None,
        }
    }

    /// The value at `index`, if `index` is current.
    pub(crate) fn get(&self, index: Index) -> Option<&T> {
        match self.slots.get(index.index as usize)? {
            Slot::Occupied { generation, value } if *generation == index.generation => Some(value),
            _ => None,
        }
    }

    /// The value at `index`, mutably, if `index` is current.
    pub(crate) fn get_mut(&mut self, index: Index) -> Option<&mut T> {
        match self.slots.get_mut(index.index as usize)? {
            Slot::Occupied { generation, value } if *generation == index.generation => Some(value),
            _ => None,
        }
    }

    /// The index and value stored in slot `slot`, if it is occupied.
    pub(crate) fn get_slot(&self, slot: u32) -> Option<(Index, &T)> {
        match self.slots.get(slot as usize)? {
            Slot::Occupied { generation, value } => Some((
                Index {
                    index: slot,
                    generation: *generation,
                },
                value,
            )),
            Slot::Free { .. } => None,
        }
    }

    /// The number of values stored.
    pub(crate) const fn len(&self) -> usize {
        self.len
    }

    /// Values with their indices, in slot order.
    pub(crate) fn iter(&self) -> impl Iterator<Item = (Index, &T)> {
        self.slots
            .iter()
            .enumerate()
            .filter_map(|(i, slot)| match slot {
                Slot::Occupied { generation, value } => Some((
                    Index {
                        index: i as u32,
                        generation: *generation,
                    },
                    value,
                )),
                Slot::Free { .. } => None,
            })
    }

    /// The same arena (slots, generations, free list) with every value mapped: how colliders become their
    /// serialisable records and back.
    pub(crate) fn try_map<U, E>(
        &self,
        mut f: impl FnMut(&T) -> Result<U, E>,
    ) -> Result<Arena<U>, E> {
        let slots = self
            .slots
            .iter()
            .map(|slot| match slot {
                Slot::Occupied { generation, value } => Ok(Slot::Occupied {
                    generation: *generation,
                    value: f(value)?,
                }),
                Slot::Free { generation } => Ok(Slot::Free {
                    generation: *generation,
                }),
            })
            .collect::<Result<Vec<_>, E>>()?;
        Ok(Arena {
            slots,
            free: self.free.clone(),
            len: self.len,
            generation_base: self.generation_base,
        })
    }

    /// The same arena with every value mapped.
    pub(crate) fn map<U>(&self, mut f: impl FnMut(&T) -> U) -> Arena<U> {
        match self.try_map(|value| Ok::<U, core::convert::Infallible>(f(value))) {
            Ok(arena) => arena,
            Err(never) => match never {},
        }
    }

    /// Whether the free list and the count agree with the slots (checked on restore: a snapshot is user data).
    pub(crate) fn is_consistent(&self) -> bool {
        let occupied = self
            .slots
            .iter()
            .filter(|s| matches!(s, Slot::Occupied { .. }))
            .count();
        let mut seen = vec![false; self.slots.len()];
        occupied == self.len
            && self.slots.len() - occupied == self.free.len()
            && self.free.iter().all(|&slot| {
                let fresh = seen
                    .get_mut(slot as usize)
                    .is_some_and(|s| !core::mem::replace(s, true));
                fresh && matches!(self.slots.get(slot as usize), Some(Slot::Free { .. }))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stale_indices_find_nothing_after_reuse() {
        let mut arena = Arena::with_generation_base(7);
        let a = arena.insert("a").unwrap();
        let b = arena.insert("b").unwrap();
        assert_eq!(arena.remove(a), Some("a"));
        assert_eq!(arena.remove(a), None);
        let c = arena.insert("c").unwrap();
        assert_eq!(c.index, a.index);
        assert_ne!(c.generation, a.generation);
        assert_eq!(arena.get(a), None);
        assert_eq!(arena.get(c), Some(&"c"));
        assert_eq!(arena.get(b), Some(&"b"));
        assert_eq!(arena.get(Index::INVALID), None);
        assert_eq!(arena.len(), 2);
        assert!(arena.is_consistent());
        let mapped: Arena<usize> = arena.try_map(|s| Ok::<_, ()>(s.len())).unwrap();
        assert_eq!(mapped.get(c), Some(&1));
        assert_eq!(mapped.get_slot(c.index).map(|(i, _)| i), Some(c));
        let other = Arena::<u8>::with_generation_base(8);
        assert_eq!(other.get(b), None);
    }
}
