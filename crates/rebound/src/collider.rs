//! Colliders: a shape placed on a body with a surface material, a density, collision groups, and the sensor
//! and enabled flags. [`ColliderDesc`] is the settings struct a user fills in; [`Collider`] is what a world
//! stores (the description, the body, the built parry3d shape and its mass). Read by the collide stage and by
//! queries; mass properties are summed into the body when colliders are inserted or removed.

use crate::ShapeError;
use crate::shape::{ColliderShape, check_pose};
use parry3d::shape::SharedShape;
use rebound_dynamics::{CombineRule, DynamicsError, MassProperties};
use rebound_math::validity::{check_finite, check_non_negative};
use rebound_math::{Pose, Quat, Vec3};
use rebound_world::BodyHandle;
use serde::{Deserialize, Serialize};

/// Which colliders may touch: a collider belongs to the groups set in `memberships` and touches the groups
/// set in `filter`. Two colliders interact only if **both** accept each other:
///
/// ```text
/// (a.memberships & b.filter) != 0  &&  (b.memberships & a.filter) != 0
/// ```
///
/// Queries test their own groups against each collider the same way.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct CollisionGroups {
    /// The groups this collider belongs to (bit mask). Default: all.
    pub memberships: u32,
    /// The groups this collider interacts with (bit mask). Default: all.
    pub filter: u32,
}

impl Default for CollisionGroups {
    fn default() -> Self {
        Self::ALL
    }
}

impl CollisionGroups {
    /// Member of every group, interacting with every group.
    pub const ALL: Self = Self {
        memberships: u32::MAX,
        filter: u32::MAX,
    };
    /// Member of no group, interacting with nothing.
    pub const NONE: Self = Self {
        memberships: 0,
        filter: 0,
    };

    /// Groups from a membership mask and a filter mask.
    #[must_use]
    pub const fn new(memberships: u32, filter: u32) -> Self {
        Self {
            memberships,
            filter,
        }
    }

    /// Whether two colliders (or a query and a collider) with these groups interact.
    #[must_use]
    pub const fn interacts_with(self, other: Self) -> bool {
        (self.memberships & other.filter) != 0 && (other.memberships & self.filter) != 0
    }
}

/// A collider's settings: public fields with [`Default`], named constructors per shape and `with_*` sugar.
/// Checked by [`crate::PhysicsWorld::insert_collider`], which returns an error naming the first bad field.
///
/// ```
/// use rebound::{ColliderDesc, CollisionGroups, CombineRule, Vec3};
/// let wheel = ColliderDesc::cylinder(0.3, 0.1)
///     .with_position(Vec3::new(1.0, 0.0, 0.0))
///     .with_friction(1.2)
///     .with_friction_combine_rule(CombineRule::Max)
///     .with_groups(CollisionGroups::new(0b01, 0b10));
/// let trigger = ColliderDesc { is_sensor: true, ..ColliderDesc::cuboid(Vec3::splat(2.0)) };
/// assert_eq!(wheel.density, 1.0);
/// assert!(trigger.is_sensor);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(remote = "Self")]
// Missing fields take their defaults, so a scene file names only what differs.
#[serde(default)]
pub struct ColliderDesc {
    /// The geometry. Default: a ball of radius 0.5 m.
    pub shape: ColliderShape,
    /// Where the shape sits on its body: position (m) and rotation relative to the body origin.
    /// Default: identity (the shape is centred on the body origin).
    pub local_pose: Pose,
    /// Density (kg/m³, ≥ 0). The body's mass properties are the sum of its colliders' (parry computes each
    /// shape's mass, centre and inertia); 0 adds no mass, and a body whose colliders all have density 0 keeps
    /// the mass properties of its [`crate::BodyDesc`]. Default: 1.0 (as rapier).
    pub density: f32,
    /// Coulomb friction coefficient (dimensionless, ≥ 0). Default: 0.5.
    pub friction: f32,
    /// How this collider's friction combines with the other's (the later rule in [`CombineRule`]'s order wins
    /// when they differ). Also used for rolling friction. Default: [`CombineRule::Average`].
    pub friction_combine_rule: CombineRule,
    /// Coefficient of restitution (dimensionless, in [0, 1]). Default: 0.
    pub restitution: f32,
    /// How this collider's restitution combines with the other's. Default: [`CombineRule::Average`].
    pub restitution_combine_rule: CombineRule,
    /// Rolling resistance lever arm (m, ≥ 0): a rolling ball slows as if its contact point were this far in
    /// front of its centre. Default: 0.
    pub rolling_friction: f32,
    /// Which colliders this one touches. Default: [`CollisionGroups::ALL`].
    pub groups: CollisionGroups,
    /// A sensor detects overlaps ([`crate::Event::SensorEntered`] and [`crate::Event::SensorExited`]) and
    /// never pushes anything. Sensors do not detect other sensors. Default: false.
    pub is_sensor: bool,
    /// A disabled collider takes no part in collisions, sensors, queries or its body's mass. Default: true.
    pub enabled: bool,
    /// Opt-in contact force events: each step in which the total normal force of a contact of this collider
    /// reaches this many newtons (≥ 0) reports a [`crate::Event::ContactForce`]. When both colliders of a
    /// pair set one, the lower counts. Default: `None` (no force events).
    pub force_event_threshold: Option<f32>,
}

