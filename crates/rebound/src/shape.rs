//! `ColliderShape`: a plain, serialisable description of a collider's geometry, checked and turned into a
//! parry3d shape when a collider is inserted (and again when a snapshot is restored). Not a step stage.
//!
//! Snapshots store these descriptions rather than parry's types, so the snapshot format does not depend on
//! parry's serde support and parry's API churn stays inside this file.
//!
//! Every check parry would make with an `assert!` or an `unwrap` (a compound without parts, nested
//! composites, a height field with fewer than 2 × 2 samples, mesh indices out of range) is made here first and
//! reported as a [`ShapeError`], so no panic reaches the user.

use crate::ShapeError;
use parry3d::math::Vector;
use parry3d::shape::SharedShape;
use rebound_math::validity::{check_finite_vec3, check_positive, check_rotation};
use rebound_math::{MathError, Pose, Vec3};
use serde::{Deserialize, Serialize};

/// The largest length or coordinate a shape may have (m). At 10⁶ m an `f32` position is only good to
/// 6 cm, and larger values let parry's intermediate products (areas, volumes, inertia) overflow to ∞.
pub const MAX_SHAPE_COORDINATE: f32 = 1.0e6;

/// The geometry of a collider, in the collider's own frame (which [`crate::ColliderDesc::local_pose`] places
/// on the body). Lengths in metres. Axis-symmetric shapes (capsule, cylinder, cone) are along the local y axis.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub enum ColliderShape {
    /// A ball centred at the origin.
    Ball {
        /// Radius (m, > 0).
        radius: f32,
    },
    /// A box centred at the origin.
    Cuboid {
        /// Half-extents along x, y, z (m, each > 0).
        half_extents: Vec3,
    },
    /// A capsule along y: a cylinder of `radius` from −`half_height` to +`half_height`, capped by two
    /// hemispheres. A half-height of 0 is a ball.
    Capsule {
        /// Radius (m, > 0).
        radius: f32,
        /// Half the length of the cylindrical part (m, ≥ 0).
        half_height: f32,
    },
    /// A solid cylinder along y, from −`half_height` to +`half_height`.
    Cylinder {
        /// Radius (m, > 0).
        radius: f32,
        /// Half-height (m, > 0).
        half_height: f32,
    },
    /// A solid cone along y: base disc at −`half_height`, apex at +`half_height`.
    Cone {
        /// Radius of the base (m, > 0).
        radius: f32,
        /// Half-height (m, > 0).
        half_height: f32,
    },
    /// The convex hull of `points` (at least 4, not all coplanar).
    ConvexHull {
        /// The points (m, collider frame).
        points: Vec<Vec3>,
    },
    /// A triangle mesh (a surface: use it on fixed bodies; it adds mass only if it is closed with outward
    /// winding).
    TriMesh {
        /// Vertex positions (m, collider frame).
        vertices: Vec<Vec3>,
        /// Triangles as indices into `vertices`, counter-clockwise seen from outside.
        indices: Vec<[u32; 3]>,
    },
    /// A height field on the x-z plane, centred at the origin: `rows` samples along z by `cols` samples along
    /// x, spanning `scale.x` by `scale.z` metres; sample heights are multiplied by `scale.y`. A surface: it
    /// adds no mass.
    HeightField {
        /// Samples along z (≥ 2).
        rows: usize,
        /// Samples along x (≥ 2).
        cols: usize,
        /// `rows × cols` heights, row-major: `heights[row * cols + col]` is at
        /// `x = (col / (cols − 1) − ½)·scale.x`, `z = (row / (rows − 1) − ½)·scale.z`.
        heights: Vec<f32>,
        /// Size along x and z and the height multiplier (m; each > 0).
        scale: Vec3,
    },
    /// A half-space: everything on the inner side of the plane through the collider origin with outward
    /// `normal` (an infinite floor or wall). It encloses no finite volume: use it on fixed or kinematic
    /// bodies (or with density 0). Its bounding box is clamped to ±[`MAX_SHAPE_COORDINATE`].
    HalfSpace {
        /// The outward normal (collider frame; any length > 0, normalised on insertion).
        normal: Vec3,
    },
    /// Several convex parts rigidly joined, each placed by a pose in the collider frame. Parts may not be
    /// compounds, meshes or height fields.
    Compound {
        /// The parts and their poses.
        parts: Vec<(Pose, ColliderShape)>,
    },
}

