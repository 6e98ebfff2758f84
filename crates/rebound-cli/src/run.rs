//! `rebound run SCENE`: load and check the scene file (nothing runs if it is bad), step it for the asked
//! time, draw the asked pictures as it goes, and print a summary.

use crate::cli::RunArgs;
use crate::error::CliError;
use crate::pictures::{self, Pictures};
use crate::progress;
use std::io::Write;
use std::path::PathBuf;

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
            message: format!("must be finite, > 0 and at most {} steps long, got {seconds}", u32::MAX),
        });
    }
    // At least one step; the cast is exact (a whole number within u32's range).
    Ok((steps as u32).max(1))
}

/// `--png-every K DIR` as a step interval and a folder.
fn png_every(args: &RunArgs) -> Result<Option<(u32, PathBuf)>, CliError> {
    let Some(values) = &args.png_every else {
        return Ok(None);
    };
    let [k, dir] = values.as_slice() else {
        return Err(CliError::Argument {
            argument: "--png-every",
            message: "needs K and DIR".to_owned(),
        });
    };
    let k = k.parse::<u32>().ok().filter(|k| *k >= 1).ok_or_else(|| CliError::Argument {
        argument: "--png-every",
        message: format!("K must be a whole number ≥ 1, got `{k}`"),
    })?;
    Ok(Some((k, PathBuf::from(dir))))
}

/// Runs the command.
///
/// # Errors
/// A bad scene file, a bad argument, or an output that cannot be written. Nothing is stepped or written
/// before the scene and the arguments are checked.
pub fn run(args: &RunArgs) -> Result<(), CliError> {
    let (scene, built) = rebound_scene::load_file(&args.scene)?;
    let mut world = built.world;
    let dt = scene.run.dt;
    let steps = step_count(args, dt, scene.run.steps)?;
    if !(args.fps.is_finite() && args.fps > 0.0) {
        return Err(CliError::Argument {
            argument: "--fps",
            message: format!("must be finite and > 0, got {}", args.fps),
        });
    }
    let png = png_every(args)?;
    let camera = pictures::camera(&args.view, scene.camera, &world)?;
    // A GIF frame every whole number of steps, as close to the asked rate as that allows.
    let gif_every = ((1.0 / (args.fps * dt)).round() as u32).max(1);
    let mut pictures = Pictures::open(
        camera,
        args.view.contacts,
        args.gif.as_deref(),
        gif_every,
        dt,
        png,
    )?;

    let bar = progress::bar(u64::from(steps), "stepping");
    pictures.capture(0, &world)?;
    let mut worst_step = std::time::Duration::ZERO;
    for step in 1..=steps {
        let report = world.step(dt);
        worst_step = worst_step.max(report.profile.total);
        if !pictures.is_empty() {
            pictures.capture(step, &world)?;
        }
        bar.inc(1);
    }
    bar.finish_and_clear();

    let name = if scene.name.is_empty() {
        args.scene.display().to_string()
    } else {
        scene.name.clone()
    };
    let mut out = std::io::stdout().lock();
    let mut lines = vec![format!(
        "{name}: {steps} steps of {:.4} s ({:.2} s), {} bodies, {} colliders, {} joints; digest {:016x}",
        dt,
        f64::from(steps) * f64::from(dt),
        world.bodies().len(),
        world.colliders().len(),
        world.world().joints().count(),
        world.state_digest(),
    )];
    lines.extend(pictures.finish()?);
    for line in lines {
        // A closed pipe is not worth an error: the run itself is done.
        if writeln!(out, "{line}").is_err() {
            break;
        }
    }
    Ok(())
}
