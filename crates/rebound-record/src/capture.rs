//! [`Tracker`]: what the recorder has told the file so far, and the two things it does each frame — find
//! what was inserted, edited or removed since the last frame (the frame's [`Changes`]), and sample the
//! world's state into a [`Frame`] with handles turned into recording indices.

use crate::contacts::{BodyFrame, write_contacts};
use crate::diagnostics::{diagnostics, inv_mass, joint_error, spring_energy};
use crate::encode::ContactTotals;
use crate::frame::{BodySample, Frame, JointSample, RecordedEvent};
use crate::handle_index::HandleIndex;
use crate::manifest::{
    BodyEntry, Changes, ColliderEntry, JointEntry, JointKindName, LimitsEntry, Manifest,
};
use rebound::{
    BodyHandle, ColliderDesc, ColliderHandle, Event, Joint, JointHandle, MassProperties,
    PhysicsWorld, Quat, RigidBody, Vec3,
};

/// A collider as last described to the file.
#[derive(Debug, Clone)]
struct WrittenCollider {
    handle: ColliderHandle,
    body: u32,
    desc: ColliderDesc,
}

/// A joint as last described to the file.
#[derive(Debug, Clone, Copy)]
struct WrittenJoint {
    handle: JointHandle,
    joint: Joint,
    body_a: Option<u32>,
    body_b: u32,
}

/// The recorder's memory of every object it has described, by recording index.
#[derive(Debug, Default)]
pub(crate) struct Tracker {
    body_index: HandleIndex,
    /// By body index: its handle and the mass properties and gravity scale last written.
    bodies: Vec<(BodyHandle, MassProperties, f32)>,
    collider_index: HandleIndex,
    /// By collider index; `None` once removed.
    colliders: Vec<Option<WrittenCollider>>,
    /// How many entries of `colliders` are `Some`.
    live_colliders: usize,
    /// The world's collider revision when the colliders were last compared (`None` before the first
    /// time): while it holds, no collider was inserted, edited or removed, and none is compared.
    collider_revision: Option<u64>,
    /// The world's body revision when the bodies were last compared, likewise for the bodies.
    body_revision: Option<u64>,
    joint_index: HandleIndex,
    joints: Vec<WrittenJoint>,
    /// By body index: the pose of the last sample, for the contact points.
    frames: Vec<BodyFrame>,
}

impl Tracker {
    /// A tracker that has described everything in `world`, and the manifest describing it.
    pub(crate) fn start(world: &PhysicsWorld) -> (Self, Manifest) {
        let settings = world.settings();
        let mut manifest =
            Manifest::new(settings.fixed_dt, settings.substep_count, settings.gravity);
        let mut tracker = Self::default();
        let changes = tracker.changes(world);
        debug_assert!(changes.colliders.is_empty() && changes.removed_colliders.is_empty());
        manifest.bodies = changes.bodies;
        manifest.joints = changes.joints;
        (tracker, manifest)
    }

    /// The body index of `handle`, if the tracker has seen it.
    fn body(&self, handle: BodyHandle) -> Option<u32> {
        self.body_index.get(handle.into_raw_parts())
    }

    /// What changed in `world` since the last call, now remembered as written.
    pub(crate) fn changes(&mut self, world: &PhysicsWorld) -> Changes {
        let mut changes = Changes::default();
        let revision = world.bodies().revision();
        if self.body_revision != Some(revision) {
            self.body_revision = Some(revision);
            self.body_changes(world, &mut changes);
        }
        let revision = world.colliders().revision();
        if self.collider_revision != Some(revision) {
            self.collider_revision = Some(revision);
            self.collider_changes(world, &mut changes);
        }
        self.joint_changes(world, &mut changes);
        changes
    }

    /// Adds to `changes` the bodies inserted (with their colliders) and those whose mass properties or
    /// gravity scale changed since the last comparison.
    fn body_changes(&mut self, world: &PhysicsWorld, changes: &mut Changes) {
        for (handle, body) in world.bodies().iter() {
            let written = (*body.mass_properties(), body.gravity_scale());
            match self.body(handle) {
                None => {
                    let index = self.bodies.len() as u32;
                    self.body_index.insert(handle.into_raw_parts(), index);
                    self.bodies.push((handle, written.0, written.1));
                    let mut entry = body_entry(index, handle, body);
                    for &collider in world.colliders().of_body(handle) {
                        if let Some(desc) =
                            world.colliders().get(collider).map(rebound::Collider::desc)
                        {
                            entry
                                .colliders
                                .push(self.new_collider(collider, index, desc));
                        }
                    }
                    changes.bodies.push(entry);
                }
                Some(index) => {
                    let Some(known) = self.bodies.get_mut(index as usize) else {
                        continue;
                    };
                    if (known.1, known.2) != written {
                        (known.1, known.2) = written;
                        changes.bodies.push(body_entry(index, handle, body));
                    }
                }
            }
        }
    }

