//! The contact manifold of two boxes (cuboid–cuboid), written for the narrow phase's most frequent pair.
//!
//! # Why not parry's
//!
//! parry's cuboid–cuboid manifold is general polyhedral machinery (support features, 2D line clipping, a
//! separating-edge search in both directions), the largest cost of the pyramid scene's collide phase. This
//! is the classic box test specialised to two boxes (Gottschalk's OBB separating-axis test, then the
//! reference/incident face clipping of Box2D's polygon manifold and of ODE's `dBoxBox`), about four times
//! cheaper, and it depends on the current poses only (no history), as the narrow phase requires.
//!
//! # How
//!
//! Everything runs in box A's frame, with B's axes `b_j` (the columns of `R`) and centre `t` in it.
//!
//! 1. **Separating axes** (15): the face normals of A and of B and the 9 cross products `a_i × b_j`. On an
//!    axis `n` the boxes are `s = |t·n| − Σ h_A,k·|a_k·n| − Σ h_B,k·|b_k·n|` apart (negative: overlapping by
//!    `−s`). If any axis separates them by more than the prediction distance there is no contact; otherwise
//!    the axis of largest `s` is the contact normal (oriented from A to B). Faces win near-ties: B's face
//!    is taken over A's only if it separates by [`FACE_TOLERANCE`] more, an edge pair over the faces only if
//!    by [`EDGE_TOLERANCE`] more — so a resting box keeps one reference face from step to step and its
//!    contact points keep their feature ids (warm starting).
//! 2. **Face contact**: the face of the winning axis is the *reference* face; the face of the other box most
//!    anti-parallel to the normal is the *incident* face. The incident quad is clipped against the four side
//!    planes of the reference face (Sutherland–Hodgman); every clipped vertex within the prediction distance
//!    of the reference plane is a contact point: on the incident box, the vertex; on the reference box, its
//!    projection onto the reference face; separation, its signed distance to the reference plane. Up to 8
//!    points, reduced to 4 by the seam.
//! 3. **Edge contact**: the closest points of the two edges (one per box) that are extreme along the
//!    normal: one point.
//!
//! Feature ids name what touches on each box, in each box's own numbering (vertices 0..8, edges 0..12,
//! faces 0..6): an incident vertex on the reference face; an incident edge on a reference edge (a cut of the
//! incident quad by a side plane); a reference corner on the incident face (a cut of a cut); two crossing
//! edges. The same touching features give the same ids step after step, whichever box is the reference —
//! warm starting matches points by them.
//!
//! Its cost beside parry's is in `docs/performance.md` ("Box–box contacts"). Which face is the reference and
//! the order of the points matter to a tall column of equal boxes (solved point after point): flipping the reference on
//! rounding-level ties tilted the pyramid out of its plane, hence [`FACE_TOLERANCE`]; the points stay in polygon order.

use crate::shape_manifold::{ShapeManifold, ShapePoint};
use parry3d::shape::PackedFeatureId;
use rebound_math::{Mat3, Quat, Vec3};

/// How much more (m) B's best face must separate the boxes than A's to be the reference face: 0.5 mm, a tenth
/// of a typical linear slop, so that equal faces (a box on a box of the same size) do not trade places.
const FACE_TOLERANCE: f32 = 5.0e-4;

/// How much more (m) an edge pair must separate the boxes than the best face to be taken: 1 mm. Face contacts
/// (up to four points) hold a resting box; an edge pair (one point) only wins where edges really cross.
const EDGE_TOLERANCE: f32 = 1.0e-3;

/// Edge pairs whose cross product is shorter than this (the sine of the angle between the edges) are
/// parallel: their axis is a face axis already tested, and normalising it would amplify rounding.
const PARALLEL_SINE: f32 = 1.0e-3;

/// Most vertices a quad can have after clipping against four planes.
const MAX_CLIPPED: usize = 8;

/// What the polygon edge leaving a vertex runs along: an incident edge (its id, 0..12), or the side plane
/// `sign·x_k ≤ h_k` of the reference face where the polygon was cut (`REFERENCE_PLANE + 2·k + (sign < 0)`).
type Carrier = u32;

