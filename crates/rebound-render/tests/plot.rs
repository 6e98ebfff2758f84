//! Plots parsed back from their SVG: the expected lines, one point per sample, placed as the data.

use rebound_render::{Panel, PlotError, PlotOptions, Series, TimeHistory, plot_svg};

/// The polylines of an SVG document with at least `min_points` points each, as (x, y) lists (pixels).
fn polylines(svg: &str, min_points: usize) -> Vec<Vec<(f64, f64)>> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    doc.descendants()
        .filter(|n| n.has_tag_name("polyline"))
        .filter_map(|n| n.attribute("points"))
        .map(|points| {
            points
                .split_whitespace()
                .map(|pair| {
                    let (x, y) = pair.split_once(',').expect("x,y");
                    (x.parse().expect("a number"), y.parse().expect("a number"))
                })
                .collect::<Vec<_>>()
        })
        .filter(|line| line.len() >= min_points)
        .collect()
}

/// A falling ball's history: energy traded between kinetic and potential, momentum growing downwards.
fn history(samples: usize) -> TimeHistory {
    let (g, m, h) = (9.81, 2.0, 10.0);
    let time: Vec<f64> = (0..samples).map(|i| i as f64 * 0.02).collect();
    let speed: Vec<f64> = time.iter().map(|t| g * t).collect();
    TimeHistory {
        kinetic_energy: speed.iter().map(|v| 0.5 * m * v * v).collect(),
        potential_energy: time.iter().map(|t| m * g * (h - 0.5 * g * t * t)).collect(),
        spring_energy: vec![0.0; samples],
        linear_momentum: speed.iter().map(|v| [0.0, -m * v, 0.0]).collect(),
        angular_momentum: vec![[0.0; 3]; samples],
        worst_joint_error: time.iter().map(|t| 1e-4 * t).collect(),
        deepest_penetration: time.iter().map(|t| 1e-3 * t * t).collect(),
        time,
    }
}

#[test]
fn a_history_plots_every_series_with_a_point_per_sample() {
    let samples = 60;
    let svg = history(samples)
        .to_svg(&PlotOptions::default())
        .expect("plots");
    let lines = polylines(&svg, 3);
    // Energy: kinetic, potential, spring, total; p and L: three components each; joint error; penetration.
    assert_eq!(lines.len(), 4 + 3 + 3 + 1 + 1);
    for line in &lines {
        assert_eq!(line.len(), samples);
        // Time runs left to right.
        assert!(line.windows(2).all(|w| w[1].0 > w[0].0));
    }
    let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
    let text: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .filter_map(|n| n.text())
        .map(str::trim)
        .collect();
    for label in [
        "Energy",
        "kinetic",
        "potential",
        "total",
        "py",
        "Deepest penetration",
        "time (s)",
    ] {
        assert!(text.contains(&label), "{label} missing from {text:?}");
    }
}

#[test]
fn values_map_to_heights_as_the_data_do() {
    // One panel, one series: y pixel = a − b·value with b > 0, so increasing data go up the picture and the
    // points lie on that line to within the backend's rounding to whole pixels.
    let time: Vec<f64> = (0..40).map(f64::from).collect();
    let values: Vec<f64> = time.iter().map(|t| t * t).collect();
    let panels = [Panel {
        title: "square".to_owned(),
        y_label: "t² (s²)".to_owned(),
        series: vec![Series {
            name: "t²".to_owned(),
            values: values.clone(),
        }],
    }];
    let svg = plot_svg(&time, &panels, &PlotOptions::default()).expect("plots");
    let lines = polylines(&svg, 3);
    assert_eq!(lines.len(), 1);
    let line = &lines[0];
    assert!(
        line.windows(2).all(|w| w[1].1 <= w[0].1),
        "heights not monotonic"
    );
    let (first, last) = (line[0], line[39]);
    let per_value = (first.1 - last.1) / (values[39] - values[0]);
    let per_second = (last.0 - first.0) / (time[39] - time[0]);
    assert!(per_value > 0.0 && per_second > 0.0);
    for (i, &(x, y)) in line.iter().enumerate() {
        assert!(
            (x - (first.0 + per_second * time[i])).abs() <= 1.0,
            "x of sample {i}"
        );
        assert!(
            (y - (first.1 - per_value * values[i])).abs() <= 1.0,
            "y of sample {i}"
        );
    }
}

#[test]
fn unrecorded_series_are_left_out() {
    let mut h = history(10);
    h.angular_momentum.clear();
    h.worst_joint_error.clear();
    let panels = h.panels();
    let titles: Vec<_> = panels.iter().map(|p| p.title.as_str()).collect();
    assert_eq!(titles, ["Energy", "Linear momentum", "Deepest penetration"]);
    let svg = h.to_svg(&PlotOptions::default()).expect("plots");
    assert_eq!(polylines(&svg, 3).len(), 4 + 3 + 1);
}

#[test]
fn bad_data_are_refused_naming_the_series_and_sample() {
    let mut h = history(10);
    h.kinetic_energy[4] = f64::NAN;
    match h.to_svg(&PlotOptions::default()) {
        Err(PlotError::Value { series, index, .. }) => {
            assert_eq!((series.as_str(), index), ("kinetic", 4));
        }
        other => panic!("{other:?}"),
    }
    let mut h = history(10);
    h.deepest_penetration.pop();
    assert!(matches!(
        h.to_svg(&PlotOptions::default()),
        Err(PlotError::Length {
            len: 9,
            expected: 10,
            ..
        })
    ));
    let mut h = history(10);
    h.spring_energy[2] = 1.0e300;
    assert!(matches!(
        h.to_svg(&PlotOptions::default()),
        Err(PlotError::Value { index: 2, .. })
    ));
    let mut h = history(10);
    h.time[3] = 0.0;
    assert!(matches!(
        h.to_svg(&PlotOptions::default()),
        Err(PlotError::Time { index: 3, .. })
    ));
    assert_eq!(
        plot_svg(&[], &[], &PlotOptions::default()),
        Err(PlotError::NoSamples)
    );
    let tiny = PlotOptions {
        width: 10,
        ..PlotOptions::default()
    };
    assert!(matches!(
        history(3).to_svg(&tiny),
        Err(PlotError::Size { field: "width", .. })
    ));
}

#[test]
fn a_single_sample_still_plots() {
    let svg = history(1).to_svg(&PlotOptions::default()).expect("plots");
    assert!(roxmltree::Document::parse(&svg).is_ok());
}

#[test]
fn extreme_ranges_plot_without_panicking() {
    let cases: [(Vec<f64>, Vec<f64>); 5] = [
        (vec![0.0, 1e-9, 2e-9], vec![0.0, 1e-30, 2e-30]),
        (vec![0.0, 1.0, 2.0], vec![-3.0e38, 0.0, 3.0e38]),
        (vec![5.0, 5.0, 5.0], vec![1.0, 1.0, 1.0]),
        (vec![0.0, 1e6, 2e6], vec![1e-300, -1e-300, 0.0]),
        (vec![-1e30, 0.0, 1e30], vec![7.0, 8.0, 7.0]),
    ];
    for (time, values) in cases {
        let panels = [Panel {
            title: "extreme".to_owned(),
            y_label: "x".to_owned(),
            series: vec![Series {
                name: "x".to_owned(),
                values,
            }],
        }];
        let svg = plot_svg(&time, &panels, &PlotOptions::default()).expect("plots");
        assert_eq!(polylines(&svg, 3).len(), 1);
    }
}