impl Default for ColliderShape {
    /// A ball of radius 0.5 m.
    fn default() -> Self {
        Self::Ball { radius: 0.5 }
    }
}

impl ColliderShape {
    /// The kind's name in lower case, as error messages use it.
    #[must_use]
    pub const fn kind_name(&self) -> &'static str {
        match self {
            Self::Ball { .. } => "ball",
            Self::Cuboid { .. } => "cuboid",
            Self::Capsule { .. } => "capsule",
            Self::Cylinder { .. } => "cylinder",
            Self::Cone { .. } => "cone",
            Self::ConvexHull { .. } => "convex hull",
            Self::TriMesh { .. } => "triangle mesh",
            Self::HeightField { .. } => "height field",
            Self::Compound { .. } => "compound",
            Self::HalfSpace { .. } => "half-space",
        }
    }

    /// Whether the shape is convex — what its parry3d shape's `is_convex` answers, read from the description
    /// without a call through the shape trait object: the primitives and hulls are, meshes, height fields and
    /// compounds are not.
    #[must_use]
    pub const fn is_convex(&self) -> bool {
        match self {
            Self::Ball { .. }
            | Self::Cuboid { .. }
            | Self::Capsule { .. }
            | Self::Cylinder { .. }
            | Self::Cone { .. }
            | Self::ConvexHull { .. }
            | Self::HalfSpace { .. } => true,
            Self::TriMesh { .. } | Self::HeightField { .. } | Self::Compound { .. } => false,
        }
    }

    /// Checks the description and builds the parry3d shape.
    ///
    /// # Errors
    /// A [`ShapeError`] naming the first invalid field: non-finite, zero or negative sizes, sizes beyond
    /// [`MAX_SHAPE_COORDINATE`], fewer than 4 non-coplanar hull points, NaN vertices, mesh indices out of
    /// range, a height field with fewer than 2 × 2 samples or non-finite heights, an empty or nested compound.
    pub fn to_parry(&self) -> Result<SharedShape, ShapeError> {
        match self {
            Self::Ball { radius } => Ok(SharedShape::ball(check_length("radius", *radius)?)),
            Self::Cuboid { half_extents } => {
                let h = check_extents("half_extents", *half_extents)?;
                Ok(SharedShape::cuboid(h.x, h.y, h.z))
            }
            Self::Capsule {
                radius,
                half_height,
            } => {
                let radius = check_length("radius", *radius)?;
                let half_height = check_length_or_zero("half_height", *half_height)?;
                // A capsule without a segment is a ball; parry's capsule code would divide by its length.
                if half_height == 0.0 {
                    Ok(SharedShape::ball(radius))
                } else {
                    Ok(SharedShape::capsule_y(half_height, radius))
                }
            }
            Self::Cylinder {
                radius,
                half_height,
            } => Ok(SharedShape::cylinder(
                check_length("half_height", *half_height)?,
                check_length("radius", *radius)?,
            )),
            Self::Cone {
                radius,
                half_height,
            } => Ok(SharedShape::cone(
                check_length("half_height", *half_height)?,
                check_length("radius", *radius)?,
            )),
            Self::ConvexHull { points } => convex_hull(points),
            Self::TriMesh { vertices, indices } => trimesh(vertices, indices),
            Self::HeightField {
                rows,
                cols,
                heights,
                scale,
            } => heightfield(*rows, *cols, heights, *scale),
            Self::Compound { parts } => compound(parts),
            Self::HalfSpace { normal } => {
                check_finite_vec3("normal", *normal)?;
                let unit = normal.try_normalize().ok_or(MathError::ZeroLength {
                    field: "normal",
                    value: *normal,
                })?;
                Ok(SharedShape::halfspace(unit))
            }
        }
    }

    /// The surface of a [`ColliderShape::ConvexHull`] as parry3d builds it: the points on the hull and
    /// triangles indexing them, counter-clockwise seen from outside (a face with more than three corners
    /// comes as several triangles) — what a renderer draws. `None` for the other kinds and for points that
    /// make no hull ([`ColliderShape::to_parry`] says why).
    ///
    /// ```
    /// use rebound::{ColliderShape, Vec3};
    /// let corners = (0..8).map(|i| Vec3::new((i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2) as f32));
    /// let cube = ColliderShape::ConvexHull { points: corners.collect() };
    /// let (vertices, triangles) = cube.convex_hull_mesh().unwrap();
    /// assert_eq!((vertices.len(), triangles.len()), (8, 12));
    /// ```
    #[must_use]
    pub fn convex_hull_mesh(&self) -> Option<(Vec<Vec3>, Vec<[u32; 3]>)> {
        let Self::ConvexHull { points } = self else {
            return None;
        };
        let shape = convex_hull(points).ok()?;
        Some(shape.as_convex_polyhedron()?.to_trimesh())
    }

    /// Checks the description without keeping the parry shape.
    ///
    /// # Errors
    /// As [`ColliderShape::to_parry`].
    pub fn validate(&self) -> Result<(), ShapeError> {
        self.to_parry().map(|_| ())
    }
}

