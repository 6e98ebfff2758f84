//! What recording costs on the SCENES.md 4,096-ball pile (`rebound_suite::scenes::Balls`): file size, the
//! memory the recorder and a read-back recording hold, and the time of a recorded step against a plain one.
//!
//! ```text
//! cargo run --release -p rebound-record --example record_cost            # both runs, sizes, memory, wall clock
//! cargo run --release -p rebound-record --example record_cost -- plain 600   # only stepping (for callgrind)
//! cargo run --release -p rebound-record --example record_cost -- record 600  # stepping and recording
//! ```
//!
//! Instruction counts (unaffected by machine load) come from running the `plain` and `record` modes under
//! `valgrind --tool=callgrind` and subtracting; `docs/recording.md` ("Cost") has the figures and commands.

#![allow(clippy::print_stdout, reason = "an example prints its results")]

use rebound_record::{Recorder, Recording};
use rebound_suite::scenes::{Balls, Scene, SceneOptions, balls};
use stats_alloc::{INSTRUMENTED_SYSTEM, Region, StatsAlloc};
use std::alloc::System;
use std::error::Error;
use std::fs::File;
use std::io::{BufReader, BufWriter};
use std::time::Instant;

#[global_allocator]
static GLOBAL: &StatsAlloc<System> = &INSTRUMENTED_SYSTEM;

/// Bytes held now that were not held when `region` started.
fn net_bytes(region: &Region<'_, System>) -> i64 {
    let change = region.change();
    change.bytes_allocated as i64 - change.bytes_deallocated as i64
        + change.bytes_reallocated as i64
}

/// A run's results: wall-clock seconds per step, the peak of the net bytes allocated since it began, and
/// the net bytes still held after its last step.
struct Run {
    seconds: Vec<f64>,
    peak_bytes: i64,
    held_bytes: i64,
}

fn run(steps: usize, out: Option<&str>) -> Result<Run, Box<dyn Error>> {
    let mut scene = Balls::new(SceneOptions::default(), balls::SIDE)?;
    let region = Region::new(GLOBAL);
    let mut recorder = match out {
        Some(path) => Some(Recorder::new(
            scene.world(),
            BufWriter::new(File::create(path)?),
        )?),
        None => None,
    };
    let mut seconds = Vec::with_capacity(steps);
    let mut peak_bytes = net_bytes(&region);
    if let Some(recorder) = recorder.as_mut() {
        recorder.record(scene.world())?;
    }
    for _ in 0..steps {
        let start = Instant::now();
        scene.step();
        if let Some(recorder) = recorder.as_mut() {
            recorder.record(scene.world())?;
        }
        seconds.push(start.elapsed().as_secs_f64());
        peak_bytes = peak_bytes.max(net_bytes(&region));
    }
    let held_bytes = net_bytes(&region);
    if let Some(recorder) = recorder {
        recorder.finish()?;
    }
    Ok(Run {
        seconds,
        peak_bytes,
        held_bytes,
    })
}

fn median(samples: &[f64]) -> f64 {
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    sorted.get(sorted.len() / 2).copied().unwrap_or(f64::NAN)
}

fn main() -> Result<(), Box<dyn Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mode = args.first().map_or("both", String::as_str);
    let steps: usize = args.get(1).map_or(Ok(600), |s| s.parse())?;
    let path = std::env::temp_dir().join("rebound-balls.rrec");
    let path = path.to_str().ok_or("temporary path is not UTF-8")?;
    match mode {
        "plain" => {
            run(steps, None)?;
        }
        "record" => {
            run(steps, Some(path))?;
        }
        _ => {
            let plain = run(steps, None)?;
            let recorded = run(steps, Some(path))?;
            let size = std::fs::metadata(path)?.len();
            let region = Region::new(GLOBAL);
            let start = Instant::now();
            let recording = Recording::read(BufReader::new(File::open(path)?))?;
            let read_seconds = start.elapsed().as_secs_f64();
            let held = net_bytes(&region);
            let frames = recording.frames();
            let contacts = frames.last().map_or(0, |f| f.contacts.len());
            println!(
                "balls scene: {} bodies, {steps} steps, {} frames",
                recording.manifest().bodies.len(),
                frames.len()
            );
            println!(
                "file: {size} bytes ({:.1} MB), {:.0} bytes per frame; last frame {contacts} contacts",
                size as f64 / 1e6,
                size as f64 / frames.len() as f64
            );
            println!(
                "recorder memory beyond the plain run's: peak {} bytes (writing the manifest), {} bytes held while recording",
                recorded.peak_bytes - plain.peak_bytes,
                recorded.held_bytes - plain.held_bytes
            );
            println!(
                "read back: {held} bytes held by the Recording ({:.2} × the file), read in {read_seconds:.2} s",
                held as f64 / size as f64
            );
            let (p, r) = (median(&plain.seconds), median(&recorded.seconds));
            println!(
                "wall clock (noisy on a shared machine): median step {:.3} ms, recorded step {:.3} ms, +{:.1} %",
                p * 1e3,
                r * 1e3,
                (r / p - 1.0) * 100.0
            );
        }
    }
    Ok(())
}
