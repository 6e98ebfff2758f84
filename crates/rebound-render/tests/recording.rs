//! Pictures and plots of a recording agree with the live world they recorded.

use rebound::prelude::*;
use rebound_record::{Recorder, Recording};
use rebound_render::{
    Camera, RecordingScenes, RenderOptions, RenderScene, TimeHistory, render, time_history,
};

const DT: f32 = 1.0 / 60.0;

/// A ground, a ball falling onto it, and a box hanging from a rope, a new body inserted mid-run.
fn world() -> PhysicsWorld {
    let mut world = PhysicsWorld::new(WorldSettings::default()).expect("settings");
    let ground = world
        .insert_body(BodyDesc::fixed().with_position(Vec3::new(0.0, -0.5, 0.0)))
        .expect("body");
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::new(10.0, 0.5, 10.0)), ground)
        .expect("collider");
    let ball = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(-1.0, 1.0, 0.0)))
        .expect("body");
    world
        .insert_collider(ColliderDesc::ball(0.5), ball)
        .expect("collider");
    let hanging = world
        .insert_body(BodyDesc::dynamic().with_position(Vec3::new(2.0, 2.0, 0.0)))
        .expect("body");
    world
        .insert_collider(ColliderDesc::cuboid(Vec3::splat(0.3)), hanging)
        .expect("collider");
    world
        .insert_world_joint(
            Joint::new(Rope::new(1.5).expect("rope"))
                .with_local_anchors(Vec3::new(2.0, 3.5, 0.0), Vec3::ZERO)
                .expect("anchors"),
            hanging,
        )
        .expect("joint");
    world
}

fn camera() -> Camera {
    Camera {
        position: Vec3::new(0.0, 3.0, 9.0),
        target: Vec3::new(0.5, 1.0, 0.0),
        width: 160,
        height: 120,
        ..Camera::default()
    }
}

#[test]
fn a_recorded_frame_renders_as_the_live_world_did_and_plots_its_diagnostics() {
    let mut world = world();
    let mut recorder = Recorder::new(&world, Vec::new()).expect("recorder");
    recorder.record(&world).expect("first frame");
    let options = RenderOptions {
        contacts: false,
        joints: false,
        ..RenderOptions::default()
    };
    let mut live = Vec::new();
    for step in 1..=40 {
        if step == 20 {
            let late = world
                .insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 3.0, 0.0)))
                .expect("body");
            world
                .insert_collider(ColliderDesc::capsule(0.2, 0.4), late)
                .expect("collider");
        }
        recorder.step(&mut world, DT).expect("step");
        if step % 10 == 0 {
            let scene = RenderScene::from_world(&world).expect("scene");
            live.push(render(&scene, &camera(), &options).expect("render"));
        }
    }
    let bytes = recorder.finish().expect("finish");
    let recording = Recording::read(bytes.as_slice()).expect("read back");
    let mut scenes = RecordingScenes::new(recording.manifest()).expect("manifest");
    let mut replayed = Vec::new();
    for (k, frame) in recording.frames().iter().enumerate() {
        if k > 0 && k % 10 == 0 {
            let scene = scenes.scene(frame).expect("scene");
            // The rope is drawn; the ball lies on the ground, so there are contacts to draw.
            assert_eq!(scene.joints.len(), 1);
            assert_eq!(scene.contacts.len(), frame.contacts.len());
            assert_eq!(scene.objects.len(), if k < 20 { 3 } else { 4 });
            replayed.push(render(&scene, &camera(), &options).expect("render"));
        } else {
            scenes.advance(frame).expect("advance");
        }
    }
    assert_eq!(replayed.len(), 4);
    // Bit for bit: the recording keeps the poses exactly, and both sides colour a body by its index.
    for (i, (a, b)) in live.iter().zip(&replayed).enumerate() {
        assert!(a.rgba() == b.rgba(), "picture {i} differs");
    }

    let history: TimeHistory = time_history(recording.frames());
    assert_eq!(history.time.len(), 41);
    for (k, frame) in recording.frames().iter().enumerate() {
        assert!((history.time[k] - frame.time).abs() < 1e-12);
        let d = frame.diagnostics;
        // The f32 numbers widened exactly: the same bits as f64::from gives.
        let same = |a: f64, b: f32| a.to_bits() == f64::from(b).to_bits();
        assert!(same(history.kinetic_energy[k], d.kinetic_energy));
        assert!(same(history.linear_momentum[k][1], d.linear_momentum.y));
        assert!(same(history.deepest_penetration[k], d.deepest_penetration));
    }
    // Energy, linear and angular momentum, joint error, penetration.
    assert_eq!(history.panels().len(), 5);
    assert!(history.to_svg(&Default::default()).is_ok());
}
