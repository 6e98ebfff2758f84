//! [`Color`]: linear RGBA in `[0, 1]`, what every line and triangle of a [`crate::DebugDraw`] carries.

/// A colour: red, green, blue and alpha (opacity), each in `[0, 1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Color {
    /// Red.
    pub r: f32,
    /// Green.
    pub g: f32,
    /// Blue.
    pub b: f32,
    /// Opacity (1 = opaque).
    pub a: f32,
}

impl Color {
    /// An opaque colour.
    #[must_use]
    pub const fn rgb(r: f32, g: f32, b: f32) -> Self {
        Self { r, g, b, a: 1.0 }
    }

    /// A colour with opacity `a`.
    #[must_use]
    pub const fn rgba(r: f32, g: f32, b: f32, a: f32) -> Self {
        Self { r, g, b, a }
    }

    /// The same colour with opacity `a`.
    #[must_use]
    pub const fn with_alpha(self, a: f32) -> Self {
        Self { a, ..self }
    }

    /// The colour as `[r, g, b, a]`.
    #[must_use]
    pub const fn to_array(self) -> [f32; 4] {
        [self.r, self.g, self.b, self.a]
    }

    /// The colour as 8-bit `[r, g, b, a]`, each channel clamped to `[0, 1]` and rounded.
    #[must_use]
    pub fn to_rgba8(self) -> [u8; 4] {
        self.to_array()
            .map(|c| (c.clamp(0.0, 1.0) * 255.0).round() as u8)
    }

    /// White.
    pub const WHITE: Self = Self::rgb(1.0, 1.0, 1.0);
    /// Black.
    pub const BLACK: Self = Self::rgb(0.0, 0.0, 0.0);
    /// Red.
    pub const RED: Self = Self::rgb(1.0, 0.0, 0.0);
    /// Green.
    pub const GREEN: Self = Self::rgb(0.0, 1.0, 0.0);
    /// Blue.
    pub const BLUE: Self = Self::rgb(0.0, 0.0, 1.0);
}
