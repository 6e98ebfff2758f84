//! Writing the bytes of `docs/recording.md`: the file header with the manifest, and a frame with its length
//! prefix. Pure functions from the plain-data types to bytes; the [`crate::Recorder`] decides what goes in.

use crate::NONE;
use crate::error::RecordingError;
use crate::format::{
    BODY_KIND_SHIFT, BODY_LEN, BODY_PRESENT, BODY_SLEEPING, CONTACT_FORCE_KIND, JOINT_BROKEN,
    JOINT_PRESENT, MAGIC, VERSION, pad4, payload_len,
};
use crate::frame::{BodySample, Frame, RecordedEvent};
use crate::manifest::Manifest;
use rebound::Vec3;
use std::ops::Range;

/// Appends `value` as JSON padded with spaces to a multiple of 4 bytes; returns the padded length.
fn put_json(
    out: &mut Vec<u8>,
    value: &impl serde::Serialize,
    what: &'static str,
    offset: u64,
) -> Result<usize, RecordingError> {
    let start = out.len();
    serde_json::to_writer(&mut *out, value).map_err(|e| RecordingError::Json {
        what,
        offset,
        message: e.to_string(),
    })?;
    let len = pad4(out.len() - start);
    out.resize(start + len, b' ');
    Ok(len)
}

/// A count as the `u32` the format stores.
fn count(what: &'static str, n: usize) -> Result<u32, RecordingError> {
    u32::try_from(n).map_err(|_| RecordingError::TooMany {
        what,
        count: n as u64,
    })
}

fn put_u32(out: &mut Vec<u8>, v: u32) {
    out.extend_from_slice(&v.to_le_bytes());
}

fn put_f32(out: &mut Vec<u8>, v: f32) {
    out.extend_from_slice(&v.to_le_bytes());
}

/// Appends `N` little-endian 32-bit words in one piece (one capacity check per entry rather than per
/// number, and straight-line stores: the body and contact blocks are most of a frame).
#[inline]
pub(crate) fn put_words<const N: usize>(out: &mut Vec<u8>, values: [u32; N]) {
    out.extend_from_slice(values.map(u32::to_le_bytes).as_flattened());
}

/// Appends the body block of `bodies` (`docs/recording.md`: positions, rotations, linear and angular
/// velocities, each an array in index order, then the flag bytes and their padding), reserved once: it
/// is a third of a frame, an entry per body, so each entry is appended inline.
fn put_bodies(out: &mut Vec<u8>, bodies: &[BodySample]) {
    let nb = bodies.len();
    out.reserve(BODY_LEN * nb + pad4(nb));
    let vec3 = |v: Vec3| v.to_array().map(f32::to_bits);
    for b in bodies {
        put_words(out, vec3(b.position));
    }
    for b in bodies {
        put_words(out, b.rotation.to_array().map(f32::to_bits));
    }
    for b in bodies {
        put_words(out, vec3(b.linear_velocity));
    }
    for b in bodies {
        put_words(out, vec3(b.angular_velocity));
    }
    out.extend(bodies.iter().map(|b| {
        let mut flags = b.kind.code() << BODY_KIND_SHIFT;
        if b.present {
            flags |= BODY_PRESENT;
        }
        if b.sleeping {
            flags |= BODY_SLEEPING;
        }
        flags
    }));
    out.resize(out.len() + (pad4(nb) - nb), 0);
}

fn put_vec3(out: &mut Vec<u8>, v: Vec3) {
    put_words(out, v.to_array().map(f32::to_bits));
}

/// Writes the 16-byte file header and the padded manifest into `out` (cleared first).
///
/// # Errors
/// [`RecordingError::Json`] if the manifest cannot be serialised, [`RecordingError::TooMany`] if it is
/// longer than 4 GiB.
pub(crate) fn encode_header(manifest: &Manifest, out: &mut Vec<u8>) -> Result<(), RecordingError> {
    out.clear();
    out.extend_from_slice(&MAGIC);
    put_u32(out, VERSION);
    put_u32(out, 0);
    let len = put_json(out, manifest, "manifest", 16)?;
    let len = count("manifest bytes", len)?;
    out[12..16].copy_from_slice(&len.to_le_bytes());
    Ok(())
}

/// What writing a frame's CONTACT entries found (see [`encode_frame`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct ContactTotals {
    /// How many CONTACT entries were written.
    pub(crate) count: usize,
    /// The largest overlap of the points (m, ≥ 0): `max(0, −separation)` over them, in their order.
    pub(crate) deepest_penetration: f32,
}

