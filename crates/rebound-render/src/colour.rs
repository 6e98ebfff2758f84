//! `Rgba`: an 8-bit sRGB colour with alpha, as pictures and scenes use it.

/// An 8-bit-per-channel sRGB colour with alpha (0 transparent, 255 opaque).
///
/// Solid shapes and the background are drawn opaque whatever their alpha; the grid and the overlays
/// (contacts, joints) blend with their alpha.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Rgba {
    /// Red (0–255).
    pub r: u8,
    /// Green (0–255).
    pub g: u8,
    /// Blue (0–255).
    pub b: u8,
    /// Alpha (0–255).
    pub a: u8,
}

impl Rgba {
    /// Opaque black.
    pub const BLACK: Self = Self::opaque(0, 0, 0);
    /// Opaque white.
    pub const WHITE: Self = Self::opaque(255, 255, 255);
    /// Opaque red.
    pub const RED: Self = Self::opaque(255, 0, 0);
    /// Opaque green.
    pub const GREEN: Self = Self::opaque(0, 255, 0);
    /// Opaque blue.
    pub const BLUE: Self = Self::opaque(0, 0, 255);

    /// A colour from its four channels.
    #[must_use]
    pub const fn new(r: u8, g: u8, b: u8, a: u8) -> Self {
        Self { r, g, b, a }
    }

    /// An opaque colour.
    #[must_use]
    pub const fn opaque(r: u8, g: u8, b: u8) -> Self {
        Self::new(r, g, b, 255)
    }

    /// The colour with each of r, g, b multiplied by `factor` (clamped to 0–1), alpha kept: the shade of a lit
    /// face.
    #[must_use]
    pub fn scaled(self, factor: f32) -> Self {
        let factor = if factor.is_nan() {
            0.0
        } else {
            factor.clamp(0.0, 1.0)
        };
        let scale = |c: u8| (f32::from(c) * factor).round() as u8;
        Self::new(scale(self.r), scale(self.g), scale(self.b), self.a)
    }

    /// The colour as tiny-skia's.
    pub(crate) fn to_skia(self) -> tiny_skia::Color {
        tiny_skia::Color::from_rgba8(self.r, self.g, self.b, self.a)
    }
}
