//! The [`Collider`] component: a facade [`ColliderDesc`] (any [`rebound::ColliderShape`], material, density,
//! groups, sensor and enabled flags) on an entity. Read by the prepare systems, which attach it to the body
//! of its own entity or, failing that, of its nearest ancestor.

use bevy_ecs::component::Component;
use rebound::prelude::{ColliderDesc, ColliderShape, Vec3};

/// A collider: a shape with a surface material, attached to a body.
///
/// * On an entity with a [`crate::Body`], it sits on that body at `desc.local_pose`.
/// * On a descendant of a body entity (through `ChildOf`), it sits on the nearest ancestor's body, placed by
///   the chain of `Transform`s from the body down to its entity, then by `desc.local_pose`. Editing that
///   entity's own `Transform` moves the collider on its body.
///
/// Editing the component replaces the collider (a new handle; the body's mass is recomputed). An invalid
/// description is refused with a [`crate::PhysicsError`] and the world keeps the collider it had.
///
/// ```
/// use rebound_bevy::prelude::*;
/// let ball = Collider::ball(0.5);
/// let trigger = Collider::new(ColliderDesc::cuboid(Vec3::splat(2.0)).with_sensor(true));
/// assert!(trigger.desc.is_sensor);
/// assert_eq!(ball.desc.density, 1.0);
/// ```
#[derive(Component, Debug, Clone, PartialEq, Default)]
pub struct Collider {
    /// The facade's description: shape, local pose (m, relative to the entity), density (kg/m³), friction,
    /// restitution, rolling friction, groups, sensor and enabled flags, each with the facade's defaults.
    pub desc: ColliderDesc,
}

impl Collider {
    /// A collider from a full description.
    #[must_use]
    pub fn new(desc: impl Into<ColliderDesc>) -> Self {
        Self { desc: desc.into() }
    }

    /// A ball of `radius` (m) with the default material.
    #[must_use]
    pub fn ball(radius: f32) -> Self {
        Self::new(ColliderDesc::ball(radius))
    }

    /// A box of `half_extents` (m) with the default material.
    #[must_use]
    pub fn cuboid(half_extents: Vec3) -> Self {
        Self::new(ColliderDesc::cuboid(half_extents))
    }

    /// A collider of any `shape` with the default material.
    #[must_use]
    pub fn shape(shape: ColliderShape) -> Self {
        Self::new(ColliderDesc::new(shape))
    }
}

impl From<ColliderDesc> for Collider {
    fn from(desc: ColliderDesc) -> Self {
        Self::new(desc)
    }
}
