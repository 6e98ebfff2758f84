//! SVG plots against time (plotters' SVG backend): one panel per quantity, stacked, each a line per series
//! with a legend. [`TimeHistory`] holds what a run's plot shows — energy, momentum, worst joint error and
//! deepest penetration — and [`plot_svg`] draws any panels over a shared time axis.

use plotters::prelude::*;

use crate::PlotError;

/// One line of a panel: a value per time sample.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// The legend's name for it.
    pub name: String,
    /// One value per time sample (the panel's unit).
    pub values: Vec<f64>,
}

/// One chart: its series share a y axis.
#[derive(Debug, Clone, PartialEq)]
pub struct Panel {
    /// Caption above the chart.
    pub title: String,
    /// Label of the y axis, with the unit, e.g. "energy (J)".
    pub y_label: String,
    /// The lines.
    pub series: Vec<Series>,
}

/// Picture size of a plot.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct PlotOptions {
    /// Width (pixels, [`MIN_PLOT_SIDE`] to [`MAX_PLOT_SIDE`]). Default: 900.
    pub width: u32,
    /// Height of each panel (pixels, [`MIN_PLOT_SIDE`] to [`MAX_PLOT_SIDE`]). Default: 260.
    pub panel_height: u32,
}

impl Default for PlotOptions {
    fn default() -> Self {
        Self {
            width: 900,
            panel_height: 260,
        }
    }
}

/// The smallest plot width or panel height (pixels).
pub const MIN_PLOT_SIDE: u32 = 100;
/// The largest plot width or panel height (pixels).
pub const MAX_PLOT_SIDE: u32 = 8_192;

/// The largest magnitude of a time or value plotted: the f32 range a recording's numbers come from
/// (≈ 3.4·10³⁸). Beyond it the padded axis range can overflow to infinity, where plotters finds no ticks.
pub const MAX_PLOT_MAGNITUDE: f64 = f32::MAX as f64;

/// Colours of a panel's series, in turn.
const SERIES_COLOURS: [RGBColor; 6] = [
    RGBColor(214, 39, 40),
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(23, 190, 207),
];

/// Draws `panels` stacked, against `time` (s), as an SVG document.
///
/// # Errors
/// [`PlotError::NoSamples`] for an empty time axis; [`PlotError::Time`] for a decreasing time or one beyond
/// ±[`MAX_PLOT_MAGNITUDE`]; [`PlotError::Length`] for a series without one value per time;
/// [`PlotError::Value`] for a value beyond ±[`MAX_PLOT_MAGNITUDE`] or not finite; [`PlotError::Size`] for a
/// size out of range.
pub fn plot_svg(
    time: &[f64],
    panels: &[Panel],
    options: &PlotOptions,
) -> Result<String, PlotError> {
    check(time, panels, options)?;
    let height = options
        .panel_height
        .saturating_mul(panels.len().max(1) as u32);
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (options.width, height)).into_drawing_area();
        root.fill(&WHITE).map_err(drawing)?;
        let areas = root.split_evenly((panels.len().max(1), 1));
        for (area, panel) in areas.iter().zip(panels) {
            draw_panel(area, time, panel)?;
        }
        root.present().map_err(drawing)?;
    }
    Ok(svg)
}

/// The refusals of [`plot_svg`].
fn check(time: &[f64], panels: &[Panel], options: &PlotOptions) -> Result<(), PlotError> {
    for (field, value) in [
        ("width", options.width),
        ("panel_height", options.panel_height),
    ] {
        if !(MIN_PLOT_SIDE..=MAX_PLOT_SIDE).contains(&value) {
            return Err(PlotError::Size {
                field,
                value,
                expected: "100 to 8192 pixels",
            });
        }
    }
    if time.is_empty() {
        return Err(PlotError::NoSamples);
    }
    let mut previous = f64::NEG_INFINITY;
    for (index, &t) in time.iter().enumerate() {
        if !plottable(t) || t < previous {
            return Err(PlotError::Time {
                index,
                value: t.to_string(),
            });
        }
        previous = t;
    }
    for series in panels.iter().flat_map(|p| &p.series) {
        if series.values.len() != time.len() {
            return Err(PlotError::Length {
                series: series.name.clone(),
                len: series.values.len(),
                expected: time.len(),
            });
        }
        if let Some((index, v)) = series
            .values
            .iter()
            .enumerate()
            .find(|(_, v)| !plottable(**v))
        {
            return Err(PlotError::Value {
                series: series.name.clone(),
                index,
                value: v.to_string(),
            });
        }
    }
    Ok(())
}

/// Finite and within ±[`MAX_PLOT_MAGNITUDE`].
fn plottable(v: f64) -> bool {
    v.is_finite() && v.abs() <= MAX_PLOT_MAGNITUDE
}

/// A plotters error as ours.
fn drawing(error: impl std::fmt::Display) -> PlotError {
    PlotError::Drawing(error.to_string())
}

/// `lo..hi` widened by 5 % each side, or by 1 about a single value.
fn padded(lo: f64, hi: f64) -> std::ops::Range<f64> {
    let span = hi - lo;
    if span > 0.0 {
        (lo - 0.05 * span)..(hi + 0.05 * span)
    } else {
        (lo - 1.0)..(hi + 1.0)
    }
}