/// The first [`Carrier`] code of a reference side plane.
const REFERENCE_PLANE: Carrier = 16;

/// A vertex of the incident polygon while it is clipped: its position (reference frame, m), the features that
/// touch there (reference box's, incident box's) and what the polygon edge leaving it runs along.
#[derive(Clone, Copy, Debug)]
struct ClipVertex {
    point: Vec3,
    features: [PackedFeatureId; 2],
    edge: Carrier,
}

/// The polygon being clipped, without allocation.
#[derive(Clone, Copy)]
struct Polygon {
    vertices: [ClipVertex; MAX_CLIPPED],
    len: usize,
}

impl Polygon {
    const EMPTY: Self = Self {
        vertices: [ClipVertex {
            point: Vec3::ZERO,
            features: [PackedFeatureId::UNKNOWN; 2],
            edge: 0,
        }; MAX_CLIPPED],
        len: 0,
    };

    fn push(&mut self, v: ClipVertex) {
        if let Some(slot) = self.vertices.get_mut(self.len) {
            *slot = v;
            self.len += 1;
        }
    }

    fn as_slice(&self) -> &[ClipVertex] {
        &self.vertices[..self.len]
    }
}

/// One box of a face contact, seen from the reference box's frame.
struct Incident {
    /// Half extents (m).
    half: Vec3,
    /// Its axes in the reference frame (columns).
    axes: Mat3,
    /// Its centre in the reference frame (m).
    center: Vec3,
}

