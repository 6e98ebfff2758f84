//! Drawing a collider's shape ([`rebound::ColliderShape`], every kind) at a pose: outlines as segments,
//! surfaces as triangles, and the exact axis-aligned bounding box ([`shape_aabb`]).
//!
//! Outlines are what a wireframe debug view shows: a ball's three great circles; a capsule's, cylinder's or
//! cone's rims, four lines along it and (capsule) the caps' half circles; a box's 12 edges; a hull's edges
//! between faces that are not coplanar; every edge of a mesh; a height field's grid. Surfaces of the round
//! shapes are solids of revolution of their profile about the local y axis, with
//! [`crate::DebugSettings::circle_segments`] slices. Every triangle is counter-clockwise seen from outside.

use crate::draw::BOX_EDGES;
use crate::{Color, DebugDraw, Layer};
use rebound::{ColliderShape, Pose, Vec3};
use std::f32::consts::{FRAC_PI_2, PI, TAU};

/// The most segments a full circle is drawn with: bounds the work of any settings.
pub const MAX_CIRCLE_SEGMENTS: u32 = 1024;

/// The world-space axis-aligned bounding box `(min, max)` of `shape` placed at `pose`, in closed form per
/// kind (a ball `c ± r`; a box `c ± |R|·h`; a capsule its segment's box grown by `r`; a cylinder or cone
/// its rims' boxes, `r·√(1 − a_i²)` about the rim centre on axis `i`, for the unit axis `a`; a hull, mesh or height field its
/// points; a compound the union of its parts). `None` for a shape without points (an empty mesh or
/// compound).
#[must_use]
pub fn shape_aabb(shape: &ColliderShape, pose: Pose) -> Option<(Vec3, Vec3)> {
    let c = pose.position;
    let axis = pose.transform_vector(Vec3::Y);
    // Half-extent of a disc of radius r perpendicular to `axis`: r·√(1 − a_i²) on axis i, written
    // r·√(a_j² + a_k²) for the unit axis, since 1 − a_i² cancels to 0 in f32 when the axis is within
    // 1e-4 rad of axis i and the disc's 4e-5·r of reach past the rim would be lost.
    let disc = |r: f32| {
        Vec3::new(
            axis.y.hypot(axis.z),
            axis.x.hypot(axis.z),
            axis.x.hypot(axis.y),
        ) * r
    };
    let points = |ps: &mut dyn Iterator<Item = Vec3>| {
        ps.map(|p| pose.transform_point(p))
            .fold(None, |acc: Option<(Vec3, Vec3)>, p| {
                Some(acc.map_or((p, p), |(lo, hi)| (lo.min(p), hi.max(p))))
            })
    };
    match shape {
        ColliderShape::Ball { radius } => {
            Some((c - Vec3::splat(*radius), c + Vec3::splat(*radius)))
        }
        ColliderShape::Cuboid { half_extents } => {
            let m = rebound::Mat3::from_quat(pose.rotation);
            let half = m.x_axis.abs() * half_extents.x
                + m.y_axis.abs() * half_extents.y
                + m.z_axis.abs() * half_extents.z;
            Some((c - half, c + half))
        }
        ColliderShape::Capsule {
            radius,
            half_height,
        } => {
            let (p, q) = (c - axis * *half_height, c + axis * *half_height);
            Some((
                p.min(q) - Vec3::splat(*radius),
                p.max(q) + Vec3::splat(*radius),
            ))
        }
        ColliderShape::Cylinder {
            radius,
            half_height,
        } => {
            let (p, q) = (c - axis * *half_height, c + axis * *half_height);
            let e = disc(*radius);
            Some((p.min(q) - e, p.max(q) + e))
        }
        ColliderShape::Cone {
            radius,
            half_height,
        } => {
            let (base, apex) = (c - axis * *half_height, c + axis * *half_height);
            let e = disc(*radius);
            Some(((base - e).min(apex), (base + e).max(apex)))
        }
        ColliderShape::ConvexHull { points: ps } => points(&mut ps.iter().copied()),
        ColliderShape::TriMesh { vertices, .. } => points(&mut vertices.iter().copied()),
        ColliderShape::HeightField {
            rows,
            cols,
            heights,
            scale,
        } => points(&mut height_field_points(*rows, *cols, heights, *scale)),
        ColliderShape::Compound { parts } => parts
            .iter()
            .filter_map(|(part_pose, part)| shape_aabb(part, pose.mul_pose(part_pose)))
            .reduce(|(lo, hi), (l, h)| (lo.min(l), hi.max(h))),
        ColliderShape::HalfSpace { normal } => points(&mut half_space_square(*normal).into_iter()),
    }
}

