//! The contact of two balls, the narrow phase's commonest pair, written out so that it skips parry's dispatch
//! and its heap-backed manifold.

use crate::shape_manifold::{ShapeManifold, ShapePoint};
use parry3d::shape::PackedFeatureId;
use rebound_math::{Vec3, rotate_inverse};

/// The contact of two balls of radii `r1` and `r2` (m), ball 2 at `pos12` in ball 1's frame, for gaps up to
/// `prediction` (m): one point on each ball along the line of centres (the normal is +y for coincident
/// centres). The formulas of parry's `contact_manifold_ball_ball`, into a [`ShapeManifold`].
///
/// Always inlined: the narrow phase's pair loop (one copy with hooks, one without) calls it for every pair
/// of balls, and a call would cost about as much as the contact itself.
#[inline(always)]
pub(crate) fn ball_ball(
    pos12: &parry3d::math::Pose,
    r1: f32,
    r2: f32,
    prediction: f32,
    out: &mut ShapeManifold,
) {
    out.points.clear();
    let center = pos12.translation;
    let center_distance = center.length();
    let dist = center_distance - r1 - r2;
    // Written as parry's `dist < prediction`, so that a NaN distance is no contact.
    let within = dist < prediction;
    if !within {
        return;
    }
    let local_n1 = if center_distance != 0.0 {
        center / center_distance
    } else {
        Vec3::Y
    };
    let local_n2 = rotate_inverse(pos12.rotation, -local_n1);
    out.local_n1 = local_n1;
    out.local_n2 = local_n2;
    let face = PackedFeatureId::face(0);
    out.points.push(ShapePoint {
        local_p1: local_n1 * r1,
        local_p2: local_n2 * r2,
        fid1: face,
        fid2: face,
        dist,
    });
}