/// Fills `out` (already emptied) with the contact manifold of box 1 (half extents `half1`, m) and box 2
/// (`half2`) at relative pose (`rotation`, `translation`) — box 2's pose in box 1's frame — for points up to
/// `prediction` (m) apart: `local_n1`/`local_n2` the normal (from 1 to 2) in each box's frame, points in each
/// box's frame with their signed distances, as parry's generators fill it. No contact leaves it empty.
pub(crate) fn box_box_manifold(
    half1: Vec3,
    half2: Vec3,
    rotation: Quat,
    translation: Vec3,
    prediction: f32,
    out: &mut ShapeManifold,
) {
    let r = Mat3::from_quat(rotation);
    let t = translation;
    // |R| with a tiny floor, so that nearly parallel axes do not let rounding report a false separation
    // (Gottschalk, "OBBTree", 1996).
    let abs_r = Mat3::from_cols(
        r.x_axis.abs() + Vec3::splat(1.0e-6),
        r.y_axis.abs() + Vec3::splat(1.0e-6),
        r.z_axis.abs() + Vec3::splat(1.0e-6),
    );
    // 1. Face axes of A: s = |t_i| − h1_i − Σ_j h2_j·|R_ij|.
    let mut face1 = (f32::NEG_INFINITY, 0);
    for i in 0..3 {
        let reach2 = half2.dot(abs_r.row(i));
        let s = t[i].abs() - half1[i] - reach2;
        if s > prediction {
            return;
        }
        if s > face1.0 {
            face1 = (s, i);
        }
    }
    // Face axes of B: s = |t·b_j| − h2_j − Σ_i h1_i·|R_ij|.
    let mut face2 = (f32::NEG_INFINITY, 0);
    for j in 0..3 {
        let axis = r.col(j);
        let reach1 = half1.dot(abs_r.col(j));
        let s = t.dot(axis).abs() - half2[j] - reach1;
        if s > prediction {
            return;
        }
        if s > face2.0 {
            face2 = (s, j);
        }
    }
    // Edge pairs L = a_i × b_j. With (i, i1, i2) and (j, j1, j2) cyclic, L = (0, −R_i2j, R_i1j) on A's axes
    // (i, i1, i2), |L| = √(R_i1j² + R_i2j²), and the reaches follow from b_k·(a_i × b_j) = a_i·(b_j × b_k):
    // t·L = t_i2·R_i1j − t_i1·R_i2j, A's reach h1_i1·|R_i2j| + h1_i2·|R_i1j|, B's h2_j1·|R_ij2| + h2_j2·|R_ij1|.
    let m = r.to_cols_array_2d(); // m[j][i] = R_ij
    let a = abs_r.to_cols_array_2d();
    let mut edge = (f32::NEG_INFINITY, 0, 0, 0.0);
    for i in 0..3 {
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        for j in 0..3 {
            let (j1, j2) = ((j + 1) % 3, (j + 2) % 3);
            let length_squared = m[j][i1] * m[j][i1] + m[j][i2] * m[j][i2];
            if length_squared < PARALLEL_SINE * PARALLEL_SINE {
                continue;
            }
            let distance = (t[i2] * m[j][i1] - t[i1] * m[j][i2]).abs();
            let reach1 = half1[i1] * a[j][i2] + half1[i2] * a[j][i1];
            let reach2 = half2[j1] * a[j2][i] + half2[j2] * a[j1][i];
            let length = length_squared.sqrt();
            let s = (distance - reach1 - reach2) / length;
            if s > prediction {
                return;
            }
            if s > edge.0 {
                edge = (s, i, j, length);
            }
        }
    }
    let use_face2 = face2.0 > face1.0 + FACE_TOLERANCE;
    let face_separation = if use_face2 { face2.0 } else { face1.0 };
    if edge.0 > face_separation + EDGE_TOLERANCE {
        let (_, i, j, length) = edge;
        let (i1, i2) = ((i + 1) % 3, (i + 2) % 3);
        let mut axis = Vec3::ZERO;
        (axis[i1], axis[i2]) = (-m[j][i2] / length, m[j][i1] / length);
        let n = if t.dot(axis) < 0.0 { -axis } else { axis };
        edge_contact(half1, half2, &r, t, (i, j), n, prediction, out);
    } else if use_face2 {
        // B's face is the reference: A seen from B's frame.
        let rt = r.transpose();
        let incident = Incident {
            half: half1,
            axes: rt,
            center: -(rt * t),
        };
        let mut points =
            [(Vec3::ZERO, Vec3::ZERO, 0.0, [PackedFeatureId::UNKNOWN; 2]); MAX_CLIPPED];
        let (count, n2) = face_contact(half2, face2.1, &incident, prediction, &mut points);
        // Back into the manifold's convention: normal from 1 to 2, p1 on box 1 (in its frame), p2 on box 2.
        out.local_n2 = n2;
        out.local_n1 = -(r * n2);
        for &(on_reference, on_incident, separation, [on_b, on_a]) in &points[..count] {
            out.points.push(ShapePoint {
                local_p1: r * on_incident + t,
                local_p2: on_reference,
                fid1: on_a,
                fid2: on_b,
                dist: separation,
            });
        }
    } else {
        let incident = Incident {
            half: half2,
            axes: r,
            center: t,
        };
        let mut points =
            [(Vec3::ZERO, Vec3::ZERO, 0.0, [PackedFeatureId::UNKNOWN; 2]); MAX_CLIPPED];
        let (count, n1) = face_contact(half1, face1.1, &incident, prediction, &mut points);
        out.local_n1 = n1;
        out.local_n2 = -(r.transpose() * n1);
        let rt = r.transpose();
        for &(on_reference, on_incident, separation, [on_a, on_b]) in &points[..count] {
            out.points.push(ShapePoint {
                local_p1: on_reference,
                local_p2: rt * (on_incident - t),
                fid1: on_a,
                fid2: on_b,
                dist: separation,
            });
        }
    }
}

/// A contact point of a face contact, in the reference frame: on the reference face, on the incident box, the
/// separation (m), and the touching features (reference box's, incident box's).
type FacePoint = (Vec3, Vec3, f32, [PackedFeatureId; 2]);