/// A length that must be finite, > 0 and at most [`MAX_SHAPE_COORDINATE`].
fn check_length(field: &'static str, value: f32) -> Result<f32, ShapeError> {
    check_positive(field, value)?;
    check_magnitude(field, value)
}

/// A length that must be finite, ≥ 0 and at most [`MAX_SHAPE_COORDINATE`].
fn check_length_or_zero(field: &'static str, value: f32) -> Result<f32, ShapeError> {
    rebound_math::validity::check_non_negative(field, value)?;
    check_magnitude(field, value)
}

fn check_magnitude(field: &'static str, value: f32) -> Result<f32, ShapeError> {
    if value.abs() <= MAX_SHAPE_COORDINATE {
        Ok(value)
    } else {
        Err(ShapeError::TooLarge {
            field,
            value,
            max: MAX_SHAPE_COORDINATE,
        })
    }
}

fn check_extents(field: &'static str, value: Vec3) -> Result<Vec3, ShapeError> {
    check_finite_vec3(field, value)?;
    for component in value.to_array() {
        check_length(field, component)?;
    }
    Ok(value)
}

/// Every point finite and within range.
fn check_points(field: &'static str, points: &[Vec3]) -> Result<(), ShapeError> {
    for (index, p) in points.iter().enumerate() {
        if !p.is_finite() {
            return Err(ShapeError::NonFiniteVertex {
                field,
                index,
                value: *p,
            });
        }
        let largest = p.abs().max_element();
        if largest > MAX_SHAPE_COORDINATE {
            return Err(ShapeError::TooLarge {
                field,
                value: largest,
                max: MAX_SHAPE_COORDINATE,
            });
        }
    }
    Ok(())
}

/// The volume of the largest tetrahedron spanned by `points`, found greedily (two far-apart points, the point
/// farthest from their line, the point farthest from their plane). Zero for coplanar points.
fn largest_tetrahedron_volume(points: &[Vec3]) -> f32 {
    let Some(&p0) = points.first() else {
        return 0.0;
    };
    let farthest = |key: &dyn Fn(Vec3) -> f32| {
        points
            .iter()
            .copied()
            .fold((0.0f32, p0), |best, p| {
                let k = key(p);
                if k > best.0 { (k, p) } else { best }
            })
            .1
    };
    let a = farthest(&|p| p.distance_squared(p0));
    let b = farthest(&|p| p.distance_squared(a));
    let ab = b - a;
    let c = farthest(&|p| ab.cross(p - a).length_squared());
    let normal = ab.cross(c - a);
    let d = farthest(&|p| normal.dot(p - a).abs());
    normal.dot(d - a).abs() / 6.0
}

