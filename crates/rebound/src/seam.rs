//! **The seam**: where a manifold from parry or from our generators becomes the world's
//! [`ContactManifold`](rebound_world::ContactManifold).
//!
//! parry's points are in each shape's (or sub-shape's) local frame; the world wants them in each body's
//! frame relative to the body origin, with the normal in world space from A to B, at most
//! [`MAX_MANIFOLD_POINTS`] points, a 32-bit feature id per point and a 64-bit key that is stable for a
//! collider pair and sub-shape pair. [`Seam::push`] does that conversion, reducing a larger patch to the
//! points that keep it ([`reduce_points`]).

use crate::Collider;
use crate::shape_manifold::ShapePoint;
use parry3d::query::TrackedContact;
use parry3d::shape::PackedFeatureId;
use rebound_dynamics::{CombineRule, RigidBody};
use rebound_math::{Pose, Vec3, rotate};
use rebound_world::{MAX_MANIFOLD_POINTS, ManifoldPoint, ManifoldWriter};

/// Packs parry's two feature ids (2-bit kind + 30-bit index each) into one `u32`: the first rotated by 16
/// bits, xor the second. Exact (no two feature pairs collide) while both indices are below 2¹⁴ = 16384,
/// which covers every primitive and, per sub-shape manifold, every triangle; beyond that ids may collide,
/// which only costs a warm start.
fn pack_feature_id(fid1: PackedFeatureId, fid2: PackedFeatureId) -> u32 {
    fid1.0.rotate_left(16) ^ fid2.0
}

/// A contact point as a generator leaves it, in its shapes' own frames: parry's [`TrackedContact`] or our
/// [`ShapePoint`], read as a [`ShapePoint`].
pub(crate) trait SeamPoint {
    /// The point's geometry and features.
    fn shape_point(&self) -> ShapePoint;
}

impl SeamPoint for TrackedContact<()> {
    fn shape_point(&self) -> ShapePoint {
        ShapePoint {
            local_p1: self.local_p1,
            local_p2: self.local_p2,
            fid1: self.fid1,
            fid2: self.fid2,
            dist: self.dist,
        }
    }
}

impl SeamPoint for ShapePoint {
    fn shape_point(&self) -> ShapePoint {
        *self
    }
}

/// Whether a point is finite (defensive: the generators' points always are).
fn is_usable(point: &impl SeamPoint) -> bool {
    let p = point.shape_point();
    p.local_p1.is_finite() && p.local_p2.is_finite() && p.dist.is_finite()
}

/// **The seam**: where one manifold of the collider pair (`c1`, `c2`), from parry or from our generators,
/// becomes the world's [`ContactManifold`](rebound_world::ContactManifold).
///
/// - body A is `c1`'s body, body B is `c2`'s; the normal is the generator's `local_n1` (outward from shape 1,
///   towards shape 2) rotated into world space;
/// - anchors: `local_p1`/`local_p2` (in each shape's or sub-shape's frame) through `frames` (the sub-shape
///   pose, then the collider's local pose) into each body's frame, relative to the body origin;
/// - separation: the signed `dist` (negative when overlapping, positive for speculative points);
/// - feature ids: `fid1`/`fid2` packed into a `u32` ([`pack_feature_id`]);
/// - key: the collider pair's hash extended with the sub-shape ids, stable from step to step;
/// - material: friction, restitution and rolling friction combined with each collider's rules;
/// - more than [`MAX_MANIFOLD_POINTS`] points are reduced to the 4 that keep the deepest point and the
///   largest contact area ([`reduce_points`]).
pub(crate) struct Seam<'a> {
    /// Shape 1's collider (on body A).
    pub(crate) c1: &'a Collider,
    /// Body A.
    pub(crate) b1: &'a RigidBody,
    /// Shape 2's collider (on body B).
    pub(crate) c2: &'a Collider,
    /// The manifold's key.
    pub(crate) key: u64,
    /// Each shape's frame in its body's frame.
    pub(crate) frames: (Pose, Pose),
}

impl Seam<'_> {
    /// Pushes the manifold of normal `local_n1` and `points` onto `out`; nothing for a manifold without
    /// points (or, defensively, without a usable normal or finite points). The manifold is written in place.
    pub(crate) fn push<P: SeamPoint>(
        &self,
        local_n1: Vec3,
        points: &[P],
        out: &mut ManifoldWriter<'_>,
    ) {
        // Most candidate pairs of a pile are within the margin but not touching: nothing to convert.
        if points.is_empty() {
            return;
        }
        let (c1, c2) = (self.c1, self.c2);
        let (frame1, frame2) = self.frames;
        let Some(normal) =
            rotate(self.b1.rotation(), frame1.transform_vector(local_n1)).try_normalize()
        else {
            return;
        };
        let (chosen, count) = reduce_points(points);
        if count == 0 {
            return;
        }
        let (friction, restitution, rolling_friction) = self.materials();
        let manifold = out.begin(c1.body, c2.body, self.key, normal, friction, restitution);
        manifold.rolling_friction = rolling_friction;
        // A shape at its body's origin (the common case) needs no transform.
        let to_body = |frame: &Pose, p: Vec3| {
            if *frame == Pose::IDENTITY {
                p
            } else {
                frame.transform_point(p)
            }
        };
        for point in chosen[..count].iter().map(|&i| points[i].shape_point()) {
            manifold.push_point(ManifoldPoint {
                local_anchor_a: to_body(&frame1, point.local_p1),
                local_anchor_b: to_body(&frame2, point.local_p2),
                separation: point.dist,
                feature_id: pack_feature_id(point.fid1, point.fid2),
                ..ManifoldPoint::default()
            });
        }
    }
}

