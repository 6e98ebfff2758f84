//! Recordings and frame dumps for the web viewer's browser tests (`viewer/test/`).
//!
//! ```sh
//! cargo run --release -p rebound-record --example viewer_fixtures -- record cradle OUT.rrec STEPS
//! cargo run --release -p rebound-record --example viewer_fixtures -- record balls OUT.rrec STEPS
//! cargo run --release -p rebound-record --example viewer_fixtures -- frames FILE.rrec N [N …]
//! ```
//!
//! `record` runs Newton's cradle (the `newtons_cradle` example's five balls on ropes, the first released
//! from 30°) or SCENES.md's 4,096-ball pile and records every step. `frames` prints frames of a recording as
//! JSON, read by this crate's reader, so the tests compare what the page draws with numbers that never went
//! through the viewer's own JavaScript reader.

#![allow(clippy::print_stdout, reason = "the example prints its JSON dump")]

use std::fs::File;
use std::io::{BufReader, BufWriter};
use std::process::ExitCode;

use rebound::prelude::*;
use rebound_record::{Frame, Recorder, Recording};
use rebound_suite::scenes::{self, SceneOptions};
use serde_json::{Value, json};

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args
        .iter()
        .map(String::as_str)
        .collect::<Vec<_>>()
        .as_slice()
    {
        ["record", scene, out, steps] => steps
            .parse::<usize>()
            .map_err(|e| format!("STEPS {steps:?}: {e}"))
            .and_then(|steps| record(scene, out, steps)),
        ["frames", file, indices @ ..] if !indices.is_empty() => frames(file, indices),
        _ => Err(
            "usage: viewer_fixtures record cradle|balls OUT STEPS | frames FILE N [N …]".to_owned(),
        ),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("viewer_fixtures: {message}");
            ExitCode::FAILURE
        }
    }
}

fn record(scene: &str, out: &str, steps: usize) -> Result<(), String> {
    let file = File::create(out).map_err(|e| format!("{out}: {e}"))?;
    let fail = |e: rebound_record::RecordingError| format!("{out}: {e}");
    match scene {
        "cradle" => {
            let mut world = cradle().map_err(|e| e.to_string())?;
            let mut recorder = Recorder::new(&world, BufWriter::new(file)).map_err(fail)?;
            recorder.record(&world).map_err(fail)?;
            for _ in 0..steps {
                recorder.step(&mut world, scenes::DT).map_err(fail)?;
            }
            recorder.finish().map_err(fail)?;
        }
        "balls" => {
            let mut pile = scenes::build("balls", SceneOptions::default())
                .map_err(|e| e.to_string())?
                .ok_or("no balls scene")?;
            let mut recorder = Recorder::new(pile.world(), BufWriter::new(file)).map_err(fail)?;
            recorder.record(pile.world()).map_err(fail)?;
            for _ in 0..steps {
                pile.step();
                recorder.record(pile.world()).map_err(fail)?;
            }
            recorder.finish().map_err(fail)?;
        }
        other => return Err(format!("unknown scene {other:?} (cradle or balls)")),
    }
    Ok(())
}

/// Five steel balls of radius 0.1 m on 1 m ropes, 1 mm apart, the first pulled back 30°.
fn cradle() -> Result<PhysicsWorld, Error> {
    let (radius, length, gap) = (0.1f32, 1.0f32, 0.001f32);
    let mut world = PhysicsWorld::new(WorldSettings::default())?;
    for i in 0..5 {
        let anchor = Vec3::new(i as f32 * (2.0 * radius + gap), 0.0, 0.0);
        let angle = if i == 0 { 30f32.to_radians() } else { 0.0 };
        let start = anchor + Vec3::new(-length * angle.sin(), -length * angle.cos(), 0.0);
        let ball = world.insert_body(BodyDesc::dynamic().with_position(start))?;
        world.insert_collider(
            ColliderDesc::ball(radius)
                .with_density(7800.0)
                .with_restitution(1.0)
                .with_restitution_combine_rule(CombineRule::Max)
                .with_friction(0.0),
            ball,
        )?;
        let rope = Joint::new(Rope::new(length)?).with_local_anchors(anchor, Vec3::ZERO)?;
        world.insert_world_joint(rope, ball)?;
    }
    Ok(world)
}

fn frames(file: &str, indices: &[&str]) -> Result<(), String> {
    let input = File::open(file).map_err(|e| format!("{file}: {e}"))?;
    let recording = Recording::read(BufReader::new(input)).map_err(|e| format!("{file}: {e}"))?;
    let all = recording.frames();
    let mut dumped = Vec::with_capacity(indices.len());
    for index in indices {
        let i: usize = index.parse().map_err(|e| format!("frame {index:?}: {e}"))?;
        let frame = all
            .get(i)
            .ok_or_else(|| format!("frame {i}: the recording has {} frames", all.len()))?;
        dumped.push(frame_json(i, frame));
    }
    let dump = json!({
        "frame_count": all.len(),
        "bodies": recording.catalog().bodies(),
        "frames": dumped,
    });
    println!("{dump}");
    Ok(())
}

const fn v3(v: Vec3) -> [f32; 3] {
    [v.x, v.y, v.z]
}

fn frame_json(index: usize, frame: &Frame) -> Value {
    let d = &frame.diagnostics;
    json!({
        "index": index,
        "step": frame.step,
        "time": frame.time,
        "kinetic_energy": d.kinetic_energy,
        "potential_energy": d.potential_energy,
        "spring_energy": d.spring_energy,
        "bodies": frame.bodies.iter().map(|b| json!({
            "position": v3(b.position),
            "rotation": [b.rotation.x, b.rotation.y, b.rotation.z, b.rotation.w],
            "linear_velocity": v3(b.linear_velocity),
            "angular_velocity": v3(b.angular_velocity),
            "present": b.present,
            "sleeping": b.sleeping,
            "kind": b.kind,
        })).collect::<Vec<_>>(),
        "contacts": frame.contacts.iter().map(|c| json!({
            "a": c.body_a,
            "b": c.body_b,
            "point": v3(c.point),
            "normal": v3(c.normal),
            "impulse": c.normal_impulse,
            "separation": c.separation,
        })).collect::<Vec<_>>(),
        "joints": frame.joints.iter().map(|j| json!({
            "anchor_a": v3(j.anchor_a),
            "anchor_b": v3(j.anchor_b),
            "error": j.error,
            "present": j.present,
            "broken": j.broken,
        })).collect::<Vec<_>>(),
    })
}
