//! `peers`: Rebound's peer comparison. Runs the benchmark scenes of docs/scenes.md in rapier3d 0.36 — single
//! thread (or `--threads N` in a build with the `parallel` feature), rapier's default
//! `IntegrationParameters`, dt = 1/60 — times every `PhysicsPipeline::step` and reports ms/step next to the
//! scenes' quality metrics.
//!
//! ```text
//! cargo run --release --manifest-path benches/peers/Cargo.toml -- [--scene NAME]... [--steps N] [--sleep] [--json]
//! cargo run --release --features parallel --manifest-path benches/peers/Cargo.toml -- --threads N [--scene NAME]...
//! cargo run --release --manifest-path benches/peers/Cargo.toml -- --params [--json]
//! ```
//!
//! See README.md for the output format.

mod metrics;
mod rng;
mod scenes;
mod world;

use std::io::{self, Write};
use std::process::ExitCode;
use std::time::Instant;

use rapier3d::prelude::*;
use serde::{Serialize, Serializer};

use crate::metrics::{Quality, TimingStats, short};
use crate::scenes::{ALL_SCENES, DEFAULT_SCENES, SceneOptions};
use crate::world::GRAVITY;

/// The rapier3d release this binary was built against (read from Cargo.lock by build.rs).
const RAPIER_VERSION: &str = env!("PEERS_RAPIER3D_VERSION");

/// Steps excluded from the timing statistics (warm-up: the pile, stack or chain is still forming).
const WARMUP_STEPS: usize = 60;

/// Steps run when `--steps` is not given.
const DEFAULT_STEPS: usize = 600;

