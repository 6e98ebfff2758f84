//! Sensor overlaps, computed after each step (after the world's events stage) at the new poses, from the
//! refreshed BVH: which non-sensor colliders overlap each enabled sensor, and the enter/exit events that
//! follow from the previous overlaps.
//!
//! A pair whose bodies are both inactive (asleep or fixed) is not tested again: it keeps its previous state,
//! so a sleeping body resting in a fixed trigger stays inside it without a cost per step.

use crate::broad_phase::{BroadPhase, is_active, world_aabb};
use crate::shape::to_parry_pose;
use crate::{ColliderHandle, ColliderSet, Event};
use parry3d::bounding_volume::BoundingVolume;
use rebound_world::BodySet;

/// Whether some collider of a set is a sensor, with the [`ColliderSet::revision`] it was read at: read again
/// only after the set changed, so that a world without sensors pays no pass over its colliders per step.
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct SensorPresence(Option<(u64, bool)>);

impl SensorPresence {
    /// Whether `colliders` holds a sensor (enabled or not).
    pub(crate) fn any(&mut self, colliders: &ColliderSet) -> bool {
        let revision = colliders.revision();
        match self.0 {
            Some((read_at, any)) if read_at == revision => any,
            _ => {
                let any = colliders.iter().any(|(_, c)| c.desc.is_sensor);
                self.0 = Some((revision, any));
                any
            }
        }
    }
}

/// Recomputes the overlaps (sorted (sensor, other) pairs) and appends enter/exit events to `events`.
pub(crate) fn update_sensors(
    colliders: &ColliderSet,
    bodies: &BodySet,
    broad_phase: &BroadPhase,
    overlaps: &mut Vec<(ColliderHandle, ColliderHandle)>,
    events: &mut Vec<Event>,
) {
    let mut next = Vec::new();
    let mut candidates = Vec::new();
    for (sensor_handle, sensor) in colliders.iter() {
        if !sensor.desc.is_sensor || !sensor.desc.enabled {
            continue;
        }
        let Some(sensor_body) = bodies.get(sensor.body) else {
            continue;
        };
        let aabb = world_aabb(sensor, sensor_body);
        broad_phase.candidates(
            colliders,
            bodies,
            |other| other.intersects(&aabb),
            &mut candidates,
        );
        let sensor_pose = to_parry_pose(sensor.world_pose(sensor_body.pose()));
        for &other_handle in &candidates {
            let Some(other) = colliders.get(other_handle) else {
                continue;
            };
            let Some(other_body) = bodies.get(other.body) else {
                continue;
            };
            if other.desc.is_sensor
                || !other.desc.enabled
                || other.body == sensor.body
                || !sensor.desc.groups.interacts_with(other.desc.groups)
            {
                continue;
            }
            let pair = (sensor_handle, other_handle);
            let overlapping = if is_active(sensor_body) || is_active(other_body) {
                let other_pose = to_parry_pose(other.world_pose(other_body.pose()));
                parry3d::query::intersection_test(
                    &sensor_pose,
                    sensor.shape.as_ref(),
                    &other_pose,
                    other.shape.as_ref(),
                )
                .is_ok_and(|hit| hit.intersecting)
            } else {
                overlaps.binary_search(&pair).is_ok()
            };
            if overlapping {
                next.push(pair);
            }
        }
    }
    next.sort_unstable();
    next.dedup();
    for pair in &next {
        if overlaps.binary_search(pair).is_err() {
            events.push(Event::SensorEntered {
                sensor: pair.0,
                collider: pair.1,
            });
        }
    }
    for pair in overlaps.iter() {
        if next.binary_search(pair).is_err() {
            events.push(Event::SensorExited {
                sensor: pair.0,
                collider: pair.1,
            });
        }
    }
    *overlaps = next;
}
