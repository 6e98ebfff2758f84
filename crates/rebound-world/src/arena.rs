//! A generational arena: the storage behind [`crate::BodyHandle`] and [`crate::JointHandle`] — and the
//! facade's collider handles (rapier's `Arena`, Box2D's id pool). Not a step stage.
//!
//! A slot is reused after removal with a higher generation, so a handle to the removed value can never reach
//! the new one: a stale handle finds nothing. Free slots are kept in a LIFO list, part of the snapshot, so
//! that a restored world hands out the same handles as the one that never stopped.

use rebound_math::par;

/// A slot index and the generation it was issued with.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Index {
    /// Slot in the arena.
    pub index: u32,
    /// Generation of the slot when the handle was issued.
    pub generation: u32,
}

impl Index {
    /// An index that no arena ever issues.
    pub const INVALID: Self = Self {
        index: u32::MAX,
        generation: u32::MAX,
    };
}

#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
enum Slot<T> {
    Occupied { generation: u32, value: T },
    Free { generation: u32 },
}

/// Values behind generational indices.
///
/// New slots start at generation `generation_base`; a world picks a different base for each arena it makes,
/// so that an index from another world (same slot, same count of reuses) is still refused.
#[derive(Debug, Clone, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct Arena<T> {
    slots: Vec<Slot<T>>,
    free: Vec<u32>,
    len: usize,
    generation_base: u32,
}

impl<T> Default for Arena<T> {
    fn default() -> Self {
        Self::with_generation_base(0)
    }
}

impl<T> Arena<T> {
    /// An empty arena whose new slots start at `generation_base`.
    #[must_use]
    pub const fn with_generation_base(generation_base: u32) -> Self {
        Self {
            slots: Vec::new(),
            free: Vec::new(),
            len: 0,
            generation_base,
        }
    }

