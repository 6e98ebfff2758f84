//! `--scaling`: Rebound alone on growing scenes, and the cost-growth exponent.

use std::fmt::Write as _;

use rebound_suite::scenes::metrics::median;
use rebound_suite::scenes::{Balls, Pyramid, Scene, SceneOptions};
use serde_json::{Map, json};

use crate::run::{Phases, WARMUP_STEPS, on_threads, rebound_engine, run_scene};

/// One point of a scaling series.
#[derive(Debug, Clone, Copy)]
pub(crate) struct ScalingPoint {
    pub(crate) bodies: usize,
    pub(crate) ms: f64,
    pub(crate) phases: Phases,
}

/// The least-squares slope of `ln ms` against `ln n`: cost ∝ n^slope.
pub(crate) fn growth_exponent(points: &[ScalingPoint]) -> f64 {
    let xs: Vec<f64> = points.iter().map(|p| (p.bodies as f64).ln()).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.ms.ln()).collect();
    let n = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// The scaling series: Rebound only.
pub(crate) fn scaling(
    rounds: Option<usize>,
    steps: Option<usize>,
    threads: Option<usize>,
    json: bool,
) -> Result<(), String> {
    let rounds = rounds.unwrap_or(1);
    // The 16,384-ball pile is the slowest scene: fewer steps than the comparison by default.
    let steps = steps.unwrap_or(180);
    type Builder = fn(usize) -> Result<Box<dyn Scene>, rebound::Error>;
    let balls: Builder = |side| Ok(Box::new(Balls::new(SceneOptions::default(), side)?));
    let pyramid: Builder = |base| Ok(Box::new(Pyramid::new(SceneOptions::default(), base)?));
    type Label = fn(usize) -> String;
    let balls_label: Label = |side| format!("{side} × 16 × {side}");
    let pyramid_label: Label = |base| format!("base {base}");
    let series: [(&str, Builder, [usize; 3], Label); 2] = [
        ("balls", balls, [8, 16, 32], balls_label),
        ("pyramid", pyramid, [20, 40, 80], pyramid_label),
    ];
    let mut table = String::new();
    let _ = writeln!(
        table,
        "{}: scaling, {}, dt = 1/60, sleeping off, {steps} steps; ms/step = median over rounds ({rounds}) \
         of each run's median over steps {WARMUP_STEPS}..{steps}; phases: mean ms/step (StepReport::profile)\n",
        rebound_engine(),
        threads.map_or_else(|| "single thread".to_owned(), |n| format!("{n} threads")),
    );
    let _ = writeln!(
        table,
        "| series | size | bodies | ms/step | µs per body | collide | prepare | solve | restitution | finalize | facade |"
    );
    let _ = writeln!(table, "|---|---|---|---|---|---|---|---|---|---|---|");
    let mut exponents = Vec::new();
    for (name, build, sizes, label) in series {
        let mut points = Vec::new();
        for size in sizes {
            let mut medians = Vec::new();
            let mut phases = Vec::new();
            let mut bodies = 0;
            for _ in 0..rounds {
                let mut scene = build(size).map_err(|e| format!("building {name} {size}: {e}"))?;
                let (timing, p) = on_threads(threads, || run_scene(scene.as_mut(), steps))?;
                bodies = scene.body_count();
                medians.push(timing.median_ms);
                phases.push(p);
            }
            let point = ScalingPoint {
                bodies,
                ms: median(&medians),
                phases: Phases::mean(&phases),
            };
            eprintln!(
                "compare: scaling {name} {size}: {bodies} bodies, {:.3} ms/step",
                point.ms
            );
            if json {
                println!(
                    "{}",
                    json!({"series": name, "size": size, "bodies": bodies, "steps": steps, "rounds": rounds,
                           "ms_median": point.ms,
                           "profile_ms": point.phases.entries().iter().map(|&(k, v)| (k.to_owned(), json!(v))).collect::<Map<_, _>>()})
                );
            }
            let _ = writeln!(
                table,
                "| {name} | {} | {bodies} | {:.3} | {:.2} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} | {:.3} |",
                label(size),
                point.ms,
                1e3 * point.ms / bodies as f64,
                point.phases.collide,
                point.phases.prepare,
                point.phases.solve,
                point.phases.restitution,
                point.phases.finalize,
                point.phases.facade,
            );
            points.push(point);
        }
        let exponent = growth_exponent(&points);
        if json {
            println!("{}", json!({"series": name, "exponent": exponent}));
        }
        exponents.push((name, exponent));
    }
    if !json {
        let _ = writeln!(
            table,
            "\nCost-growth exponent (least-squares slope of log ms/step against log bodies; 1 = linear):"
        );
        for (name, exponent) in exponents {
            let _ = writeln!(table, "- {name}: {exponent:.2}");
        }
        print!("{table}");
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::{ScalingPoint, growth_exponent};

    #[test]
    fn exponent_of_a_power_law() {
        let points: Vec<ScalingPoint> = [1000usize, 4000, 16000]
            .iter()
            .map(|&n| ScalingPoint {
                bodies: n,
                ms: 2e-3 * (n as f64).powf(1.3),
                phases: crate::run::Phases::default(),
            })
            .collect();
        assert!((growth_exponent(&points) - 1.3).abs() < 1e-9);
    }
}
