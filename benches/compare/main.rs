//! `compare`: Rebound and rapier3d side by side on the peer scenes of docs/scenes.md, in one run on one machine.
//!
//! ```text
//! cargo run --release --bin compare -- [--rounds R] [--steps N] [--scene NAME|all]... [--json]
//! cargo run --release --bin compare -- --engine rebound [--rounds R] [--steps N] [--scene NAME|all]...
//! cargo run --release --bin compare -- --scaling [--rounds R] [--steps N] [--json]
//! ```
//!
//! It builds the rapier side (`benches/peers`, its own Cargo project) with `cargo build --release`, then, for
//! each round and each scene, runs Rebound in this process and rapier as a subprocess
//! (`benches/peers/target/release/peers --scene S --steps N --json`), alternating which engine goes first
//! scene by scene, because the shared machine's speed drifts for minutes at a time. Both engines time only
//! their step call and report the median ms/step over steps 60..N; the table shows, per scene, the median
//! over the rounds of those medians, the ratio Rebound/rapier, each round's own ratio and their median (the
//! steadier figure when the machine's speed moves between rounds: each round's two runs are back to back),
//! the ratio of each engine's fastest run (the figure least touched by the machine's slow periods), both
//! engines' quality metrics side by side, and where Rebound's step spends its time
//! (`StepReport::profile`).
//!
//! `--engine rebound` runs Rebound alone on the chosen scenes, without building or running rapier: the
//! run to count Rebound's instructions per scene under `valgrind --tool=callgrind` (docs/performance.md,
//! "Layout check").
//!
//! `--scaling` runs Rebound alone on growing scenes instead: balls with 1,024, 4,096 and 16,384 balls and
//! pyramids of base 20, 40 and 80, and fits the cost-growth exponent (the slope of log ms against log n).

#![allow(
    clippy::print_stdout,
    reason = "a command-line report: printing the table is what it is for"
)]

use std::env;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::{Duration, Instant};

use rebound_suite::scenes::metrics::{DisplayJson, TimingStats, median};
use rebound_suite::scenes::{
    self, ALL_SCENES, Balls, DEFAULT_SCENES, Pyramid, Scene, SceneOptions, Value,
};
use serde_json::{Map, Value as Json, json};

/// Steps excluded from the timing statistics (warm-up: the pile, stack or chain is still forming), as in
/// the rapier side.
const WARMUP_STEPS: usize = 60;

const USAGE: &str = "\
usage: compare [--engine both|rebound] [--rounds R] [--steps N] [--scene NAME|all]... [--json]
       compare --scaling [--rounds R] [--steps N] [--json]

  --engine E    both (default): Rebound beside rapier; rebound: Rebound alone, rapier neither built nor run
  --rounds R    rounds of every scene in both engines (default 3); times are the median over rounds
  --steps N     steps per run (default 600); timing statistics cover steps 60..N
  --scene NAME  balls | pyramid | chain | springs | bridge | chain_spherical | all
                (repeatable; default: the five peer scenes of docs/scenes.md)
  --scaling     Rebound alone: balls at 1k, 4k, 16k and pyramid bases 20, 40, 80, with the cost-growth
                exponent (default 180 steps, 1 round: about 3.5 minutes, most of it
                the 16k-ball pile)
  --json        one JSON object per line instead of the tables
";

/// Which engines a comparison runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Engines {
    /// Rebound and rapier side by side.
    Both,
    /// Rebound alone (no rapier build).
    Rebound,
}

/// Parsed command line.
#[derive(Debug, Clone, PartialEq, Eq)]
struct Args {
    engines: Engines,
    rounds: Option<usize>,
    steps: Option<usize>,
    scenes: Vec<String>,
    scaling: bool,
    json: bool,
}