/// The sample points of a height field (collider frame), row by row; only the samples `heights` holds.
fn height_field_points(
    rows: usize,
    cols: usize,
    heights: &[f32],
    scale: Vec3,
) -> impl Iterator<Item = Vec3> + '_ {
    let rows = sample_rows(rows, cols, heights);
    (0..rows).flat_map(move |row| {
        (0..cols).filter_map(move |col| height_field_point(rows, cols, heights, scale, row, col))
    })
}

/// The rows of a height field that `heights` holds completely (at most `rows`).
fn sample_rows(rows: usize, cols: usize, heights: &[f32]) -> usize {
    heights
        .len()
        .checked_div(cols)
        .map_or(0, |full| rows.min(full))
}

/// Sample `(row, col)` of a height field with `rows` rows (collider frame), if it exists.
fn height_field_point(
    rows: usize,
    cols: usize,
    heights: &[f32],
    scale: Vec3,
    row: usize,
    col: usize,
) -> Option<Vec3> {
    if row >= rows || col >= cols {
        return None;
    }
    let h = *heights.get(row.checked_mul(cols)?.checked_add(col)?)?;
    let fraction = |i: usize, n: usize| {
        if n > 1 {
            i as f32 / (n - 1) as f32 - 0.5
        } else {
            0.0
        }
    };
    Some(Vec3::new(
        fraction(col, cols) * scale.x,
        h * scale.y,
        fraction(row, rows) * scale.z,
    ))
}

/// A point on the circle of `radius` about `centre` in the plane of the unit vectors `u`, `v`, at angle
/// `angle` from `u` towards `v`.
fn on_circle(centre: Vec3, u: Vec3, v: Vec3, radius: f32, angle: f32) -> Vec3 {
    let (sin, cos) = angle.sin_cos();
    centre + (u * cos + v * sin) * radius
}

/// One segment of a shape's outline, mapped to the world.
struct Pen<'a> {
    draw: &'a mut DebugDraw,
    pose: Pose,
    color: Color,
}

impl Pen<'_> {
    fn line(&mut self, a: Vec3, b: Vec3) {
        let (a, b) = (self.pose.transform_point(a), self.pose.transform_point(b));
        self.draw.line(a, b, self.color, Layer::Shape);
    }

    /// An arc from `from` to `to` (rad) in `segments` pieces.
    fn arc(
        &mut self,
        centre: Vec3,
        u: Vec3,
        v: Vec3,
        radius: f32,
        from: f32,
        to: f32,
        segments: u32,
    ) {
        let step = (to - from) / segments as f32;
        for k in 0..segments {
            let a = on_circle(centre, u, v, radius, from + step * k as f32);
            // The last point is computed at exactly `to` (a full circle closes on its first point's angle).
            let end = if k + 1 == segments {
                to
            } else {
                from + step * (k + 1) as f32
            };
            let b = on_circle(centre, u, v, radius, end);
            self.line(a, b);
        }
    }

    fn circle(&mut self, centre: Vec3, u: Vec3, v: Vec3, radius: f32, segments: u32) {
        self.arc(centre, u, v, radius, 0.0, TAU, segments);
    }

    /// A triangle given in the collider frame, turned to face away from `inside` (a point inside the convex
    /// solid it bounds).
    fn facing_out(&mut self, [a, b, c]: [Vec3; 3], inside: Vec3) {
        let normal = (b - a).cross(c - a);
        if normal.length_squared() <= f32::MIN_POSITIVE {
            return;
        }
        let corners = if normal.dot((a + b + c) / 3.0 - inside) >= 0.0 {
            [a, b, c]
        } else {
            [a, c, b]
        };
        let corners = corners.map(|p| self.pose.transform_point(p));
        self.draw.triangle(corners, self.color, Layer::Shape);
    }

    /// A triangle given in the collider frame, as wound.
    fn triangle(&mut self, corners: [Vec3; 3]) {
        let corners = corners.map(|p| self.pose.transform_point(p));
        self.draw.triangle(corners, self.color, Layer::Shape);
    }

    /// The surface of revolution of `profile` (pairs of radius and height, from the bottom pole to the top)
    /// about the y axis, with `slices` slices; the origin must be inside.
    fn lathe(&mut self, profile: &[(f32, f32)], slices: u32) {
        let at = |(r, y): (f32, f32), j: u32| {
            let (sin, cos) = (TAU * j as f32 / slices as f32).sin_cos();
            Vec3::new(r * cos, y, r * sin)
        };
        for ring in profile.windows(2) {
            let (low, high) = (ring[0], ring[1]);
            for j in 0..slices {
                let next = (j + 1) % slices;
                let (p00, p01) = (at(low, j), at(low, next));
                let (p10, p11) = (at(high, j), at(high, next));
                self.facing_out([p00, p10, p11], Vec3::ZERO);
                self.facing_out([p00, p11, p01], Vec3::ZERO);
            }
        }
    }
}