impl Seam<'_> {
    /// The pair's friction, restitution and rolling friction, each combined with the colliders' rules.
    pub(crate) fn materials(&self) -> (f32, f32, f32) {
        let (d1, d2) = (&self.c1.desc, &self.c2.desc);
        (
            CombineRule::combine(
                d1.friction,
                d1.friction_combine_rule,
                d2.friction,
                d2.friction_combine_rule,
            ),
            CombineRule::combine(
                d1.restitution,
                d1.restitution_combine_rule,
                d2.restitution,
                d2.restitution_combine_rule,
            ),
            CombineRule::combine(
                d1.rolling_friction,
                d1.friction_combine_rule,
                d2.rolling_friction,
                d2.friction_combine_rule,
            ),
        )
    }
}

/// Indices (and their count) of at most [`MAX_MANIFOLD_POINTS`] usable points that keep the contact patch:
/// all of them if they fit; otherwise the deepest point, the point farthest from it, the point farthest from
/// their line, then the point adding the most area to that triangle (Box2D's and Jolt's manifold reduction).
/// Ties go to the lower index, so the choice is deterministic. Points are compared in shape 1's frame. No
/// allocation.
fn reduce_points<P: SeamPoint>(points: &[P]) -> ([usize; MAX_MANIFOLD_POINTS], usize) {
    let mut chosen = [0; MAX_MANIFOLD_POINTS];
    let mut count = 0;
    let usable_count = points.iter().filter(|p| is_usable(*p)).count();
    if usable_count <= MAX_MANIFOLD_POINTS {
        for (i, _) in points.iter().enumerate().filter(|(_, p)| is_usable(*p)) {
            chosen[count] = i;
            count += 1;
        }
        return (chosen, count);
    }
    let p = |i: usize| points[i].shape_point().local_p1;
    // The usable, not yet chosen point with the highest score (the first one on ties).
    let argmax = |score: &dyn Fn(usize) -> f32, taken: &[usize]| {
        (0..points.len())
            .filter(|&i| is_usable(&points[i]) && !taken.contains(&i))
            .fold(None, |best: Option<(usize, f32)>, i| {
                let s = score(i);
                match best {
                    Some((_, b)) if s <= b => best,
                    _ => Some((i, s)),
                }
            })
            .map(|(i, _)| i)
    };
    let Some(deepest) = argmax(&|i| -points[i].shape_point().dist, &[]) else {
        return (chosen, 0);
    };
    chosen[0] = deepest;
    count = 1;
    let a = p(deepest);
    let Some(second) = argmax(&|i| p(i).distance_squared(a), &chosen[..count]) else {
        return (chosen, count);
    };
    chosen[1] = second;
    count = 2;
    let b = p(second);
    let Some(third) = argmax(
        &|i| (b - a).cross(p(i) - a).length_squared(),
        &chosen[..count],
    ) else {
        return (chosen, count);
    };
    chosen[2] = third;
    count = 3;
    let c = p(third);
    // Area a point adds outside the triangle: the sum of the three sub-triangle areas minus the triangle's
    // own (0 inside).
    let triangle = (b - a).cross(c - a).length();
    let added = |i: usize| {
        let q = p(i);
        (a - q).cross(b - q).length()
            + (b - q).cross(c - q).length()
            + (c - q).cross(a - q).length()
            - triangle
    };
    if let Some(fourth) = argmax(&added, &chosen[..count]) {
        chosen[3] = fourth;
        count = 4;
    }
    (chosen, count)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn contact(x: f32, z: f32, dist: f32) -> TrackedContact<()> {
        TrackedContact::new(
            Vec3::new(x, 0.0, z),
            Vec3::new(x, 0.0, z),
            PackedFeatureId::UNKNOWN,
            PackedFeatureId::UNKNOWN,
            dist,
        )
    }

    #[test]
    fn reduction_keeps_the_deepest_point_and_the_corners() {
        // A square's corners, its centre (deepest) and edge midpoints.
        let points = [
            contact(0.0, 0.0, -0.02),
            contact(-1.0, -1.0, -0.01),
            contact(1.0, -1.0, -0.01),
            contact(1.0, 1.0, -0.01),
            contact(-1.0, 1.0, -0.01),
            contact(0.0, 1.0, -0.01),
        ];
        let (chosen, count) = reduce_points(&points);
        assert_eq!(count, 4);
        assert_eq!(chosen[0], 0, "the deepest point comes first");
        // Then a corner, the opposite corner, and one of the remaining corners.
        assert!(
            chosen[1..].iter().all(|&i| (1..=4).contains(&i)),
            "{chosen:?}"
        );
    }

    #[test]
    fn feature_ids_pack_without_collisions_for_small_indices() {
        let mut seen = std::collections::BTreeSet::new();
        for f1 in [
            PackedFeatureId::vertex(3),
            PackedFeatureId::edge(3),
            PackedFeatureId::face(3),
            PackedFeatureId::face(16383),
        ] {
            for f2 in [
                PackedFeatureId::vertex(3),
                PackedFeatureId::edge(5),
                PackedFeatureId::face(3),
                PackedFeatureId::vertex(16383),
            ] {
                let point = TrackedContact::<()>::new(Vec3::ZERO, Vec3::ZERO, f1, f2, 0.0);
                assert!(seen.insert(pack_feature_id(point.fid1, point.fid2)));
            }
        }
    }
}
