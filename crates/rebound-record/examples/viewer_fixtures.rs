//! Recordings and frame dumps for the web viewer's tests (`viewer/test/`).
//!
//! ```sh
//! cargo run --release -p rebound-record --example viewer_fixtures -- record scenes/newtons_cradle.ron OUT.rrec STEPS
//! cargo run --release -p rebound-record --example viewer_fixtures -- frames FILE.rrec N [N …]
//! ```
//!
//! `record` loads a scene file (rebound-scene), steps it `STEPS` times by the scene's `run.dt` and records the
//! start and every step. `frames` prints frames of a recording as JSON, read by this crate's reader, so the
//! tests compare what the page draws with numbers that never went through the viewer's JavaScript reader.

#![allow(clippy::print_stdout, reason = "the example prints its JSON dump")]

use std::fs::File;
use std::io::{BufReader, BufWriter};
use std::process::ExitCode;

use rebound::prelude::Vec3;
use rebound_record::{Frame, Recorder, Recording};
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
            "usage: viewer_fixtures record SCENE.ron OUT STEPS | frames FILE N [N …]".to_owned(),
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
    let (scene, built) = rebound_scene::load_file(scene).map_err(|e| format!("{scene}: {e}"))?;
    let mut world = built.world;
    let file = File::create(out).map_err(|e| format!("{out}: {e}"))?;
    let fail = |e: rebound_record::RecordingError| format!("{out}: {e}");
    let mut recorder = Recorder::new(&world, BufWriter::new(file)).map_err(fail)?;
    recorder.record(&world).map_err(fail)?;
    for _ in 0..steps {
        recorder.step(&mut world, scene.run.dt).map_err(fail)?;
    }
    recorder.finish().map_err(fail)?;
    Ok(())
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
