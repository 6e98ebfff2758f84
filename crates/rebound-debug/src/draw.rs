//! [`DebugDraw`]: the output — coloured line segments and triangles in world space, each tagged with the
//! [`Layer`] it belongs to so a viewer can hide a layer without drawing again. Any backend draws it: a
//! gizmo system, an image rasteriser, a web page.

use crate::Color;
use rebound::Vec3;

/// What a line or triangle depicts.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Layer {
    /// A collider's outline or surface.
    Shape,
    /// A bounding box.
    BoundingBox,
    /// A contact point, normal or impulse.
    Contact,
    /// A joint's anchors, axes or limits.
    Joint,
}

/// A line segment from `a` to `b` (world space, m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Line {
    /// One end.
    pub a: Vec3,
    /// The other end.
    pub b: Vec3,
    /// Its colour.
    pub color: Color,
    /// What it depicts.
    pub layer: Layer,
}

/// A triangle (world space, m), counter-clockwise seen from outside the solid it belongs to, so its normal
/// is `(b − a) × (c − a)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Triangle {
    /// The corners.
    pub vertices: [Vec3; 3],
    /// Its colour.
    pub color: Color,
    /// What it depicts.
    pub layer: Layer,
}

impl Triangle {
    /// The unit outward normal (zero for a degenerate triangle).
    #[must_use]
    pub fn normal(&self) -> Vec3 {
        let [a, b, c] = self.vertices;
        (b - a).cross(c - a).normalize_or_zero()
    }
}

/// What to draw: line segments and triangles. Fill it with [`DebugDraw::world`] or the per-item methods;
/// [`DebugDraw::clear`] keeps the buffers for the next frame.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DebugDraw {
    /// The segments.
    pub lines: Vec<Line>,
    /// The triangles.
    pub triangles: Vec<Triangle>,
}

impl DebugDraw {
    /// Nothing to draw.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Removes everything, keeping the allocations.
    pub fn clear(&mut self) {
        self.lines.clear();
        self.triangles.clear();
    }

    /// Adds a segment.
    pub fn line(&mut self, a: Vec3, b: Vec3, color: Color, layer: Layer) {
        self.lines.push(Line { a, b, color, layer });
    }

    /// Adds a triangle (counter-clockwise seen from the side its normal should face).
    pub fn triangle(&mut self, vertices: [Vec3; 3], color: Color, layer: Layer) {
        self.triangles.push(Triangle {
            vertices,
            color,
            layer,
        });
    }

    /// Adds a cross of three segments of half-length `size` (m) along the world axes, centred at `at`.
    pub fn cross(&mut self, at: Vec3, size: f32, color: Color, layer: Layer) {
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            self.line(at - axis * size, at + axis * size, color, layer);
        }
    }

    /// Adds the 12 edges of the axis-aligned box from `min` to `max`.
    pub fn aabb(&mut self, min: Vec3, max: Vec3, color: Color) {
        let corner = |i: usize| {
            Vec3::new(
                if i & 1 == 0 { min.x } else { max.x },
                if i & 2 == 0 { min.y } else { max.y },
                if i & 4 == 0 { min.z } else { max.z },
            )
        };
        for (i, j) in BOX_EDGES {
            self.line(corner(i), corner(j), color, Layer::BoundingBox);
        }
    }

    /// The segments of one layer.
    pub fn lines_of(&self, layer: Layer) -> impl Iterator<Item = &Line> {
        self.lines.iter().filter(move |l| l.layer == layer)
    }
}

/// The 12 edges of a box whose corner `i` has bit 0 = +x, bit 1 = +y, bit 2 = +z.
pub(crate) const BOX_EDGES: [(usize, usize); 12] = [
    (0, 1),
    (2, 3),
    (4, 5),
    (6, 7),
    (0, 2),
    (1, 3),
    (4, 6),
    (5, 7),
    (0, 4),
    (1, 5),
    (2, 6),
    (3, 7),
];
