//! `compare`: Rebound and rapier3d side by side on the peer scenes of docs/scenes.md, in one run on one machine.
//!
//! ```text
//! cargo run --release --bin compare -- [--rounds R] [--steps N] [--scene NAME|all]... [--json]
//! cargo run --release --bin compare -- --engine rebound [--rounds R] [--steps N] [--scene NAME|all]...
//! cargo run --release --bin compare -- --scaling [--rounds R] [--steps N] [--threads N] [--json]
//! cargo run --release --features parallel --bin compare -- --threads N [--rounds R] [--scene NAME|all]...
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
//! `--threads N` runs both engines on N threads: Rebound (built with `--features parallel`) inside a rayon
//! pool of N threads, rapier from a second build of `benches/peers` with rapier's `parallel` feature
//! (`benches/peers/target/parallel/release/peers --threads N`); the table is the same.
//!
//! `--engine rebound` runs Rebound alone on the chosen scenes, without building or running rapier: the
//! run to count Rebound's instructions per scene under `valgrind --tool=callgrind` (docs/performance.md,
//! "Layout check").
//!
//! `--scaling` runs Rebound alone on growing scenes instead: balls with 1,024, 4,096 and 16,384 balls and
//! pyramids of base 20, 40 and 80, and fits the cost-growth exponent (the slope of log ms against log n);
//! with `--threads N`, on a pool of N threads.

#![allow(
    clippy::print_stdout,
    reason = "a command-line report: printing the table is what it is for"
)]

use std::env;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitCode};
use std::time::Instant;

use rebound_suite::scenes::metrics::{DisplayJson, TimingStats, median};
use rebound_suite::scenes::{ALL_SCENES, DEFAULT_SCENES};
use serde_json::{Map, Value as Json, json};

mod run;
mod scaling;

use run::{Phases, Run, WARMUP_STEPS, rebound_engine, run_rebound};

const USAGE: &str = "\
usage: compare [--engine both|rebound] [--rounds R] [--steps N] [--threads N] [--scene NAME|all]... [--json]
       compare --scaling [--rounds R] [--steps N] [--threads N] [--json]

  --engine E    both (default): Rebound beside rapier; rebound: Rebound alone, rapier neither built nor run
  --rounds R    rounds of every scene in both engines (default 3); times are the median over rounds
  --steps N     steps per run (default 600); timing statistics cover steps 60..N
  --scene NAME  balls | pyramid | chain | springs | bridge | chain_spherical | ragdolls | all
                (repeatable; default: the five peer scenes of docs/scenes.md)
  --threads N   both engines on N threads (Rebound built with --features parallel; rapier from a second
                build of benches/peers with its `parallel` feature); default: one thread, serial builds
  --scaling     Rebound alone: balls at 1k, 4k, 16k and pyramid bases 20, 40, 80, with the cost-growth
                exponent (default 180 steps, 1 round: about 3.5 minutes, most of it
                the 16k-ball pile); with --threads N, on a pool of N threads
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
    /// `--threads N`: both engines on N threads (their parallel builds).
    threads: Option<usize>,
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
        threads: None,
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
            "--threads" => {
                let threads = positive("--threads", args.next())?;
                if !cfg!(feature = "parallel") {
                    return Err(format!(
                        "--threads {threads} needs Rebound's parallel build: cargo run --release --features parallel --bin compare"
                    ));
                }
                parsed.threads = Some(threads);
            }
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

/// Runs a scene in rapier through the peers binary and reads its `--json` line.
fn run_rapier(
    peers: &Path,
    name: &str,
    steps: usize,
    threads: Option<usize>,
) -> Result<(Run, String), String> {
    let mut command = Command::new(peers);
    command.args(["--scene", name, "--steps", &steps.to_string(), "--json"]);
    if let Some(threads) = threads {
        command.args(["--threads", &threads.to_string()]);
    }
    let output = command
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

/// Builds the rapier side with `cargo build --release` and returns the path of its binary; with `parallel`,
/// the second build, with rapier's `parallel` feature, in its own target directory.
fn build_peers(parallel: bool) -> Result<PathBuf, String> {
    let root = workspace_root();
    let manifest = root.join("benches/peers/Cargo.toml");
    let cargo = env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    let target = if parallel {
        root.join("benches/peers/target/parallel")
    } else {
        root.join("benches/peers/target")
    };
    let mut command = Command::new(&cargo);
    command
        .arg("build")
        .arg("--release")
        .arg("--manifest-path")
        .arg(&manifest);
    if parallel {
        command
            .args(["--features", "parallel", "--target-dir"])
            .arg(&target);
    }
    eprintln!("compare: building the rapier side ({command:?})");
    let status = command
        .status()
        .map_err(|e| format!("running cargo: {e}"))?;
    if !status.success() {
        return Err(format!("building benches/peers failed ({status})"));
    }
    let exe = target
        .join("release")
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
    let peers = build_peers(args.threads.is_some())?;
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
                    rebound = Some(run_rebound(&result.name, steps, args.threads)?);
                } else {
                    let (run, engine) = run_rapier(&peers, &result.name, steps, args.threads)?;
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
            comparison_table(&results, steps, rounds, &rapier_engine, args.threads)
        );
    }
    Ok(())
}

/// How many threads a table's runs used.
fn threads_label(threads: Option<usize>) -> String {
    match threads {
        None => "single thread".to_owned(),
        Some(n) => format!("{n} thread(s), parallel builds"),
    }
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
        "{}: peer scenes, Rebound alone, {}, dt = 1/60, sleeping off, {steps} steps; \
         ms/step = median over rounds ({rounds}) of each run's median over steps {warmup}..{steps}\n",
        rebound_engine(),
        threads_label(args.threads)
    );
    let _ = writeln!(out, "| scene | bodies / joints | ms/step | quality |");
    let _ = writeln!(out, "|---|---|---|---|");
    for name in &args.scenes {
        let runs = (0..rounds)
            .map(|_| run_rebound(name, steps, args.threads))
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
                        "profile_ms": Phases::mean(&runs.iter().filter_map(|r| r.phases).collect::<Vec<_>>())
                            .entries().iter().map(|&(k, v)| (k.to_owned(), json!(v))).collect::<Map<_, _>>(),
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
    threads: Option<usize>,
) -> String {
    let warmup = if steps > WARMUP_STEPS {
        WARMUP_STEPS
    } else {
        0
    };
    let mut out = String::new();
    let _ = writeln!(
        out,
        "{} vs {rapier_engine}: peer scenes (docs/scenes.md), {}, dt = 1/60, sleeping off, {steps} steps;\n\
         ms/step = median over rounds ({rounds}) of each run's median over steps {warmup}..{steps}; \
         engines alternate scene by scene\n",
        rebound_engine(),
        threads_label(threads)
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
        scaling::scaling(args.rounds, args.steps, args.threads, args.json)
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
    use super::{Engines, parse_args};

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
        assert!(parse_args(args(&["--threads", "0"])).is_err());
        // Two threads need the parallel build; in it, both engines run on them.
        let two = parse_args(args(&["--threads", "2"]));
        assert_eq!(
            two.map(|a| a.threads).ok(),
            cfg!(feature = "parallel").then_some(Some(2))
        );
        assert!(parse_args(args(&["--frobnicate"])).is_err());
    }
}