/// The rotation that turns the y axis onto x (−90° about z).
const Y_TO_X: Quat = Quat::from_xyzw(
    0.0,
    0.0,
    -core::f32::consts::FRAC_1_SQRT_2,
    core::f32::consts::FRAC_1_SQRT_2,
);

/// The rotation that turns the y axis onto z (+90° about x).
const Y_TO_Z: Quat = Quat::from_xyzw(
    core::f32::consts::FRAC_1_SQRT_2,
    0.0,
    0.0,
    core::f32::consts::FRAC_1_SQRT_2,
);

rebound_math::checked_serde!(remote_self always ColliderDesc, ColliderDesc::validated);

impl Default for ColliderDesc {
    fn default() -> Self {
        Self {
            shape: ColliderShape::default(),
            local_pose: Pose::IDENTITY,
            density: 1.0,
            friction: 0.5,
            friction_combine_rule: CombineRule::Average,
            restitution: 0.0,
            restitution_combine_rule: CombineRule::Average,
            rolling_friction: 0.0,
            groups: CollisionGroups::ALL,
            is_sensor: false,
            enabled: true,
            force_event_threshold: None,
        }
    }
}

impl ColliderDesc {
    /// A collider of `shape` with the defaults.
    #[must_use]
    pub fn new(shape: ColliderShape) -> Self {
        Self {
            shape,
            ..Self::default()
        }
    }

    /// A ball of `radius` (m).
    #[must_use]
    pub fn ball(radius: f32) -> Self {
        Self::new(ColliderShape::Ball { radius })
    }

    /// A box of `half_extents` (m).
    #[must_use]
    pub fn cuboid(half_extents: Vec3) -> Self {
        Self::new(ColliderShape::Cuboid { half_extents })
    }

    /// A capsule along y of `radius` whose cylindrical part spans ±`half_height` (m).
    #[must_use]
    pub fn capsule(radius: f32, half_height: f32) -> Self {
        Self::new(ColliderShape::Capsule {
            radius,
            half_height,
        })
    }

    /// A cylinder along y of `radius` spanning ±`half_height` (m).
    #[must_use]
    pub fn cylinder(radius: f32, half_height: f32) -> Self {
        Self::new(ColliderShape::Cylinder {
            radius,
            half_height,
        })
    }

    /// A capsule along x of `radius` whose cylindrical part spans ±`half_height` (m): the y capsule turned
    /// onto x by the collider's local rotation (a later [`ColliderDesc::with_rotation`] replaces it).
    #[must_use]
    pub fn capsule_x(radius: f32, half_height: f32) -> Self {
        Self::capsule(radius, half_height).with_rotation(Y_TO_X)
    }

