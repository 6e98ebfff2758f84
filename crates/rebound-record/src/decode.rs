//! Reading the bytes of `docs/recording.md` back into the plain-data types: a frame payload into a
//! [`Frame`], checked field by field against the format and the [`Catalog`] of what the recording has
//! described so far. Never panics: every read is bounds-checked and every problem is a
//! [`RecordingError`] with the byte offset of the field.

use crate::NONE;
use crate::catalog::Catalog;
use crate::contacts::contact_entry;
use crate::error::RecordingError;
use crate::format::{
    BODY_KIND_SHIFT, BODY_LEN, BODY_PRESENT, BODY_SLEEPING, CONTACT_FORCE_KIND, CONTACT_LEN,
    FRAME_HEADER_LEN, JOINT_BROKEN, JOINT_PRESENT, pad4, payload_len,
};
use crate::frame::{BodySample, Diagnostics, Frame, JointSample, RecordedEvent};
use crate::manifest::{BodyKind, Changes};
use rebound::{Quat, Vec3};
use serde::de::DeserializeOwned;

/// Parses `bytes` (UTF-8 JSON, trailing spaces allowed) that start at file offset `offset`.
pub(crate) fn parse_json<T: DeserializeOwned>(
    bytes: &[u8],
    what: &'static str,
    offset: u64,
) -> Result<T, RecordingError> {
    let json = |message: String| RecordingError::Json {
        what,
        offset,
        message,
    };
    let text = std::str::from_utf8(bytes).map_err(|e| {
        json(format!(
            "not UTF-8 ({e}), at byte {}",
            offset + e.valid_up_to() as u64
        ))
    })?;
    serde_json::from_str(text).map_err(|e| json(e.to_string()))
}

/// Bounds-checked little-endian reads from a payload; `base` is the payload's offset in the file.
struct Cursor<'a> {
    bytes: &'a [u8],
    at: usize,
    base: u64,
}

impl<'a> Cursor<'a> {
    const fn new(bytes: &'a [u8], base: u64) -> Self {
        Self { bytes, at: 0, base }
    }

    /// The file offset of the next byte.
    const fn offset(&self) -> u64 {
        self.base + self.at as u64
    }

    fn take<const N: usize>(&mut self) -> Result<[u8; N], RecordingError> {
        let end = self.at.checked_add(N);
        let slice = end.and_then(|end| self.bytes.get(self.at..end));
        let Some(array) = slice.and_then(|s| <[u8; N]>::try_from(s).ok()) else {
            return Err(RecordingError::Truncated {
                what: "frame payload",
                offset: self.offset(),
                needed: N as u64,
                available: self.bytes.len().saturating_sub(self.at) as u64,
            });
        };
        self.at += N;
        Ok(array)
    }

    fn bytes(&mut self, n: usize) -> Result<&'a [u8], RecordingError> {
        let Some(slice) = self
            .at
            .checked_add(n)
            .and_then(|end| self.bytes.get(self.at..end))
        else {
            return Err(RecordingError::Truncated {
                what: "frame payload",
                offset: self.offset(),
                needed: n as u64,
                available: self.bytes.len().saturating_sub(self.at) as u64,
            });
        };
        self.at += n;
        Ok(slice)
    }

    fn u8(&mut self) -> Result<u8, RecordingError> {
        Ok(self.take::<1>()?[0])
    }

    fn u32(&mut self) -> Result<u32, RecordingError> {
        self.take().map(u32::from_le_bytes)
    }

    fn u64(&mut self) -> Result<u64, RecordingError> {
        self.take().map(u64::from_le_bytes)
    }

    fn f32(&mut self) -> Result<f32, RecordingError> {
        self.take().map(f32::from_le_bytes)
    }

    fn f64(&mut self) -> Result<f64, RecordingError> {
        self.take().map(f64::from_le_bytes)
    }

    fn vec3(&mut self) -> Result<Vec3, RecordingError> {
        Ok(Vec3::new(self.f32()?, self.f32()?, self.f32()?))
    }

    fn quat(&mut self) -> Result<Quat, RecordingError> {
        Ok(Quat::from_xyzw(
            self.f32()?,
            self.f32()?,
            self.f32()?,
            self.f32()?,
        ))
    }
}

/// A `BadValue` error.
fn bad(field: &'static str, offset: u64, value: String) -> RecordingError {
    RecordingError::BadValue {
        field,
        offset,
        value,
    }
}

/// An index field that must be below `count` or [`NONE`].
fn optional_index(
    field: &'static str,
    offset: u64,
    value: u32,
    count: usize,
) -> Result<Option<u32>, RecordingError> {
    if value == NONE {
        Ok(None)
    } else if (value as usize) < count {
        Ok(Some(value))
    } else {
        Err(bad(
            field,
            offset,
            format!("{value} (there are {count}; {NONE} means none)"),
        ))
    }
}