fn convex_hull(points: &[Vec3]) -> Result<SharedShape, ShapeError> {
    check_points("points", points)?;
    let volume = largest_tetrahedron_volume(points);
    // Coplanar within a relative tolerance: the tetrahedron is thinner than 1e-4 of the points' extent.
    let extent = points
        .iter()
        .fold(0.0f32, |m, p| m.max(p.distance(points[0])));
    // (Both are finite: the points are checked above.)
    if points.len() < 4 || volume <= 1e-4 * extent * extent * extent {
        return Err(ShapeError::DegenerateHull {
            count: points.len(),
            volume,
        });
    }
    let parry_points: Vec<Vector> = points.to_vec();
    SharedShape::convex_hull(&parry_points).ok_or(ShapeError::HullFailed {
        count: points.len(),
    })
}

fn trimesh(vertices: &[Vec3], indices: &[[u32; 3]]) -> Result<SharedShape, ShapeError> {
    if vertices.is_empty() || indices.is_empty() {
        return Err(ShapeError::EmptyMesh {
            vertex_count: vertices.len(),
            triangle_count: indices.len(),
        });
    }
    check_points("vertices", vertices)?;
    for (triangle, tri) in indices.iter().enumerate() {
        if let Some(&index) = tri.iter().find(|&&i| i as usize >= vertices.len()) {
            return Err(ShapeError::IndexOutOfRange {
                triangle,
                index,
                vertex_count: vertices.len(),
            });
        }
    }
    SharedShape::trimesh(vertices.to_vec(), indices.to_vec())
        .map_err(|e| ShapeError::MeshRejected(e.to_string()))
}

fn heightfield(
    rows: usize,
    cols: usize,
    heights: &[f32],
    scale: Vec3,
) -> Result<SharedShape, ShapeError> {
    if rows < 2 || cols < 2 || rows.checked_mul(cols) != Some(heights.len()) {
        return Err(ShapeError::HeightFieldSize {
            rows,
            cols,
            height_count: heights.len(),
        });
    }
    let scale = check_extents("scale", scale)?;
    for (index, &value) in heights.iter().enumerate() {
        if !value.is_finite() {
            return Err(ShapeError::NonFiniteHeight {
                index,
                row: index / cols,
                col: index % cols,
                value,
            });
        }
        check_magnitude("heights × scale.y", value * scale.y)?;
    }
    // parry's `Array2` is column-major with rows along z and columns along x.
    let mut column_major = vec![0.0; heights.len()];
    for row in 0..rows {
        for col in 0..cols {
            column_major[row + col * rows] = heights[row * cols + col];
        }
    }
    let heights = parry3d::utils::Array2::new(rows, cols, column_major);
    Ok(SharedShape::heightfield(heights, scale))
}

fn compound(parts: &[(Pose, ColliderShape)]) -> Result<SharedShape, ShapeError> {
    if parts.is_empty() {
        return Err(ShapeError::EmptyCompound);
    }
    let mut built = Vec::with_capacity(parts.len());
    for (index, (pose, shape)) in parts.iter().enumerate() {
        if let ColliderShape::Compound { .. }
        | ColliderShape::TriMesh { .. }
        | ColliderShape::HeightField { .. } = shape
        {
            return Err(ShapeError::NestedComposite {
                index,
                kind: shape.kind_name(),
            });
        }
        let part = || -> Result<(parry3d::math::Pose, SharedShape), ShapeError> {
            let pose = check_pose("pose", *pose)?;
            Ok((to_parry_pose(pose), shape.to_parry()?))
        };
        built.push(part().map_err(|source| ShapeError::InvalidPart {
            index,
            source: Box::new(source),
        })?);
    }
    Ok(SharedShape::compound(built))
}

