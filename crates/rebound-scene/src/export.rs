//! A world as a scene: what [`Scene::from_world`] reads back from a [`PhysicsWorld`] — its settings, every
//! body with its colliders, every joint with its bodies — so that a scene built in code can be written to a
//! file that builds the same world.

use crate::{Scene, SceneBody, SceneJoint};
use rebound::RigidBody;
use rebound::prelude::*;
use std::collections::HashMap;

/// The description that builds `body` as it is now (pose, velocities, flags), with `mass_properties` the
/// body's own unless a collider gives it mass.
fn body_desc(body: &RigidBody, colliders_give_mass: bool) -> BodyDesc {
    BodyDesc {
        body_type: body.body_type(),
        position: body.position(),
        rotation: body.rotation(),
        linear_velocity: body.linear_velocity(),
        angular_velocity: body.angular_velocity(),
        mass_properties: if colliders_give_mass {
            MassProperties::default()
        } else {
            *body.mass_properties()
        },
        gravity_scale: body.gravity_scale(),
        linear_damping: body.linear_damping(),
        angular_damping: body.angular_damping(),
        integrator: body.integrator(),
        gyroscopic: body.gyroscopic(),
        sleeping: body.is_sleeping(),
        can_sleep: body.can_sleep(),
        locked_axes: body.locked_axes(),
    }
}

impl Scene {
    /// The scene that builds `world` as it is now: its settings, its bodies in handle order with their
    /// colliders in insertion order, its joints in handle order. Forces waiting to be applied, contacts and
    /// warm-start impulses are not part of a scene; for a world that has not stepped, building the scene
    /// makes the same calls the world was made with and gives the same
    /// [`PhysicsWorld::state_digest`] after any number of steps.
    ///
    /// A body's `mass_properties` is written only when no collider of it has density (otherwise the colliders
    /// give the mass). A body whose mass was set with [`PhysicsWorld::set_body_mass_properties`] while its
    /// colliders also have density is not described exactly.
    #[must_use]
    pub fn from_world(world: &PhysicsWorld) -> Self {
        let mut index = HashMap::new();
        let mut bodies = Vec::with_capacity(world.bodies().len());
        for (handle, body) in world.bodies().iter() {
            let colliders: Vec<ColliderDesc> = world
                .colliders()
                .of_body(handle)
                .iter()
                .filter_map(|&c| world.collider(c).map(|c| c.desc().clone()))
                .collect();
            let gives_mass = colliders.iter().any(|c| c.enabled && c.density > 0.0);
            index.insert(handle, bodies.len());
            bodies.push(SceneBody {
                name: String::new(),
                body: body_desc(body, gives_mass),
                colliders,
            });
        }
        let joints = world
            .world()
            .joints()
            .filter_map(|(handle, joint)| {
                let (a, b) = world.joint_bodies(handle)?;
                Some(SceneJoint {
                    body_a: a.and_then(|a| index.get(&a).copied()),
                    body_b: *index.get(&b)?,
                    joint: *joint,
                    contacts_enabled: world.joint_contacts_enabled(handle).unwrap_or(true),
                })
            })
            .collect();
        Self {
            settings: *world.settings(),
            bodies,
            joints,
            ..Self::default()
        }
    }
}