const USAGE: &str = "\
usage: peers [--scene NAME]... [--steps N] [--sleep] [--json]
       peers --params [--json]

  --scene NAME  balls | pyramid | chain | springs | bridge | chain_spherical | all
                (repeatable; `all` = the five default scenes, also the default when no --scene is given)
  --steps N     steps per scene (default 600); timing statistics cover steps 60..N
  --sleep       let dynamic bodies sleep (rapier's default; off here unless given)
  --threads N   step on a rayon pool of N threads (N > 1 needs the `parallel` feature; default 1)
  --params      print rapier's IntegrationParameters and the other settings used, then exit
  --json        machine-readable output: one JSON object per line
";

/// Parsed command line.
#[derive(Debug, Clone)]
struct Args {
    scenes: Vec<String>,
    steps: usize,
    sleep: bool,
    params: bool,
    json: bool,
    threads: usize,
}

/// Parses the command line; `Err` carries the message to print (the usage text for `--help`).
fn parse_args(args: impl IntoIterator<Item = String>) -> Result<Args, String> {
    let mut parsed = Args {
        scenes: Vec::new(),
        steps: DEFAULT_STEPS,
        sleep: false,
        params: false,
        json: false,
        threads: 1,
    };
    let mut args = args.into_iter();
    while let Some(arg) = args.next() {
        match arg.as_str() {
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
            "--steps" => {
                let n = args.next().ok_or("--steps needs a number")?;
                parsed.steps = n
                    .parse()
                    .ok()
                    .filter(|&n: &usize| n > 0)
                    .ok_or_else(|| format!("--steps: `{n}` is not a positive integer"))?;
            }
            "--threads" => {
                let n = args.next().ok_or("--threads needs a number")?;
                parsed.threads = n
                    .parse()
                    .ok()
                    .filter(|&n: &usize| n > 0)
                    .ok_or_else(|| format!("--threads: `{n}` is not a positive integer"))?;
                if parsed.threads > 1 && !cfg!(feature = "parallel") {
                    return Err(
                        "--threads above 1 needs the `parallel` feature (cargo build --features parallel)"
                            .to_owned(),
                    );
                }
            }
            "--sleep" => parsed.sleep = true,
            "--params" => parsed.params = true,
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

/// One scene's result: exactly the `--json` line.
#[derive(Debug, Serialize)]
struct Report {
    /// `"rapier3d <version>"`.
    engine: String,
    /// Scene name.
    scene: String,
    /// Steps run.
    steps: usize,
    /// Dynamic bodies.
    bodies: usize,
    /// Joints.
    joints: usize,
    /// Median ms per `PhysicsPipeline::step` over steps 60..N.
    ms_median: f64,
    /// Mean ms per step over steps 60..N.
    ms_mean: f64,
    /// The scene's quality metrics at the end (and maximised over the run where the name says so).
    quality: Quality,
}

/// Builds and runs one scene: `steps` timed steps, each followed by the scene's (untimed) observation.
fn run_scene(name: &str, steps: usize, options: SceneOptions) -> Report {
    let mut scene = scenes::build(name, options).expect("scene names are validated by parse_args");
    let mut step_ms = Vec::with_capacity(steps);
    for step in 1..=steps {
        let world = scene.world_mut();
        let start = Instant::now();
        world.step();
        step_ms.push(start.elapsed().as_secs_f64() * 1e3);
        scene.observe(step, steps);
    }
    // Statistics over steps 60..N; a run too short for that is summarised whole.
    let warmup = if steps > WARMUP_STEPS {
        WARMUP_STEPS
    } else {
        0
    };
    let timing = TimingStats::of(&step_ms[warmup..]);
    Report {
        engine: format!("rapier3d {RAPIER_VERSION}"),
        scene: name.to_owned(),
        steps,
        bodies: scene.world().dynamic_body_count(),
        joints: scene.world().joint_count(),
        ms_median: round_ns(timing.median_ms),
        ms_mean: round_ns(timing.mean_ms),
        quality: scene.quality(),
    }
}

/// Milliseconds rounded to whole nanoseconds, the resolution `Instant` is read at.
fn round_ns(ms: f64) -> f64 {
    (ms * 1e6).round() / 1e6
}

/// The settings every scene runs with, as (name, value) pairs: rapier's defaults as this build reports them.
/// `num_solver_iterations` is the number of substeps (dt/4 each) in rapier 0.36; the softness pairs are
/// (natural frequency in Hz, damping ratio).
fn settings() -> Vec<(&'static str, serde_json::Value)> {
    use serde_json::json;
    let p = IntegrationParameters::default();
    let joint = RopeJoint::new(1.0).softness();
    let collider = ColliderBuilder::ball(1.0);
    vec![
        ("engine", json!(format!("rapier3d {RAPIER_VERSION}"))),
        ("threads", json!(1)),
        ("dt", json!(short(p.dt))),
        ("min_ccd_dt", json!(short(p.min_ccd_dt))),
        ("num_solver_iterations", json!(p.num_solver_iterations)),
        (
            "num_internal_pgs_iterations",
            json!(p.num_internal_pgs_iterations),
        ),
        (
            "num_internal_stabilization_iterations",
            json!(p.num_internal_stabilization_iterations),
        ),
        (
            "warmstart_coefficient",
            json!(short(p.warmstart_coefficient)),
        ),
        ("warmstart_joints", json!(p.warmstart_joints)),
        (
            "contact_softness",
            json!([
                short(p.contact_softness.natural_frequency),
                short(p.contact_softness.damping_ratio)
            ]),
        ),
        (
            "static_contact_softness",
            json!([
                short(p.static_contact_softness.natural_frequency),
                short(p.static_contact_softness.damping_ratio)
            ]),
        ),
        (
            "joint_softness",
            json!([short(joint.natural_frequency), short(joint.damping_ratio)]),
        ),
        ("length_unit", json!(short(p.length_unit))),
        (
            "normalized_allowed_linear_error",
            json!(short(p.normalized_allowed_linear_error)),
        ),
        (
            "normalized_max_corrective_velocity",
            json!(short(p.normalized_max_corrective_velocity)),
        ),
        (
            "normalized_prediction_distance",
            json!(short(p.normalized_prediction_distance)),
        ),
        (
            "normalized_max_linear_velocity",
            json!(short(p.normalized_max_linear_velocity)),
        ),
        ("max_ccd_substeps", json!(p.max_ccd_substeps)),
        ("contact_clustering", json!(p.contact_clustering)),
        ("contact_recycling", json!(p.contact_recycling)),
        (
            "normalized_contact_recycle_distance",
            json!(short(p.normalized_contact_recycle_distance)),
        ),
        ("friction_in_bias_pass", json!(p.friction_in_bias_pass)),
        ("friction_model", json!(format!("{:?}", p.friction_model))),
        (
            "gravity",
            json!([short(GRAVITY.x), short(GRAVITY.y), short(GRAVITY.z)]),
        ),
        ("gravity_springs", json!([0.0, 0.0, 0.0])),
        ("collider_friction", json!(short(collider.friction))),
        ("collider_restitution", json!(short(collider.restitution))),
        (
            "collider_density",
            json!(short(ColliderBuilder::default_density())),
        ),
        (
            "sleeping",
            json!("disabled on every dynamic body unless --sleep"),
        ),
    ]
}

/// `--params`: the settings, as one JSON object or as a table.
fn print_params(json: bool, out: &mut impl Write) -> io::Result<()> {
    let settings = settings();
    if json {
        // In the table's order, not serde_json::Map's sorted one.
        let mut line = Vec::new();
        serde_json::Serializer::new(&mut line)
            .collect_map(settings.iter().map(|(k, v)| (k, v)))
            .map_err(io::Error::other)?;
        out.write_all(&line)?;
        writeln!(out)?;
    } else {
        for (name, value) in &settings {
            writeln!(out, "{name:<45} {value}")?;
        }
        writeln!(
            out,
            "\nIntegrationParameters::default() as rapier prints it:\n{:#?}",
            IntegrationParameters::default()
        )?;
    }
    Ok(())
}

/// Prints one scene's result as a block of the human-readable table.
fn print_table_row(report: &Report, out: &mut impl Write) -> io::Result<()> {
    writeln!(
        out,
        "{:<16} {:>7} {:>7} {:>10.3} {:>10.3}",
        report.scene, report.bodies, report.joints, report.ms_median, report.ms_mean
    )?;
    for (name, value) in report.quality.entries() {
        writeln!(out, "    {name:<24} {value}")?;
    }
    Ok(())
}

fn main() -> ExitCode {
    let args = match parse_args(std::env::args().skip(1)) {
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
    match run(&args) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) if err.kind() == io::ErrorKind::BrokenPipe => ExitCode::SUCCESS,
        Err(err) => {
            eprintln!("peers: {err}");
            ExitCode::FAILURE
        }
    }
}

/// Runs what the command line asks for, printing as each scene finishes.
fn run(args: &Args) -> io::Result<()> {
    let mut out = io::stdout().lock();
    if args.params {
        return print_params(args.json, &mut out);
    }
    let options = SceneOptions { sleep: args.sleep };
    if !args.json {
        let warmup = if args.steps > WARMUP_STEPS {
            WARMUP_STEPS
        } else {
            0
        };
        writeln!(
            out,
            "rapier3d {RAPIER_VERSION}: {} thread(s), default IntegrationParameters, dt = 1/60, \
             {} steps, ms/step over steps {warmup}..{}, sleeping {}",
            args.threads,
            args.steps,
            args.steps,
            if args.sleep { "allowed" } else { "off" }
        )?;
        writeln!(
            out,
            "{:<16} {:>7} {:>7} {:>10} {:>10}",
            "scene", "bodies", "joints", "ms median", "ms mean"
        )?;
    }
    #[cfg(feature = "parallel")]
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads)
        .build()
        .map_err(io::Error::other)?;
    for name in &args.scenes {
        #[cfg(feature = "parallel")]
        let report = pool.install(|| run_scene(name, args.steps, options));
        #[cfg(not(feature = "parallel"))]
        let report = run_scene(name, args.steps, options);
        if args.json {
            let line = serde_json::to_string(&report).map_err(io::Error::other)?;
            writeln!(out, "{line}")?;
        } else {
            print_table_row(&report, &mut out)?;
        }
        out.flush()?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::parse_args;

    fn args(list: &[&str]) -> Vec<String> {
        list.iter().map(|&s| s.to_owned()).collect()
    }

    #[test]
    fn defaults_and_all() {
        let a = parse_args(args(&[])).expect("valid");
        assert_eq!(a.scenes, ["balls", "pyramid", "chain", "springs", "bridge"]);
        assert_eq!(a.steps, 600);
        assert!(!a.sleep && !a.json && !a.params);
        let a = parse_args(args(&[
            "--scene",
            "chain_spherical",
            "--scene",
            "all",
            "--steps",
            "10",
        ]))
        .expect("valid");
        assert_eq!(a.scenes.len(), 6);
        assert_eq!(a.steps, 10);
    }

    #[test]
    fn rejects_bad_input() {
        assert!(parse_args(args(&["--scene", "nope"])).is_err());
        assert!(parse_args(args(&["--steps", "0"])).is_err());
        assert!(parse_args(args(&["--frobnicate"])).is_err());
    }
}