    /// Stores `value` and returns its index. `None` only when 2³² − 1 slots are in use.
    pub fn insert(&mut self, value: T) -> Option<Index> {
        if let Some(slot) = self.free.pop() {
            let entry = &mut self.slots[slot as usize];
            let generation = match entry {
                Slot::Free { generation } => *generation,
                Slot::Occupied { .. } => unreachable_free_slot(),
            };
            *entry = Slot::Occupied { generation, value };
            self.len += 1;
            return Some(Index {
                index: slot,
                generation,
            });
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
    pub fn remove(&mut self, index: Index) -> Option<T> {
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
    #[must_use]
    pub fn get(&self, index: Index) -> Option<&T> {
        match self.slots.get(index.index as usize)? {
            Slot::Occupied { generation, value } if *generation == index.generation => Some(value),
            _ => None,
        }
    }

    /// The value at `index`, mutably, if `index` is current.
    pub fn get_mut(&mut self, index: Index) -> Option<&mut T> {
        match self.slots.get_mut(index.index as usize)? {
            Slot::Occupied { generation, value } if *generation == index.generation => Some(value),
            _ => None,
        }
    }

    /// Whether `index` is current.
    #[must_use]
    pub fn contains(&self, index: Index) -> bool {
        self.get(index).is_some()
    }

    /// The number of values stored.
    #[must_use]
    pub const fn len(&self) -> usize {
        self.len
    }

    /// Whether the arena is empty.
    #[must_use]
    pub const fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// One more than the highest slot ever used: the size of a per-slot side table.
    #[must_use]
    pub fn capacity(&self) -> usize {
        self.slots.len()
    }

    /// Values with their indices, in slot order (deterministic).
    pub fn iter(&self) -> impl Iterator<Item = (Index, &T)> {
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

    /// Calls `f(slot, value)` for every stored value, each once, over the thread pool
    /// ([`rebound_math::par::for_each_mut`]; a plain loop in slot order in the serial build).
    pub fn for_each_value_mut(&mut self, f: impl Fn(u32, &mut T) + Sync + Send)
    where
        T: Send,
    {
        par::for_each_mut(&mut self.slots, par::MIN_ITEMS_PER_TASK, |i, slot| {
            if let Slot::Occupied { value, .. } = slot {
                f(i as u32, value);
            }
        });
    }

    /// `out[slot]` becomes `Some(f(index, value))` for every stored value and `None` for every free slot,
    /// over the thread pool, in slot order whichever thread computed each ([`par::map_collect_in_order`];
    /// `out`'s allocation is reused).
    pub fn map_in_slot_order<'a, U: Send>(
        &'a self,
        out: &mut Vec<Option<U>>,
        f: impl Fn(Index, &'a T) -> U + Sync + Send,
    ) where
        T: Sync,
    {
        let slots = &self.slots;
        // Each slot read through `slots` (not the closure's argument), so that `f` sees it for `'a`.
        par::map_collect_in_order(slots, out, par::MIN_ITEMS_PER_TASK, |i, _| {
            match &slots[i] {
                Slot::Occupied { generation, value } => Some(f(
                    Index {
                        index: i as u32,
                        generation: *generation,
                    },
                    value,
                )),
                Slot::Free { .. } => None,
            }
        });
    }

    /// The index and value stored in slot `slot`, if it is occupied.
    #[must_use]
    pub fn get_slot(&self, slot: u32) -> Option<(Index, &T)> {
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

    /// The same arena (slots, generations, free list) with every value mapped — how a snapshot turns stored
    /// values into serialisable records and back.
    ///
    /// # Errors
    /// The first error `f` returns.
    pub fn try_map<U, E>(&self, mut f: impl FnMut(&T) -> Result<U, E>) -> Result<Arena<U>, E> {
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
    #[must_use]
    pub fn map<U>(&self, mut f: impl FnMut(&T) -> U) -> Arena<U> {
        match self.try_map(|value| Ok::<U, core::convert::Infallible>(f(value))) {
            Ok(arena) => arena,
            Err(never) => match never {},
        }
    }

    /// Whether the free list and the count agree with the slots. A deserialised arena is user data: check it
    /// before trusting it (an inconsistent free list would hand out an occupied slot).
    #[must_use]
    pub fn is_consistent(&self) -> bool {
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

    /// Values with their indices, mutably, in slot order.
    pub fn iter_mut(&mut self) -> impl Iterator<Item = (Index, &mut T)> {
        self.slots
            .iter_mut()
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
}

#[cold]
fn unreachable_free_slot() -> u32 {
    // The free list only ever holds slots that `remove` turned free; reaching this is a bug in this file.
    debug_assert!(false, "invariant: the free list names only free slots");
    0
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn stale_indices_find_nothing_after_reuse() {
        let mut arena = Arena::default();
        let a = arena.insert("a").unwrap();
        let b = arena.insert("b").unwrap();
        assert_eq!(arena.remove(a), Some("a"));
        assert_eq!(arena.remove(a), None, "removing twice");
        let c = arena.insert("c").unwrap();
        assert_eq!(c.index, a.index, "the slot is reused");
        assert_ne!(c.generation, a.generation);
        assert_eq!(
            arena.get(a),
            None,
            "the stale index does not reach the new value"
        );
        assert_eq!(arena.get(c), Some(&"c"));
        assert_eq!(arena.get(b), Some(&"b"));
        assert_eq!(arena.len(), 2);
        assert_eq!(arena.get(Index::INVALID), None);
        // An arena with another base refuses the first arena's indices.
        let mut other = Arena::with_generation_base(0x5EED);
        let d = other.insert("d").unwrap();
        assert_eq!(d.index, 0);
        assert_eq!(
            other.get(Index {
                index: 0,
                generation: 0
            }),
            None
        );
        let order: Vec<_> = arena.iter().map(|(_, v)| *v).collect();
        assert_eq!(order, ["c", "b"], "slot order");
    }
}