/// One panel: axes, a line per series, a legend.
fn draw_panel<B: DrawingBackend>(
    area: &DrawingArea<B, plotters::coord::Shift>,
    time: &[f64],
    panel: &Panel,
) -> Result<(), PlotError> {
    let values = panel.series.iter().flat_map(|s| s.values.iter().copied());
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
        (lo.min(v), hi.max(v))
    });
    let y_range = if lo <= hi { padded(lo, hi) } else { -1.0..1.0 };
    let (t0, t1) = (
        time.first().copied().unwrap_or(0.0),
        time.last().copied().unwrap_or(0.0),
    );
    let x_range = if t1 > t0 { t0..t1 } else { padded(t0, t1) };
    let mut chart = ChartBuilder::on(area)
        .caption(&panel.title, ("sans-serif", 16))
        .margin(10)
        .x_label_area_size(32)
        .y_label_area_size(70)
        .build_cartesian_2d(x_range, y_range)
        .map_err(drawing)?;
    chart
        .configure_mesh()
        .x_desc("time (s)")
        .y_desc(panel.y_label.as_str())
        .draw()
        .map_err(drawing)?;
    for (k, series) in panel.series.iter().enumerate() {
        let colour = SERIES_COLOURS[k % SERIES_COLOURS.len()];
        let points = time.iter().copied().zip(series.values.iter().copied());
        chart
            .draw_series(LineSeries::new(points, colour.stroke_width(2)))
            .map_err(drawing)?
            .label(series.name.as_str())
            .legend(move |(x, y)| Rectangle::new([(x, y - 4), (x + 16, y + 4)], colour.filled()));
    }
    if !panel.series.is_empty() {
        chart
            .configure_series_labels()
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .draw()
            .map_err(drawing)?;
    }
    Ok(())
}

/// What a run's plot shows, one sample per recorded frame. A series left empty was not recorded and is
/// left out (a panel with no series left is left out too).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TimeHistory {
    /// Simulated time of each sample (s, non-decreasing).
    pub time: Vec<f64>,
    /// Kinetic energy, translational plus rotational (J).
    pub kinetic_energy: Vec<f64>,
    /// Gravitational potential energy (J, relative to y = 0).
    pub potential_energy: Vec<f64>,
    /// Energy stored in springs and soft joints (J).
    pub spring_energy: Vec<f64>,
    /// Total linear momentum (N·s, world x, y, z).
    pub linear_momentum: Vec<[f64; 3]>,
    /// Total angular momentum about the world origin (N·m·s, world x, y, z).
    pub angular_momentum: Vec<[f64; 3]>,
    /// The largest joint position error of the sample (m).
    pub worst_joint_error: Vec<f64>,
    /// The deepest contact penetration of the sample (m, ≥ 0: the most negative separation, negated).
    pub deepest_penetration: Vec<f64>,
}

impl TimeHistory {
    /// The panels: energy (kinetic, potential, spring and their total), linear momentum, angular momentum,
    /// worst joint error, deepest penetration.
    #[must_use]
    pub fn panels(&self) -> Vec<Panel> {
        let series = |name: &str, values: &[f64]| Series {
            name: name.to_owned(),
            values: values.to_vec(),
        };
        let mut energy: Vec<Series> = [
            ("kinetic", &self.kinetic_energy),
            ("potential", &self.potential_energy),
            ("spring", &self.spring_energy),
        ]
        .into_iter()
        .filter(|(_, v)| !v.is_empty())
        .map(|(name, v)| series(name, v))
        .collect();
        if energy.len() > 1 && energy.iter().all(|s| s.values.len() == self.time.len()) {
            let total = (0..self.time.len())
                .map(|i| energy.iter().map(|s| s.values[i]).sum())
                .collect();
            energy.push(Series {
                name: "total".to_owned(),
                values: total,
            });
        }
        let components = |prefix: &str, v: &[[f64; 3]]| -> Vec<Series> {
            if v.is_empty() {
                return Vec::new();
            }
            ["x", "y", "z"]
                .iter()
                .enumerate()
                .map(|(axis, name)| Series {
                    name: format!("{prefix}{name}"),
                    values: v.iter().map(|c| c[axis]).collect(),
                })
                .collect()
        };
        let single = |name: &str, v: &[f64]| {
            if v.is_empty() {
                Vec::new()
            } else {
                vec![series(name, v)]
            }
        };
        let panel = |title: &str, y_label: &str, series: Vec<Series>| Panel {
            title: title.to_owned(),
            y_label: y_label.to_owned(),
            series,
        };
        [
            panel("Energy", "energy (J)", energy),
            panel(
                "Linear momentum",
                "momentum (N·s)",
                components("p", &self.linear_momentum),
            ),
            panel(
                "Angular momentum",
                "angular momentum (N·m·s)",
                components("L", &self.angular_momentum),
            ),
            panel(
                "Worst joint error",
                "error (m)",
                single("joint error", &self.worst_joint_error),
            ),
            panel(
                "Deepest penetration",
                "depth (m)",
                single("penetration", &self.deepest_penetration),
            ),
        ]
        .into_iter()
        .filter(|p| !p.series.is_empty())
        .collect()
    }

    /// [`TimeHistory::panels`] drawn by [`plot_svg`].
    ///
    /// # Errors
    /// As [`plot_svg`] (a series neither empty nor one value per time is refused with its name).
    pub fn to_svg(&self, options: &PlotOptions) -> Result<String, PlotError> {
        plot_svg(&self.time, &self.panels(), options)
    }
}
