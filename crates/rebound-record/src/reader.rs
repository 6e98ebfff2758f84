//! Reading a recording: [`FrameReader`] streams frames one at a time from any [`Read`] (memory: one frame),
//! [`Recording`] holds a whole file. Both check everything `docs/recording.md` defines and never panic.

use crate::catalog::Catalog;
use crate::decode::{decode_frame, parse_json};
use crate::error::RecordingError;
use crate::format::{FILE_HEADER_LEN, FORMAT_NAME, MAGIC, VERSION, pad4};
use crate::frame::Frame;
use crate::manifest::Manifest;
use std::io::Read;

/// Reads up to `n` bytes into `buf` (cleared first); returns how many there were.
fn read_up_to(
    reader: &mut impl Read,
    n: u64,
    buf: &mut Vec<u8>,
    offset: u64,
) -> Result<u64, RecordingError> {
    buf.clear();
    reader
        .take(n)
        .read_to_end(buf)
        .map(|read| read as u64)
        .map_err(|source| RecordingError::Io { offset, source })
}

/// Reads exactly `n` bytes or reports `what` as truncated.
fn read_exact(
    reader: &mut impl Read,
    n: u64,
    buf: &mut Vec<u8>,
    what: &'static str,
    offset: u64,
) -> Result<(), RecordingError> {
    let got = read_up_to(reader, n, buf, offset)?;
    if got == n {
        Ok(())
    } else {
        Err(RecordingError::Truncated {
            what,
            offset,
            needed: n,
            available: got,
        })
    }
}

/// Reads the frames of a recording one at a time, checking each.
///
/// ```
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// use rebound::prelude::*;
/// use rebound_record::{FrameReader, Recorder};
/// let mut world = PhysicsWorld::new(WorldSettings::default())?;
/// let ball = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 2.0, 0.0)))?;
/// world.insert_collider(ColliderDesc::ball(0.5), ball)?;
/// let mut recorder = Recorder::new(&world, Vec::new())?;
/// recorder.record(&world)?;
/// for _ in 0..10 {
///     recorder.step(&mut world, 1.0 / 60.0)?;
/// }
/// let bytes = recorder.finish()?;
/// let mut reader = FrameReader::new(bytes.as_slice())?;
/// assert_eq!(reader.manifest().bodies.len(), 1);
/// let heights: Vec<f32> = reader.by_ref().map(|f| f.map(|f| f.bodies[0].position.y)).collect::<Result<_, _>>()?;
/// assert_eq!(heights.len(), 11);
/// assert!(heights[10] < 2.0);
/// # Ok(())
/// # }
/// ```
#[derive(Debug)]
pub struct FrameReader<R> {
    reader: R,
    /// File offset of the next frame.
    offset: u64,
    manifest: Manifest,
    catalog: Catalog,
    buffer: Vec<u8>,
    /// Set after the end or an error: the iterator then yields nothing more.
    done: bool,
}

impl<R: Read> FrameReader<R> {
    /// Reads and checks the file header and the manifest.
    ///
    /// # Errors
    /// [`RecordingError::BadMagic`], [`RecordingError::UnsupportedVersion`], a truncated header or manifest,
    /// a manifest length not a multiple of 4, bad manifest JSON or contents.
    pub fn new(mut reader: R) -> Result<Self, RecordingError> {
        let mut buffer = Vec::new();
        let got = read_up_to(&mut reader, FILE_HEADER_LEN as u64, &mut buffer, 0)?;
        if buffer.get(..8) != Some(MAGIC.as_slice()) {
            return Err(RecordingError::BadMagic {
                found: buffer.iter().take(8).copied().collect(),
                expected: MAGIC,
            });
        }
        let word = |at: usize| {
            buffer
                .get(at..at + 4)
                .and_then(|b| <[u8; 4]>::try_from(b).ok())
                .map(u32::from_le_bytes)
        };
        let Some(version) = word(8) else {
            return Err(RecordingError::Truncated {
                what: "format version",
                offset: 8,
                needed: 4,
                available: got.saturating_sub(8),
            });
        };
        if version != VERSION {
            return Err(RecordingError::UnsupportedVersion {
                found: version,
                supported: VERSION,
            });
        }
        let Some(manifest_len) = word(12) else {
            return Err(RecordingError::Truncated {
                what: "manifest length",
                offset: 12,
                needed: 4,
                available: got.saturating_sub(12),
            });
        };
        if !manifest_len.is_multiple_of(4) {
            return Err(RecordingError::BadLength {
                what: "manifest length",
                offset: 12,
                found: u64::from(manifest_len),
                expected: pad4(manifest_len as usize) as u64,
            });
        }
        let start = FILE_HEADER_LEN as u64;
        read_exact(
            &mut reader,
            u64::from(manifest_len),
            &mut buffer,
            "manifest",
            start,
        )?;
        let manifest: Manifest = parse_json(&buffer, "manifest", start)?;
        if manifest.format != FORMAT_NAME {
            return Err(RecordingError::BadValue {
                field: "format",
                offset: start,
                value: format!("{:?} (expected {FORMAT_NAME:?})", manifest.format),
            });
        }
        let catalog = Catalog::from_manifest(&manifest, start)?;
        Ok(Self {
            reader,
            offset: start + u64::from(manifest_len),
            manifest,
            catalog,
            buffer,
            done: false,
        })
    }