/// The profile of a capsule (radius, height) from its bottom pole to its top, `quarter` steps per quarter
/// circle.
fn capsule_profile(radius: f32, half_height: f32, quarter: u32) -> Vec<(f32, f32)> {
    let step = FRAC_PI_2 / quarter as f32;
    // Angle φ from the bottom pole: (r·sin φ, −h − r·cos φ) on the lower cap, then the upper cap. The
    // poles are set exactly (sin π is not 0 in floating point), so the triangles meeting there are
    // exactly degenerate and left out.
    let ring = |phi: f32, centre: f32| (radius * phi.sin(), centre - radius * phi.cos());
    let bottom = (0..=quarter).map(|k| ring(step * k as f32, -half_height));
    let top = (0..=quarter).map(|k| ring(FRAC_PI_2 + step * k as f32, half_height));
    let mut profile: Vec<(f32, f32)> = bottom.chain(top).collect();
    if let Some(first) = profile.first_mut() {
        *first = (0.0, -half_height - radius);
    }
    if let Some(last) = profile.last_mut() {
        *last = (0.0, half_height + radius);
    }
    profile
}

/// The edges of a triangle list, each once: `(i, j)` with `i < j`, sorted.
fn unique_edges(triangles: &[[u32; 3]]) -> Vec<(u32, u32)> {
    let mut edges: Vec<(u32, u32)> = triangles
        .iter()
        .flat_map(|&[a, b, c]| [(a, b), (b, c), (c, a)])
        .map(|(a, b)| (a.min(b), a.max(b)))
        .collect();
    edges.sort_unstable();
    edges.dedup();
    edges
}

/// The edges of a closed convex mesh where the two faces meeting there are not coplanar (a hull's quad face
/// comes as two triangles; the diagonal between them is no edge of the solid).
fn feature_edges(vertices: &[Vec3], triangles: &[[u32; 3]]) -> Vec<(u32, u32)> {
    let normal = |&[a, b, c]: &[u32; 3]| -> Option<Vec3> {
        let p = |i: u32| vertices.get(i as usize).copied();
        let (a, b, c) = (p(a)?, p(b)?, p(c)?);
        Some((b - a).cross(c - a).normalize_or_zero())
    };
    let mut half: Vec<((u32, u32), Vec3)> = triangles
        .iter()
        .flat_map(|t| {
            let n = normal(t).unwrap_or(Vec3::ZERO);
            let [a, b, c] = *t;
            [(a, b), (b, c), (c, a)].map(|(i, j)| ((i.min(j), i.max(j)), n))
        })
        .collect();
    half.sort_unstable_by_key(|(edge, _)| *edge);
    let mut edges = Vec::new();
    for group in half.chunk_by(|x, y| x.0 == y.0) {
        let coplanar = group.len() == 2 && group[0].1.dot(group[1].1) > 1.0 - 1e-4;
        if !coplanar {
            edges.push(group[0].0);
        }
    }
    edges
}

impl DebugDraw {
    /// Draws `shape` at the world pose `pose` (the body pose times the collider's local pose) in `color`:
    /// the outline with `outlines`, the surface with `solids`, `segments` per full circle (3 to
    /// [`MAX_CIRCLE_SEGMENTS`]).
    pub fn shape(
        &mut self,
        shape: &ColliderShape,
        pose: Pose,
        color: Color,
        outlines: bool,
        solids: bool,
        segments: u32,
    ) {
        let segments = segments.clamp(3, MAX_CIRCLE_SEGMENTS);
        if outlines {
            self.shape_outline(shape, pose, color, segments);
        }
        if solids {
            self.shape_solid(shape, pose, color, segments);
        }
    }