    /// A capsule along z of `radius` whose cylindrical part spans ±`half_height` (m); see
    /// [`ColliderDesc::capsule_x`].
    #[must_use]
    pub fn capsule_z(radius: f32, half_height: f32) -> Self {
        Self::capsule(radius, half_height).with_rotation(Y_TO_Z)
    }

    /// A cylinder along x of `radius` spanning ±`half_height` (m); see [`ColliderDesc::capsule_x`].
    #[must_use]
    pub fn cylinder_x(radius: f32, half_height: f32) -> Self {
        Self::cylinder(radius, half_height).with_rotation(Y_TO_X)
    }

    /// A cylinder along z of `radius` spanning ±`half_height` (m); see [`ColliderDesc::capsule_x`].
    #[must_use]
    pub fn cylinder_z(radius: f32, half_height: f32) -> Self {
        Self::cylinder(radius, half_height).with_rotation(Y_TO_Z)
    }

    /// A half-space through the collider origin with outward `normal` (see [`ColliderShape::HalfSpace`]).
    #[must_use]
    pub fn half_space(normal: Vec3) -> Self {
        Self::new(ColliderShape::HalfSpace { normal })
    }

    /// A cone along y: base of `radius` at −`half_height`, apex at +`half_height` (m).
    #[must_use]
    pub fn cone(radius: f32, half_height: f32) -> Self {
        Self::new(ColliderShape::Cone {
            radius,
            half_height,
        })
    }

    /// The convex hull of `points` (m; at least 4, not coplanar — checked on insertion).
    #[must_use]
    pub fn convex_hull(points: impl Into<Vec<Vec3>>) -> Self {
        Self::new(ColliderShape::ConvexHull {
            points: points.into(),
        })
    }

    /// A triangle mesh of `vertices` (m) and counter-clockwise `indices`.
    #[must_use]
    pub fn trimesh(vertices: impl Into<Vec<Vec3>>, indices: impl Into<Vec<[u32; 3]>>) -> Self {
        Self::new(ColliderShape::TriMesh {
            vertices: vertices.into(),
            indices: indices.into(),
        })
    }

    /// A height field of `rows` (along z) × `cols` (along x) row-major `heights`, spanning `scale` (see
    /// [`ColliderShape::HeightField`]).
    #[must_use]
    pub fn heightfield(
        rows: usize,
        cols: usize,
        heights: impl Into<Vec<f32>>,
        scale: Vec3,
    ) -> Self {
        Self::new(ColliderShape::HeightField {
            rows,
            cols,
            heights: heights.into(),
            scale,
        })
    }

    /// A compound of convex `parts`, each at a pose in the collider frame.
    #[must_use]
    pub fn compound(parts: impl Into<Vec<(Pose, ColliderShape)>>) -> Self {
        Self::new(ColliderShape::Compound {
            parts: parts.into(),
        })
    }

    /// Sets the pose on the body.
    #[must_use]
    pub fn with_local_pose(mut self, local_pose: Pose) -> Self {
        self.local_pose = local_pose;
        self
    }

    /// Sets the position on the body (m, body frame).
    #[must_use]
    pub fn with_position(mut self, position: Vec3) -> Self {
        self.local_pose.position = position;
        self
    }

    /// Sets the rotation on the body (unit quaternion, body frame).
    #[must_use]
    pub fn with_rotation(mut self, rotation: Quat) -> Self {
        self.local_pose.rotation = rotation;
        self
    }

    /// Sets the density (kg/m³).
    #[must_use]
    pub fn with_density(mut self, density: f32) -> Self {
        self.density = density;
        self
    }

    /// Sets the friction coefficient.
    #[must_use]
    pub fn with_friction(mut self, friction: f32) -> Self {
        self.friction = friction;
        self
    }

    /// Sets the friction combine rule.
    #[must_use]
    pub fn with_friction_combine_rule(mut self, rule: CombineRule) -> Self {
        self.friction_combine_rule = rule;
        self
    }

