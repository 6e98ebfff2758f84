//! `Mesh`: a collider shape as triangles in its own frame, made once per shape and drawn every frame.
//!
//! The triangles are `rebound-debug`'s surfaces of each kind (the one tessellation of the workspace, the
//! same a debug view draws, built on the facade's own convex hull), kept here with whether each belongs to
//! a closed piece: every shape but a triangle mesh or height field is closed, its triangles wound
//! counter-clockwise seen from outside, so the renderer may skip the faces turned away from the camera.
//! Triangle meshes and height fields are surfaces, drawn from both sides.

use rebound::ColliderShape;
use rebound::prelude::{Pose, Vec3};
use rebound_debug::{Color, DebugDraw, MAX_CIRCLE_SEGMENTS};

use crate::RenderError;

/// Segments of a round shape's full circle by default (a ball or capsule cap has a quarter as many bands
/// from its equator to a pole).
pub const DEFAULT_ROUND_SUBDIVISIONS: u32 = 16;

/// The fewest segments of a round shape's full circle.
pub const MIN_ROUND_SUBDIVISIONS: u32 = 3;

/// The most segments of a round shape's full circle.
pub const MAX_ROUND_SUBDIVISIONS: u32 = MAX_CIRCLE_SEGMENTS;

/// A triangle mesh in a shape's own frame (m).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    positions: Vec<Vec3>,
    /// Each triangle's vertex indices and whether it belongs to a closed (convex) piece.
    triangles: Vec<([u32; 3], bool)>,
}

impl Mesh {
    /// The triangles of `shape`, round shapes with `subdivisions` segments per full circle (clamped to
    /// [`MIN_ROUND_SUBDIVISIONS`]..=[`MAX_ROUND_SUBDIVISIONS`]).
    ///
    /// # Errors
    /// [`RenderError::Shape`] if the facade refuses the shape (the check a collider gets when inserted).
    pub fn from_shape(shape: &ColliderShape, subdivisions: u32) -> Result<Self, RenderError> {
        shape.validate()?;
        let mut draw = DebugDraw::new();
        let segments = subdivisions.clamp(MIN_ROUND_SUBDIVISIONS, MAX_ROUND_SUBDIVISIONS);
        draw.shape(shape, Pose::IDENTITY, Color::WHITE, false, true, segments);
        let closed = !matches!(
            shape,
            ColliderShape::TriMesh { .. }
                | ColliderShape::HeightField { .. }
                | ColliderShape::HalfSpace { .. }
        );
        let positions: Vec<Vec3> = draw.triangles.iter().flat_map(|t| t.vertices).collect();
        let triangles = (0..draw.triangles.len() as u32)
            .map(|i| ([3 * i, 3 * i + 1, 3 * i + 2], closed))
            .collect();
        Ok(Self {
            positions,
            triangles,
        })
    }

    /// An open mesh (a surface drawn from both sides) from vertex positions (m) and triangles.
    ///
    /// # Errors
    /// [`RenderError::Options`] naming `triangles` if an index is out of range, or `positions` if a position
    /// is not finite.
    pub fn from_triangles(
        positions: Vec<Vec3>,
        triangles: &[[u32; 3]],
    ) -> Result<Self, RenderError> {
        if let Some(p) = positions.iter().find(|p| !p.is_finite()) {
            return Err(RenderError::Options {
                field: "positions",
                value: p.to_string(),
                expected: "finite",
            });
        }
        let count = positions.len();
        if let Some(index) = triangles.iter().flatten().find(|&&i| i as usize >= count) {
            return Err(RenderError::Options {
                field: "triangles",
                value: index.to_string(),
                expected: "indices below the number of positions",
            });
        }
        Ok(Self {
            positions,
            triangles: triangles.iter().map(|&t| (t, false)).collect(),
        })
    }

    /// Vertex positions (m, shape frame).
    #[must_use]
    pub fn positions(&self) -> &[Vec3] {
        &self.positions
    }

    /// Triangles as vertex indices.
    pub fn triangles(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        self.triangles.iter().map(|&(t, _)| t)
    }

    /// Triangles with whether each belongs to a closed piece (wound counter-clockwise seen from outside).
    pub(crate) fn triangles_closed(&self) -> &[([u32; 3], bool)] {
        &self.triangles
    }

    /// Number of triangles.
    #[must_use]
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }
}
