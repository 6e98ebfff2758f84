//! The plugin's cost per step on SCENES.md's `balls` scene (4,096 balls falling into a pile), against the bare
//! facade: the same scene built as entities, stepped once per `App::update`, next to the suite's `Balls`
//! stepped with `PhysicsWorld::step`. Both worlds are checked to stay bit-identical, so both do the same
//! physics and the difference is the plugin's work (prepare, writeback, change detection, schedule).
//!
//! Meant for instruction counts, which machine load does not disturb:
//!
//! ```text
//! cargo bench -p rebound-bevy --bench plugin_overhead --no-run
//! valgrind --tool=callgrind --toggle-collect='*measured_facade_steps*' <bench binary> facade
//! valgrind --tool=callgrind --toggle-collect='*measured_plugin_frames*' <bench binary> plugin
//! ```
//!
//! Without valgrind it prints the wall-clock time per step of each, for a rough look.

#![allow(clippy::print_stdout, reason = "a bench prints its results")]

use bevy_app::App;
use bevy_time::{Fixed, Time, TimePlugin, TimeUpdateStrategy};
use bevy_transform::components::Transform;
use core::time::Duration;
use rebound::prelude::*;
use rebound_bevy::prelude::{Body, Collider};
use rebound_bevy::{Physics, PhysicsSettings, ReboundPlugin};
use rebound_suite::XorShift64Star;
use rebound_suite::scenes::{Balls, DT, Scene, SceneOptions, balls};
use std::time::Instant;

/// Steps run before the measured ones: the pile is forming, with contacts everywhere.
const WARM_UP: usize = 60;
/// Steps measured.
const MEASURED: usize = 20;

/// The `balls` scene as entities, spawned in the order `Balls::new` inserts bodies.
fn plugin_app() -> App {
    let options = SceneOptions::default();
    let mut app = App::new();
    app.add_plugins((
        TimePlugin,
        ReboundPlugin::default().with_settings(PhysicsSettings {
            world: options.settings(Vec3::new(0.0, -9.81, 0.0)),
            paused: false,
        }),
    ));
    app.insert_resource(Time::<Fixed>::from_duration(Duration::from_secs_f32(DT)));
    app.insert_resource(TimeUpdateStrategy::FixedTimesteps(1));
    // Bevy's clock starts at the first update, which runs no fixed step.
    app.update();
    app.world_mut().spawn((
        Body::fixed(),
        Collider::cuboid(Vec3::new(100.0, 0.5, 100.0)),
        Transform::from_xyz(0.0, -0.5, 0.0),
    ));
    let mut rng = XorShift64Star::new(balls::SEED);
    let side = balls::SIDE;
    let centre = (side - 1) as f32 / 2.0;
    for i in 0..side {
        for j in 0..balls::LAYERS {
            for k in 0..side {
                let jx = rng.uniform(-balls::JITTER, balls::JITTER);
                let jz = rng.uniform(-balls::JITTER, balls::JITTER);
                let x = (i as f32 - centre) * balls::SPACING + jx;
                let y = 0.6 + j as f32 * balls::SPACING;
                let z = (k as f32 - centre) * balls::SPACING + jz;
                app.world_mut().spawn((
                    Body::new(BodyDesc::dynamic().with_can_sleep(options.sleep)),
                    Collider::new(ColliderDesc::ball(balls::RADIUS).with_density(1.0)),
                    Transform::from_xyz(x, y, z),
                ));
            }
        }
    }
    app
}

#[inline(never)]
fn measured_facade_steps(scene: &mut Balls) {
    for _ in 0..MEASURED {
        scene.step();
    }
}

#[inline(never)]
fn measured_plugin_frames(app: &mut App) {
    for _ in 0..MEASURED {
        app.update();
    }
}

fn main() -> Result<(), Error> {
    let which = std::env::args().nth(1).unwrap_or_default();
    let run_facade = which != "plugin";
    let run_plugin = which != "facade";
    let mut digests = (None, None);
    if run_facade {
        let mut scene = Balls::new(SceneOptions::default(), balls::SIDE)?;
        for _ in 0..WARM_UP {
            scene.step();
        }
        let start = Instant::now();
        measured_facade_steps(&mut scene);
        let per_step = start.elapsed() / MEASURED as u32;
        digests.0 = Some(scene.world().state_digest());
        println!(
            "facade: {per_step:?} per step (wall clock), digest {:016x}",
            scene.world().state_digest()
        );
    }
    if run_plugin {
        let mut app = plugin_app();
        let dt = app
            .world()
            .resource::<Time<Fixed>>()
            .timestep()
            .as_secs_f32();
        assert_eq!(
            dt.to_bits(),
            DT.to_bits(),
            "the app steps by the scene's dt"
        );
        for _ in 0..WARM_UP {
            app.update();
        }
        let start = Instant::now();
        measured_plugin_frames(&mut app);
        let per_step = start.elapsed() / MEASURED as u32;
        let physics = app.world().resource::<Physics>();
        digests.1 = Some(physics.state_digest());
        println!(
            "plugin: {per_step:?} per step (wall clock), {} steps, digest {:016x}",
            physics.world().step_count(),
            physics.state_digest()
        );
    }
    if let (Some(facade), Some(plugin)) = digests {
        assert_eq!(facade, plugin, "the two worlds must stay bit-identical");
        println!("bit-identical: yes");
    }
    Ok(())
}
