//! Typed errors of the facade (`docs/architecture.md`, "Errors"). Every error names the field and the value that were
//! wrong, and the world is unchanged when one is returned. Not part of any step stage: input is checked where it enters
//! (insertion, setters, queries), and the step never fails.

use crate::ColliderHandle;
use rebound_dynamics::DynamicsError;
use rebound_math::{MathError, Vec3};
use rebound_world::WorldError;

/// Why a shape description cannot become a collider shape.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum ShapeError {
    /// A number failed a basic check (NaN, ∞, zero or negative); the message names the field and the value.
    #[error(transparent)]
    Math(#[from] MathError),
    /// A length or coordinate is larger than [`crate::MAX_SHAPE_COORDINATE`] (m), where `f32` positions lose
    /// centimetre precision and parry's computations may overflow.
    #[error("`{field}` must be at most {max} m in magnitude, got {value}")]
    TooLarge {
        /// The field.
        field: &'static str,
        /// The value given.
        value: f32,
        /// The largest accepted magnitude (m).
        max: f32,
    },
    /// A point or vertex has a NaN or infinite coordinate.
    #[error("`{field}[{index}]` must be finite, got {value}")]
    NonFiniteVertex {
        /// `"points"` (convex hull) or `"vertices"` (triangle mesh).
        field: &'static str,
        /// The index of the point.
        index: usize,
        /// The point given.
        value: Vec3,
    },
    /// A convex hull needs at least 4 points that are not all in one plane.
    #[error(
        "`points` must hold at least 4 points that are not coplanar, got {count} points (largest tetrahedron volume {volume} m³)"
    )]
    DegenerateHull {
        /// The number of points given.
        count: usize,
        /// The volume of the largest tetrahedron found among them (m³).
        volume: f32,
    },
    /// parry could not build a convex hull from points that passed the checks above (numerically degenerate).
    #[error("`points`: no convex hull could be computed from {count} points")]
    HullFailed {
        /// The number of points given.
        count: usize,
    },
    /// A shape that encloses no volume (an open or inside-out triangle mesh, a height field, a half-space)
    /// with a density > 0 on a dynamic body: it could give the body no mass.
    #[error(
        "a {kind} encloses no volume, so it cannot give a dynamic body mass: put it on a fixed or kinematic body, or give it density 0 and the body its own mass"
    )]
    NoVolume {
        /// The shape's kind ([`crate::ColliderShape::kind_name`]).
        kind: &'static str,
    },
    /// A triangle mesh has no vertices or no triangles.
    #[error(
        "a triangle mesh needs vertices and triangles, got {vertex_count} vertices and {triangle_count} triangles"
    )]
    EmptyMesh {
        /// Vertices given.
        vertex_count: usize,
        /// Triangles given.
        triangle_count: usize,
    },
    /// A triangle names a vertex that does not exist.
    #[error(
        "`indices[{triangle}]` names vertex {index}, but the mesh has only {vertex_count} vertices"
    )]
    IndexOutOfRange {
        /// The triangle.
        triangle: usize,
        /// The vertex index it names.
        index: u32,
        /// The number of vertices.
        vertex_count: usize,
    },
    /// parry refused the triangle mesh.
    #[error("the triangle mesh was refused: {0}")]
    MeshRejected(String),
    /// A height field needs at least 2 × 2 samples, and exactly `rows × cols` heights.
    #[error(
        "a height field needs rows ≥ 2, cols ≥ 2 and rows × cols heights, got {rows} × {cols} with {height_count} heights"
    )]
    HeightFieldSize {
        /// Rows given (along z).
        rows: usize,
        /// Columns given (along x).
        cols: usize,
        /// Heights given.
        height_count: usize,
    },
    /// A height is NaN or infinite.
    #[error("`heights[{index}]` (row {row}, column {col}) must be finite, got {value}")]
    NonFiniteHeight {
        /// Index into `heights`.
        index: usize,
        /// Its row.
        row: usize,
        /// Its column.
        col: usize,
        /// The value given.
        value: f32,
    },
    /// A compound shape needs at least one part.
    #[error("a compound shape needs at least one part")]
    EmptyCompound,
    /// A compound part is itself a compound, a mesh or a height field (parry allows only convex parts).
    #[error("compound part {index} is a {kind}; compound parts must be convex primitives or hulls")]
    NestedComposite {
        /// The part.
        index: usize,
        /// Its kind.
        kind: &'static str,
    },
    /// A compound part is invalid.
    #[error("compound part {index}: {source}")]
    InvalidPart {
        /// The part.
        index: usize,
        /// What is wrong with it.
        source: Box<ShapeError>,
    },
    /// The shape's mass properties at the given density are not usable (overflow to ∞).
    #[error("mass properties of the shape at density {density} kg/m³ are invalid: {source}")]
    MassProperties {
        /// The density given (kg/m³).
        density: f32,
        /// Why the dynamics layer refused them.
        source: DynamicsError,
    },
}

/// An invalid call on a [`crate::PhysicsWorld`]. Nothing changes when one is returned.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[non_exhaustive]
pub enum Error {
    /// The world refused the call (a stale body or joint handle, an invalid body or joint description, invalid
    /// settings).
    #[error(transparent)]
    World(#[from] WorldError),
    /// A shape description was invalid.
    #[error(transparent)]
    Shape(#[from] ShapeError),
    /// A number failed a basic check; the message names the field and the value.
    #[error(transparent)]
    Math(#[from] MathError),
    /// Mass properties were refused.
    #[error(transparent)]
    Dynamics(#[from] DynamicsError),
    /// A joint description or setting was refused (so `?` works on joint builders in a function returning
    /// this error).
    #[error(transparent)]
    Constraint(#[from] rebound_constraints::ConstraintError),
    /// A character controller setting or move argument was refused.
    #[error(transparent)]
    Character(#[from] crate::CharacterError),
    /// A material value lies outside its range.
    #[error("`{field}` must lie in [{min}, {max}], got {value}")]
    OutOfRange {
        /// The field.
        field: &'static str,
        /// The value given.
        value: f32,
        /// The smallest accepted value.
        min: f32,
        /// The largest accepted value.
        max: f32,
    },
    /// The collider handle refers to no collider in this world (removed, or from another world).
    #[error("stale or foreign collider handle {0:?}")]
    StaleCollider(ColliderHandle),
    /// The world cannot hold more colliders (2³² − 1).
    #[error("the world is full: no more colliders can be inserted")]
    Full,
    /// A thread pool for the step could not be made (`PhysicsWorld::set_thread_count`, with the `parallel`
    /// feature): a count of zero, or the operating system refused the threads.
    #[error("`thread_count` must be at least 1 and its threads must start, got {count}: {reason}")]
    ThreadPool {
        /// The thread count given.
        count: usize,
        /// Why it was refused.
        reason: String,
    },
    /// A snapshot could not be restored (another format version, an inconsistent table).
    #[error("snapshot cannot be restored: {0}")]
    BadSnapshot(String),
    /// A snapshot held a value its constructors would have refused, or a handle that resolves to nothing in
    /// it (a collider on a body that does not exist): `item` says where (`collider 2`), `source` what.
    #[error("snapshot cannot be restored: {item}: {source}")]
    InvalidSnapshot {
        /// Where in the snapshot.
        item: String,
        /// The error its constructor, setter or handle lookup would have returned.
        source: Box<Error>,
    },
}