    /// The manifest.
    #[must_use]
    pub fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    /// The descriptions of the bodies, colliders and joints as of the last frame read.
    #[must_use]
    pub fn catalog(&self) -> &Catalog {
        &self.catalog
    }

    /// The file offset of the next frame.
    #[must_use]
    pub fn offset(&self) -> u64 {
        self.offset
    }

    /// The next frame, `Ok(None)` at the end of the file.
    ///
    /// # Errors
    /// A truncated length or payload, or a payload that disagrees with the format, at its byte offset.
    pub fn next_frame(&mut self) -> Result<Option<Frame>, RecordingError> {
        let at = self.offset;
        let got = read_up_to(&mut self.reader, 4, &mut self.buffer, at)?;
        if got == 0 {
            return Ok(None);
        }
        let Ok(prefix) = <[u8; 4]>::try_from(self.buffer.as_slice()) else {
            return Err(RecordingError::Truncated {
                what: "frame length",
                offset: at,
                needed: 4,
                available: got,
            });
        };
        let len = u32::from_le_bytes(prefix);
        if !len.is_multiple_of(4) {
            return Err(RecordingError::BadLength {
                what: "frame payload length",
                offset: at,
                found: u64::from(len),
                expected: pad4(len as usize) as u64,
            });
        }
        read_exact(
            &mut self.reader,
            u64::from(len),
            &mut self.buffer,
            "frame payload",
            at + 4,
        )?;
        let frame = decode_frame(&self.buffer, at, &mut self.catalog)?;
        self.offset = at + 4 + u64::from(len);
        Ok(Some(frame))
    }
}

impl<R: Read> Iterator for FrameReader<R> {
    type Item = Result<Frame, RecordingError>;

    /// The next frame; after the end or the first error, `None`.
    fn next(&mut self) -> Option<Self::Item> {
        if self.done {
            return None;
        }
        let next = self.next_frame().transpose();
        if !matches!(next, Some(Ok(_))) {
            self.done = true;
        }
        next
    }
}

/// A whole recording in memory: the manifest and every frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Recording {
    manifest: Manifest,
    frames: Vec<Frame>,
    catalog: Catalog,
}

impl Recording {
    /// Reads and checks a whole recording.
    ///
    /// # Errors
    /// The first problem found, as [`FrameReader`] reports it.
    pub fn read(reader: impl Read) -> Result<Self, RecordingError> {
        match Self::read_lossy(reader)? {
            (recording, None) => Ok(recording),
            (_, Some(error)) => Err(error),
        }
    }

    /// Reads a recording up to its first bad frame: the frames before it, and the error that stopped the
    /// reading, if any (a run that was cut short leaves a truncated last frame).
    ///
    /// # Errors
    /// A bad file header or manifest (then there is nothing to give back).
    pub fn read_lossy(reader: impl Read) -> Result<(Self, Option<RecordingError>), RecordingError> {
        let mut frames_in = FrameReader::new(reader)?;
        let mut frames = Vec::new();
        let error = loop {
            match frames_in.next_frame() {
                Ok(Some(frame)) => frames.push(frame),
                Ok(None) => break None,
                Err(e) => break Some(e),
            }
        };
        let FrameReader {
            manifest, catalog, ..
        } = frames_in;
        Ok((
            Self {
                manifest,
                frames,
                catalog,
            },
            error,
        ))
    }

    /// The manifest.
    #[must_use]
    pub fn manifest(&self) -> &Manifest {
        &self.manifest
    }

    /// Every frame, in file order.
    #[must_use]
    pub fn frames(&self) -> &[Frame] {
        &self.frames
    }

    /// The descriptions as of the last frame (every body, collider and joint the recording ever described).
    #[must_use]
    pub fn catalog(&self) -> &Catalog {
        &self.catalog
    }

    /// The descriptions as of frame `frame` (the manifest with the changes of frames `0..=frame` applied);
    /// `None` if there is no such frame.
    #[must_use]
    pub fn catalog_at(&self, frame: usize) -> Option<Catalog> {
        let mut catalog = Catalog::from_manifest(&self.manifest, 0).ok()?;
        for f in self.frames.get(..=frame)? {
            if let Some(changes) = &f.changes {
                catalog.apply(changes, 0).ok()?;
            }
        }
        Some(catalog)
    }
}
