//! [`RecordingError`]: everything that can go wrong writing or reading a recording, each naming what is
//! wrong and the byte offset in the file where.

use thiserror::Error;

/// A recording could not be written or read. Every variant that concerns a place in the file carries its
/// byte offset from the start of the file.
#[derive(Debug, Error)]
pub enum RecordingError {
    /// Reading or writing the underlying stream failed.
    #[error("I/O error at byte {offset}: {source}")]
    Io {
        /// Where in the file the operation was.
        offset: u64,
        /// The error of the stream.
        source: std::io::Error,
    },
    /// The file does not start with the recording magic.
    #[error(
        "not a Rebound recording: the first 8 bytes are {found:02x?}, expected {expected:02x?}"
    )]
    BadMagic {
        /// The bytes found (fewer if the file is shorter).
        found: Vec<u8>,
        /// [`crate::MAGIC`].
        expected: [u8; 8],
    },
    /// The format version is not one this reader knows.
    #[error(
        "unsupported recording format version {found} at byte 8 (this reader reads version {supported})"
    )]
    UnsupportedVersion {
        /// The version in the file.
        found: u32,
        /// [`crate::VERSION`].
        supported: u32,
    },
    /// The file ends before something it announces.
    #[error(
        "truncated recording: {what} at byte {offset} needs {needed} bytes, only {available} remain"
    )]
    Truncated {
        /// What was being read (`"manifest"`, `"frame length"`, `"frame payload"`, …).
        what: &'static str,
        /// Where it starts.
        offset: u64,
        /// Its length in bytes.
        needed: u64,
        /// The bytes that were there.
        available: u64,
    },
    /// A length field is impossible: not a multiple of 4, or not what the counts next to it imply.
    #[error("bad {what} at byte {offset}: {found} bytes, expected {expected}")]
    BadLength {
        /// Which length (`"manifest length"`, `"frame payload length"`, `"changes length"`).
        what: &'static str,
        /// Where the length field is.
        offset: u64,
        /// The length in the file.
        found: u64,
        /// What it should be (for the multiple-of-4 rule: the length rounded up).
        expected: u64,
    },
    /// The manifest or a frame's changes is not valid UTF-8 JSON of the expected shape.
    #[error("bad {what} JSON at byte {offset}: {message}")]
    Json {
        /// `"manifest"` or `"changes"`.
        what: &'static str,
        /// Where the JSON starts.
        offset: u64,
        /// The parser's message, with the JSON line and column.
        message: String,
    },
    /// A field holds a value the format does not allow (an unknown event kind, a body kind code of 3, an
    /// index out of range, a count that went down, a non-finite position, …).
    #[error("bad {field} at byte {offset}: {value}")]
    BadValue {
        /// The field, as `docs/recording.md` names it.
        field: &'static str,
        /// Where it is.
        offset: u64,
        /// The value found, and what was allowed.
        value: String,
    },
    /// A collider's shape description is invalid.
    #[error("bad shape of collider {collider} at byte {offset}: {source}")]
    Shape {
        /// The collider's index.
        collider: u32,
        /// Where the JSON holding it starts.
        offset: u64,
        /// What the facade's check found.
        source: rebound::ShapeError,
    },
    /// The world holds more objects than the format can count (2³² − 1 of a kind) or a frame longer than
    /// 4 GiB.
    #[error("too many {what} to record: {count}")]
    TooMany {
        /// What overflowed.
        what: &'static str,
        /// How many there were.
        count: u64,
    },
}

impl RecordingError {
    /// The byte offset the error concerns, if it concerns a place in the file.
    #[must_use]
    pub fn offset(&self) -> Option<u64> {
        match self {
            Self::Io { offset, .. }
            | Self::Truncated { offset, .. }
            | Self::BadLength { offset, .. }
            | Self::Json { offset, .. }
            | Self::BadValue { offset, .. }
            | Self::Shape { offset, .. } => Some(*offset),
            Self::BadMagic { .. } => Some(0),
            Self::UnsupportedVersion { .. } => Some(8),
            Self::TooMany { .. } => None,
        }
    }
}
