//! `PhysicsWorld`'s colliders: attaching, removing and editing them, with their mass summed into their body
//! and the bodies resting on them woken.

use super::PhysicsWorld;
use crate::broad_phase::aabb_at;
use crate::collider::check_solvable;
use crate::{
    Collider, ColliderDesc, ColliderHandle, ColliderSet, CollisionGroups, Error, ShapeError,
};
use parry3d::bounding_volume::{Aabb, BoundingVolume};
use rebound_dynamics::{MassProperties, RigidBody};
use rebound_math::Pose;
use rebound_world::{BodyHandle, WorldError};

impl PhysicsWorld {
    /// Attaches a collider to `body` and adds its mass (if its density is > 0) to the body's: the body's
    /// mass properties become the combination of its colliders'. Wakes the body.
    ///
    /// # Errors
    /// A stale body, or an invalid description: [`Error::Shape`] for the shape (and
    /// [`crate::ShapeError::NoVolume`] for a shape without volume and with density > 0 on a dynamic body:
    /// an open mesh, a height field, a half-space), [`Error::Math`] or [`Error::OutOfRange`] naming a
    /// material field. The world is unchanged.
    pub fn insert_collider(
        &mut self,
        desc: impl Into<ColliderDesc>,
        body: BodyHandle,
    ) -> Result<ColliderHandle, Error> {
        let target = self.world.body(body).ok_or(WorldError::StaleBody(body))?;
        let (body_pose, dynamic) = (target.pose(), target.is_dynamic());
        let collider = Collider::new(desc.into(), body)?;
        if dynamic && collider.desc.density > 0.0 && collider.mass.is_none() {
            return Err(ShapeError::NoVolume {
                kind: collider.desc.shape.kind_name(),
            }
            .into());
        }
        let mass = self.body_mass(body, None, Some(&collider))?;
        let backend = self.world.backend_mut();
        let handle = backend.colliders.insert(collider).ok_or(Error::Full)?;
        if let Some(collider) = backend.colliders.get(handle) {
            backend.broad_phase.insert_leaf(handle, collider, body_pose);
        }
        // A collider in a freed slot has its predecessor's manifold keys: nothing may be recycled.
        self.world.forget_contact_bases(body);
        self.set_mass(body, mass);
        let boxes: Vec<Aabb> = self.collider_aabb(handle).into_iter().collect();
        self.wake_bodies_touching(&boxes);
        Ok(handle)
    }

    /// Removes a collider and takes its mass out of its body's. Wakes the body.
    ///
    /// # Errors
    /// [`Error::StaleCollider`].
    pub fn remove_collider(&mut self, handle: ColliderHandle) -> Result<ColliderDesc, Error> {
        let body = self
            .collider(handle)
            .ok_or(Error::StaleCollider(handle))?
            .body();
        let mass = if self.world.body(body).is_some() {
            Some(self.body_mass(body, Some((handle, None)), None)?)
        } else {
            None
        };
        let boxes: Vec<Aabb> = self.collider_aabb(handle).into_iter().collect();
        let backend = self.world.backend_mut();
        let collider = backend
            .colliders
            .remove(handle)
            .ok_or(Error::StaleCollider(handle))?;
        backend.broad_phase.remove_leaf(handle);
        self.world.forget_contact_bases(body);
        if let Some(mass) = mass {
            self.set_mass(body, mass);
        }
        self.wake_bodies_touching(&boxes);
        Ok(collider.desc)
    }

    /// The collider behind `handle`.
    #[must_use]
    pub fn collider(&self, handle: ColliderHandle) -> Option<&Collider> {
        self.world.backend().colliders.get(handle)
    }

    /// All colliders.
    #[must_use]
    pub fn colliders(&self) -> &ColliderSet {
        &self.world.backend().colliders
    }

