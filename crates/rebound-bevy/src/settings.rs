//! [`PhysicsSettings`]: the resource that configures the world and the plugin. Read by the prepare systems
//! (world settings, when the resource changes) and the step system (pause).

use bevy_ecs::resource::Resource;
use rebound::prelude::WorldSettings;

/// The plugin's settings. Changing the resource applies the world settings at the next step; invalid ones
/// are refused with a [`crate::PhysicsError::Settings`] and the previous ones stay.
#[derive(Resource, Debug, Clone, Copy, PartialEq, Default)]
pub struct PhysicsSettings {
    /// The world's settings: gravity (m/s², default (0, −9.81, 0)), substeps, contact softness, sleep. The
    /// step length is the schedule's `Time` delta (the fixed timestep in `FixedPostUpdate`), not
    /// `world.fixed_dt`. Default: [`WorldSettings::default`].
    pub world: WorldSettings,
    /// While true the world is not stepped (edits still reach it). Default: false.
    pub paused: bool,
}
