//! A frame's CONTACT block (`docs/recording.md`) written straight from the world's manifolds into the
//! frame's bytes, in one pass: the recorder reads the manifolds the world already holds and builds no
//! per-point sample to copy and encode again. A pile holds about 2.5 contact points per body, so this pass
//! is most of what recording a frame costs; the bytes are the only copy, and
//! [`read_contacts`] turns them back into [`ContactSample`]s when they are asked for.

use crate::encode::{ContactTotals, put_words};
use crate::format::CONTACT_LEN;
use crate::frame::{BodySample, ContactSample};
use rebound::math::glam::{Mat3A, Vec3A};
use rebound::{BodyHandle, ContactManifold, Vec3};

/// A body's pose at the frame as a rotation matrix and a position, made once per frame for the contact
/// points: moving an anchor to world space by a matrix is a third of a quaternion rotation's arithmetic,
/// and each point moves two.
#[derive(Debug, Clone, Copy)]
pub(crate) struct BodyFrame {
    rotation: Mat3A,
    position: Vec3A,
}

impl BodyFrame {
    /// The frame of a body sampled as `sample`.
    #[inline]
    pub(crate) fn of(sample: &BodySample) -> Self {
        Self {
            rotation: Mat3A::from_quat(sample.rotation),
            position: sample.position.into(),
        }
    }

    /// The world position of the body-frame point `local` (m).
    #[inline]
    fn transform_point(&self, local: Vec3) -> Vec3A {
        self.rotation * Vec3A::from(local) + self.position
    }
}

/// Appends a CONTACT entry for every point of `manifolds` (the first `point_count` of each, in order)
/// whose two bodies have a recording index (`index`) and a frame in `frames` (by index). The point is the
/// midpoint of the point's anchor on A and its anchor on B in world space, as
/// `rebound::world::ManifoldPoint::world_point` defines it, with the rotations as `frames` holds them
/// (equal to that method's result to float rounding).
pub(crate) fn write_contacts(
    manifolds: &[ContactManifold],
    index: impl Fn(BodyHandle) -> Option<u32>,
    frames: &[BodyFrame],
    out: &mut Vec<u8>,
) -> ContactTotals {
    let mut totals = ContactTotals::default();
    for manifold in manifolds {
        let (Some(a), Some(b)) = (index(manifold.body_a), index(manifold.body_b)) else {
            continue;
        };
        let (Some(frame_a), Some(frame_b)) = (frames.get(a as usize), frames.get(b as usize))
        else {
            continue;
        };
        let [nx, ny, nz] = manifold.normal.to_array().map(f32::to_bits);
        let count = manifold.point_count.min(manifold.points.len());
        for p in &manifold.points[..count] {
            let point = (frame_a.transform_point(p.local_anchor_a)
                + frame_b.transform_point(p.local_anchor_b))
                * 0.5;
            let [px, py, pz] = point.to_array().map(f32::to_bits);
            put_words(
                out,
                [
                    a,
                    b,
                    px,
                    py,
                    pz,
                    nx,
                    ny,
                    nz,
                    p.normal_impulse.to_bits(),
                    p.separation.to_bits(),
                ],
            );
            totals.deepest_penetration = totals.deepest_penetration.max(-p.separation);
        }
        totals.count += count;
    }
    totals
}

/// The contact sample of one CONTACT entry's bytes (no check of its body indices).
pub(crate) fn contact_entry(bytes: &[u8; CONTACT_LEN]) -> ContactSample {
    let word = |i: usize| {
        let mut w = [0; 4];
        w.copy_from_slice(&bytes[4 * i..4 * i + 4]);
        u32::from_le_bytes(w)
    };
    let float = |i: usize| f32::from_bits(word(i));
    let vec3 = |i: usize| Vec3::new(float(i), float(i + 1), float(i + 2));
    ContactSample {
        body_a: word(0),
        body_b: word(1),
        point: vec3(2),
        normal: vec3(5),
        normal_impulse: float(8),
        separation: float(9),
    }
}

/// The samples of a block of CONTACT entries, into `out` (cleared first); a trailing partial entry is
/// ignored.
pub(crate) fn read_contacts(block: &[u8], out: &mut Vec<ContactSample>) {
    out.clear();
    out.extend(
        block
            .chunks_exact(CONTACT_LEN)
            .filter_map(|entry| <&[u8; CONTACT_LEN]>::try_from(entry).ok())
            .map(contact_entry),
    );
}