    fn shape_outline(&mut self, shape: &ColliderShape, pose: Pose, color: Color, segments: u32) {
        let mut pen = Pen {
            draw: self,
            pose,
            color,
        };
        let (x, y, z) = (Vec3::X, Vec3::Y, Vec3::Z);
        match shape {
            ColliderShape::Ball { radius } => {
                pen.circle(Vec3::ZERO, x, y, *radius, segments);
                pen.circle(Vec3::ZERO, y, z, *radius, segments);
                pen.circle(Vec3::ZERO, z, x, *radius, segments);
            }
            ColliderShape::Cuboid { half_extents } => {
                let corner = |i: usize| {
                    let sign = |bit: usize| if i & bit == 0 { -1.0 } else { 1.0 };
                    *half_extents * Vec3::new(sign(1), sign(2), sign(4))
                };
                for (i, j) in BOX_EDGES {
                    pen.line(corner(i), corner(j));
                }
            }
            ColliderShape::Capsule {
                radius,
                half_height,
            } => {
                let (top, bottom) = (y * *half_height, -y * *half_height);
                pen.circle(top, z, x, *radius, segments);
                pen.circle(bottom, z, x, *radius, segments);
                let half = (segments / 2).max(2);
                for u in [x, z] {
                    pen.arc(top, u, y, *radius, 0.0, PI, half);
                    pen.arc(bottom, u, y, *radius, PI, TAU, half);
                    pen.line(bottom + u * *radius, top + u * *radius);
                    pen.line(bottom - u * *radius, top - u * *radius);
                }
            }
            ColliderShape::Cylinder {
                radius,
                half_height,
            } => {
                let (top, bottom) = (y * *half_height, -y * *half_height);
                pen.circle(top, z, x, *radius, segments);
                pen.circle(bottom, z, x, *radius, segments);
                for u in [x, z, -x, -z] {
                    pen.line(bottom + u * *radius, top + u * *radius);
                }
            }
            ColliderShape::Cone {
                radius,
                half_height,
            } => {
                let (apex, base) = (y * *half_height, -y * *half_height);
                pen.circle(base, z, x, *radius, segments);
                for u in [x, z, -x, -z] {
                    pen.line(base + u * *radius, apex);
                }
            }
            ColliderShape::ConvexHull { .. } => {
                if let Some((vertices, triangles)) = shape.convex_hull_mesh() {
                    for (i, j) in feature_edges(&vertices, &triangles) {
                        if let (Some(&a), Some(&b)) =
                            (vertices.get(i as usize), vertices.get(j as usize))
                        {
                            pen.line(a, b);
                        }
                    }
                }
            }
            ColliderShape::HalfSpace { normal } => {
                let corners = half_space_square(*normal);
                for (k, &corner) in corners.iter().enumerate() {
                    pen.line(corner, corners[(k + 1) % 4]);
                }
                let unit = normal.try_normalize().unwrap_or(Vec3::Y);
                pen.line(Vec3::ZERO, unit);
            }
            ColliderShape::TriMesh { vertices, indices } => {
                for (i, j) in unique_edges(indices) {
                    if let (Some(&a), Some(&b)) =
                        (vertices.get(i as usize), vertices.get(j as usize))
                    {
                        pen.line(a, b);
                    }
                }
            }
            ColliderShape::HeightField {
                rows,
                cols,
                heights,
                scale,
            } => {
                let rows = sample_rows(*rows, *cols, heights);
                let point = |r, c| height_field_point(rows, *cols, heights, *scale, r, c);
                for r in 0..rows {
                    for c in 0..*cols {
                        let here = point(r, c);
                        for next in [point(r, c + 1), point(r + 1, c)] {
                            if let (Some(a), Some(b)) = (here, next) {
                                pen.line(a, b);
                            }
                        }
                    }
                }
            }
            ColliderShape::Compound { parts } => {
                for (part_pose, part) in parts {
                    self.shape_outline(part, pose.mul_pose(part_pose), color, segments);
                }
            }
        }
    }