    /// Adds to `changes` the colliders inserted, edited or removed since the last comparison.
    fn collider_changes(&mut self, world: &PhysicsWorld, changes: &mut Changes) {
        // The world's colliders found among the live ones: if that is all of them, none was removed.
        let mut seen = 0;
        for (handle, collider) in world.colliders().iter() {
            let Some(body) = self.body(collider.body()) else {
                continue;
            };
            seen += 1;
            match self.collider_index.get(handle.into_raw_parts()) {
                None => changes
                    .colliders
                    .push(self.new_collider(handle, body, collider.desc())),
                Some(index) => {
                    let Some(Some(known)) = self.colliders.get_mut(index as usize) else {
                        continue;
                    };
                    if known.body != body || known.desc != *collider.desc() {
                        known.body = body;
                        known.desc = collider.desc().clone();
                        changes
                            .colliders
                            .push(collider_entry(index, body, collider.desc()));
                    }
                }
            }
        }
        if seen != self.live_colliders {
            for (index, slot) in self.colliders.iter_mut().enumerate() {
                if let Some(known) = slot
                    && !world.colliders().contains(known.handle)
                {
                    *slot = None;
                    self.live_colliders -= 1;
                    changes.removed_colliders.push(index as u32);
                }
            }
        }
    }

    /// Adds to `changes` the joints inserted or edited since the last call.
    fn joint_changes(&mut self, world: &PhysicsWorld, changes: &mut Changes) {
        for (handle, joint) in world.world().joints() {
            let Some((a, b)) = world.joint_bodies(handle) else {
                continue;
            };
            let body_a = a.and_then(|a| self.body(a));
            let (Some(body_b), true) = (self.body(b), a.is_none() || body_a.is_some()) else {
                continue;
            };
            let written = WrittenJoint {
                handle,
                joint: *joint,
                body_a,
                body_b,
            };
            match self.joint_index.get(handle.into_raw_parts()) {
                None => {
                    let index = self.joints.len() as u32;
                    self.joint_index.insert(handle.into_raw_parts(), index);
                    self.joints.push(written);
                    changes.joints.push(joint_entry(index, &written));
                }
                Some(index) => {
                    let Some(known) = self.joints.get_mut(index as usize) else {
                        continue;
                    };
                    if (known.joint, known.body_a, known.body_b) != (*joint, body_a, body_b) {
                        *known = written;
                        changes.joints.push(joint_entry(index, &written));
                    }
                }
            }
        }
    }

    /// Gives a new collider the next index and returns its entry.
    fn new_collider(
        &mut self,
        handle: ColliderHandle,
        body: u32,
        desc: &ColliderDesc,
    ) -> ColliderEntry {
        let index = self.colliders.len() as u32;
        self.collider_index.insert(handle.into_raw_parts(), index);
        self.colliders.push(Some(WrittenCollider {
            handle,
            body,
            desc: desc.clone(),
        }));
        self.live_colliders += 1;
        collider_entry(index, body, desc)
    }

    /// Fills `frame` (all but step, time, changes and contacts, and the deepest penetration, which
    /// [`Tracker::write_contacts`] finds) with the state of `world`, reusing its buffers.
    pub(crate) fn sample(&mut self, world: &PhysicsWorld, frame: &mut Frame) {
        frame.bodies.clear();
        frame.bodies.extend(self.bodies.iter().map(|&(handle, ..)| {
            world
                .body(handle)
                .map_or(BodySample::REMOVED, |body| BodySample {
                    position: body.position(),
                    rotation: body.rotation(),
                    linear_velocity: body.linear_velocity(),
                    angular_velocity: body.angular_velocity(),
                    present: true,
                    sleeping: body.is_sleeping(),
                    kind: body.body_type().into(),
                })
        }));
        // The contacts are written straight into the frame's bytes (`Tracker::write_contacts`); the
        // frame holds them only when asked for (`Recorder::last_frame`).
        frame.contacts.clear();
        self.frames.clear();
        self.frames.extend(frame.bodies.iter().map(BodyFrame::of));
        frame.joints.clear();
        let mut springs = 0.0;
        for written in &self.joints {
            let sample = self.sample_joint(world, written.handle, &mut springs);
            frame.joints.push(sample.unwrap_or_default());
        }
        frame.events.clear();
        frame
            .events
            .extend(world.events().iter().filter_map(|e| self.event(e)));
        frame.diagnostics = diagnostics(world, springs, &frame.joints);
    }

    /// Appends the CONTACT entries of `world`'s manifolds to `out`, with the poses of the last
    /// [`Tracker::sample`].
    pub(crate) fn write_contacts(&self, world: &PhysicsWorld, out: &mut Vec<u8>) -> ContactTotals {
        write_contacts(world.contacts(), |h| self.body(h), &self.frames, out)
    }