    /// Sets the coefficient of restitution.
    #[must_use]
    pub fn with_restitution(mut self, restitution: f32) -> Self {
        self.restitution = restitution;
        self
    }

    /// Sets the restitution combine rule.
    #[must_use]
    pub fn with_restitution_combine_rule(mut self, rule: CombineRule) -> Self {
        self.restitution_combine_rule = rule;
        self
    }

    /// Sets the rolling resistance lever arm (m).
    #[must_use]
    pub fn with_rolling_friction(mut self, rolling_friction: f32) -> Self {
        self.rolling_friction = rolling_friction;
        self
    }

    /// Sets the collision groups.
    #[must_use]
    pub fn with_groups(mut self, groups: CollisionGroups) -> Self {
        self.groups = groups;
        self
    }

    /// Makes the collider a sensor (or not).
    #[must_use]
    pub fn with_sensor(mut self, is_sensor: bool) -> Self {
        self.is_sensor = is_sensor;
        self
    }

    /// Enables or disables the collider.
    #[must_use]
    pub fn with_enabled(mut self, enabled: bool) -> Self {
        self.enabled = enabled;
        self
    }

    /// Sets [`ColliderDesc::force_event_threshold`] (N): contact force events from this force on.
    #[must_use]
    pub fn with_force_event_threshold(mut self, threshold: f32) -> Self {
        self.force_event_threshold = Some(threshold);
        self
    }

    /// Returns `self` if its pose and material pass the checks of [`crate::PhysicsWorld::insert_collider`]
    /// (the check of a deserialised description). The shape is checked where it is built, on insertion and
    /// on restore ([`ColliderShape::validate`] builds it): checking it here too would build a large mesh
    /// twice.
    ///
    /// # Errors
    /// The first invalid field, by name.
    pub fn validated(self) -> Result<Self, crate::Error> {
        self.clone().checked_material()?;
        Ok(self)
    }

    /// Checks every field except the shape (which [`ColliderShape::to_parry`] checks); returns the
    /// description with its rotation normalised.
    pub(crate) fn checked_material(mut self) -> Result<Self, crate::Error> {
        self.local_pose = check_pose("local_pose", self.local_pose)?;
        check_non_negative("density", self.density)?;
        check_non_negative("friction", self.friction)?;
        check_finite("restitution", self.restitution)?;
        if !(0.0..=1.0).contains(&self.restitution) {
            return Err(crate::Error::OutOfRange {
                field: "restitution",
                value: self.restitution,
                min: 0.0,
                max: 1.0,
            });
        }
        check_non_negative("rolling_friction", self.rolling_friction)?;
        if let Some(threshold) = self.force_event_threshold {
            check_non_negative("force_event_threshold", threshold)?;
        }
        Ok(self)
    }
}

impl From<ColliderShape> for ColliderDesc {
    fn from(shape: ColliderShape) -> Self {
        Self::new(shape)
    }
}

/// A collider as a world stores it: its (checked) description, its body, the parry3d shape built from it, and
/// its mass properties in the body frame.
#[derive(Debug, Clone)]
pub struct Collider {
    pub(crate) desc: ColliderDesc,
    pub(crate) body: BodyHandle,
    pub(crate) shape: SharedShape,
    /// In the body frame, `None` when the density is 0 or the shape encloses no volume.
    pub(crate) mass: Option<MassProperties>,
}

impl Collider {
    /// Checks `desc` and builds the collider for `body`.
    pub(crate) fn new(desc: ColliderDesc, body: BodyHandle) -> Result<Self, crate::Error> {
        let shape = desc.shape.to_parry()?;
        Self::with_shape(desc, body, shape)
    }

    /// Checks `desc` (all but its shape) and builds the collider around an already built `shape`.
    pub(crate) fn with_shape(
        desc: ColliderDesc,
        body: BodyHandle,
        shape: SharedShape,
    ) -> Result<Self, crate::Error> {
        let desc = desc.checked_material()?;
        let mass = mass_of(&shape, desc.density, desc.local_pose)?;
        Ok(Self {
            desc,
            body,
            shape,
            mass,
        })
    }

