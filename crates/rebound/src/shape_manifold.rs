//! The contact of two convex shapes as our own generators ([`crate::ball_ball`], [`crate::box_box`]) write
//! it: the fields of parry's `ContactManifold` a convex pair uses, on the stack instead of a heap buffer, read
//! by the narrow phase's seam ([`crate::seam`]).

use parry3d::shape::PackedFeatureId;
use rebound_math::Vec3;

/// Most points a generator writes: a box face clipped against the four side planes of another (8).
const MAX_SHAPE_POINTS: usize = 8;

/// A contact point of two convex shapes, in the shapes' own frames (parry's `TrackedContact` without its user
/// data).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ShapePoint {
    /// The point on shape 1, in shape 1's frame (m).
    pub(crate) local_p1: Vec3,
    /// The point on shape 2, in shape 2's frame (m).
    pub(crate) local_p2: Vec3,
    /// What touches on shape 1.
    pub(crate) fid1: PackedFeatureId,
    /// What touches on shape 2.
    pub(crate) fid2: PackedFeatureId,
    /// Signed distance along the normal (m): negative when overlapping.
    pub(crate) dist: f32,
}

impl ShapePoint {
    /// A placeholder for unused slots.
    const UNUSED: Self = Self {
        local_p1: Vec3::ZERO,
        local_p2: Vec3::ZERO,
        fid1: PackedFeatureId::UNKNOWN,
        fid2: PackedFeatureId::UNKNOWN,
        dist: 0.0,
    };
}

/// The points of a [`ShapeManifold`], without allocation (at most [`MAX_SHAPE_POINTS`]; a push beyond is dropped).
#[derive(Clone, Copy, Debug)]
pub(crate) struct ShapePoints {
    points: [ShapePoint; MAX_SHAPE_POINTS],
    len: usize,
}

impl Default for ShapePoints {
    fn default() -> Self {
        Self {
            points: [ShapePoint::UNUSED; MAX_SHAPE_POINTS],
            len: 0,
        }
    }
}

impl ShapePoints {
    /// Appends a point (dropped if full: no generator makes more than [`MAX_SHAPE_POINTS`]).
    pub(crate) fn push(&mut self, point: ShapePoint) {
        if let Some(slot) = self.points.get_mut(self.len) {
            *slot = point;
            self.len += 1;
        }
    }

    /// Forgets every point.
    pub(crate) fn clear(&mut self) {
        self.len = 0;
    }
}

impl<'a> IntoIterator for &'a ShapePoints {
    type Item = &'a ShapePoint;
    type IntoIter = core::slice::Iter<'a, ShapePoint>;

    fn into_iter(self) -> Self::IntoIter {
        self.iter()
    }
}

impl core::ops::Deref for ShapePoints {
    type Target = [ShapePoint];

    fn deref(&self) -> &[ShapePoint] {
        &self.points[..self.len]
    }
}

/// The contact of two convex shapes in their own frames, as our generators write it for the narrow phase's
/// seam: the fields of parry's `ContactManifold` a convex pair uses, on the stack instead of a heap buffer.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct ShapeManifold {
    /// The normal, from shape 1 towards shape 2, in shape 1's frame.
    pub(crate) local_n1: Vec3,
    /// The same normal in shape 2's frame, pointing back towards shape 1.
    pub(crate) local_n2: Vec3,
    /// The points (none: no contact).
    pub(crate) points: ShapePoints,
}
