//! `rebound render RECORDING`: draw a recording's frames, read one at a time, as an animated GIF and/or PNG
//! frames.

use crate::cli::RenderArgs;
use crate::drawing::Drawing;
use crate::error::CliError;
use crate::pictures::{self, Pictures};
use crate::run::print;
use crate::{progress, recording_file};
use rebound_record::BodyKind;

/// Runs the command.
///
/// # Errors
/// A file that is not a recording, a bad argument, or an output that cannot be written.
pub fn render(args: &RenderArgs) -> Result<(), CliError> {
    if args.output.gif.is_none() && args.output.png_every.is_none() {
        return Err(CliError::Argument {
            argument: "--gif / --png-every",
            message: "say what to write: --gif FILE and/or --png-every K DIR".to_owned(),
        });
    }
    let mut reader = recording_file::open(&args.recording)?;
    let manifest = reader.manifest().clone();
    let Some(first) = reader.next_frame()? else {
        return Err(CliError::Argument {
            argument: "RECORDING",
            message: format!("{} holds no frames", args.recording.display()),
        });
    };
    let bodies: Vec<_> = manifest
        .bodies
        .iter()
        .zip(&first.bodies)
        .map(|(entry, sample)| (sample.position, entry.kind != BodyKind::Fixed))
        .collect();
    let camera = pictures::camera(&args.view, None, &bodies)?;
    let pictures = Pictures::open(camera, args.view.contacts, &args.output, manifest.dt)?;
    let mut drawing = Drawing::new(&manifest, pictures)?;
    let size = std::fs::metadata(&args.recording).map_or(0, |m| m.len());
    let bar = progress::byte_bar(size, "drawing");
    drawing.frame(&first)?;
    while let Some(frame) = reader.next_frame()? {
        drawing.frame(&frame)?;
        bar.set_position(reader.offset());
    }
    bar.finish_and_clear();
    print(&drawing.finish()?);
    Ok(())
}