/// The face contact with the reference box's face `axis` (0, 1, 2: x, y, z; the side facing the incident
/// box): writes its points into `points` and returns their count and the outward reference normal.
fn face_contact(
    half: Vec3,
    axis: usize,
    incident: &Incident,
    prediction: f32,
    points: &mut [FacePoint; MAX_CLIPPED],
) -> (usize, Vec3) {
    let side = if incident.center[axis] < 0.0 {
        -1.0
    } else {
        1.0
    };
    let normal = Vec3::AXES[axis] * side;
    // The incident face: the incident box's face most anti-parallel to the normal.
    let mut best = (f32::NEG_INFINITY, 0);
    for j in 0..3 {
        let d = normal.dot(incident.axes.col(j)).abs();
        if d > best.0 {
            best = (d, j);
        }
    }
    let j = best.1;
    let along = incident.axes.col(j);
    let facing = if normal.dot(along) > 0.0 { -1.0 } else { 1.0 };
    let face_center = incident.center + along * (facing * incident.half[j]);
    let (u, v) = ((j + 1) % 3, (j + 2) % 3);
    let du = incident.axes.col(u) * incident.half[u];
    let dv = incident.axes.col(v) * incident.half[v];
    let mut polygon = Polygon::EMPTY;
    // The quad's corners in order; the edge leaving corner k runs along u for k = 0, 2 and along v for 1, 3.
    let corners = [(1.0, 1.0), (-1.0, 1.0), (-1.0, -1.0), (1.0, -1.0)];
    let reference_face = face_feature(face_id(axis, side));
    for (k, &(su, sv)) in corners.iter().enumerate() {
        let mut signs = [0.0; 3];
        (signs[j], signs[u], signs[v]) = (facing, su, sv);
        let leaving = if k % 2 == 0 { u } else { v };
        polygon.push(ClipVertex {
            point: face_center + du * su + dv * sv,
            features: [reference_face, vertex_feature(vertex_id(signs))],
            edge: edge_id(leaving, signs),
        });
    }
    // Clip against the reference face's four side planes sign·x_k ≤ h_k, k ≠ axis; each is the plane through
    // one edge of the reference face. A plane every vertex is inside of (a box on a larger box) is skipped.
    let incident_face = face_id(j, facing);
    let mut spare = Polygon::EMPTY;
    for k in [(axis + 1) % 3, (axis + 2) % 3] {
        for sign in [1.0, -1.0] {
            let limit = half[k];
            if polygon
                .as_slice()
                .iter()
                .all(|v| sign * v.point[k] <= limit)
            {
                continue;
            }
            let mut signs = [0.0; 3];
            (signs[axis], signs[k]) = (side, sign);
            let plane = Plane {
                k,
                sign,
                limit,
                signs,
                edge: edge_id(3 - axis - k, signs),
            };
            clip(&polygon, &plane, incident_face, &mut spare);
            core::mem::swap(&mut polygon, &mut spare);
        }
    }
    let mut count = 0;
    for vertex in polygon.as_slice() {
        let separation = vertex.point[axis] * side - half[axis];
        if separation > prediction {
            continue;
        }
        let on_reference = vertex.point - normal * separation;
        points[count] = (on_reference, vertex.point, separation, vertex.features);
        count += 1;
    }
    (count, normal)
}

/// A side plane of the reference face, `sign·x_k ≤ limit`, through the reference edge `edge` whose signs on
/// the reference box's axes are `signs` (0 on the edge's own axis).
struct Plane {
    k: usize,
    sign: f32,
    limit: f32,
    signs: [f32; 3],
    edge: u32,
}