/// Decodes the payload of a frame that starts at file offset `offset` (its length prefix), applying its
/// changes to `catalog` (left unchanged on error).
///
/// # Errors
/// Any disagreement with `docs/recording.md`, as a [`RecordingError`] with the offset of the field.
pub(crate) fn decode_frame(
    payload: &[u8],
    offset: u64,
    catalog: &mut Catalog,
) -> Result<Frame, RecordingError> {
    let base = offset + 4;
    if payload.len() < FRAME_HEADER_LEN {
        return Err(RecordingError::Truncated {
            what: "frame header",
            offset: base,
            needed: FRAME_HEADER_LEN as u64,
            available: payload.len() as u64,
        });
    }
    let mut c = Cursor::new(payload, base);
    let step = c.u64()?;
    let time = c.f64()?;
    let nb = c.u32()? as usize;
    let nc = c.u32()? as usize;
    let nj = c.u32()? as usize;
    let ne = c.u32()? as usize;
    let changes_len = c.u32()? as usize;
    let nf = c.u32()? as usize;
    if !changes_len.is_multiple_of(4) {
        return Err(RecordingError::BadLength {
            what: "changes length",
            offset: base + 32,
            found: changes_len as u64,
            expected: pad4(changes_len) as u64,
        });
    }
    let expected = payload_len(changes_len, nb, nc, nj, ne, nf);
    if expected != Some(payload.len()) {
        return Err(RecordingError::BadLength {
            what: "frame payload length",
            offset,
            found: payload.len() as u64,
            expected: expected.map_or(u64::MAX, |n| n as u64),
        });
    }
    let diagnostics = Diagnostics {
        kinetic_energy: c.f32()?,
        potential_energy: c.f32()?,
        spring_energy: c.f32()?,
        linear_momentum: c.vec3()?,
        angular_momentum: c.vec3()?,
        worst_joint_error: c.f32()?,
        deepest_penetration: c.f32()?,
    };
    let mut next_catalog = None;
    let changes = if changes_len > 0 {
        let at = c.offset();
        let json = c.bytes(changes_len)?;
        let changes: Changes = parse_json(json, "changes", at)?;
        let mut updated = catalog.clone();
        updated.apply(&changes, at)?;
        next_catalog = Some(updated);
        Some(changes)
    } else {
        None
    };
    let known = next_catalog.as_ref().unwrap_or(catalog);
    if nb != known.bodies().len() {
        return Err(bad(
            "body count",
            base + 16,
            format!(
                "{nb} (the recording has described {})",
                known.bodies().len()
            ),
        ));
    }
    if nj != known.joints().len() {
        return Err(bad(
            "joint count",
            base + 24,
            format!(
                "{nj} (the recording has described {})",
                known.joints().len()
            ),
        ));
    }
    let colliders = known.collider_count();
    let bodies = decode_bodies(&mut c, nb)?;
    let mut contacts = Vec::with_capacity(nc);
    for _ in 0..nc {
        let at = c.offset();
        let contact = contact_entry(&c.take::<CONTACT_LEN>()?);
        for (field, value, off) in [
            ("contact body A", contact.body_a, at),
            ("contact body B", contact.body_b, at + 4),
        ] {
            if value as usize >= nb {
                return Err(bad(field, off, format!("{value} (there are {nb} bodies)")));
            }
        }
        contacts.push(contact);
    }
    let mut joints = Vec::with_capacity(nj);
    for _ in 0..nj {
        let anchor_a = c.vec3()?;
        let anchor_b = c.vec3()?;
        let error = c.f32()?;
        let reaction_force = c.f32()?;
        let reaction_torque = c.f32()?;
        let at = c.offset();
        let flags = c.u32()?;
        if flags & !(JOINT_PRESENT | JOINT_BROKEN) != 0 {
            return Err(bad(
                "joint flags",
                at,
                format!("{flags:#x} (only bits 0 and 1 are defined)"),
            ));
        }
        joints.push(JointSample {
            anchor_a,
            anchor_b,
            error,
            reaction_force,
            reaction_torque,
            present: flags & JOINT_PRESENT != 0,
            broken: flags & JOINT_BROKEN != 0,
        });
    }
    let mut events = Vec::with_capacity(ne);
    for _ in 0..ne {
        events.push(decode_event(&mut c, nb, nj, colliders)?);
    }
    let force_events = events
        .iter()
        .filter(|e| matches!(e, RecordedEvent::ContactForce { .. }))
        .count();
    if force_events != nf {
        return Err(bad(
            "contact force count",
            base + 36,
            format!("{nf} (the frame has {force_events} contact force events)"),
        ));
    }
    for event in &mut events {
        if let RecordedEvent::ContactForce {
            collider_a,
            collider_b,
            normal,
            total_impulse,
            max_impulse_point,
            max_impulse,
            ..
        } = event
        {
            let at = c.offset();
            *collider_a = optional_index("contact force collider A", at, c.u32()?, colliders)?;
            *collider_b = optional_index("contact force collider B", at + 4, c.u32()?, colliders)?;
            *normal = c.vec3()?;
            *total_impulse = c.f32()?;
            *max_impulse_point = c.vec3()?;
            *max_impulse = c.f32()?;
        }
    }
    if let Some(updated) = next_catalog {
        *catalog = updated;
    }
    Ok(Frame {
        step,
        time,
        changes,
        bodies,
        contacts,
        joints,
        events,
        diagnostics,
    })
}

