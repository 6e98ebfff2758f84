//! [`ReboundPlugin`]: registers the resources, messages and systems, and orders them in the physics schedule
//! (`FixedPostUpdate` by default) as three system sets, [`PhysicsSystems::Prepare`] →
//! [`PhysicsSystems::Step`] → [`PhysicsSystems::Writeback`]; transform interpolation runs once per frame after
//! the fixed main loop.

use crate::debug_render::build_debug_render;
use crate::interpolation::interpolate_transforms;
use crate::prepare::{
    apply_forces, apply_mass_overrides, apply_settings, insert_bodies, insert_colliders,
    insert_joints, remove_despawned, sync_body_edits,
};
use crate::writeback::{step_world, writeback};
use crate::{Physics, PhysicsDebugRender, PhysicsError, PhysicsEvent, PhysicsSettings};
use bevy_app::{App, FixedPostUpdate, Plugin, RunFixedMainLoop, RunFixedMainLoopSystems};
use bevy_ecs::schedule::{InternedScheduleLabel, IntoScheduleConfigs, ScheduleLabel, SystemSet};
use rebound::prelude::{PhysicsWorld, WorldSettings};

/// The physics stages, to order your systems against: `my_system.before(PhysicsSystems::Prepare)` runs in
/// the physics schedule before the world sees this step's edits; `.after(PhysicsSystems::Writeback)` sees
/// the new poses and events.
#[derive(SystemSet, Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PhysicsSystems {
    /// Component edits, new and despawned entities, forces and impulses reach the world.
    Prepare,
    /// The world takes one step of the schedule's `Time` delta.
    Step,
    /// Poses, velocities and sleep states are written to the components; events are sent; the debug lines
    /// ([`crate::PhysicsDebugRender`]) are rebuilt.
    Writeback,
}

/// Rebound as a Bevy plugin. Needs Bevy's `TimePlugin` (part of `DefaultPlugins` and `MinimalPlugins`) for the
/// step length; `TransformPlugin` is needed only for `GlobalTransform`s (rendering).
///
/// ```
/// use bevy_app::App;
/// use bevy_time::TimePlugin;
/// use rebound_bevy::prelude::*;
///
/// let mut app = App::new();
/// app.add_plugins((TimePlugin, ReboundPlugin::default()));
/// app.world_mut().spawn((Body::dynamic(), Collider::ball(0.5)));
/// app.update();
/// assert!(app.world().resource::<Physics>().world().bodies().len() <= 1);
/// ```
#[derive(Debug, Clone)]
pub struct ReboundPlugin {
    /// The schedule the world is stepped in. Default: `FixedPostUpdate`.
    pub schedule: InternedScheduleLabel,
    /// The initial settings (also the [`PhysicsSettings`] resource). Default: [`PhysicsSettings::default`].
    pub settings: PhysicsSettings,
}

impl Default for ReboundPlugin {
    fn default() -> Self {
        Self::new(FixedPostUpdate)
    }
}

impl ReboundPlugin {
    /// The plugin stepping the world in `schedule` (whose `Time` delta is the step length).
    #[must_use]
    pub fn new(schedule: impl ScheduleLabel) -> Self {
        Self {
            schedule: schedule.intern(),
            settings: PhysicsSettings::default(),
        }
    }

    /// Sets the initial settings.
    #[must_use]
    pub fn with_settings(mut self, settings: PhysicsSettings) -> Self {
        self.settings = settings;
        self
    }
}

impl Plugin for ReboundPlugin {
    fn build(&self, app: &mut App) {
        // Invalid settings leave the world on the defaults; the first prepare then reports them.
        let world = PhysicsWorld::new(self.settings.world)
            .or_else(|_| PhysicsWorld::new(WorldSettings::default()));
        let world = match world {
            Ok(world) => world,
            Err(error) => {
                log::error!("rebound: no physics world could be made: {error}");
                return;
            }
        };
        app.insert_resource(self.settings)
            .insert_resource(Physics::new(world))
            .init_resource::<PhysicsDebugRender>()
            .add_message::<PhysicsEvent>()
            .add_message::<PhysicsError>();
        let schedule = self.schedule;
        app.configure_sets(
            schedule,
            (
                PhysicsSystems::Prepare,
                PhysicsSystems::Step,
                PhysicsSystems::Writeback,
            )
                .chain(),
        );
        app.add_systems(
            schedule,
            (
                apply_settings,
                remove_despawned,
                insert_bodies,
                sync_body_edits,
                insert_colliders,
                insert_joints,
                apply_mass_overrides,
                apply_forces,
            )
                .chain()
                .in_set(PhysicsSystems::Prepare),
        );
        app.add_systems(schedule, step_world.in_set(PhysicsSystems::Step));
        app.add_systems(
            schedule,
            (writeback, build_debug_render)
                .chain()
                .in_set(PhysicsSystems::Writeback),
        );
        app.add_systems(
            RunFixedMainLoop,
            interpolate_transforms.in_set(RunFixedMainLoopSystems::AfterFixedMainLoop),
        );
    }
}
