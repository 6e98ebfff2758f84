//! [`Recorder`]: captures a run of a [`PhysicsWorld`] frame by frame and streams it, in the format of
//! `docs/recording.md`, to any [`Write`]. Memory: the descriptions it has written (to notice changes) and
//! one frame's buffers, reused; nothing grows with the number of frames.

use crate::capture::Tracker;
use crate::contacts::read_contacts;
use crate::encode::{encode_frame, encode_header};
use crate::error::RecordingError;
use crate::frame::Frame;
use rebound::{PhysicsWorld, StepReport};
use std::io::Write;
use std::ops::Range;

/// Writes a recording of a world's run.
///
/// Call [`Recorder::record`] after each step (and once before the first, for the initial state), or let
/// [`Recorder::step`] do both. Bodies, colliders and joints inserted, edited or removed between calls are
/// noticed and written as the frame's changes (give it the same world each time: edits are noticed by the
/// world's [`rebound::ColliderSet::revision`] and [`rebound::BodySet::revision`]). [`Recorder::finish`]
/// flushes the writer and hands it back.
///
/// ```
/// # fn main() -> Result<(), Box<dyn std::error::Error>> {
/// use rebound::prelude::*;
/// use rebound_record::{Recorder, Recording};
/// let mut world = PhysicsWorld::new(WorldSettings::default())?;
/// let ball = world.insert_body(BodyDesc::dynamic().with_position(Vec3::new(0.0, 5.0, 0.0)))?;
/// world.insert_collider(ColliderDesc::ball(0.5), ball)?;
/// let mut recorder = Recorder::new(&world, Vec::new())?;
/// recorder.record(&world)?;
/// for _ in 0..60 {
///     recorder.step(&mut world, 1.0 / 60.0)?;
/// }
/// let bytes = recorder.finish()?;
/// let recording = Recording::read(bytes.as_slice())?;
/// assert_eq!(recording.frames().len(), 61);
/// let last = &recording.frames()[60];
/// assert_eq!(last.bodies[0].position, world.body(ball).unwrap().position());
/// # Ok(())
/// # }
/// ```
#[derive(Debug)]
pub struct Recorder<W: Write> {
    out: W,
    /// Bytes written so far (the file offset of the next frame).
    offset: u64,
    tracker: Tracker,
    /// The last frame's samples; its contacts only once read back from `buffer` (see
    /// [`Recorder::last_frame`]).
    frame: Frame,
    /// The last frame's bytes.
    buffer: Vec<u8>,
    /// Where the last frame's CONTACT entries lie in `buffer`, until they are read into `frame`.
    contacts: Option<Range<usize>>,
    /// The step count of the last frame, if any.
    last_step: Option<u64>,
    frames: u64,
}

impl<W: Write> Recorder<W> {
    /// Starts a recording of `world` into `out`: writes the file header and the manifest describing
    /// everything `world` holds now.
    ///
    /// # Errors
    /// [`RecordingError::Io`] if writing fails.
    pub fn new(world: &PhysicsWorld, mut out: W) -> Result<Self, RecordingError> {
        let (tracker, manifest) = Tracker::start(world);
        let mut buffer = Vec::new();
        encode_header(&manifest, &mut buffer)?;
        out.write_all(&buffer)
            .map_err(|source| RecordingError::Io { offset: 0, source })?;
        Ok(Self {
            out,
            offset: buffer.len() as u64,
            tracker,
            frame: Frame::default(),
            // The manifest can be many times a frame's size: the frames start a buffer of their own.
            buffer: Vec::new(),
            contacts: None,
            last_step: None,
            frames: 0,
        })
    }

    /// Writes a frame of `world`'s current state. Its time advances from the previous frame's by the steps
    /// taken since, times the world's `fixed_dt` (the first frame's time is `step_count · fixed_dt`); use
    /// [`Recorder::step`] when stepping by another `dt`.
    ///
    /// # Errors
    /// [`RecordingError::Io`] if writing fails (the file then ends inside this frame).
    pub fn record(&mut self, world: &PhysicsWorld) -> Result<(), RecordingError> {
        let step = world.step_count();
        let steps = step - self.last_step.map_or(0, |last| last.min(step));
        let time = self.frame.time + steps as f64 * f64::from(world.settings().fixed_dt);
        self.write_frame(world, time)
    }

    /// Steps `world` by `dt` seconds and records the result; the frame's time advances by `dt` if the world
    /// stepped.
    ///
    /// # Errors
    /// As [`Recorder::record`].
    pub fn step(
        &mut self,
        world: &mut PhysicsWorld,
        dt: f32,
    ) -> Result<StepReport, RecordingError> {
        let before = world.step_count();
        if self.last_step.is_none() {
            // A recording that starts here starts at the world's elapsed time.
            self.frame.time = before as f64 * f64::from(world.settings().fixed_dt);
            self.last_step = Some(before);
        }
        let report = world.step(dt);
        let steps = world.step_count() - before;
        let time = self.frame.time + steps as f64 * f64::from(dt);
        self.write_frame(world, time)?;
        Ok(report)
    }

    fn write_frame(&mut self, world: &PhysicsWorld, time: f64) -> Result<(), RecordingError> {
        let changes = self.tracker.changes(world);
        self.frame.step = world.step_count();
        self.frame.time = time;
        self.frame.changes = (!changes.is_empty()).then_some(changes);
        self.tracker.sample(world, &mut self.frame);
        let tracker = &self.tracker;
        let (totals, contacts) = encode_frame(
            &self.frame,
            |out| tracker.write_contacts(world, out),
            self.offset,
            &mut self.buffer,
        )?;
        self.frame.diagnostics.deepest_penetration = totals.deepest_penetration;
        self.contacts = Some(contacts);
        self.out
            .write_all(&self.buffer)
            .map_err(|source| RecordingError::Io {
                offset: self.offset,
                source,
            })?;
        self.offset += self.buffer.len() as u64;
        self.last_step = Some(self.frame.step);
        self.frames += 1;
        Ok(())
    }

    /// The last frame written (as the reader will give it back), if any. Its contacts are read back from
    /// the frame's bytes on the first call after each frame (they are written straight from the world's
    /// manifolds; a recording that never asks pays nothing for them).
    pub fn last_frame(&mut self) -> Option<&Frame> {
        if self.frames == 0 {
            return None;
        }
        if let Some(contacts) = self.contacts.take() {
            read_contacts(
                self.buffer.get(contacts).unwrap_or_default(),
                &mut self.frame.contacts,
            );
        }
        Some(&self.frame)
    }

    /// The number of frames written.
    #[must_use]
    pub fn frames_written(&self) -> u64 {
        self.frames
    }

    /// The number of bytes written (header, manifest and frames).
    #[must_use]
    pub fn bytes_written(&self) -> u64 {
        self.offset
    }

    /// Flushes the writer and returns it.
    ///
    /// # Errors
    /// [`RecordingError::Io`] if flushing fails.
    pub fn finish(mut self) -> Result<W, RecordingError> {
        self.out.flush().map_err(|source| RecordingError::Io {
            offset: self.offset,
            source,
        })?;
        Ok(self.out)
    }
}