    /// A joint's sample (`None` if it no longer exists); adds its spring energy to `springs` if unbroken.
    fn sample_joint(
        &self,
        world: &PhysicsWorld,
        handle: JointHandle,
        springs: &mut f32,
    ) -> Option<JointSample> {
        let joint = world.joint(handle)?;
        let (a, b) = world.joint_bodies(handle)?;
        let body_a = match a {
            Some(a) => Some(world.body(a)?),
            None => None,
        };
        let body_b = world.body(b)?;
        let state = world.joint_state(handle)?;
        let anchor_a = body_a.map_or(joint.local_anchor_a(), |body| {
            body.pose().transform_point(joint.local_anchor_a())
        });
        let anchor_b = body_b.pose().transform_point(joint.local_anchor_b());
        let rotation_a = body_a.map_or(Quat::IDENTITY, RigidBody::rotation);
        if !state.broken {
            *springs += spring_energy(
                joint,
                anchor_a,
                anchor_b,
                inv_mass(body_a),
                inv_mass(Some(body_b)),
            );
        }
        Some(JointSample {
            anchor_a,
            anchor_b,
            error: joint_error(joint, anchor_a, anchor_b, rotation_a),
            reaction_force: state.reaction_force,
            reaction_torque: state.reaction_torque,
            present: true,
            broken: state.broken,
        })
    }

    /// An engine event with handles as indices; `None` for quarantines, which the format does not record (a
    /// quarantined body shows in the frames as a body at rest).
    fn event(&self, event: &Event) -> Option<RecordedEvent> {
        let collider = |h: ColliderHandle| self.collider_index.get(h.into_raw_parts());
        Some(match *event {
            Event::BodyQuarantined { .. } => return None,
            Event::ContactForce { colliders, force } => RecordedEvent::ContactForce {
                body_a: self.body(force.body_a),
                body_b: self.body(force.body_b),
                collider_a: colliders.and_then(|(a, _)| collider(a)),
                collider_b: colliders.and_then(|(_, b)| collider(b)),
                normal: force.normal,
                total_impulse: force.total_impulse,
                total_force: force.total_force,
                max_impulse_point: force.max_impulse_point,
                max_impulse: force.max_impulse,
            },
            Event::ContactBegan {
                body_a,
                body_b,
                approach_speed,
            } => RecordedEvent::ContactBegan {
                body_a: self.body(body_a),
                body_b: self.body(body_b),
                approach_speed,
            },
            Event::ContactEnded { body_a, body_b } => RecordedEvent::ContactEnded {
                body_a: self.body(body_a),
                body_b: self.body(body_b),
            },
            Event::JointBroken { joint } => RecordedEvent::JointBroken {
                joint: self.joint_index.get(joint.into_raw_parts()),
            },
            Event::BodyFellAsleep { body } => RecordedEvent::BodyFellAsleep {
                body: self.body(body),
            },
            Event::BodyWoke { body } => RecordedEvent::BodyWoke {
                body: self.body(body),
            },
            Event::SensorEntered {
                sensor,
                collider: c,
            } => RecordedEvent::SensorEntered {
                sensor: collider(sensor),
                collider: collider(c),
            },
            Event::SensorExited {
                sensor,
                collider: c,
            } => RecordedEvent::SensorExited {
                sensor: collider(sensor),
                collider: collider(c),
            },
        })
    }
}

/// A body's manifest entry, without colliders.
fn body_entry(index: u32, handle: BodyHandle, body: &RigidBody) -> BodyEntry {
    let mass = body.mass_properties();
    let (slot, generation) = handle.into_raw_parts();
    BodyEntry {
        index,
        handle: [slot, generation],
        kind: body.body_type().into(),
        mass: mass.mass(),
        local_center_of_mass: mass.local_center_of_mass(),
        inertia: mass.local_inertia().transpose().to_cols_array_2d(),
        gravity_scale: body.gravity_scale(),
        colliders: Vec::new(),
    }
}

/// A collider's manifest entry.
fn collider_entry(index: u32, body: u32, desc: &ColliderDesc) -> ColliderEntry {
    ColliderEntry {
        index,
        body,
        shape: desc.shape.clone(),
        local_pose: desc.local_pose,
        density: desc.density,
        friction: desc.friction,
        restitution: desc.restitution,
        rolling_friction: desc.rolling_friction,
        sensor: desc.is_sensor,
        enabled: desc.enabled,
    }
}

/// A joint's manifest entry.
fn joint_entry(index: u32, written: &WrittenJoint) -> JointEntry {
    let joint = &written.joint;
    JointEntry {
        index,
        kind: JointKindName::from(joint.kind()),
        body_a: written.body_a,
        body_b: written.body_b,
        local_anchor_a: joint.local_anchor_a(),
        local_anchor_b: joint.local_anchor_b(),
        local_basis_a: joint.local_basis_a(),
        local_basis_b: joint.local_basis_b(),
        local_axis_a: joint.local_basis_a() * Vec3::X,
        local_axis_b: joint.local_basis_b() * Vec3::X,
        limits: joint.limits().map(|l| LimitsEntry {
            lower: l.lower(),
            upper: l.upper(),
        }),
        length: joint.length(),
        break_force: joint.break_force(),
        break_torque: joint.break_torque(),
        params: serde_json::to_value(joint.kind()).unwrap_or(serde_json::Value::Null),
    }
}