/// The body block: four arrays of `nb` entries, then the flags, then padding.
fn decode_bodies(c: &mut Cursor<'_>, nb: usize) -> Result<Vec<BodySample>, RecordingError> {
    let start = c.offset();
    let mut bodies = vec![BodySample::REMOVED; nb];
    for b in &mut bodies {
        b.position = c.vec3()?;
    }
    for b in &mut bodies {
        b.rotation = c.quat()?;
    }
    for b in &mut bodies {
        b.linear_velocity = c.vec3()?;
    }
    for b in &mut bodies {
        b.angular_velocity = c.vec3()?;
    }
    for (i, b) in bodies.iter_mut().enumerate() {
        let at = c.offset();
        let flags = c.u8()?;
        let kind = BodyKind::from_code((flags >> BODY_KIND_SHIFT) & 0b11)
            .filter(|_| flags >> (BODY_KIND_SHIFT + 2) == 0)
            .ok_or_else(|| {
                bad(
                    "body flags",
                    at,
                    format!("{flags:#04x} (bits 2-3 kind 0-2, bits 4-7 zero)"),
                )
            })?;
        b.present = flags & BODY_PRESENT != 0;
        b.sleeping = flags & BODY_SLEEPING != 0;
        b.kind = kind;
        let finite = b.position.is_finite()
            && b.rotation.is_finite()
            && b.linear_velocity.is_finite()
            && b.angular_velocity.is_finite();
        if !finite {
            // The sample's first field: the position array entry of body i.
            return Err(bad(
                "body state",
                start + (i * 12) as u64,
                format!("body {i} has a non-finite position, rotation or velocity"),
            ));
        }
    }
    c.bytes(pad4(nb) - nb)?;
    debug_assert_eq!(c.offset() - start, (nb * BODY_LEN + pad4(nb)) as u64);
    Ok(bodies)
}

/// One EVENT entry.
fn decode_event(
    c: &mut Cursor<'_>,
    bodies: usize,
    joints: usize,
    colliders: usize,
) -> Result<RecordedEvent, RecordingError> {
    let at = c.offset();
    let kind = c.u32()?;
    let a = c.u32()?;
    let b = c.u32()?;
    let value = c.f32()?;
    let body = |field, v, off| optional_index(field, off, v, bodies);
    let collider = |field, v, off| optional_index(field, off, v, colliders);
    let unused = |v: u32, off: u64| {
        if v == NONE {
            Ok(())
        } else {
            Err(bad(
                "event field b",
                off,
                format!("{v} (unused: must be {NONE})"),
            ))
        }
    };
    Ok(match kind {
        1 => RecordedEvent::ContactBegan {
            body_a: body("event body A", a, at + 4)?,
            body_b: body("event body B", b, at + 8)?,
            approach_speed: value,
        },
        2 => RecordedEvent::ContactEnded {
            body_a: body("event body A", a, at + 4)?,
            body_b: body("event body B", b, at + 8)?,
        },
        3 => {
            unused(b, at + 8)?;
            RecordedEvent::JointBroken {
                joint: optional_index("event joint", at + 4, a, joints)?,
            }
        }
        4 => {
            unused(b, at + 8)?;
            RecordedEvent::BodyFellAsleep {
                body: body("event body", a, at + 4)?,
            }
        }
        5 => {
            unused(b, at + 8)?;
            RecordedEvent::BodyWoke {
                body: body("event body", a, at + 4)?,
            }
        }
        6 => RecordedEvent::SensorEntered {
            sensor: collider("event sensor", a, at + 4)?,
            collider: collider("event collider", b, at + 8)?,
        },
        7 => RecordedEvent::SensorExited {
            sensor: collider("event sensor", a, at + 4)?,
            collider: collider("event collider", b, at + 8)?,
        },
        CONTACT_FORCE_KIND => RecordedEvent::ContactForce {
            body_a: body("event body A", a, at + 4)?,
            body_b: body("event body B", b, at + 8)?,
            total_force: value,
            // The rest is the frame's FORCE entry for this event, read after the events.
            collider_a: None,
            collider_b: None,
            normal: Vec3::ZERO,
            total_impulse: 0.0,
            max_impulse_point: Vec3::ZERO,
            max_impulse: 0.0,
        },
        other => return Err(bad("event kind", at, format!("{other} (1 to 8)"))),
    })
}
