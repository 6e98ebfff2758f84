//! `rebound run` as a user runs it: the binary on the scene files, checked by the files it writes and the
//! status and messages it exits with.

use rebound::prelude::*;
use rebound_render::{Camera, PALETTE};
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

fn repository() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

/// A fresh, empty folder for one test's files.
fn scratch(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rebound-cli-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("a scratch folder");
    dir
}

fn rebound(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_rebound"))
        .args(args)
        .current_dir(repository())
        .output()
        .expect("the binary runs")
}

fn text(bytes: &[u8]) -> String {
    String::from_utf8_lossy(bytes).into_owned()
}

/// The GIF's frames as RGBA images (each frame covers the whole picture, as the renderer writes them).
fn gif_frames(path: &Path) -> (u32, u32, Vec<Vec<u8>>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options
        .read_info(std::fs::File::open(path).expect("the GIF exists"))
        .expect("a GIF");
    let (w, h) = (u32::from(decoder.width()), u32::from(decoder.height()));
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().expect("a frame") {
        assert_eq!((u32::from(frame.width), u32::from(frame.height)), (w, h));
        frames.push(frame.buffer.to_vec());
    }
    (w, h, frames)
}

/// The mean pixel column of the pixels whose colour is a shade of `colour` (the same direction in RGB
/// space, closer to it than to any other palette colour or the background), and how many there are.
fn centroid_x(rgba: &[u8], width: u32, colour: [u8; 3]) -> (f32, usize) {
    let direction = |c: [f32; 3]| {
        let n = (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt().max(1e-6);
        [c[0] / n, c[1] / n, c[2] / n]
    };
    let dot = |a: [f32; 3], b: [f32; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    let as_f32 = |c: [u8; 3]| [f32::from(c[0]), f32::from(c[1]), f32::from(c[2])];
    let wanted = direction(as_f32(colour));
    let mut others: Vec<[f32; 3]> = PALETTE
        .iter()
        .map(|c| direction(as_f32([c.r, c.g, c.b])))
        .filter(|d| dot(*d, wanted) < 0.9999)
        .collect();
    others.push(direction([205.0, 215.0, 225.0]));
    let (mut sum, mut count) = (0.0f32, 0usize);
    for (i, px) in rgba.chunks_exact(4).enumerate() {
        let d = direction(as_f32([px[0], px[1], px[2]]));
        let similarity = dot(d, wanted);
        if similarity > 0.995 && others.iter().all(|o| dot(d, *o) < similarity) {
            sum += (i as u32 % width) as f32;
            count += 1;
        }
    }
    (sum / count.max(1) as f32, count)
}

#[test]
fn the_cradle_gif_shows_the_last_ball_swinging_out() {
    let dir = scratch("cradle");
    let gif = dir.join("cradle.gif");
    let out = rebound(&[
        "run",
        "scenes/newtons_cradle.ron",
        "--gif",
        gif.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(text(&out.stdout).contains("wrote"), "{}", text(&out.stdout));

    // Where the last ball hangs at rest, and where it is 0.3 m further out, in pixels of the scene's camera.
    let scene =
        rebound_scene::Scene::from_file(repository().join("scenes/newtons_cradle.ron")).unwrap();
    let view = scene.camera.unwrap();
    let camera = Camera {
        position: view.position,
        target: view.target,
        fov_y: view.fov_degrees.to_radians(),
        width: 640,
        height: 480,
    };
    let projection = camera.projection().unwrap();
    let rest = scene.bodies[4].body.position;
    let (rest_x, _, _) = projection.project(rest).unwrap();
    let (out_x, _, _) = projection.project(rest + Vec3::new(0.3, 0.0, 0.0)).unwrap();

    let (w, h, frames) = gif_frames(&gif);
    assert_eq!((w, h), (640, 480));
    // 150 steps at 60 Hz, a frame every 2 steps (30 fps) and the start: 76 frames.
    assert_eq!(frames.len(), 76);
    let purple = [PALETTE[4].r, PALETTE[4].g, PALETTE[4].b];
    let (first_x, first_count) = centroid_x(&frames[0], w, purple);
    assert!(
        first_count > 200,
        "the last ball is visible: {first_count} pixels"
    );
    assert!(
        (first_x - rest_x).abs() < 3.0,
        "at the start the last ball hangs at rest: column {first_x} vs {rest_x}"
    );
    // The swing peaks about a second in (frames 25 to 40): the ball is then more than 0.3 m out.
    let farthest = frames[25..40]
        .iter()
        .map(|f| centroid_x(f, w, purple).0)
        .fold(f32::NEG_INFINITY, f32::max);
    assert!(
        farthest > out_x,
        "the last ball swings out past 0.3 m: column {farthest}, 0.3 m is column {out_x}"
    );
    // And the first ball, which was lifted, is back near the row: it gave its momentum away.
    let orange = [PALETTE[0].r, PALETTE[0].g, PALETTE[0].b];
    let (first_ball_x, _) = centroid_x(&frames[32], w, orange);
    let (first_rest_x, _, _) = projection
        .project(scene.bodies[1].body.position - Vec3::new(0.201, 0.0, 0.0))
        .unwrap();
    assert!(
        (first_ball_x - first_rest_x).abs() < (out_x - rest_x),
        "the first ball stays near its rest column: {first_ball_x} vs {first_rest_x}"
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn png_frames_are_written_every_k_steps() {
    let dir = scratch("png");
    let frames = dir.join("frames");
    let out = rebound(&[
        "run",
        "scenes/drag_and_drop.ron",
        "--steps",
        "20",
        "--png-every",
        "10",
        frames.to_str().unwrap(),
        "--size",
        "160x120",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let mut names: Vec<String> = std::fs::read_dir(&frames)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        ["step_00000.png", "step_00010.png", "step_00020.png"]
    );
    assert!(
        text(&out.stdout).contains("20 steps"),
        "{}",
        text(&out.stdout)
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_bad_scene_file_is_reported_with_its_place_and_nothing_runs() {
    let dir = scratch("bad");
    let scene = dir.join("bad.ron");
    std::fs::write(
        &scene,
        "Scene(\n    bodies: [\n        (colliders: [(shape: Ball(radius: -1.0))]),\n    ],\n)\n",
    )
    .unwrap();
    let gif = dir.join("never.gif");
    let out = rebound(&[
        "run",
        scene.to_str().unwrap(),
        "--gif",
        gif.to_str().unwrap(),
    ]);
    assert_eq!(out.status.code(), Some(1));
    let stderr = text(&out.stderr);
    assert!(
        stderr.starts_with(
            "error: line 3, column 35: bodies[0].colliders[0]: `radius` must be > 0, got -1"
        ),
        "{stderr}"
    );
    assert_eq!(
        stderr.lines().count(),
        1,
        "the cause is not repeated: {stderr}"
    );
    assert!(out.stdout.is_empty());
    assert!(!gif.exists(), "nothing is written for a bad scene");
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn bad_arguments_exit_non_zero_without_a_panic() {
    for args in [
        &["run", "no/such/scene.ron"][..],
        &["run", "scenes/newtons_cradle.ron", "--steps", "0"],
        &["run", "scenes/newtons_cradle.ron", "--seconds", "-1"],
        &["run", "scenes/newtons_cradle.ron", "--camera", "1,2:3,4,5"],
        &[
            "run",
            "scenes/newtons_cradle.ron",
            "--steps",
            "5",
            "--seconds",
            "1",
        ],
        &["run", "scenes/newtons_cradle.ron", "--png-every", "0", "x"],
        &["frobnicate"],
    ] {
        let out = rebound(args);
        let stderr = text(&out.stderr);
        assert!(!out.status.success(), "{args:?} succeeded");
        assert!(!stderr.contains("panicked"), "{args:?}: {stderr}");
        assert!(stderr.contains("error"), "{args:?}: {stderr}");
    }
}

#[test]
fn a_recorded_run_is_summarised_rendered_and_plotted() {
    let dir = scratch("record");
    let path = |name: &str| dir.join(name).to_str().unwrap().to_owned();
    let out = rebound(&[
        "run",
        "scenes/newtons_cradle.ron",
        "--record",
        &path("cradle.rrec"),
        "--gif",
        &path("run.gif"),
        "--plot",
        &path("run.svg"),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));

    // `info --json`: the recording's counts, and the elastic cradle's energy kept within 1 % over 2.5 s.
    let out = rebound(&["info", &path("cradle.rrec"), "--json"]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let info: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(info["bodies"], 5);
    assert_eq!(info["dynamic_bodies"], 5);
    assert_eq!(info["joints"], 5);
    assert_eq!(info["frames"], 151);
    assert_eq!(info["steps"], 150);
    let drift = info["relative_energy_drift"].as_f64().unwrap();
    assert!(drift.abs() < 0.01, "energy drift {drift}");
    let penetration = info["worst_penetration"].as_f64().unwrap();
    assert!(
        (0.0..0.01).contains(&penetration),
        "penetration {penetration} m"
    );
    let out = rebound(&["info", &path("cradle.rrec")]);
    assert!(
        text(&out.stdout).contains("bodies: 5 (5 dynamic), joints: 5"),
        "{}",
        text(&out.stdout)
    );

    // `render` with the scene's camera draws the recording's frames exactly as the run drew them.
    let out = rebound(&[
        "render",
        &path("cradle.rrec"),
        "--gif",
        &path("render.gif"),
        "--camera",
        "0.4,-0.55,2.6:0.4,-0.75,0:40",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let (_, _, ran) = gif_frames(&dir.join("run.gif"));
    let (_, _, rendered) = gif_frames(&dir.join("render.gif"));
    assert_eq!(rendered.len(), ran.len());
    assert!(ran == rendered, "the rendered frames are the run's");

    // `plot` writes the same SVG as the run's --plot: one sample per frame.
    let out = rebound(&["plot", &path("cradle.rrec"), "-o", &path("plot.svg")]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        text(&out.stdout).contains("151 samples"),
        "{}",
        text(&out.stdout)
    );
    let plotted = std::fs::read_to_string(dir.join("plot.svg")).unwrap();
    assert!(
        plotted.starts_with("<svg"),
        "{}",
        &plotted[..plotted.len().min(80)]
    );
    assert_eq!(
        plotted,
        std::fs::read_to_string(dir.join("run.svg")).unwrap()
    );

    // Not a recording: a clear error, status 1.
    let out = rebound(&["info", "scenes/newtons_cradle.ron"]);
    assert_eq!(out.status.code(), Some(1));
    assert!(
        text(&out.stderr).starts_with("error: not a Rebound recording"),
        "{}",
        text(&out.stderr)
    );
    let _ = std::fs::remove_dir_all(dir);
}

#[test]
fn a_built_in_scene_runs_by_name_away_from_the_source_tree() {
    let dir = scratch("built-in");
    let run = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_rebound"))
            .args(args)
            .current_dir(&dir)
            .output()
            .expect("the binary runs")
    };
    let out = run(&[
        "run",
        "newtons_cradle",
        "--steps",
        "30",
        "--record",
        "c.rrec",
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let by_name = std::fs::read(dir.join("c.rrec")).expect("the recording");
    let by_path = dir.join("p.rrec");
    let file = repository().join("scenes/newtons_cradle.ron");
    let out = run(&[
        "run",
        file.to_str().unwrap(),
        "--steps",
        "30",
        "--record",
        by_path.to_str().unwrap(),
    ]);
    assert!(out.status.success(), "{}", text(&out.stderr));
    assert!(
        by_name == std::fs::read(by_path).unwrap(),
        "the same run, byte for byte"
    );
    let out = run(&["run", "no_such_scene"]);
    let stderr = text(&out.stderr);
    assert!(!out.status.success());
    assert!(
        stderr.contains("no_such_scene") && stderr.contains("newtons_cradle"),
        "names the argument and the built-in scenes: {stderr}"
    );
    let _ = std::fs::remove_dir_all(dir);
}
