//! `RenderError` and `PlotError`: what the picture and plot doors refuse, each naming the field and the value.

use rebound::ShapeError;

/// Why a picture could not be made. Nothing is drawn or written when one is returned.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum RenderError {
    /// A [`crate::Camera`] field is out of range.
    #[error("camera `{field}` is {value}: {expected}")]
    Camera {
        /// The field's name.
        field: &'static str,
        /// The refused value, printed.
        value: String,
        /// What the field must be.
        expected: &'static str,
    },
    /// A [`crate::RenderOptions`] (or [`crate::Grid`]) field is out of range.
    #[error("render option `{field}` is {value}: {expected}")]
    Options {
        /// The field's name.
        field: &'static str,
        /// The refused value, printed.
        value: String,
        /// What the field must be.
        expected: &'static str,
    },
    /// A shape description is invalid (the facade's own check, as when a collider is inserted).
    #[error("shape: {0}")]
    Shape(#[from] ShapeError),
    /// A recording's descriptions or changes are inconsistent.
    #[error("recording: {0}")]
    Recording(#[from] rebound_record::RecordingError),
    /// A frame given to an animation is not of the animation's size.
    #[error(
        "frame is {width}×{height} pixels but the animation is {expected_width}×{expected_height}"
    )]
    FrameSize {
        /// The frame's width (pixels).
        width: u32,
        /// The frame's height (pixels).
        height: u32,
        /// The animation's width (pixels).
        expected_width: u32,
        /// The animation's height (pixels).
        expected_height: u32,
    },
    /// The PNG encoder failed (in practice: the writer failed).
    #[error("PNG encoding: {0}")]
    Png(#[from] png::EncodingError),
    /// The GIF encoder failed (in practice: the writer failed).
    #[error("GIF encoding: {0}")]
    Gif(#[from] gif::EncodingError),
    /// Reading or writing a file failed.
    #[error("I/O: {0}")]
    Io(#[from] std::io::Error),
}

/// Why a plot could not be made. Nothing is written when one is returned.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum PlotError {
    /// The time axis is empty.
    #[error("the time axis has no samples")]
    NoSamples,
    /// A time is not finite, is beyond ±[`crate::MAX_PLOT_MAGNITUDE`] or is less than the one before it.
    #[error("time[{index}] is {value}: times must be finite, within ±3.4e38 s and non-decreasing")]
    Time {
        /// Index of the sample.
        index: usize,
        /// The refused value, printed.
        value: String,
    },
    /// A series does not have one value per time sample.
    #[error("series `{series}` has {len} values for {expected} time samples")]
    Length {
        /// The series' name.
        series: String,
        /// Its number of values.
        len: usize,
        /// The number of time samples.
        expected: usize,
    },
    /// A series value is not finite or is beyond ±[`crate::MAX_PLOT_MAGNITUDE`].
    #[error("series `{series}`[{index}] is {value}: values must be finite and within ±3.4e38")]
    Value {
        /// The series' name.
        series: String,
        /// Index of the sample.
        index: usize,
        /// The refused value, printed.
        value: String,
    },
    /// The plot's size is out of range.
    #[error("plot `{field}` is {value}: {expected}")]
    Size {
        /// The field's name.
        field: &'static str,
        /// The refused value, printed.
        value: u32,
        /// What the field must be.
        expected: &'static str,
    },
    /// The SVG backend failed.
    #[error("drawing the SVG: {0}")]
    Drawing(String),
}
