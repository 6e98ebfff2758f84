//! `Image`: a rendered picture (opaque RGBA, 8 bits a channel) and its PNG encoding (the `png` crate).

use std::io::Write;
use std::path::Path;

use tiny_skia::Pixmap;

use crate::{RenderError, Rgba};

/// A picture: `width × height` opaque RGBA pixels, row-major from the top-left.
#[derive(Debug, Clone, PartialEq)]
pub struct Image {
    pub(crate) pixmap: Pixmap,
}

impl Image {
    /// Width (pixels).
    #[must_use]
    pub fn width(&self) -> u32 {
        self.pixmap.width()
    }

    /// Height (pixels).
    #[must_use]
    pub fn height(&self) -> u32 {
        self.pixmap.height()
    }

    /// The pixel at column `x`, row `y` (from the top), or `None` outside the picture.
    #[must_use]
    pub fn pixel(&self, x: u32, y: u32) -> Option<Rgba> {
        // Every pixel is opaque, so tiny-skia's premultiplied bytes are the straight colour.
        self.pixmap
            .pixel(x, y)
            .map(|p| Rgba::new(p.red(), p.green(), p.blue(), p.alpha()))
    }

    /// The pixels as RGBA bytes, 4 a pixel, row-major from the top-left.
    #[must_use]
    pub fn rgba(&self) -> &[u8] {
        self.pixmap.data()
    }

    /// Writes the picture as an 8-bit RGBA PNG to `writer`.
    ///
    /// # Errors
    /// [`RenderError::Png`] if writing fails.
    pub fn write_png(&self, writer: impl Write) -> Result<(), RenderError> {
        let mut encoder = png::Encoder::new(writer, self.width(), self.height());
        encoder.set_color(png::ColorType::Rgba);
        encoder.set_depth(png::BitDepth::Eight);
        let mut writer = encoder.write_header()?;
        writer.write_image_data(self.rgba())?;
        writer.finish()?;
        Ok(())
    }

    /// The picture as PNG bytes.
    ///
    /// # Errors
    /// [`RenderError::Png`] (not expected: the writer is memory).
    pub fn to_png(&self) -> Result<Vec<u8>, RenderError> {
        let mut bytes = Vec::new();
        self.write_png(&mut bytes)?;
        Ok(bytes)
    }

    /// Writes the picture as a PNG file at `path` (created or replaced).
    ///
    /// # Errors
    /// [`RenderError::Io`] if the file cannot be created, [`RenderError::Png`] if writing fails.
    pub fn save_png(&self, path: impl AsRef<Path>) -> Result<(), RenderError> {
        let file = std::io::BufWriter::new(std::fs::File::create(path)?);
        self.write_png(file)
    }
}
