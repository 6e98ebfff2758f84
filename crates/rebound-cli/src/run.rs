//! `rebound run SCENE`: load and check the scene file (nothing runs if it is bad), step it for the asked
//! time while recording it, draw the asked pictures and plot from the recording's frames, and print a
//! summary.

use crate::bundled;
use crate::cli::RunArgs;
use crate::drawing::Drawing;
use crate::error::CliError;
use crate::pictures::{self, Pictures};
use crate::progress;
use rebound::prelude::*;
use rebound_record::{Frame, Recorder};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::Path;

/// The number of steps of `dt` the run takes.
fn step_count(args: &RunArgs, dt: f32, default: u32) -> Result<u32, CliError> {
    if let Some(steps) = args.steps {
        if steps == 0 {
            return Err(CliError::Argument {
                argument: "--steps",
                message: "must be at least 1".to_owned(),
            });
        }
        return Ok(steps);
    }
    let Some(seconds) = args.seconds else {
        return Ok(default);
    };
    let steps = (seconds / f64::from(dt)).round();
    if !(seconds.is_finite() && seconds > 0.0 && steps <= f64::from(u32::MAX)) {
        return Err(CliError::Argument {
            argument: "--seconds",
            message: format!(
                "must be finite, > 0 and at most {} steps long, got {seconds}",
                u32::MAX
            ),
        });
    }
    // At least one step; the cast is exact (a whole number within u32's range).
    Ok((steps as u32).max(1))
}

/// Creates `path` for writing.
pub fn create(path: &Path) -> Result<BufWriter<File>, CliError> {
    File::create(path)
        .map(BufWriter::new)
        .map_err(|source| CliError::Write {
            path: path.to_owned(),
            source,
        })
}

/// Writes `text` to `path`.
pub fn write_text(path: &Path, text: &str) -> Result<(), CliError> {
    std::fs::write(path, text).map_err(|source| CliError::Write {
        path: path.to_owned(),
        source,
    })
}

/// Prints `lines` on standard output; a closed pipe is not worth an error, the work itself is done.
pub fn print(lines: &[String]) {
    let mut out = std::io::stdout().lock();
    for line in lines {
        if writeln!(out, "{line}").is_err() {
            break;
        }
    }
}

/// Runs the command.
///
/// # Errors
/// A bad scene file, a bad argument, or an output that cannot be written. Nothing is stepped or written
/// before the scene and the arguments are checked.
pub fn run(args: &RunArgs) -> Result<(), CliError> {
    let (scene, built) = match bundled::scene(&args.scene) {
        Some(source) => rebound_scene::load_str(source)?,
        None if !args.scene.exists() => {
            return Err(CliError::Argument {
                argument: "SCENE",
                message: format!(
                    "no file {}, and not a built-in scene ({})",
                    args.scene.display(),
                    bundled::names()
                ),
            });
        }
        None => rebound_scene::load_file(&args.scene)?,
    };
    let mut world = built.world;
    let dt = scene.run.dt;
    let steps = step_count(args, dt, scene.run.steps)?;
    let bodies: Vec<(Vec3, bool)> = world
        .bodies()
        .iter()
        .map(|(_, b)| (b.position(), b.body_type() != BodyType::Fixed))
        .collect();
    let camera = pictures::camera(&args.view, scene.camera, &bodies)?;
    let pictures = Pictures::open(camera, args.view.contacts, &args.output, dt)?;
    let wants_pictures = !pictures.is_empty();
    let mut drawing = Drawing::new(&pictures::manifest_of(&world)?, pictures)?;
    let out: Box<dyn Write> = match &args.record {
        Some(path) => Box::new(create(path)?),
        None => Box::new(std::io::sink()),
    };
    let mut recorder = Recorder::new(&world, out)?;
    // For the plot: each frame's time and diagnostics, without its bodies and contacts.
    let mut history: Vec<Frame> = Vec::new();
    let mut take = |recorder: &mut Recorder<Box<dyn Write>>| -> Result<(), CliError> {
        let Some(frame) = recorder.last_frame() else {
            return Ok(());
        };
        if wants_pictures {
            drawing.frame(frame)?;
        }
        if args.plot.is_some() {
            history.push(Frame {
                step: frame.step,
                time: frame.time,
                diagnostics: frame.diagnostics,
                ..Frame::default()
            });
        }
        Ok(())
    };

    let bar = progress::bar(u64::from(steps), "stepping");
    recorder.record(&world)?;
    take(&mut recorder)?;
    for _ in 0..steps {
        recorder.step(&mut world, dt)?;
        take(&mut recorder)?;
        bar.inc(1);
    }
    bar.finish_and_clear();
    let frames = recorder.frames_written();
    let bytes = recorder.bytes_written();
    recorder.finish()?;

    let name = if scene.name.is_empty() {
        args.scene.display().to_string()
    } else {
        scene.name.clone()
    };
    let mut lines = vec![format!(
        "{name}: {steps} steps of {dt:.4} s ({:.2} s), {} bodies, {} colliders, {} joints; digest {:016x}",
        f64::from(steps) * f64::from(dt),
        world.bodies().len(),
        world.colliders().len(),
        world.world().joints().count(),
        world.state_digest(),
    )];
    if let Some(path) = &args.record {
        lines.push(format!(
            "wrote {} ({frames} frames, {bytes} bytes)",
            path.display()
        ));
    }
    if let Some(path) = &args.plot {
        let svg = rebound_render::time_history(&history)
            .to_svg(&rebound_render::PlotOptions::default())?;
        write_text(path, &svg)?;
        lines.push(format!(
            "wrote {} ({} samples)",
            path.display(),
            history.len()
        ));
    }
    lines.extend(drawing.finish()?);
    print(&lines);
    Ok(())
}