/// Parses the command line; `Err` carries the message to print (the usage text for `--help`).
fn parse_args(args: impl IntoIterator<Item = String>) -> Result<Args, String> {
    let mut parsed = Args {
        engines: Engines::Both,
        rounds: None,
        steps: None,
        scenes: Vec::new(),
        scaling: false,
        json: false,
    };
    let positive = |flag: &str, value: Option<String>| -> Result<usize, String> {
        let value = value.ok_or_else(|| format!("{flag} needs a number"))?;
        value
            .parse()
            .ok()
            .filter(|&n: &usize| n > 0)
            .ok_or_else(|| format!("{flag}: `{value}` is not a positive integer"))
    };
    let mut args = args.into_iter();
    while let Some(arg) = args.next() {
        match arg.as_str() {
            "--engine" => {
                parsed.engines = match args.next().as_deref() {
                    Some("both") => Engines::Both,
                    Some("rebound") => Engines::Rebound,
                    Some(other) => {
                        return Err(format!(
                            "--engine: `{other}` is not an engine (expected both or rebound)"
                        ));
                    }
                    None => return Err("--engine needs both or rebound".to_owned()),
                };
            }
            "--rounds" => parsed.rounds = Some(positive("--rounds", args.next())?),
            "--steps" => parsed.steps = Some(positive("--steps", args.next())?),
            "--scene" => {
                let name = args.next().ok_or("--scene needs a scene name")?;
                if name == "all" {
                    parsed
                        .scenes
                        .extend(DEFAULT_SCENES.iter().map(|&s| s.to_owned()));
                } else if ALL_SCENES.contains(&name.as_str()) {
                    parsed.scenes.push(name);
                } else {
                    return Err(format!(
                        "unknown scene `{name}` (expected one of {} or all)",
                        ALL_SCENES.join(", ")
                    ));
                }
            }
            "--scaling" => parsed.scaling = true,
            "--json" => parsed.json = true,
            "-h" | "--help" => return Err(USAGE.to_owned()),
            other => return Err(format!("unknown argument `{other}`\n\n{USAGE}")),
        }
    }
    if parsed.scenes.is_empty() {
        parsed.scenes = DEFAULT_SCENES.iter().map(|&s| s.to_owned()).collect();
    }
    Ok(parsed)
}

/// Where Rebound's step spends its time: the mean over steps 60..N of each `StepReport::profile` phase (ms),
/// plus the facade's own work after the world's step (query BVH refresh, sensors): measured wall time minus
/// the world's `total`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
struct Phases {
    collide: f64,
    prepare: f64,
    solve: f64,
    restitution: f64,
    finalize: f64,
    /// `PhysicsWorld::step` beyond the world's step.
    facade: f64,
    /// The measured step (wall clock).
    wall: f64,
}

