//! What can go wrong in a command, as one typed error that `main` prints with its causes.

use std::path::PathBuf;

/// A command's failure. `main` prints it (and the chain of its sources) and exits with status 1.
#[derive(Debug, thiserror::Error)]
pub enum CliError {
    /// The scene file could not be read or is not a valid scene.
    #[error(transparent)]
    Scene(#[from] rebound_scene::SceneError),
    /// A picture could not be drawn or encoded.
    #[error(transparent)]
    Render(#[from] rebound_render::RenderError),
    /// `rebound view` cannot start (viewer files missing, not a recording, no port).
    #[error(transparent)]
    View(#[from] crate::view::ViewError),
    /// A recording could not be written or read.
    #[error(transparent)]
    Recording(#[from] rebound_record::RecordingError),
    /// A plot could not be drawn.
    #[error(transparent)]
    Plot(#[from] rebound_render::PlotError),
    /// A file could not be opened.
    #[error("cannot read {path}: {source}")]
    Read {
        /// The file.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// A file or folder could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: std::io::Error,
    },
    /// An argument that clap accepted but the run cannot use.
    #[error("{argument}: {message}")]
    Argument {
        /// The argument (`--seconds`).
        argument: &'static str,
        /// What is wrong with its value.
        message: String,
    },
}