/// Sutherland–Hodgman: the part of `polygon` inside `plane`, into `out`. A vertex made where an edge crosses
/// the plane touches the reference edge of the plane and the incident edge the polygon edge ran along — or,
/// if that polygon edge ran along an earlier plane, it is the reference face's corner where the two planes
/// meet, touching the incident face (`incident_face`). So a point's features name what touches, whichever
/// box is the reference and however the polygon was cut.
fn clip(polygon: &Polygon, plane: &Plane, incident_face: u32, out: &mut Polygon) {
    out.len = 0;
    let vertices = polygon.as_slice();
    let Some(&last) = vertices.last() else {
        return;
    };
    let distance = |v: &ClipVertex| plane.sign * v.point[plane.k] - plane.limit;
    let cut = |from: &ClipVertex, to: &ClipVertex, d_from: f32, d_to: f32, edge: Carrier| {
        let s = d_from / (d_from - d_to);
        let features = if from.edge < REFERENCE_PLANE {
            [edge_feature(plane.edge), edge_feature(from.edge)]
        } else {
            let other = (from.edge - REFERENCE_PLANE) as usize;
            let mut signs = plane.signs;
            signs[other / 2] = if other.is_multiple_of(2) { 1.0 } else { -1.0 };
            [
                vertex_feature(vertex_id(signs)),
                face_feature(incident_face),
            ]
        };
        ClipVertex {
            point: from.point + (to.point - from.point) * s,
            features,
            edge,
        }
    };
    let along_plane = REFERENCE_PLANE + 2 * plane.k as u32 + u32::from(plane.sign < 0.0);
    let mut previous = last;
    let mut previous_distance = distance(&previous);
    for &current in vertices {
        let current_distance = distance(&current);
        match (previous_distance <= 0.0, current_distance <= 0.0) {
            (true, true) => out.push(current),
            // Leaving: the new vertex's outgoing edge runs along the plane.
            (true, false) => out.push(cut(
                &previous,
                &current,
                previous_distance,
                current_distance,
                along_plane,
            )),
            // Entering: the new vertex's outgoing edge is the rest of the crossing edge.
            (false, true) => {
                out.push(cut(
                    &previous,
                    &current,
                    previous_distance,
                    current_distance,
                    previous.edge,
                ));
                out.push(current);
            }
            (false, false) => {}
        }
        previous = current;
        previous_distance = current_distance;
    }
}

/// A feature id of parry's layout (kind in the top two bits, our code below), built directly: our codes are
/// below 16, so parry's constructors' range check (an assert that stays out of line, on the hot path of
/// every box pair) has nothing to check.
const fn feature(kind: u32, code: u32) -> PackedFeatureId {
    PackedFeatureId(kind << 30 | code)
}

/// A vertex as a feature id.
const fn vertex_feature(code: u32) -> PackedFeatureId {
    feature(0b01, code)
}

/// An edge as a feature id.
const fn edge_feature(code: u32) -> PackedFeatureId {
    feature(0b10, code)
}

/// A face as a feature id.
const fn face_feature(code: u32) -> PackedFeatureId {
    feature(0b11, code)
}

/// A cuboid's face on `axis` (0, 1, 2) on the side `sign`: ids 0..6.
fn face_id(axis: usize, sign: f32) -> u32 {
    2 * axis as u32 + u32::from(sign < 0.0)
}

/// A cuboid's vertex with the given signs on its three axes: ids 0..8.
fn vertex_id(signs: [f32; 3]) -> u32 {
    u32::from(signs[0] > 0.0) | u32::from(signs[1] > 0.0) << 1 | u32::from(signs[2] > 0.0) << 2
}

/// A cuboid's edge along `axis` with the given signs on the two other axes: ids 0..12 (the same numbering as
/// the edge contact's).
fn edge_id(axis: usize, signs: [f32; 3]) -> u32 {
    let (k1, k2) = ((axis + 1) % 3, (axis + 2) % 3);
    axis as u32 * 4 + 2 * u32::from(signs[k1] > 0.0) + u32::from(signs[k2] > 0.0)
}