    /// Changes a collider's density (kg/m³, ≥ 0) and its body's mass. Wakes the body.
    ///
    /// # Errors
    /// A stale handle; a negative or non-finite density; mass properties that overflow.
    pub fn set_collider_density(
        &mut self,
        handle: ColliderHandle,
        density: f32,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.density = density)
    }

    /// Moves a collider on its body (pose relative to the body origin) and updates the body's mass. Wakes
    /// the body.
    ///
    /// # Errors
    /// A stale handle; a non-finite position or a non-unit rotation.
    pub fn set_collider_local_pose(
        &mut self,
        handle: ColliderHandle,
        local_pose: Pose,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.local_pose = local_pose)
    }

    /// Changes a collider's friction coefficient (≥ 0). Wakes its body.
    ///
    /// # Errors
    /// A stale handle; a negative or non-finite value.
    pub fn set_collider_friction(
        &mut self,
        handle: ColliderHandle,
        friction: f32,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.friction = friction)
    }

    /// Changes a collider's coefficient of restitution (in [0, 1]). Wakes its body.
    ///
    /// # Errors
    /// A stale handle; a value outside [0, 1].
    pub fn set_collider_restitution(
        &mut self,
        handle: ColliderHandle,
        restitution: f32,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.restitution = restitution)
    }

    /// Changes a collider's collision groups. Wakes its body.
    ///
    /// # Errors
    /// A stale handle.
    pub fn set_collider_groups(
        &mut self,
        handle: ColliderHandle,
        groups: CollisionGroups,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.groups = groups)
    }

    /// Makes a collider a sensor or a solid collider. Wakes its body.
    ///
    /// # Errors
    /// A stale handle.
    pub fn set_collider_sensor(
        &mut self,
        handle: ColliderHandle,
        is_sensor: bool,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.is_sensor = is_sensor)
    }

    /// Enables or disables a collider (a disabled collider takes no part in collisions, sensors, queries or
    /// its body's mass). Wakes its body.
    ///
    /// # Errors
    /// A stale handle.
    pub fn set_collider_enabled(
        &mut self,
        handle: ColliderHandle,
        enabled: bool,
    ) -> Result<(), Error> {
        self.edit_collider(handle, |desc| desc.enabled = enabled)
    }

    /// Applies `edit` to a copy of a collider's description (not its shape), checks it, recomputes the body's
    /// mass, and only then commits both.
    fn edit_collider(
        &mut self,
        handle: ColliderHandle,
        edit: impl FnOnce(&mut ColliderDesc),
    ) -> Result<(), Error> {
        let old = self.collider(handle).ok_or(Error::StaleCollider(handle))?;
        let mut desc = old.desc.clone();
        edit(&mut desc);
        let body = old.body;
        let updated = Collider::with_shape(desc, body, old.shape.clone())?;
        let body_pose = self.world.body(body).map(RigidBody::pose);
        let mass = match body_pose {
            Some(_) => Some(self.body_mass(body, Some((handle, Some(&updated))), None)?),
            None => None,
        };
        let mut boxes: Vec<Aabb> = self.collider_aabb(handle).into_iter().collect();
        let backend = self.world.backend_mut();
        if let Some(slot) = backend.colliders.get_mut(handle) {
            *slot = updated;
        }
        if let (Some(pose), Some(collider)) = (body_pose, backend.colliders.get(handle)) {
            backend.broad_phase.insert_leaf(handle, collider, pose);
        }
        // A moved collider's contacts cannot be recycled (its body's pose did not change).
        self.world.forget_contact_bases(body);
        if let Some(mass) = mass {
            self.set_mass(body, mass);
        }
        boxes.extend(self.collider_aabb(handle));
        self.wake_bodies_touching(&boxes);
        Ok(())
    }

    /// The box of a collider at its body's current pose, grown by the speculative margin.
    pub(super) fn collider_aabb(&self, handle: ColliderHandle) -> Option<Aabb> {
        let collider = self.collider(handle)?;
        let body = self.world.body(collider.body())?;
        Some(aabb_at(collider, body.pose()).loosened(self.settings().speculative_margin))
    }

    /// Wakes the bodies whose colliders overlap any of `boxes`: what rested on a collider that was removed,
    /// moved or changed must notice (a sleeping body is never tested against a fixed one, so nothing else
    /// would wake it).
    pub(super) fn wake_bodies_touching(&mut self, boxes: &[Aabb]) {
        // Nothing asleep, nothing to wake: building a scene of n bodies before its first step would otherwise
        // test every collider for every insertion (the query tree is stale until the step), O(n²).
        if boxes.is_empty() || !self.world.has_sleeping_bodies() {
            return;
        }
        let backend = self.world.backend();
        let mut handles = Vec::new();
        backend.broad_phase.candidates(
            &backend.colliders,
            self.world.bodies(),
            |other| boxes.iter().any(|b| b.intersects(other)),
            &mut handles,
        );
        // The tree's leaves may be larger than their colliders' boxes, by as much as the tree's history made
        // them (a restored world's start tight): each candidate's own box at its body's pose decides, so that
        // the same calls on the same state wake the same bodies.
        let all = self.world.bodies();
        let mut bodies: Vec<BodyHandle> = handles
            .iter()
            .filter_map(|&h| backend.colliders.get(h))
            .filter(|c| {
                all.get(c.body()).is_some_and(|body| {
                    body.is_sleeping() && {
                        let own = aabb_at(c, body.pose());
                        boxes.iter().any(|b| b.intersects(&own))
                    }
                })
            })
            .map(Collider::body)
            .collect();
        bodies.sort_unstable();
        bodies.dedup();
        for body in bodies {
            let _ = self.world.wake_body(body);
        }
    }

    /// The mass properties of `body` from its colliders, with one collider replaced (or removed, `None`) and
    /// one added: the combination of the parts with mass, or the body's own mass properties if there are none.
    pub(super) fn body_mass(
        &self,
        body: BodyHandle,
        replace: Option<(ColliderHandle, Option<&Collider>)>,
        add: Option<&Collider>,
    ) -> Result<MassProperties, Error> {
        let colliders = &self.world.backend().colliders;
        let mut parts: Vec<MassProperties> = colliders
            .of_body(body)
            .iter()
            .filter_map(|&h| match replace {
                Some((replaced, with)) if replaced == h => with,
                _ => colliders.get(h),
            })
            .filter_map(Collider::mass_properties)
            .collect();
        parts.extend(add.and_then(Collider::mass_properties));
        if parts.is_empty() {
            return Ok(self.own_mass.get(&body).copied().unwrap_or_default());
        }
        let combined = MassProperties::combine(&parts)?;
        check_solvable(&combined)?;
        Ok(combined)
    }

    /// Gives `body` new mass properties and wakes it.
    pub(super) fn set_mass(&mut self, body: BodyHandle, mass: MassProperties) {
        if let Some(b) = self.world.body_mut(body) {
            b.set_mass_properties(mass);
        }
        let _ = self.world.wake_body(body);
    }
}
