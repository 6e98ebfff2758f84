//! A headless app with the plugin and a hand-driven clock, and helpers to read its physics.

use bevy_app::App;
use bevy_ecs::entity::Entity;
use bevy_ecs::message::Messages;
use bevy_time::{Fixed, Time, TimePlugin, TimeUpdateStrategy};
use rebound::RigidBody;
use rebound::prelude::*;
use rebound_bevy::{Physics, PhysicsError, PhysicsEvent, PhysicsSettings, ReboundPlugin};

/// An app with the plugin on `settings`, running exactly one fixed step per `update` from now on (Bevy's
/// clock starts at the first update, which runs no fixed step: it is run here, on an empty world).
pub fn app_with(settings: WorldSettings) -> App {
    let mut app = App::new();
    app.add_plugins((
        TimePlugin,
        ReboundPlugin::default().with_settings(PhysicsSettings {
            world: settings,
            paused: false,
        }),
    ));
    app.insert_resource(TimeUpdateStrategy::FixedTimesteps(1));
    app.update();
    app
}

/// An app with the default settings.
pub fn app() -> App {
    app_with(WorldSettings::default())
}

/// The fixed step length the app uses (s): Bevy's default timestep, 1/64 s, exact in `f32`.
pub fn dt(app: &App) -> f32 {
    app.world()
        .resource::<Time<Fixed>>()
        .timestep()
        .as_secs_f32()
}

/// The physics resource.
pub fn physics(app: &App) -> &Physics {
    app.world().resource::<Physics>()
}

/// The body of an entity in the plugin's world.
pub fn body(app: &App, entity: Entity) -> Option<&RigidBody> {
    let physics = physics(app);
    physics
        .body_handle(entity)
        .and_then(|h| physics.world().body(h))
}

/// Takes every physics event sent since the last call.
pub fn take_events(app: &mut App) -> Vec<PhysicsEvent> {
    let mut messages = app.world_mut().resource_mut::<Messages<PhysicsEvent>>();
    messages.drain().collect()
}

/// Takes every physics error sent since the last call.
pub fn take_errors(app: &mut App) -> Vec<PhysicsError> {
    let mut messages = app.world_mut().resource_mut::<Messages<PhysicsError>>();
    messages.drain().collect()
}

/// The bit patterns of some floats, for bit-exact comparisons.
pub fn bits<const N: usize>(values: [f32; N]) -> [u32; N] {
    values.map(f32::to_bits)
}
