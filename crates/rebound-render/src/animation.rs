//! `GifWriter`: pictures gathered into a looping animated GIF (the `gif` crate: each frame quantised to its
//! own 256-colour palette with NeuQuant, LZW-compressed).
//!
//! Each frame after the first stores only the pixels that changed: the others are written transparent and
//! the frame is shown over the one before (disposal "keep"). With a still camera the background, the grid
//! and everything at rest are the same from frame to frame, and runs of the transparent index compress to
//! almost nothing.

use std::io::Write;

use crate::{Image, RenderError};

/// The slowest frame interval a GIF can state (s): delays are 16-bit counts of centiseconds.
pub const MAX_FRAME_INTERVAL: f32 = 655.35;

/// The shortest frame interval written (s). Viewers show GIF delays below 2 cs slowly (as 10 cs), so shorter
/// intervals are raised to this.
pub const MIN_FRAME_INTERVAL: f32 = 0.02;

/// Quantiser speed (1 best and slowest, 30 fastest) given to the `gif` crate. 10 keeps gradients of the
/// shaded faces smooth at a few milliseconds a 640×480 frame.
const QUANTISER_SPEED: i32 = 10;

/// Writes frames of one size, one after another, as an animated GIF that loops forever.
pub struct GifWriter<W: Write> {
    encoder: gif::Encoder<W>,
    width: u32,
    height: u32,
    /// Delay of every frame (centiseconds).
    delay_cs: u16,
    /// Frames written.
    frames: usize,
    /// The last frame's pixels (RGBA), to find what changed.
    previous: Vec<u8>,
}

impl<W: Write> std::fmt::Debug for GifWriter<W> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GifWriter")
            .field("width", &self.width)
            .field("height", &self.height)
            .field("delay_cs", &self.delay_cs)
            .field("frames", &self.frames)
            .finish_non_exhaustive()
    }
}

impl<W: Write> GifWriter<W> {
    /// Starts a GIF of `width × height` pixels showing each frame for `frame_interval` seconds (rounded to
    /// centiseconds, at least [`MIN_FRAME_INTERVAL`]).
    ///
    /// # Errors
    /// [`RenderError::Options`] naming `width`, `height` (0 or above 65535) or `frame_interval` (not finite,
    /// ≤ 0 or above [`MAX_FRAME_INTERVAL`]); [`RenderError::Gif`] if writing the header fails.
    pub fn new(
        writer: W,
        width: u32,
        height: u32,
        frame_interval: f32,
    ) -> Result<Self, RenderError> {
        let side = |field, value: u32| {
            u16::try_from(value)
                .ok()
                .filter(|&v| v > 0)
                .ok_or(RenderError::Options {
                    field,
                    value: value.to_string(),
                    expected: "1 to 65535 pixels",
                })
        };
        let (w, h) = (side("width", width)?, side("height", height)?);
        if !(frame_interval.is_finite()
            && frame_interval > 0.0
            && frame_interval <= MAX_FRAME_INTERVAL)
        {
            return Err(RenderError::Options {
                field: "frame_interval",
                value: frame_interval.to_string(),
                expected: "finite, > 0 and at most 655.35 s",
            });
        }
        let delay_cs = (frame_interval.max(MIN_FRAME_INTERVAL) * 100.0).round() as u16;
        let mut encoder = gif::Encoder::new(writer, w, h, &[])?;
        encoder.set_repeat(gif::Repeat::Infinite)?;
        Ok(Self {
            encoder,
            width,
            height,
            delay_cs,
            frames: 0,
            previous: Vec::new(),
        })
    }

    /// Appends a frame.
    ///
    /// # Errors
    /// [`RenderError::FrameSize`] if the image is not of the animation's size (nothing is written);
    /// [`RenderError::Gif`] if writing fails.
    pub fn add_frame(&mut self, image: &Image) -> Result<(), RenderError> {
        if image.width() != self.width || image.height() != self.height {
            return Err(RenderError::FrameSize {
                width: image.width(),
                height: image.height(),
                expected_width: self.width,
                expected_height: self.height,
            });
        }
        let mut rgba = image.rgba().to_vec();
        if self.previous.len() == rgba.len() {
            for (pixel, before) in rgba.chunks_exact_mut(4).zip(self.previous.chunks_exact(4)) {
                if pixel == before {
                    pixel.copy_from_slice(&[0; 4]);
                }
            }
        }
        // The sides were checked to fit in u16 in `new`, and the image has the same sides.
        let (w, h) = (self.width as u16, self.height as u16);
        let mut frame = gif::Frame::from_rgba_speed(w, h, &mut rgba, QUANTISER_SPEED);
        frame.delay = self.delay_cs;
        frame.dispose = gif::DisposalMethod::Keep;
        self.encoder.write_frame(&frame)?;
        self.previous.clear();
        self.previous.extend_from_slice(image.rgba());
        self.frames += 1;
        Ok(())
    }

    /// Frames written so far.
    #[must_use]
    pub fn frame_count(&self) -> usize {
        self.frames
    }

    /// Delay of each frame (centiseconds).
    #[must_use]
    pub fn delay_cs(&self) -> u16 {
        self.delay_cs
    }

    /// Writes the trailer and returns the writer.
    ///
    /// # Errors
    /// [`RenderError::Gif`] if writing fails.
    pub fn finish(self) -> Result<W, RenderError> {
        Ok(self.encoder.into_inner()?)
    }
}
