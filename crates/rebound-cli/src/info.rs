//! `rebound info RECORDING`: what a recording holds and how well the run kept its invariants — bodies and
//! joints, steps and time, energy drift, deepest penetration, worst joint error — as text or JSON.

use crate::cli::InfoArgs;
use crate::error::CliError;
use crate::recording_file;
use crate::run::print;
use rebound_record::BodyKind;
use serde::Serialize;

/// The summary, as `--json` prints it. Energies in J, lengths in m, times in s.
#[derive(Debug, Serialize)]
pub struct Summary {
    /// Bodies in the recording's manifest.
    pub bodies: usize,
    /// Of which dynamic.
    pub dynamic_bodies: usize,
    /// Joints in the manifest.
    pub joints: usize,
    /// Frames in the file.
    pub frames: u64,
    /// Steps between the first and the last frame.
    pub steps: u64,
    /// Step length (s).
    pub dt: f32,
    /// Time of the first and the last frame (s).
    pub start_time: f64,
    /// Time of the last frame (s).
    pub end_time: f64,
    /// Total (kinetic + potential + spring) energy of the first frame (J).
    pub start_energy: f32,
    /// Total energy of the last frame (J).
    pub end_energy: f32,
    /// `end_energy − start_energy` (J).
    pub energy_drift: f32,
    /// The drift as a fraction of the largest |total energy| over the run (0 if that is 0).
    pub relative_energy_drift: f32,
    /// The deepest contact overlap of any frame (m).
    pub worst_penetration: f32,
    /// The step of that frame.
    pub worst_penetration_step: u64,
    /// The largest joint error of any frame (m).
    pub worst_joint_error: f32,
}

/// Reads the recording and sums it up.
///
/// # Errors
/// A file that is not a recording or holds no frames.
pub fn summarise(args: &InfoArgs) -> Result<Summary, CliError> {
    let mut reader = recording_file::open(&args.recording)?;
    let manifest = reader.manifest().clone();
    let Some(first) = reader.next_frame()? else {
        return Err(CliError::Argument {
            argument: "RECORDING",
            message: format!("{} holds no frames", args.recording.display()),
        });
    };
    let mut summary = Summary {
        bodies: manifest.bodies.len(),
        dynamic_bodies: manifest
            .bodies
            .iter()
            .filter(|b| b.kind == BodyKind::Dynamic)
            .count(),
        joints: manifest.joints.len(),
        frames: 1,
        steps: 0,
        dt: manifest.dt,
        start_time: first.time,
        end_time: first.time,
        start_energy: first.diagnostics.total_energy(),
        end_energy: first.diagnostics.total_energy(),
        energy_drift: 0.0,
        relative_energy_drift: 0.0,
        worst_penetration: first.diagnostics.deepest_penetration,
        worst_penetration_step: first.step,
        worst_joint_error: first.diagnostics.worst_joint_error,
    };
    let mut largest_energy = summary.start_energy.abs();
    let mut last_step = first.step;
    while let Some(frame) = reader.next_frame()? {
        let d = frame.diagnostics;
        summary.frames += 1;
        summary.end_time = frame.time;
        summary.end_energy = d.total_energy();
        largest_energy = largest_energy.max(summary.end_energy.abs());
        if d.deepest_penetration > summary.worst_penetration {
            summary.worst_penetration = d.deepest_penetration;
            summary.worst_penetration_step = frame.step;
        }
        summary.worst_joint_error = summary.worst_joint_error.max(d.worst_joint_error);
        last_step = frame.step;
    }
    summary.steps = last_step.saturating_sub(first.step);
    summary.energy_drift = summary.end_energy - summary.start_energy;
    summary.relative_energy_drift = if largest_energy > 0.0 {
        summary.energy_drift / largest_energy
    } else {
        0.0
    };
    Ok(summary)
}

/// Runs the command.
///
/// # Errors
/// As [`summarise`].
pub fn info(args: &InfoArgs) -> Result<(), CliError> {
    let s = summarise(args)?;
    if args.json {
        // A struct of numbers always serialises.
        print(&[serde_json::to_string_pretty(&s).unwrap_or_default()]);
        return Ok(());
    }
    print(&[
        format!(
            "bodies: {} ({} dynamic), joints: {}",
            s.bodies, s.dynamic_bodies, s.joints
        ),
        format!(
            "frames: {}, steps: {} of {:.4} s, time {:.3} s to {:.3} s",
            s.frames, s.steps, s.dt, s.start_time, s.end_time
        ),
        format!(
            "energy: {:.6} J at the start, {:.6} J at the end: drift {:+.6} J ({:+.3} % of the largest)",
            s.start_energy,
            s.end_energy,
            s.energy_drift,
            100.0 * s.relative_energy_drift
        ),
        format!(
            "worst penetration: {:.6} m (step {}); worst joint error: {:.6} m",
            s.worst_penetration, s.worst_penetration_step, s.worst_joint_error
        ),
    ]);
    Ok(())
}
