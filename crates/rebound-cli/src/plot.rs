//! `rebound plot RECORDING -o FILE.svg`: energy, momentum, worst joint error and deepest penetration against
//! time, from every frame of a recording.

use crate::cli::PlotArgs;
use crate::error::CliError;
use crate::recording_file;
use crate::run::{print, write_text};
use rebound_record::Frame;

/// Runs the command.
///
/// # Errors
/// A file that is not a recording, a recording without frames, or an SVG that cannot be written.
pub fn plot(args: &PlotArgs) -> Result<(), CliError> {
    let mut reader = recording_file::open(&args.recording)?;
    let mut history = Vec::new();
    while let Some(frame) = reader.next_frame()? {
        history.push(Frame {
            step: frame.step,
            time: frame.time,
            diagnostics: frame.diagnostics,
            ..Frame::default()
        });
    }
    let svg =
        rebound_render::time_history(&history).to_svg(&rebound_render::PlotOptions::default())?;
    write_text(&args.output, &svg)?;
    print(&[format!(
        "wrote {} ({} samples)",
        args.output.display(),
        history.len()
    )]);
    Ok(())
}
