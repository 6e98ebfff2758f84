//! `PhysicsWorld`'s joints: inserting and removing them, and which joined bodies collide with each other.

use super::PhysicsWorld;
use crate::Error;
use crate::broad_phase::ordered;
use rebound_constraints::{Joint, JointState};
use rebound_world::{BodyHandle, JointHandle, WorldError};
use std::collections::BTreeSet;

impl PhysicsWorld {
    /// Connects two bodies with `joint` (its anchor A on `body_a`, anchor B on `body_b`). The two bodies
    /// keep colliding with each other unless [`PhysicsWorld::set_joint_contacts_enabled`] says otherwise.
    /// Wakes both.
    ///
    /// # Errors
    /// An invalid joint ([`Joint::validated`]), a stale handle, or the same body twice. Nothing changes on
    /// error.
    pub fn insert_joint(
        &mut self,
        joint: impl Into<Joint>,
        body_a: BodyHandle,
        body_b: BodyHandle,
    ) -> Result<JointHandle, Error> {
        Ok(self.world.insert_joint(joint.into(), body_a, body_b)?)
    }

    /// Connects `body` to a fixed point of the world: the joint's anchor A is a world point (m). Wakes the
    /// body.
    ///
    /// # Errors
    /// An invalid joint ([`Joint::validated`]) or a stale handle. Nothing changes on error.
    pub fn insert_world_joint(
        &mut self,
        joint: impl Into<Joint>,
        body: BodyHandle,
    ) -> Result<JointHandle, Error> {
        Ok(self.world.insert_world_joint(joint.into(), body)?)
    }

    /// Removes a joint and wakes the bodies it held.
    ///
    /// # Errors
    /// [`WorldError::StaleJoint`].
    pub fn remove_joint(&mut self, handle: JointHandle) -> Result<Joint, Error> {
        let joint = self.world.remove_joint(handle)?;
        if self.joints_without_contacts.remove(&handle) {
            self.update_disabled_pairs();
        }
        Ok(joint)
    }

    /// The joint behind `handle`.
    #[must_use]
    pub fn joint(&self, handle: JointHandle) -> Option<&Joint> {
        self.world.joint(handle)
    }

    /// The joint behind `handle`, mutably (its setters validate). Wakes the bodies it connects.
    pub fn joint_mut(&mut self, handle: JointHandle) -> Option<&mut Joint> {
        self.world.joint_mut(handle)
    }

    /// The solver state of a joint (accumulated impulses, whether it broke).
    #[must_use]
    pub fn joint_state(&self, handle: JointHandle) -> Option<&JointState> {
        self.world.joint_state(handle)
    }

    /// The bodies a joint connects: `(None, b)` for a world joint.
    #[must_use]
    pub fn joint_bodies(&self, handle: JointHandle) -> Option<(Option<BodyHandle>, BodyHandle)> {
        self.world.joint_bodies(handle)
    }

    /// Whether the two bodies of a joint may collide with each other (`None` for a stale handle). Default:
    /// true.
    #[must_use]
    pub fn joint_contacts_enabled(&self, handle: JointHandle) -> Option<bool> {
        self.world
            .joint(handle)
            .map(|_| !self.joints_without_contacts.contains(&handle))
    }

    /// Lets the two bodies of a joint collide with each other, or not (a rope bridge's planks, a ragdoll's
    /// limbs). Contacts stay disabled while at least one unbroken joint between the pair disables them (a
    /// joint that breaks lets its bodies collide again). Wakes both bodies. No effect on world joints.
    ///
    /// # Errors
    /// [`WorldError::StaleJoint`].
    pub fn set_joint_contacts_enabled(
        &mut self,
        handle: JointHandle,
        enabled: bool,
    ) -> Result<(), Error> {
        let (a, b) = self
            .world
            .joint_bodies(handle)
            .ok_or(WorldError::StaleJoint(handle))?;
        if enabled {
            self.joints_without_contacts.remove(&handle);
        } else {
            self.joints_without_contacts.insert(handle);
        }
        self.update_disabled_pairs();
        if let Some(a) = a {
            let _ = self.world.wake_body(a);
        }
        let _ = self.world.wake_body(b);
        Ok(())
    }

    /// Recomputes the backend's set of body pairs without contacts from the (unbroken) joints that disable
    /// them.
    pub(crate) fn update_disabled_pairs(&mut self) {
        let world = &self.world;
        self.joints_without_contacts
            .retain(|&joint| world.joint(joint).is_some());
        let pairs: BTreeSet<(BodyHandle, BodyHandle)> = self
            .joints_without_contacts
            .iter()
            .filter(|&&joint| world.joint_state(joint).is_some_and(|s| !s.broken))
            .filter_map(|&joint| match world.joint_bodies(joint) {
                Some((Some(a), b)) => Some(ordered(a, b)),
                _ => None,
            })
            .collect();
        self.world.backend_mut().disabled_pairs = pairs;
    }
}
