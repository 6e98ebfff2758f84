//! Drawing a recording's frames as they come, from a run or from a file: the frames' scenes (with joints and
//! contacts, from `rebound-render`'s [`RecordingScenes`]) into the [`Pictures`] outputs.

use crate::error::CliError;
use crate::pictures::Pictures;
use rebound_record::{Frame, Manifest};
use rebound_render::RecordingScenes;

/// Follows a recording frame by frame and draws the frames the outputs want.
pub struct Drawing {
    scenes: RecordingScenes,
    pictures: Pictures,
    first_step: Option<u64>,
}

impl Drawing {
    /// Starts at `manifest`, drawing into `pictures`.
    ///
    /// # Errors
    /// [`CliError::Render`] if the manifest's descriptions are inconsistent.
    pub fn new(manifest: &Manifest, pictures: Pictures) -> Result<Self, CliError> {
        Ok(Self {
            scenes: RecordingScenes::new(manifest)?,
            pictures,
            first_step: None,
        })
    }

    /// Takes the next frame (every frame must be given, in order): draws it if an output wants its step,
    /// counted from the first frame's.
    ///
    /// # Errors
    /// A frame that does not fit the descriptions, or a picture that cannot be drawn or written.
    pub fn frame(&mut self, frame: &Frame) -> Result<(), CliError> {
        let first = *self.first_step.get_or_insert(frame.step);
        let step = frame.step.saturating_sub(first);
        if self.pictures.wants(step) {
            let scene = self.scenes.scene(frame)?;
            self.pictures.capture(step, &scene)?;
        } else {
            self.scenes.advance(frame)?;
        }
        Ok(())
    }

    /// Finishes the outputs; a line per output written.
    ///
    /// # Errors
    /// As [`Pictures::finish`].
    pub fn finish(self) -> Result<Vec<String>, CliError> {
        self.pictures.finish()
    }
}