/// A checked pose: finite position within [`MAX_SHAPE_COORDINATE`], finite unit rotation (normalised).
pub(crate) fn check_pose(field: &'static str, pose: Pose) -> Result<Pose, ShapeError> {
    check_finite_vec3(field, pose.position)?;
    check_rotation(field, pose.rotation)?;
    check_magnitude(field, pose.position.abs().max_element())?;
    Ok(Pose::new(pose.position, pose.rotation.normalize()))
}

/// Rebound's pose as parry's (the same glam types, rotation and translation).
pub(crate) fn to_parry_pose(pose: Pose) -> parry3d::math::Pose {
    parry3d::math::Pose::from_parts(pose.position, pose.rotation)
}

/// parry's pose as Rebound's.
pub(crate) fn from_parry_pose(pose: &parry3d::math::Pose) -> Pose {
    Pose::new(pose.translation, pose.rotation)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn height_field_samples_land_where_documented() {
        // 2 rows (z) × 3 columns (x); the sample at row 1, column 2 is the far corner (+x, +z).
        let shape = ColliderShape::HeightField {
            rows: 2,
            cols: 3,
            heights: vec![0.0, 0.0, 0.0, 0.0, 0.0, 1.0],
            scale: Vec3::new(2.0, 1.0, 2.0),
        };
        let parry = shape.to_parry().unwrap();
        let aabb = parry.compute_local_aabb();
        assert!((aabb.maxs.y - 1.0).abs() < 1e-6);
        // Straight down onto the surface: the far corner (+x, +z) is raised, the (−x, +z) and (+x, −z)
        // corners are not.
        let height_at = |x: f32, z: f32| {
            let ray = parry3d::query::Ray::new(Vec3::new(x, 5.0, z), -Vec3::Y);
            5.0 - parry.cast_local_ray(&ray, 10.0, true).unwrap_or(f32::NAN)
        };
        assert!(height_at(0.99, 0.99) > 0.97, "{}", height_at(0.99, 0.99));
        assert!(height_at(-0.99, 0.99).abs() < 1e-4);
        assert!(height_at(0.99, -0.99).abs() < 1e-4);
    }

    #[test]
    fn convexity_is_parrys() {
        let tetrahedron = vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z];
        let shapes = [
            ColliderShape::Ball { radius: 0.5 },
            ColliderShape::Cuboid {
                half_extents: Vec3::splat(0.5),
            },
            ColliderShape::Capsule {
                radius: 0.5,
                half_height: 1.0,
            },
            ColliderShape::Capsule {
                radius: 0.5,
                half_height: 0.0,
            },
            ColliderShape::Cylinder {
                radius: 0.5,
                half_height: 1.0,
            },
            ColliderShape::Cone {
                radius: 0.5,
                half_height: 1.0,
            },
            ColliderShape::ConvexHull {
                points: tetrahedron.clone(),
            },
            ColliderShape::TriMesh {
                vertices: tetrahedron,
                indices: vec![[0, 1, 2], [0, 3, 1], [0, 2, 3], [1, 3, 2]],
            },
            ColliderShape::HeightField {
                rows: 2,
                cols: 2,
                heights: vec![0.0; 4],
                scale: Vec3::ONE,
            },
            ColliderShape::Compound {
                parts: vec![(Pose::IDENTITY, ColliderShape::Ball { radius: 0.5 })],
            },
        ];
        for shape in shapes {
            let parry = shape.to_parry().unwrap();
            assert_eq!(
                shape.is_convex(),
                parry.is_convex(),
                "{}",
                shape.kind_name()
            );
        }
    }

    #[test]
    fn coplanar_points_make_no_hull() {
        let square = vec![
            Vec3::new(0.0, 0.0, 0.0),
            Vec3::new(1.0, 0.0, 0.0),
            Vec3::new(0.0, 0.0, 1.0),
            Vec3::new(1.0, 0.0, 1.0),
        ];
        assert!(matches!(
            ColliderShape::ConvexHull { points: square }.to_parry(),
            Err(ShapeError::DegenerateHull { count: 4, .. })
        ));
    }
}
