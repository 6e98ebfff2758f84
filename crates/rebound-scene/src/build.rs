//! Building a [`PhysicsWorld`] from a [`Scene`]: every body, collider and joint goes through the engine's own
//! checked insertion, in the scene's order, so a file builds the same world (the same handles, the same
//! bits) as code making the same calls. The first refusal stops the build and names its item.

use crate::error::Place;
use crate::{Scene, SceneError};
use rebound::prelude::*;

/// A scene built into a world, with the handle of every body and joint in the scene's order.
#[derive(Debug)]
pub struct BuiltScene {
    /// The world, ready to step.
    pub world: PhysicsWorld,
    /// `bodies[i]` is the handle of the scene's body `i`.
    pub bodies: Vec<BodyHandle>,
    /// `joints[k]` is the handle of the scene's joint `k`.
    pub joints: Vec<JointHandle>,
}

/// A place without a location (the scene may not come from text; [`crate::load`] adds it).
fn at(item: impl Into<String>) -> Place {
    Place {
        item: item.into(),
        location: None,
    }
}

fn invalid(item: impl Into<String>) -> impl FnOnce(Error) -> SceneError {
    move |source| SceneError::Invalid {
        place: at(item),
        source: Box::new(source),
    }
}

impl Scene {
    /// Checks the scene and builds its world.
    ///
    /// # Errors
    /// The first item the engine refuses, as a [`SceneError`] naming the item (`bodies[3].colliders[0]`),
    /// the field and the value; a joint naming a body the scene does not have; unusable run settings or mass
    /// properties. Nothing is returned half-built.
    pub fn build(&self) -> Result<BuiltScene, SceneError> {
        self.check_run()?;
        let mut world = PhysicsWorld::new(self.settings).map_err(invalid("settings"))?;
        let mut bodies = Vec::with_capacity(self.bodies.len());
        for (i, body) in self.bodies.iter().enumerate() {
            check_mass(&format!("bodies[{i}].body"), &body.body.mass_properties)?;
            let handle = world
                .insert_body(body.body)
                .map_err(invalid(format!("bodies[{i}].body")))?;
            for (j, collider) in body.colliders.iter().enumerate() {
                world
                    .insert_collider(collider.clone(), handle)
                    .map_err(invalid(format!("bodies[{i}].colliders[{j}]")))?;
            }
            bodies.push(handle);
        }
        let mut joints = Vec::with_capacity(self.joints.len());
        for (k, entry) in self.joints.iter().enumerate() {
            let item = format!("joints[{k}]");
            let body = |field: &'static str, index: usize| {
                bodies
                    .get(index)
                    .copied()
                    .ok_or_else(|| SceneError::UnknownBody {
                        place: at(item.clone()),
                        field,
                        index,
                        body_count: bodies.len(),
                    })
            };
            let body_b = body("body_b", entry.body_b)?;
            let body_a = entry.body_a.map(|a| body("body_a", a)).transpose()?;
            let joint = entry
                .joint
                .validated()
                .map_err(|e| invalid(item.clone())(e.into()))?;
            let handle = match body_a {
                Some(body_a) => world.insert_joint(joint, body_a, body_b),
                None => world.insert_world_joint(joint, body_b),
            }
            .map_err(invalid(item.clone()))?;
            if !entry.contacts_enabled {
                world
                    .set_joint_contacts_enabled(handle, false)
                    .map_err(invalid(item.clone()))?;
            }
            joints.push(handle);
        }
        Ok(BuiltScene {
            world,
            bodies,
            joints,
        })
    }

    fn check_run(&self) -> Result<(), SceneError> {
        let dt = self.run.dt;
        if !(dt.is_finite() && dt > 0.0) {
            return Err(SceneError::InvalidRun {
                place: at("run"),
                field: "dt",
                expected: "finite and > 0 (s)",
                value: format!("{dt:?}"),
            });
        }
        if self.run.steps == 0 {
            return Err(SceneError::InvalidRun {
                place: at("run"),
                field: "steps",
                expected: "at least 1",
                value: "0".to_owned(),
            });
        }
        if let Some(camera) = self.camera {
            let fov = camera.fov_degrees;
            let bad_fov = !(fov > 0.0 && fov < 180.0);
            let bad_pose = !(camera.position.is_finite() && camera.target.is_finite())
                || camera.position == camera.target;
            if bad_fov || bad_pose {
                return Err(SceneError::InvalidRun {
                    place: at("camera"),
                    field: if bad_fov { "fov_degrees" } else { "position" },
                    expected: if bad_fov {
                        "in (0, 180) degrees"
                    } else {
                        "finite and apart from `target`"
                    },
                    value: if bad_fov {
                        format!("{fov:?}")
                    } else {
                        format!("{:?}", camera.position)
                    },
                });
            }
        }
        Ok(())
    }
}

/// Mass properties read from a file bypass [`MassProperties::new`]'s checks, so they are checked here: a
/// finite mass > 0 whose inverse is finite, a finite centre and a finite inertia.
fn check_mass(item: &str, mass: &MassProperties) -> Result<(), SceneError> {
    let bad = |field: &'static str, value: String| {
        Err(SceneError::InvalidMass {
            place: at(item),
            field,
            value,
        })
    };
    let m = mass.mass();
    if !(m.is_finite() && m > 0.0 && m.recip().is_finite()) {
        return bad("mass", format!("{m:?}"));
    }
    let center = mass.local_center_of_mass();
    if !center.is_finite() {
        return bad("local_center_of_mass", format!("{center:?}"));
    }
    let inertia = mass.local_inertia();
    if !inertia.is_finite() {
        return bad("local_inertia", format!("{inertia:?}"));
    }
    Ok(())
}