/// Writes `frame` with its length prefix into `out` (cleared first); `offset` is where the frame will
/// start in the file, for error messages. The CONTACT entries are not taken from `frame.contacts`:
/// `write_contacts` appends them and returns their count and deepest penetration, which go into the header
/// (the recorder writes them straight from the world's manifolds: `contacts::write_contacts`).
/// Returns those totals and where in `out` the entries lie.
///
/// # Errors
/// [`RecordingError::TooMany`] for counts or a payload beyond `u32`; [`RecordingError::Json`] if the
/// changes cannot be serialised.
pub(crate) fn encode_frame(
    frame: &Frame,
    write_contacts: impl FnOnce(&mut Vec<u8>) -> ContactTotals,
    offset: u64,
    out: &mut Vec<u8>,
) -> Result<(ContactTotals, Range<usize>), RecordingError> {
    out.clear();
    let nb = frame.bodies.len();
    let nj = frame.joints.len();
    let ne = frame.events.len();
    let nf = frame
        .events
        .iter()
        .filter(|e| matches!(e, RecordedEvent::ContactForce { .. }))
        .count();
    let estimate = payload_len(0, nb, 0, nj, ne, nf).unwrap_or(0);
    out.reserve(estimate + 4);
    put_u32(out, 0); // payload length, filled in below
    out.extend_from_slice(&frame.step.to_le_bytes());
    out.extend_from_slice(&frame.time.to_le_bytes());
    put_u32(out, count("bodies", nb)?);
    put_u32(out, 0); // contact count, filled in below
    put_u32(out, count("joints", nj)?);
    put_u32(out, count("events", ne)?);
    put_u32(out, 0); // changes length, filled in below
    put_u32(out, count("contact forces", nf)?);
    let d = &frame.diagnostics;
    put_f32(out, d.kinetic_energy);
    put_f32(out, d.potential_energy);
    put_f32(out, d.spring_energy);
    put_vec3(out, d.linear_momentum);
    put_vec3(out, d.angular_momentum);
    put_f32(out, d.worst_joint_error);
    put_f32(out, 0.0); // deepest penetration, filled in below
    if let Some(changes) = frame.changes.as_ref().filter(|c| !c.is_empty()) {
        let len = put_json(out, changes, "changes", offset + 4 + 84)?;
        let len = count("changes bytes", len)?;
        out[4 + 32..4 + 36].copy_from_slice(&len.to_le_bytes());
    }
    put_bodies(out, &frame.bodies);
    let contacts_at = out.len();
    let totals = write_contacts(out);
    let contacts = contacts_at..out.len();
    let start = 4; // the payload's first byte
    out[start + 20..start + 24].copy_from_slice(&count("contacts", totals.count)?.to_le_bytes());
    out[start + 80..start + 84].copy_from_slice(&totals.deepest_penetration.to_le_bytes());
    for j in &frame.joints {
        let [ax, ay, az] = j.anchor_a.to_array().map(f32::to_bits);
        let [bx, by, bz] = j.anchor_b.to_array().map(f32::to_bits);
        let mut flags = 0;
        if j.present {
            flags |= JOINT_PRESENT;
        }
        if j.broken {
            flags |= JOINT_BROKEN;
        }
        put_words(
            out,
            [
                ax,
                ay,
                az,
                bx,
                by,
                bz,
                j.error.to_bits(),
                j.reaction_force.to_bits(),
                j.reaction_torque.to_bits(),
                flags,
            ],
        );
    }
    for e in &frame.events {
        let (kind, a, b, value) = event_fields(e);
        put_words(
            out,
            [kind, a.unwrap_or(NONE), b.unwrap_or(NONE), value.to_bits()],
        );
    }
    for e in &frame.events {
        if let RecordedEvent::ContactForce {
            collider_a,
            collider_b,
            normal,
            total_impulse,
            max_impulse_point,
            max_impulse,
            ..
        } = *e
        {
            let [nx, ny, nz] = normal.to_array().map(f32::to_bits);
            let [px, py, pz] = max_impulse_point.to_array().map(f32::to_bits);
            put_words(
                out,
                [
                    collider_a.unwrap_or(NONE),
                    collider_b.unwrap_or(NONE),
                    nx,
                    ny,
                    nz,
                    total_impulse.to_bits(),
                    px,
                    py,
                    pz,
                    max_impulse.to_bits(),
                ],
            );
        }
    }
    let len = count("frame payload bytes", out.len() - 4)?;
    out[0..4].copy_from_slice(&len.to_le_bytes());
    Ok((totals, contacts))
}

/// An event's kind code, its two index fields and its value (`docs/recording.md`, EVENT).
pub(crate) fn event_fields(event: &RecordedEvent) -> (u32, Option<u32>, Option<u32>, f32) {
    match *event {
        RecordedEvent::ContactBegan {
            body_a,
            body_b,
            approach_speed,
        } => (1, body_a, body_b, approach_speed),
        RecordedEvent::ContactEnded { body_a, body_b } => (2, body_a, body_b, 0.0),
        RecordedEvent::JointBroken { joint } => (3, joint, None, 0.0),
        RecordedEvent::BodyFellAsleep { body } => (4, body, None, 0.0),
        RecordedEvent::BodyWoke { body } => (5, body, None, 0.0),
        RecordedEvent::SensorEntered { sensor, collider } => (6, sensor, collider, 0.0),
        RecordedEvent::SensorExited { sensor, collider } => (7, sensor, collider, 0.0),
        RecordedEvent::ContactForce {
            body_a,
            body_b,
            total_force,
            ..
        } => (CONTACT_FORCE_KIND, body_a, body_b, total_force),
    }
}
