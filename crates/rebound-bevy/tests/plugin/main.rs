//! The plugin driven frame by frame in a headless `App`, with time advanced by hand (one fixed step of
//! 1/64 s per `update` unless a test says otherwise), so every run is deterministic.

#![allow(
    clippy::needless_pass_by_value,
    reason = "Bevy system parameters are passed by value"
)]

mod support;

mod bad_values_are_errors;
mod ball_falls_as_facade;
mod debug_lines_outline_colliders;
mod despawn_removes_everything;
mod events_name_entities;
mod forces_targets_and_mass;
mod interpolation_midpoint;
mod rollback_is_bit_identical;
mod schedule_is_configurable;
mod spatial_query_names_entities;
mod transform_edit_teleports;
