//! The plugin driven frame by frame in a headless `App`, with time advanced by hand (one fixed step of
//! 1/64 s per `update` unless a test says otherwise), so every run is deterministic.

mod support;

mod bad_values_are_errors;
mod ball_falls_as_facade;
mod despawn_removes_everything;
mod events_name_entities;
mod interpolation_midpoint;
mod rollback_is_bit_identical;
mod transform_edit_teleports;