impl Phases {
    /// The phase names and values, in step order.
    fn entries(&self) -> [(&'static str, f64); 7] {
        [
            ("collide", self.collide),
            ("prepare", self.prepare),
            ("solve", self.solve),
            ("restitution", self.restitution),
            ("finalize", self.finalize),
            ("facade", self.facade),
            ("wall", self.wall),
        ]
    }

    /// The element-wise mean of several.
    fn mean(all: &[Self]) -> Self {
        let n = all.len().max(1) as f64;
        let sum = |f: fn(&Self) -> f64| all.iter().map(f).sum::<f64>() / n;
        Self {
            collide: sum(|p| p.collide),
            prepare: sum(|p| p.prepare),
            solve: sum(|p| p.solve),
            restitution: sum(|p| p.restitution),
            finalize: sum(|p| p.finalize),
            facade: sum(|p| p.facade),
            wall: sum(|p| p.wall),
        }
    }
}

/// One engine's run of one scene.
#[derive(Debug, Clone)]
struct Run {
    bodies: usize,
    joints: usize,
    timing: TimingStats,
    /// Metric name → JSON value, in the order the engine reported them.
    quality: Vec<(String, Json)>,
    /// Rebound only.
    phases: Option<Phases>,
}

/// Steps one Rebound scene `steps` times, timing only [`Scene::step`].
fn run_scene(scene: &mut dyn Scene, steps: usize) -> (TimingStats, Phases) {
    let mut step_ms = Vec::with_capacity(steps);
    let mut phases = Vec::with_capacity(steps);
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    for step in 1..=steps {
        let start = Instant::now();
        let report = scene.step();
        let wall = ms(start.elapsed());
        step_ms.push(wall);
        let p = report.profile;
        phases.push(Phases {
            collide: ms(p.collide),
            prepare: ms(p.prepare),
            solve: ms(p.solve),
            restitution: ms(p.restitution),
            finalize: ms(p.finalize),
            facade: wall - ms(p.total),
            wall,
        });
        scene.observe(step);
    }
    let warmup = if steps > WARMUP_STEPS {
        WARMUP_STEPS
    } else {
        0
    };
    (
        TimingStats::of(&step_ms[warmup..]),
        Phases::mean(&phases[warmup..]),
    )
}

/// Builds and runs a scene in Rebound.
fn run_rebound(name: &str, steps: usize) -> Result<Run, String> {
    let mut scene = scenes::build(name, SceneOptions::default())
        .map_err(|e| format!("building `{name}` in Rebound: {e}"))?
        .ok_or_else(|| format!("unknown scene `{name}`"))?;
    let (timing, phases) = run_scene(scene.as_mut(), steps);
    Ok(Run {
        bodies: scene.body_count(),
        joints: scene.joint_count(),
        timing,
        quality: quality_json(&scene.quality()),
        phases: Some(phases),
    })
}

/// A Rebound scene's metrics as (name, JSON value) pairs.
fn quality_json(quality: &[(&'static str, Value)]) -> Vec<(String, Json)> {
    quality
        .iter()
        .map(|&(name, value)| (name.to_owned(), value.to_json()))
        .collect()
}

/// Runs a scene in rapier through the peers binary and reads its `--json` line.
fn run_rapier(peers: &Path, name: &str, steps: usize) -> Result<(Run, String), String> {
    let output = Command::new(peers)
        .args(["--scene", name, "--steps", &steps.to_string(), "--json"])
        .output()
        .map_err(|e| format!("running {}: {e}", peers.display()))?;
    if !output.status.success() {
        return Err(format!(
            "{} --scene {name} failed ({}): {}",
            peers.display(),
            output.status,
            String::from_utf8_lossy(&output.stderr)
        ));
    }
    let stdout = String::from_utf8_lossy(&output.stdout);
    let line = stdout
        .lines()
        .find(|l| l.trim_start().starts_with('{'))
        .ok_or_else(|| format!("peers printed no JSON line for `{name}`: {stdout}"))?;
    let report: Json =
        serde_json::from_str(line).map_err(|e| format!("peers' JSON for `{name}`: {e}"))?;
    let number = |key: &str| report.get(key).and_then(Json::as_f64);
    let count = |key: &str| {
        report
            .get(key)
            .and_then(Json::as_u64)
            .and_then(|n| usize::try_from(n).ok())
            .unwrap_or(0)
    };
    let quality = report
        .get("quality")
        .and_then(Json::as_object)
        .map(|q| q.iter().map(|(k, v)| (k.clone(), v.clone())).collect())
        .unwrap_or_default();
    let engine = report
        .get("engine")
        .and_then(Json::as_str)
        .unwrap_or("rapier3d")
        .to_owned();
    let run = Run {
        bodies: count("bodies"),
        joints: count("joints"),
        timing: TimingStats {
            median_ms: number("ms_median").unwrap_or(f64::NAN),
            mean_ms: number("ms_mean").unwrap_or(f64::NAN),
        },
        quality,
        phases: None,
    };
    Ok((run, engine))
}

/// The workspace root (this package's manifest directory).
fn workspace_root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Builds the rapier side with `cargo build --release` and returns the path of its binary.
fn build_peers() -> Result<PathBuf, String> {
    let root = workspace_root();
    let manifest = root.join("benches/peers/Cargo.toml");
    let cargo = env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    eprintln!(
        "compare: building the rapier side (cargo build --release --manifest-path benches/peers/Cargo.toml)"
    );
    let status = Command::new(&cargo)
        .arg("build")
        .arg("--release")
        .arg("--manifest-path")
        .arg(&manifest)
        .status()
        .map_err(|e| format!("running cargo: {e}"))?;
    if !status.success() {
        return Err(format!("building benches/peers failed ({status})"));
    }
    let exe = root
        .join("benches/peers/target/release")
        .join(format!("peers{}", env::consts::EXE_SUFFIX));
    if exe.is_file() {
        Ok(exe)
    } else {
        Err(format!("{} is missing after the build", exe.display()))
    }
}

/// All rounds of one scene in both engines.
#[derive(Debug, Clone)]
struct SceneResult {
    name: String,
    rebound: Vec<Run>,
    rapier: Vec<Run>,
}

impl SceneResult {
    fn rebound_ms(&self) -> f64 {
        median(
            &self
                .rebound
                .iter()
                .map(|r| r.timing.median_ms)
                .collect::<Vec<_>>(),
        )
    }

    fn rapier_ms(&self) -> f64 {
        median(
            &self
                .rapier
                .iter()
                .map(|r| r.timing.median_ms)
                .collect::<Vec<_>>(),
        )
    }

    /// The fastest run of each engine, Rebound's over rapier's: the shared machines switch between two
    /// speeds for minutes at a time, and a round whose two runs straddle a switch gives a ratio off by up
    /// to 1.5× either way; each engine's fastest run is the one least touched by the slow periods.
    fn fastest_ratio(&self) -> f64 {
        let fastest = |runs: &[Run]| {
            runs.iter()
                .map(|r| r.timing.median_ms)
                .fold(f64::INFINITY, f64::min)
        };
        fastest(&self.rebound) / fastest(&self.rapier)
    }

    fn round_ratios(&self) -> Vec<f64> {
        self.rebound
            .iter()
            .zip(&self.rapier)
            .map(|(a, b)| a.timing.median_ms / b.timing.median_ms)
            .collect()
    }

    fn phases(&self) -> Phases {
        let all: Vec<Phases> = self.rebound.iter().filter_map(|r| r.phases).collect();
        Phases::mean(&all)
    }
}

/// The peer comparison.
fn compare(args: &Args) -> Result<(), String> {
    let rounds = args.rounds.unwrap_or(3);
    let steps = args.steps.unwrap_or(600);
    let peers = build_peers()?;
    let mut results: Vec<SceneResult> = args
        .scenes
        .iter()
        .map(|name| SceneResult {
            name: name.clone(),
            rebound: Vec::new(),
            rapier: Vec::new(),
        })
        .collect();
    let mut rapier_engine = String::from("rapier3d");
    let started = Instant::now();
    for round in 0..rounds {
        for (i, result) in results.iter_mut().enumerate() {
            // Alternate which engine goes first, scene by scene and round by round, so that neither always
            // runs in the same slot of the machine's drifting speed.
            let rebound_first = (round + i) % 2 == 0;
            let mut rebound = None;
            for turn in 0..2 {
                if (turn == 0) == rebound_first {
                    rebound = Some(run_rebound(&result.name, steps)?);
                } else {
                    let (run, engine) = run_rapier(&peers, &result.name, steps)?;
                    rapier_engine = engine;
                    result.rapier.push(run);
                }
            }
            if let Some(run) = rebound {
                eprintln!(
                    "compare: round {}/{rounds} {:<16} Rebound {:>8.3} ms  rapier {:>8.3} ms  ({:.0} s)",
                    round + 1,
                    result.name,
                    run.timing.median_ms,
                    result
                        .rapier
                        .last()
                        .map_or(f64::NAN, |r| r.timing.median_ms),
                    started.elapsed().as_secs_f64()
                );
                result.rebound.push(run);
            }
        }
    }
    if args.json {
        for result in &results {
            println!("{}", scene_json(result, steps, rounds, &rapier_engine));
        }
    } else {
        print!(
            "{}",
            comparison_table(&results, steps, rounds, &rapier_engine)
        );
    }
    Ok(())
}

/// Rebound alone on the chosen scenes: times, quality and phases, no rapier build.
fn rebound_alone(args: &Args) -> Result<(), String> {
    let rounds = args.rounds.unwrap_or(3);
    let steps = args.steps.unwrap_or(600);
    let warmup = if steps > WARMUP_STEPS {
        WARMUP_STEPS
    } else {
        0
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{}: SCENES peer scenes alone, single thread, dt = 1/60, sleeping off, {steps} steps; \
         ms/step = median over rounds ({rounds}) of each run's median over steps {warmup}..{steps}\n",
        rebound_engine()
    );
    let _ = writeln!(out, "| scene | bodies / joints | ms/step | quality |");
    let _ = writeln!(out, "|---|---|---|---|");
    for name in &args.scenes {
        let runs = (0..rounds)
            .map(|_| run_rebound(name, steps))
            .collect::<Result<Vec<_>, _>>()?;
        let ms = median(&runs.iter().map(|r| r.timing.median_ms).collect::<Vec<_>>());
        let Some(last) = runs.last() else {
            continue;
        };
        if args.json {
            println!(
                "{}",
                json!({
                    "scene": name,
                    "steps": steps,
                    "rounds": rounds,
                    "rebound": {
                        "engine": rebound_engine(),
                        "bodies": last.bodies,
                        "joints": last.joints,
                        "ms_median": ms,
                        "quality": Json::Object(last.quality.iter().cloned().collect()),
                    },
                })
            );
        }
        let quality: Vec<String> = last
            .quality
            .iter()
            .map(|(k, v)| format!("`{k}` {}", DisplayJson(v)))
            .collect();
        let _ = writeln!(
            out,
            "| {name} | {} / {} | {ms:.3} | {} |",
            last.bodies,
            last.joints,
            quality.join(", ")
        );
    }
    if !args.json {
        print!("{out}");
    }
    Ok(())
}

/// The Rebound version of this build.
fn rebound_engine() -> String {
    format!("rebound {}", env!("CARGO_PKG_VERSION"))
}

/// One scene's result as a JSON object.
fn scene_json(result: &SceneResult, steps: usize, rounds: usize, rapier_engine: &str) -> Json {
    let quality = |run: Option<&Run>| -> Json {
        Json::Object(
            run.map(|r| r.quality.iter().cloned().collect::<Map<_, _>>())
                .unwrap_or_default(),
        )
    };
    let runs = |runs: &[Run]| -> Vec<f64> { runs.iter().map(|r| r.timing.median_ms).collect() };
    let phases = result.phases();
    json!({
        "scene": result.name,
        "steps": steps,
        "rounds": rounds,
        "ratio": result.rebound_ms() / result.rapier_ms(),
        "median_round_ratio": median(&result.round_ratios()),
        "fastest_ratio": result.fastest_ratio(),
        "rebound": {
            "engine": rebound_engine(),
            "bodies": result.rebound.last().map_or(0, |r| r.bodies),
            "joints": result.rebound.last().map_or(0, |r| r.joints),
            "ms_median": result.rebound_ms(),
            "ms_runs": runs(&result.rebound),
            "profile_ms": phases.entries().iter().map(|&(k, v)| (k.to_owned(), json!(v))).collect::<Map<_, _>>(),
            "quality": quality(result.rebound.last()),
        },
        "rapier": {
            "engine": rapier_engine,
            "bodies": result.rapier.last().map_or(0, |r| r.bodies),
            "joints": result.rapier.last().map_or(0, |r| r.joints),
            "ms_median": result.rapier_ms(),
            "ms_runs": runs(&result.rapier),
            "quality": quality(result.rapier.last()),
        },
    })
}

/// The tables of the comparison: times and ratios, quality side by side, Rebound's per-phase profile.
fn comparison_table(
    results: &[SceneResult],
    steps: usize,
    rounds: usize,
    rapier_engine: &str,
) -> String {
    let warmup = if steps > WARMUP_STEPS {
        WARMUP_STEPS
    } else {
        0
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{} vs {rapier_engine}: peer scenes (docs/scenes.md), single thread, dt = 1/60, sleeping off, {steps} steps;\n\
         ms/step = median over rounds ({rounds}) of each run's median over steps {warmup}..{steps}; \
         engines alternate scene by scene\n",
        rebound_engine()
    );
    let _ = writeln!(
        out,
        "| scene | bodies / joints | Rebound ms/step | rapier ms/step | ratio Rebound/rapier | ratio per round | median round ratio | fastest runs' ratio |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|");
    for result in results {
        let (bodies, joints) = result
            .rebound
            .last()
            .map_or((0, 0), |r| (r.bodies, r.joints));
        let (rapier_bodies, rapier_joints) = result
            .rapier
            .last()
            .map_or((0, 0), |r| (r.bodies, r.joints));
        let counts = if (bodies, joints) == (rapier_bodies, rapier_joints) {
            format!("{bodies} / {joints}")
        } else {
            format!("{bodies} / {joints} (rapier {rapier_bodies} / {rapier_joints})")
        };
        let per_round: Vec<String> = result
            .round_ratios()
            .iter()
            .map(|r| format!("{r:.2}"))
            .collect();
        let _ = writeln!(
            out,
            "| {} | {counts} | {:.3} | {:.3} | {:.2} | {} | {:.2} | {:.2} |",
            result.name,
            result.rebound_ms(),
            result.rapier_ms(),
            result.rebound_ms() / result.rapier_ms(),
            per_round.join(" "),
            median(&result.round_ratios()),
            result.fastest_ratio()
        );
    }

    let _ = writeln!(
        out,
        "\nQuality at step {steps} (`_run`: over every step), Rebound beside rapier:\n"
    );
    let _ = writeln!(out, "| scene | metric | Rebound | rapier |");
    let _ = writeln!(out, "|---|---|---|---|");
    for result in results {
        let (Some(ours), Some(theirs)) = (result.rebound.last(), result.rapier.last()) else {
            continue;
        };
        for (name, value) in &ours.quality {
            let other = theirs
                .quality
                .iter()
                .find(|(k, _)| k == name)
                .map_or(Json::Null, |(_, v)| v.clone());
            let _ = writeln!(
                out,
                "| {} | `{name}` | {} | {} |",
                result.name,
                DisplayJson(value),
                DisplayJson(&other)
            );
        }
    }

    let _ = writeln!(
        out,
        "\nRebound per phase (StepReport::profile; mean ms/step over steps {warmup}..{steps}, mean of the rounds; \
         `facade` = PhysicsWorld::step beyond the world's step: query BVH refresh and sensors):\n"
    );
    let _ = writeln!(
        out,
        "| scene | collide | prepare | solve | restitution | finalize | facade | wall (mean) |"
    );
    let _ = writeln!(out, "|---|---|---|---|---|---|---|---|");
    for result in results {
        let phases = result.phases();
        let mut row = format!("| {} |", result.name);
        for (name, ms) in phases.entries() {
            if name == "wall" {
                let _ = write!(row, " {ms:.3} |");
            } else {
                let share = if phases.wall > 0.0 {
                    100.0 * ms / phases.wall
                } else {
                    f64::NAN
                };
                let _ = write!(row, " {ms:.3} ({share:.0} %) |");
            }
        }
        let _ = writeln!(out, "{row}");
    }
    out
}

/// One point of a scaling series.
#[derive(Debug, Clone, Copy)]
struct ScalingPoint {
    bodies: usize,
    ms: f64,
    phases: Phases,
}

/// The least-squares slope of `ln ms` against `ln n`: cost ∝ n^slope.
fn growth_exponent(points: &[ScalingPoint]) -> f64 {
    let xs: Vec<f64> = points.iter().map(|p| (p.bodies as f64).ln()).collect();
    let ys: Vec<f64> = points.iter().map(|p| p.ms.ln()).collect();
    let n = xs.len() as f64;
    let (mx, my) = (xs.iter().sum::<f64>() / n, ys.iter().sum::<f64>() / n);
    let sxy: f64 = xs.iter().zip(&ys).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = xs.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

/// The scaling series: Rebound only.
fn scaling(args: &Args) -> Result<(), String> {
    let rounds = args.rounds.unwrap_or(1);
    // 16,384 balls take about a second per step in Rebound today: fewer steps than the comparison by default.
    let steps = args.steps.unwrap_or(180);
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
        "{}: scaling, single thread, dt = 1/60, sleeping off, {steps} steps; ms/step = median over rounds ({rounds}) \
         of each run's median over steps {WARMUP_STEPS}..{steps}; phases: mean ms/step (StepReport::profile)\n",
        rebound_engine()
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
                let (timing, p) = run_scene(scene.as_mut(), steps);
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
            if args.json {
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
        if args.json {
            println!("{}", json!({"series": name, "exponent": exponent}));
        }
        exponents.push((name, exponent));
    }
    if !args.json {
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

fn main() -> ExitCode {
    let args = match parse_args(env::args().skip(1)) {
        Ok(args) => args,
        Err(message) if message == USAGE => {
            print!("{USAGE}");
            return ExitCode::SUCCESS;
        }
        Err(message) => {
            eprintln!("{message}");
            return ExitCode::FAILURE;
        }
    };
    if cfg!(debug_assertions) {
        eprintln!("compare: warning: a debug build; run with `cargo run --release --bin compare`");
    }
    let outcome = if args.scaling {
        scaling(&args)
    } else if args.engines == Engines::Rebound {
        rebound_alone(&args)
    } else {
        compare(&args)
    };
    match outcome {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("compare: {message}");
            ExitCode::FAILURE
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{Engines, ScalingPoint, growth_exponent, parse_args};

    fn args(list: &[&str]) -> Vec<String> {
        list.iter().map(|&s| s.to_owned()).collect()
    }

    #[test]
    fn defaults_and_options() {
        let a = parse_args(args(&[])).expect("valid");
        assert_eq!(a.scenes, ["balls", "pyramid", "chain", "springs", "bridge"]);
        assert_eq!(
            (a.rounds, a.steps, a.scaling, a.json),
            (None, None, false, false)
        );
        let a = parse_args(args(&[
            "--scene", "chain", "--rounds", "2", "--steps", "90", "--json",
        ]))
        .expect("valid");
        assert_eq!(a.scenes, ["chain"]);
        assert_eq!((a.rounds, a.steps, a.json), (Some(2), Some(90), true));
        assert_eq!(a.engines, Engines::Both);
        let a = parse_args(args(&["--engine", "rebound", "--scene", "bridge"])).expect("valid");
        assert_eq!(
            (a.engines, a.scenes.as_slice()),
            (Engines::Rebound, &["bridge".to_owned()][..])
        );
        assert!(parse_args(args(&["--engine", "bullet"])).is_err());
        assert!(parse_args(args(&["--engine"])).is_err());
        assert!(parse_args(args(&["--scene", "nope"])).is_err());
        assert!(parse_args(args(&["--rounds", "0"])).is_err());
        assert!(parse_args(args(&["--frobnicate"])).is_err());
    }

    #[test]
    fn exponent_of_a_power_law() {
        let points: Vec<ScalingPoint> = [1000usize, 4000, 16000]
            .iter()
            .map(|&n| ScalingPoint {
                bodies: n,
                ms: 2e-3 * (n as f64).powf(1.3),
                phases: super::Phases::default(),
            })
            .collect();
        assert!((growth_exponent(&points) - 1.3).abs() < 1e-9);
    }
}