    /// The description (as checked on insertion, with the current settings).
    #[must_use]
    pub fn desc(&self) -> &ColliderDesc {
        &self.desc
    }

    /// The body it is attached to.
    #[must_use]
    pub fn body(&self) -> BodyHandle {
        self.body
    }

    /// The parry3d shape built from the description.
    #[must_use]
    pub fn shape(&self) -> &SharedShape {
        &self.shape
    }

    /// The pose on the body.
    #[must_use]
    pub fn local_pose(&self) -> Pose {
        self.desc.local_pose
    }

    /// The world pose for a body at `body_pose`.
    #[must_use]
    #[inline]
    pub fn world_pose(&self, body_pose: Pose) -> Pose {
        // Most colliders sit at their body's origin: no composition to compute (the same pose but for the
        // sign of a zero).
        if self.desc.local_pose == Pose::IDENTITY {
            return body_pose;
        }
        body_pose.mul_pose(&self.desc.local_pose)
    }

    /// The mass properties this collider adds to its body, in the body frame (`None` for density 0, a shape
    /// without volume, or a disabled collider).
    #[must_use]
    pub fn mass_properties(&self) -> Option<MassProperties> {
        self.mass.filter(|_| self.desc.enabled)
    }

    /// Whether it is a sensor.
    #[must_use]
    pub fn is_sensor(&self) -> bool {
        self.desc.is_sensor
    }

    /// Whether it is enabled.
    #[must_use]
    pub fn is_enabled(&self) -> bool {
        self.desc.enabled
    }

    /// Its collision groups.
    #[must_use]
    pub fn groups(&self) -> CollisionGroups {
        self.desc.groups
    }
}

/// The mass properties of `shape` at `density`, placed at `local_pose` in the body frame: parry's mass,
/// centre and principal inertia, converted to Rebound's [`MassProperties`] at this one place.
///
/// `None` for density 0 and for shapes that enclose no volume (height fields, open meshes).
///
/// # Errors
/// Mass properties that overflow (huge shapes at high density), as [`ShapeError::MassProperties`].
pub(crate) fn mass_of(
    shape: &SharedShape,
    density: f32,
    local_pose: Pose,
) -> Result<Option<MassProperties>, ShapeError> {
    if density == 0.0 {
        return Ok(None);
    }
    // parry at unit density, scaled here: parry reports an overflowing mass (1/0) as 0, indistinguishable
    // from a shape without volume, while the product below overflows to ∞ and is refused.
    let unit = shape.mass_properties(1.0);
    let volume = unit.mass();
    if volume.is_nan() || volume <= 0.0 {
        // No enclosed volume (height fields, open or inside-out meshes): no mass to add.
        return Ok(None);
    }
    let inertia = unit.reconstruct_inertia_matrix() * density;
    // R·diag(I)·Rᵀ is symmetric up to rounding; make it exactly symmetric for the tensor check.
    let inertia = (inertia + inertia.transpose()) * 0.5;
    let properties = MassProperties::from_inertia_tensor(volume * density, unit.local_com, inertia)
        .map_err(|source| ShapeError::MassProperties { density, source })?;
    let placed = properties
        .transformed(local_pose)
        .map_err(|source| ShapeError::MassProperties { density, source })?;
    Ok(Some(placed))
}

/// Checks that the solver can use `mass` ([`MassProperties::validated`]: finite centre and tensor, finite
/// inverses), and that its inverse tensor as the solver computes it is finite.
pub(crate) fn check_solvable(mass: &MassProperties) -> Result<(), DynamicsError> {
    mass.validated()?;
    if !mass.local_inv_inertia().is_finite() {
        return Err(DynamicsError::InvalidInertia {
            field: "inertia",
            value: mass.local_inertia(),
        });
    }
    Ok(())
}
