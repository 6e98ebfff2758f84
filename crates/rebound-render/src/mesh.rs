//! `Mesh`: a collider shape as triangles in its own frame, made once per shape and drawn every frame.
//!
//! The triangles come from parry3d's own tessellations (`to_trimesh` of each shape, its convex hull for a
//! hull), so the picture shows the geometry the engine collides with. Convex pieces are closed, and each of
//! their triangles is wound counter-clockwise seen from outside (re-oriented here against the piece's
//! centroid, which lies inside a convex piece), so the renderer may skip the faces turned away from the
//! camera. Triangle meshes and height fields are surfaces: open, drawn from both sides.

use rebound::ColliderShape;
use rebound::parry3d;
use rebound::parry3d::shape::{Ball, Capsule, Cone, Cuboid, Cylinder};
use rebound::prelude::{Pose, Vec3};

use crate::RenderError;

/// Subdivisions around a round shape's axis (and half as many from pole to pole) by default.
pub const DEFAULT_ROUND_SUBDIVISIONS: u32 = 16;

/// The fewest subdivisions around a round shape's axis.
pub const MIN_ROUND_SUBDIVISIONS: u32 = 3;

/// The most subdivisions around a round shape's axis.
pub const MAX_ROUND_SUBDIVISIONS: u32 = 256;

/// A triangle mesh in a shape's own frame (m).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh {
    positions: Vec<Vec3>,
    /// Each triangle's vertex indices and whether it belongs to a closed (convex) piece.
    triangles: Vec<([u32; 3], bool)>,
}

impl Mesh {
    /// The triangles of `shape`, round shapes with `subdivisions` around their axis (clamped to
    /// [`MIN_ROUND_SUBDIVISIONS`]..=[`MAX_ROUND_SUBDIVISIONS`]).
    ///
    /// # Errors
    /// [`RenderError::Shape`] if the facade refuses the shape (the check a collider gets when inserted).
    pub fn from_shape(shape: &ColliderShape, subdivisions: u32) -> Result<Self, RenderError> {
        shape.validate()?;
        let mut mesh = Self::default();
        mesh.add_shape(
            shape,
            &Pose::IDENTITY,
            subdivisions.clamp(MIN_ROUND_SUBDIVISIONS, MAX_ROUND_SUBDIVISIONS),
        )?;
        Ok(mesh)
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

    /// Appends `shape` placed by `pose`; the shape has been validated.
    fn add_shape(
        &mut self,
        shape: &ColliderShape,
        pose: &Pose,
        subdivisions: u32,
    ) -> Result<(), RenderError> {
        let around = subdivisions;
        let pole_to_pole = (subdivisions / 2).max(2);
        let (vertices, triangles) = match shape {
            ColliderShape::Ball { radius } => Ball::new(*radius).to_trimesh(around, pole_to_pole),
            ColliderShape::Cuboid { half_extents } => Cuboid::new(*half_extents).to_trimesh(),
            ColliderShape::Capsule {
                radius,
                half_height,
            } => {
                if *half_height > 0.0 {
                    Capsule::new_y(*half_height, *radius).to_trimesh(around, pole_to_pole)
                } else {
                    Ball::new(*radius).to_trimesh(around, pole_to_pole)
                }
            }
            ColliderShape::Cylinder {
                radius,
                half_height,
            } => Cylinder::new(*half_height, *radius).to_trimesh(around),
            ColliderShape::Cone {
                radius,
                half_height,
            } => Cone::new(*half_height, *radius).to_trimesh(around),
            ColliderShape::ConvexHull { points } => parry3d::transformation::convex_hull(points),
            ColliderShape::TriMesh { vertices, indices } => {
                self.append(pose, vertices, indices, false);
                return Ok(());
            }
            ColliderShape::HeightField { .. } => {
                let parry = shape.to_parry()?;
                let (vertices, triangles) = parry
                    .as_heightfield()
                    .map(parry3d::shape::HeightField::to_trimesh)
                    .unwrap_or_default();
                self.append(pose, &vertices, &triangles, false);
                return Ok(());
            }
            ColliderShape::Compound { parts } => {
                for (part_pose, part) in parts {
                    self.add_shape(part, &pose.mul_pose(part_pose), subdivisions)?;
                }
                return Ok(());
            }
        };
        self.append(
            pose,
            &vertices,
            &orient_outwards(&vertices, triangles),
            true,
        );
        Ok(())
    }

    /// Appends triangles over `vertices` placed by `pose`.
    fn append(&mut self, pose: &Pose, vertices: &[Vec3], triangles: &[[u32; 3]], closed: bool) {
        let base = self.positions.len() as u32;
        self.positions
            .extend(vertices.iter().map(|&v| pose.transform_point(v)));
        self.triangles.extend(
            triangles
                .iter()
                .map(|t| ([t[0] + base, t[1] + base, t[2] + base], closed)),
        );
    }
}

/// The triangles of a convex piece, each wound counter-clockwise seen from outside: its normal points away
/// from the vertices' centroid, which is inside. Degenerate triangles (zero area) are dropped.
fn orient_outwards(vertices: &[Vec3], triangles: Vec<[u32; 3]>) -> Vec<[u32; 3]> {
    if vertices.is_empty() {
        return Vec::new();
    }
    let centroid = vertices.iter().copied().sum::<Vec3>() / vertices.len() as f32;
    let at = |i: u32| vertices.get(i as usize).copied();
    triangles
        .into_iter()
        .filter_map(|[a, b, c]| {
            let (pa, pb, pc) = (at(a)?, at(b)?, at(c)?);
            let normal = (pb - pa).cross(pc - pa);
            let outward = normal.dot((pa + pb + pc) / 3.0 - centroid);
            if normal.length_squared() == 0.0 {
                None
            } else if outward >= 0.0 {
                Some([a, b, c])
            } else {
                Some([a, c, b])
            }
        })
        .collect()
}