    fn shape_solid(&mut self, shape: &ColliderShape, pose: Pose, color: Color, segments: u32) {
        let mut pen = Pen {
            draw: self,
            pose,
            color,
        };
        let quarter = (segments / 4).max(1);
        match shape {
            ColliderShape::Ball { radius } => {
                pen.lathe(&capsule_profile(*radius, 0.0, quarter), segments);
            }
            ColliderShape::Capsule {
                radius,
                half_height,
            } => pen.lathe(&capsule_profile(*radius, *half_height, quarter), segments),
            ColliderShape::Cylinder {
                radius,
                half_height,
            } => {
                let (r, h) = (*radius, *half_height);
                pen.lathe(&[(0.0, -h), (r, -h), (r, h), (0.0, h)], segments);
            }
            ColliderShape::Cone {
                radius,
                half_height,
            } => {
                let (r, h) = (*radius, *half_height);
                pen.lathe(&[(0.0, -h), (r, -h), (0.0, h)], segments);
            }
            ColliderShape::Cuboid { half_extents } => {
                let corner = |i: usize| {
                    let sign = |bit: usize| if i & bit == 0 { -1.0 } else { 1.0 };
                    *half_extents * Vec3::new(sign(1), sign(2), sign(4))
                };
                // Each face as two triangles: the face's four corners differ in two bits.
                for (axis, others) in [(1, [2, 4]), (2, [1, 4]), (4, [1, 2])] {
                    for side in [0, axis] {
                        let [u, v] = others;
                        let quad = [side, side | u, side | u | v, side | v].map(corner);
                        pen.facing_out([quad[0], quad[1], quad[2]], Vec3::ZERO);
                        pen.facing_out([quad[0], quad[2], quad[3]], Vec3::ZERO);
                    }
                }
            }
            ColliderShape::ConvexHull { .. } => {
                if let Some((vertices, triangles)) = shape.convex_hull_mesh() {
                    let inside =
                        vertices.iter().copied().sum::<Vec3>() / vertices.len().max(1) as f32;
                    for t in &triangles {
                        if let Some(corners) = corners(&vertices, *t) {
                            pen.facing_out(corners, inside);
                        }
                    }
                }
            }
            ColliderShape::HalfSpace { normal } => {
                let [a, b, c, d] = half_space_square(*normal);
                pen.triangle([a, b, c]);
                pen.triangle([a, c, d]);
            }
            ColliderShape::TriMesh { vertices, indices } => {
                for t in indices {
                    if let Some(corners) = corners(vertices, *t) {
                        pen.triangle(corners);
                    }
                }
            }
            ColliderShape::HeightField {
                rows,
                cols,
                heights,
                scale,
            } => {
                let rows = sample_rows(*rows, *cols, heights);
                let point = |r, c| height_field_point(rows, *cols, heights, *scale, r, c);
                for r in 0..rows.saturating_sub(1) {
                    for c in 0..cols.saturating_sub(1) {
                        let cell = (
                            point(r, c),
                            point(r + 1, c),
                            point(r, c + 1),
                            point(r + 1, c + 1),
                        );
                        if let (Some(a), Some(b), Some(c), Some(d)) = cell {
                            // Wound so the normals point up (+y): x runs along columns, z along rows.
                            pen.triangle([a, b, c]);
                            pen.triangle([c, b, d]);
                        }
                    }
                }
            }
            ColliderShape::Compound { parts } => {
                for (part_pose, part) in parts {
                    self.shape_solid(part, pose.mul_pose(part_pose), color, segments);
                }
            }
        }
    }
}

/// The corners of triangle `t`, if its indices are in range.
fn corners(vertices: &[Vec3], [a, b, c]: [u32; 3]) -> Option<[Vec3; 3]> {
    let p = |i: u32| vertices.get(i as usize).copied();
    Some([p(a)?, p(b)?, p(c)?])
}

/// Half the side (m) of the square a half-space is drawn as: its surface is infinite.
pub const HALF_SPACE_DRAWN_HALF_SIDE: f32 = 10.0;

/// The corners of the square, centred on the collider origin in the boundary plane, that a half-space with
/// outward `normal` is drawn as (collider frame), in order around it.
fn half_space_square(normal: Vec3) -> [Vec3; 4] {
    let n = normal.try_normalize().unwrap_or(Vec3::Y);
    let (u, v) = n.any_orthonormal_pair();
    let h = HALF_SPACE_DRAWN_HALF_SIDE;
    [(-u - v) * h, (u - v) * h, (u + v) * h, (-u + v) * h]
}
