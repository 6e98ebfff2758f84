//! What can go wrong in a command, as one typed error that `main` prints with its causes.

use std::fmt;
use std::io;
use std::path::PathBuf;

use rebound_record::VERSION;

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
    View(#[from] ViewError),
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
        source: io::Error,
    },
    /// A file or folder could not be written.
    #[error("cannot write {path}: {source}")]
    Write {
        /// The file or folder.
        path: PathBuf,
        /// What the system said.
        #[source]
        source: io::Error,
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

/// Why `rebound view` cannot start.
#[derive(Debug)]
pub enum ViewError {
    /// The viewer directory lacks a file it needs (`index.html`, or three.js before `npm ci`).
    ViewerIncomplete {
        /// The viewer directory searched.
        dir: PathBuf,
        /// The missing file, relative to `dir`.
        missing: &'static str,
    },
    /// The recording cannot be opened.
    Recording {
        /// The path given.
        path: PathBuf,
        /// Why it cannot be opened.
        source: io::Error,
    },
    /// The file does not start as a version-1 recording does (magic bytes and format version).
    NotARecording {
        /// The path given.
        path: PathBuf,
    },
    /// No loopback port could be bound.
    Bind {
        /// The port asked for (0 = any free port).
        port: u16,
        /// The server's message.
        reason: String,
    },
}

impl fmt::Display for ViewError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Self::ViewerIncomplete { dir, missing } => write!(
                f,
                "the viewer directory {} has no {missing} (run `npm ci` in viewer/, or pass --viewer-dir)",
                dir.display()
            ),
            Self::Recording { path, source } => {
                write!(f, "cannot open the recording {}: {source}", path.display())
            }
            Self::NotARecording { path } => write!(
                f,
                "{} is not a Rebound recording (version {VERSION}): its first 12 bytes are not the format's header",
                path.display()
            ),
            Self::Bind { port, reason } => write!(f, "cannot listen on 127.0.0.1:{port}: {reason}"),
        }
    }
}

impl std::error::Error for ViewError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        match self {
            Self::Recording { source, .. } => Some(source),
            Self::ViewerIncomplete { .. } | Self::NotARecording { .. } | Self::Bind { .. } => None,
        }
    }
}