/// The edge contact on axis `n` (A's frame, from A to B) of A's edges along `a_i` and B's along `b_j`: the
/// closest points of the two edges that are extreme along `n`.
#[allow(
    clippy::too_many_arguments,
    reason = "one call site; the SAT result passed through"
)]
fn edge_contact(
    half1: Vec3,
    half2: Vec3,
    r: &Mat3,
    t: Vec3,
    (i, j): (usize, usize),
    n: Vec3,
    prediction: f32,
    out: &mut ShapeManifold,
) {
    // A's edge farthest along n: its centre takes the sign of n on the two other axes.
    let mut center1 = Vec3::ZERO;
    let mut signs1 = [0.0; 3];
    for k in [(i + 1) % 3, (i + 2) % 3] {
        signs1[k] = if n[k] >= 0.0 { 1.0 } else { -1.0 };
        center1[k] = signs1[k] * half1[k];
    }
    // B's edge farthest against n.
    let mut center2 = t;
    let mut signs2 = [0.0; 3];
    for k in [(j + 1) % 3, (j + 2) % 3] {
        let axis = r.col(k);
        signs2[k] = if axis.dot(n) < 0.0 { 1.0 } else { -1.0 };
        center2 += axis * (signs2[k] * half2[k]);
    }
    let (d1, d2) = (Vec3::AXES[i], r.col(j));
    // Closest points of the lines c1 + s·d1 and c2 + u·d2 (unit directions), clamped to the edges.
    let w = center1 - center2;
    let b = d1.dot(d2);
    let (d, e) = (d1.dot(w), d2.dot(w));
    let denominator = 1.0 - b * b;
    let s = if denominator > 1.0e-12 {
        ((b * e - d) / denominator).clamp(-half1[i], half1[i])
    } else {
        0.0
    };
    let u = (e + b * s).clamp(-half2[j], half2[j]);
    let s = (b * u - d).clamp(-half1[i], half1[i]);
    let p1 = center1 + d1 * s;
    let p2 = center2 + d2 * u;
    let separation = (p2 - p1).dot(n);
    if separation > prediction {
        return;
    }
    out.local_n1 = n;
    out.local_n2 = -(r.transpose() * n);
    out.points.push(ShapePoint {
        local_p1: p1,
        local_p2: r.transpose() * (p2 - t),
        fid1: edge_feature(edge_id(i, signs1)),
        fid2: edge_feature(edge_id(j, signs2)),
        dist: separation,
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use parry3d::query::{
        ContactManifold as ParryManifold, DefaultQueryDispatcher, PersistentQueryDispatcher,
    };
    use parry3d::shape::Cuboid;
    use proptest::prelude::*;

    fn manifold(
        half1: Vec3,
        half2: Vec3,
        rotation: Quat,
        translation: Vec3,
        prediction: f32,
    ) -> ShapeManifold {
        let mut out = ShapeManifold::default();
        box_box_manifold(half1, half2, rotation, translation, prediction, &mut out);
        out
    }

    /// Whether `p` lies on the surface of the box of half extents `half` (within `tol`).
    fn on_surface(p: Vec3, half: Vec3, tol: f32) -> bool {
        let inside = (0..3).all(|k| p[k].abs() <= half[k] + tol);
        let on_face = (0..3).any(|k| (p[k].abs() - half[k]).abs() <= tol);
        inside && on_face
    }

    #[test]
    fn a_box_resting_on_a_larger_box_touches_at_its_four_bottom_corners() {
        // B (half 0.5) sunk 1 cm into A's top face (half height 0.5), turned 30° about y.
        let (half1, half2) = (Vec3::new(2.0, 0.5, 2.0), Vec3::splat(0.5));
        let rotation = Quat::from_rotation_y(30f32.to_radians());
        let m = manifold(half1, half2, rotation, Vec3::new(0.2, 0.99, 0.1), 0.02);
        assert_eq!(m.points.len(), 4);
        assert!((m.local_n1 - Vec3::Y).length() < 1e-6, "{:?}", m.local_n1);
        for p in &m.points {
            assert!((p.dist + 0.01).abs() < 1e-5, "{}", p.dist);
            assert!((p.local_p1.y - 0.5).abs() < 1e-5, "{:?}", p.local_p1);
            // B's bottom corners, in B's frame.
            assert!(
                (p.local_p2.abs() - Vec3::splat(0.5)).length() < 1e-5,
                "{:?}",
                p.local_p2
            );
            assert!(p.local_p2.y < 0.0);
        }
    }

    #[test]
    fn boxes_apart_give_speculative_points_within_the_prediction_and_none_beyond() {
        let half = Vec3::splat(0.5);
        let m = manifold(half, half, Quat::IDENTITY, Vec3::new(0.3, 1.05, 0.0), 0.1);
        assert_eq!(m.points.len(), 4);
        for p in &m.points {
            assert!((p.dist - 0.05).abs() < 1e-6, "{}", p.dist);
        }
        let far = manifold(half, half, Quat::IDENTITY, Vec3::new(0.3, 1.2, 0.0), 0.1);
        assert!(far.points.is_empty());
    }

    #[test]
    fn crossed_edges_touch_at_one_point() {
        // A's top is an edge along x (A turned 45° about x); B's bottom an edge along z (B turned 45° about
        // z); B 1 cm lower than touching. In A's frame.
        let reach = 0.5 * 2f32.sqrt();
        let turn_a = Quat::from_rotation_x(45f32.to_radians());
        let turn_b = Quat::from_rotation_z(45f32.to_radians());
        let rotation = turn_a.inverse() * turn_b;
        let translation = turn_a.inverse() * Vec3::new(0.0, 2.0 * reach - 0.01, 0.0);
        let half = Vec3::splat(0.5);
        let m = manifold(half, half, rotation, translation, 0.02);
        assert_eq!(m.points.len(), 1);
        let n = turn_a * m.local_n1;
        assert!((n - Vec3::Y).length() < 1e-5, "{n:?}");
        let p = &m.points[0];
        assert!((p.dist + 0.01).abs() < 1e-5, "{}", p.dist);
        assert!((turn_a * p.local_p1 - Vec3::new(0.0, reach, 0.0)).length() < 1e-5);
    }

    #[test]
    fn the_same_contact_keeps_its_feature_ids_when_the_boxes_move_a_little() {
        let half = Vec3::splat(0.5);
        let ids = |dx: f32, angle: f32| {
            let m = manifold(
                half,
                half,
                Quat::from_rotation_y(angle),
                Vec3::new(0.3 + dx, 0.995, 0.2),
                0.02,
            );
            let mut ids: Vec<_> = m.points.iter().map(|p| (p.fid1, p.fid2)).collect();
            ids.sort_by_key(|&(a, b)| (a.0, b.0));
            ids
        };
        // B overhangs A's top face on two sides: two of the four points are cuts of B's edges by A's side
        // planes, which must keep their ids too.
        let before = ids(0.0, 0.1);
        assert_eq!(before.len(), 4, "{before:?}");
        assert_eq!(
            before
                .iter()
                .filter(|(a, b)| a.is_edge() && b.is_edge())
                .count(),
            2
        );
        assert_eq!(before, ids(0.002, 0.101));
        // Distinct ids for distinct points.
        let mut unique = before.clone();
        unique.dedup();
        assert_eq!(unique.len(), before.len());
    }

    #[test]
    fn feature_ids_have_parrys_layout() {
        for code in 0..16 {
            assert_eq!(vertex_feature(code), PackedFeatureId::vertex(code));
            assert_eq!(edge_feature(code), PackedFeatureId::edge(code));
            assert_eq!(face_feature(code), PackedFeatureId::face(code));
        }
    }

    #[test]
    fn feature_ids_do_not_depend_on_which_box_is_the_reference() {
        // Two equal boxes, the upper one shifted and turned a little: seen from either box, the contact patch
        // is the same four corners with the same touching features (fid1 always on the first box).
        let half = Vec3::splat(0.5);
        let rotation = Quat::from_rotation_y(0.05);
        let translation = Vec3::new(0.3, 0.995, 0.2);
        let ids = |m: &ShapeManifold, swap: bool| {
            let mut ids: Vec<_> = m
                .points
                .iter()
                .map(|p| {
                    if swap {
                        (p.fid2.0, p.fid1.0)
                    } else {
                        (p.fid1.0, p.fid2.0)
                    }
                })
                .collect();
            ids.sort_unstable();
            ids
        };
        let from_a = manifold(half, half, rotation, translation, 0.02);
        let from_b = manifold(
            half,
            half,
            rotation.inverse(),
            -(rotation.inverse() * translation),
            0.02,
        );
        assert_eq!(from_a.points.len(), 4);
        assert_eq!(ids(&from_a, false), ids(&from_b, true));
    }

    proptest! {
        /// Against parry's generator on random overlapping and nearly touching boxes: the same deepest
        /// separation (the minimum-overlap axis is unique up to the face preference), every point on both
        /// boxes' surfaces and `p₂ − p₁` along the normal by its separation.
        #[test]
        fn agrees_with_parry_and_puts_points_on_both_surfaces(
            h1 in (0.1f32..2.0, 0.1f32..2.0, 0.1f32..2.0),
            h2 in (0.1f32..2.0, 0.1f32..2.0, 0.1f32..2.0),
            axis in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
            angle in -3.1f32..3.1,
            direction in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
            reach in 0.0f32..1.2,
        ) {
            let (half1, half2) = (Vec3::new(h1.0, h1.1, h1.2), Vec3::new(h2.0, h2.1, h2.2));
            let axis = Vec3::new(axis.0, axis.1, axis.2);
            let direction = Vec3::new(direction.0, direction.1, direction.2);
            prop_assume!(axis.length() > 0.1 && direction.length() > 0.1);
            let rotation = Quat::from_axis_angle(axis.normalize(), angle);
            let translation = direction.normalize() * reach * (half1 + half2).length();
            let prediction = 0.05;
            let ours = manifold(half1, half2, rotation, translation, prediction);
            let mut theirs = ParryManifold::<(), ()>::new();
            let pos12 = parry3d::math::Pose::from_parts(translation, rotation);
            DefaultQueryDispatcher
                .contact_manifold_convex_convex(
                    &pos12,
                    &Cuboid::new(half1),
                    &Cuboid::new(half2),
                    None,
                    None,
                    prediction,
                    &mut theirs,
                )
                .map_err(|e| TestCaseError::fail(format!("{e:?}")))?;
            let (a, b) = (
                ours.points.iter().map(|p| p.dist).fold(f32::INFINITY, f32::min),
                theirs.points.iter().map(|p| p.dist).fold(f32::INFINITY, f32::min),
            );
            if a.is_finite() && b.is_finite() {
                if b < 0.0 {
                    // Overlapping: the same depth (the minimum-overlap axis), up to the face/edge preference.
                    prop_assert!((a - b).abs() <= 2.0 * EDGE_TOLERANCE, "ours {a}, parry {b}");
                } else {
                    // Apart: a separating axis's gap is a lower bound of the distance, and the two
                    // generators may pick different axes; ours must not report a larger gap (a speculative
                    // contact that lets the boxes close more than they may).
                    prop_assert!(a <= b + 2.0 * EDGE_TOLERANCE, "ours {a}, parry {b}");
                }
            }
            // A clear overlap is never missed.
            if b < -0.01 {
                prop_assert!(a.is_finite(), "parry {b}, ours none");
            }
            let n = ours.local_n1;
            if !ours.points.is_empty() {
                prop_assert!((n.length() - 1.0).abs() < 1e-4);
                prop_assert!((rotation * ours.local_n2 + n).length() < 1e-4);
            }
            for p in &ours.points {
                prop_assert!(p.dist <= prediction + 1e-5);
                prop_assert!(on_surface(p.local_p1, half1, 1e-3), "{:?} on {half1:?}", p.local_p1);
                prop_assert!(on_surface(p.local_p2, half2, 1e-3), "{:?} on {half2:?}", p.local_p2);
                let gap = rotation * p.local_p2 + translation - p.local_p1;
                prop_assert!((gap.dot(n) - p.dist).abs() < 1e-4, "gap {gap:?}, n {n:?}, dist {}", p.dist);
                // Touching points face each other along the normal. (A speculative point of two edges
                // apart may be a corner's: then only its distance along the normal is the separation.)
                if p.dist <= 0.0 {
                    prop_assert!((gap - n * p.dist).length() < 1e-3, "gap {gap:?}, n {n:?}, dist {}", p.dist);
                }
            }
        }
    }
}
