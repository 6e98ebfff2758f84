//! [`Catalog`]: the descriptions of every body, collider and joint a recording knows at a frame — the
//! manifest with the changes of the frames so far applied. The reader keeps one up to date and checks each
//! change against it (indices in sequence, references in range, valid shapes), so a frame never refers to an
//! object it has not described.

use crate::error::RecordingError;
use crate::manifest::{BodyEntry, Changes, ColliderEntry, JointEntry, Manifest};

/// Bodies (each with its current colliders), colliders and joints by recording index.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Catalog {
    bodies: Vec<BodyEntry>,
    joints: Vec<JointEntry>,
    /// By collider index: its body, `None` once removed.
    collider_bodies: Vec<Option<u32>>,
}

impl Catalog {
    /// The catalog of a manifest, checked as a frame's changes are (`offset`: where the manifest starts).
    ///
    /// # Errors
    /// As [`Catalog::apply`].
    pub fn from_manifest(manifest: &Manifest, offset: u64) -> Result<Self, RecordingError> {
        let mut catalog = Self::default();
        catalog.apply_entries(&manifest.bodies, &[], &manifest.joints, &[], offset)?;
        Ok(catalog)
    }

    /// Every body index assigned so far (removed bodies keep their description).
    #[must_use]
    pub fn bodies(&self) -> &[BodyEntry] {
        &self.bodies
    }

    /// Every joint index assigned so far.
    #[must_use]
    pub fn joints(&self) -> &[JointEntry] {
        &self.joints
    }

    /// The number of collider indices assigned so far (removed colliders included).
    #[must_use]
    pub fn collider_count(&self) -> usize {
        self.collider_bodies.len()
    }

    /// The collider of index `index`, if it exists and has not been removed.
    #[must_use]
    pub fn collider(&self, index: u32) -> Option<&ColliderEntry> {
        let body = self
            .collider_bodies
            .get(index as usize)
            .copied()
            .flatten()?;
        self.bodies
            .get(body as usize)?
            .colliders
            .iter()
            .find(|c| c.index == index)
    }

    /// Applies a frame's changes (`offset`: where their JSON starts in the file). Nothing changes on error.
    ///
    /// # Errors
    /// [`RecordingError::BadValue`] for an index out of sequence, a reference to an unknown body, a replaced
    /// body entry listing colliders, a removed collider that does not exist; [`RecordingError::Shape`] for
    /// an invalid shape.
    pub fn apply(&mut self, changes: &Changes, offset: u64) -> Result<(), RecordingError> {
        let mut next = self.clone();
        next.apply_entries(
            &changes.bodies,
            &changes.colliders,
            &changes.joints,
            &changes.removed_colliders,
            offset,
        )?;
        *self = next;
        Ok(())
    }

    fn apply_entries(
        &mut self,
        bodies: &[BodyEntry],
        colliders: &[ColliderEntry],
        joints: &[JointEntry],
        removed: &[u32],
        offset: u64,
    ) -> Result<(), RecordingError> {
        let bad = |field: &'static str, value: String| RecordingError::BadValue {
            field,
            offset,
            value,
        };
        for body in bodies {
            let known = self.bodies.len();
            match body.index as usize {
                i if i == known => {
                    let mut entry = body.clone();
                    entry.colliders.clear();
                    self.bodies.push(entry);
                    for collider in &body.colliders {
                        if collider.body != body.index {
                            return Err(bad(
                                "collider body",
                                format!(
                                    "collider {} of body {} names body {}",
                                    collider.index, body.index, collider.body
                                ),
                            ));
                        }
                        self.put_collider(collider, offset)?;
                    }
                }
                i if i < known => {
                    if !body.colliders.is_empty() {
                        return Err(bad(
                            "body colliders",
                            format!(
                                "the entry replacing body {} lists colliders (it may not)",
                                body.index
                            ),
                        ));
                    }
                    let colliders = std::mem::take(&mut self.bodies[i].colliders);
                    self.bodies[i] = BodyEntry {
                        colliders,
                        ..body.clone()
                    };
                }
                _ => {
                    return Err(bad(
                        "body index",
                        format!("{} (next new body is {known})", body.index),
                    ));
                }
            }
        }
        for collider in colliders {
            self.put_collider(collider, offset)?;
        }
        for joint in joints {
            let body_count = self.bodies.len();
            let in_range = |b: u32| (b as usize) < body_count;
            if !joint.body_a.is_none_or(in_range) || !in_range(joint.body_b) {
                return Err(bad(
                    "joint bodies",
                    format!(
                        "joint {} joins {:?} and {} of {body_count} bodies",
                        joint.index, joint.body_a, joint.body_b
                    ),
                ));
            }
            let known = self.joints.len();
            match joint.index as usize {
                i if i == known => self.joints.push(joint.clone()),
                i if i < known => self.joints[i] = joint.clone(),
                _ => {
                    return Err(bad(
                        "joint index",
                        format!("{} (next new joint is {known})", joint.index),
                    ));
                }
            }
        }
        for &index in removed {
            let Some(body) = self.collider_bodies.get(index as usize).copied().flatten() else {
                return Err(bad(
                    "removed_colliders",
                    format!("{index} is not a present collider"),
                ));
            };
            if let Some(entry) = self.bodies.get_mut(body as usize) {
                entry.colliders.retain(|c| c.index != index);
            }
            self.collider_bodies[index as usize] = None;
        }
        Ok(())
    }

    /// Adds a new collider or replaces a present one (moving it to the body it now names).
    fn put_collider(
        &mut self,
        collider: &ColliderEntry,
        offset: u64,
    ) -> Result<(), RecordingError> {
        let bad = |field: &'static str, value: String| RecordingError::BadValue {
            field,
            offset,
            value,
        };
        if collider.body as usize >= self.bodies.len() {
            return Err(bad(
                "collider body",
                format!(
                    "collider {} names body {} of {}",
                    collider.index,
                    collider.body,
                    self.bodies.len()
                ),
            ));
        }
        collider
            .shape
            .validate()
            .map_err(|source| RecordingError::Shape {
                collider: collider.index,
                offset,
                source,
            })?;
        let known = self.collider_bodies.len();
        let index = collider.index as usize;
        if index == known {
            self.collider_bodies.push(Some(collider.body));
        } else if let Some(Some(old_body)) = self.collider_bodies.get(index).copied() {
            if let Some(entry) = self.bodies.get_mut(old_body as usize) {
                entry.colliders.retain(|c| c.index != collider.index);
            }
            self.collider_bodies[index] = Some(collider.body);
        } else {
            return Err(bad(
                "collider index",
                format!(
                    "{} (neither the next new collider, {known}, nor a present one)",
                    collider.index
                ),
            ));
        }
        let list = &mut self.bodies[collider.body as usize].colliders;
        let at = list.partition_point(|c| c.index < collider.index);
        list.insert(at, collider.clone());
        Ok(())
    }
}
