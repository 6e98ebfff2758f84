//! The command line: subcommands and their arguments (clap derive), and the parsers of the values clap cannot
//! read on its own (a camera, a picture size).

use clap::{Args, Parser, Subcommand};
use rebound::prelude::Vec3;
use std::path::PathBuf;

/// Run Rebound scene files and see what happened: pictures, animated GIFs and plots.
#[derive(Debug, Parser)]
#[command(name = "rebound", version, about)]
pub struct Cli {
    /// What to do.
    #[command(subcommand)]
    pub command: Command,
}

/// The subcommands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Load a scene file, check it, step it, and write what was asked (recording, GIF, PNG frames, plot).
    Run(RunArgs),
    /// Summarise a recording: bodies, steps, energy drift, worst penetration and joint error.
    Info(InfoArgs),
    /// Draw a recording as an animated GIF and/or PNG frames.
    Render(RenderArgs),
    /// Plot a recording's energy, momentum, joint error and penetration against time, as SVG.
    Plot(PlotArgs),
    /// Serve the web viewer and a recording on 127.0.0.1, print the address to open, and run until Ctrl-C.
    View(ServeArgs),
}

/// `rebound view`.
#[derive(Debug, Args)]
pub struct ServeArgs {
    /// The recording (`.rrec`, see docs/recording.md) to open in the viewer.
    pub recording: PathBuf,
    /// The port on 127.0.0.1. Default: 0, a free one (the printed address names it).
    #[arg(long, default_value_t = 0)]
    pub port: u16,
    /// The viewer's directory (with `npm ci` run in it). Default: `REBOUND_VIEWER_DIR`, else this source
    /// tree's `viewer/`.
    #[arg(long, value_name = "DIR")]
    pub viewer_dir: Option<PathBuf>,
}

/// `rebound info`.
#[derive(Debug, Args)]
pub struct InfoArgs {
    /// The recording (`.rrec`).
    pub recording: PathBuf,
    /// Print the summary as one JSON object.
    #[arg(long)]
    pub json: bool,
}

/// `rebound render`.
#[derive(Debug, Args)]
pub struct RenderArgs {
    /// The recording (`.rrec`).
    pub recording: PathBuf,
    /// What to write.
    #[command(flatten)]
    pub output: PictureArgs,
    /// Picture options.
    #[command(flatten)]
    pub view: ViewArgs,
}

/// `rebound plot`.
#[derive(Debug, Args)]
pub struct PlotArgs {
    /// The recording (`.rrec`).
    pub recording: PathBuf,
    /// The SVG file to write.
    #[arg(long, short, value_name = "FILE.svg")]
    pub output: PathBuf,
}

/// Which pictures to write.
#[derive(Debug, Args, Clone)]
pub struct PictureArgs {
    /// Write an animated GIF here.
    #[arg(long, value_name = "FILE")]
    pub gif: Option<PathBuf>,
    /// Write every K-th step as a PNG into DIR (`step_00000.png` is the start), creating DIR if needed.
    #[arg(long, num_args = 2, value_names = ["K", "DIR"])]
    pub png_every: Option<Vec<String>>,
    /// Frames per second of the GIF (the frame interval is rounded to whole steps).
    #[arg(long, default_value_t = 30.0)]
    pub fps: f32,
}

/// `rebound run`.
#[derive(Debug, Args)]
pub struct RunArgs {
    /// The scene file (RON; see `scenes/`), or the name of a built-in scene: newtons_cradle, rope_bridge,
    /// pyramid, car, chain, drag_and_drop, spring_camera (a file of that name wins).
    pub scene: PathBuf,
    /// How many steps to run. Default: the scene's `run.steps`.
    #[arg(long, conflicts_with = "seconds")]
    pub steps: Option<u32>,
    /// How long to run (s of simulated time, rounded to whole steps).
    #[arg(long)]
    pub seconds: Option<f64>,
    /// Write a recording of the run (`.rrec`, see docs/recording.md) here.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
    /// Write an SVG plot of energy, momentum, joint error and penetration against time here.
    #[arg(long, value_name = "FILE.svg")]
    pub plot: Option<PathBuf>,
    /// Pictures to write.
    #[command(flatten)]
    pub output: PictureArgs,
    /// Picture options.
    #[command(flatten)]
    pub view: ViewArgs,
}

/// Where pictures look from and how large they are.
#[derive(Debug, Args, Clone)]
pub struct ViewArgs {
    /// The camera as `X,Y,Z:X,Y,Z[:FOV]`: eye position, point looked at (m) and vertical field of view
    /// (degrees). Default: the scene's camera, or one framing the bodies.
    #[arg(long, value_name = "EYE:TARGET[:FOV]", value_parser = parse_camera)]
    pub camera: Option<CameraArg>,
    /// Picture size in pixels as `WIDTHxHEIGHT`.
    #[arg(long, value_name = "WxH", default_value = "640x480", value_parser = parse_size)]
    pub size: (u32, u32),
    /// Draw contact points and normals.
    #[arg(long)]
    pub contacts: bool,
}

/// A camera given on the command line.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CameraArg {
    /// Eye position (m).
    pub position: Vec3,
    /// The point looked at (m).
    pub target: Vec3,
    /// Vertical field of view (degrees), if given.
    pub fov_degrees: Option<f32>,
}

fn parse_vec3(text: &str) -> Result<Vec3, String> {
    let parts: Vec<&str> = text.split(',').collect();
    let [x, y, z] = parts.as_slice() else {
        return Err(format!("`{text}` is not three numbers X,Y,Z"));
    };
    let number = |s: &str| {
        s.trim()
            .parse::<f32>()
            .ok()
            .filter(|v| v.is_finite())
            .ok_or_else(|| format!("`{s}` is not a finite number"))
    };
    Ok(Vec3::new(number(x)?, number(y)?, number(z)?))
}

/// Parses `X,Y,Z:X,Y,Z[:FOV]`.
///
/// # Errors
/// A message naming the part that is not numbers.
pub fn parse_camera(text: &str) -> Result<CameraArg, String> {
    let parts: Vec<&str> = text.split(':').collect();
    let (eye, target, fov) = match parts.as_slice() {
        [eye, target] => (eye, target, None),
        [eye, target, fov] => (eye, target, Some(fov)),
        _ => {
            return Err(format!(
                "`{text}` is not EYE:TARGET[:FOV], e.g. 0,2,10:0,1,0:45"
            ));
        }
    };
    let fov_degrees = fov
        .map(|f| {
            f.trim()
                .parse::<f32>()
                .ok()
                .filter(|v| *v > 0.0 && *v < 180.0)
                .ok_or_else(|| {
                    format!("field of view `{f}` is not a number of degrees in (0, 180)")
                })
        })
        .transpose()?;
    let camera = CameraArg {
        position: parse_vec3(eye)?,
        target: parse_vec3(target)?,
        fov_degrees,
    };
    if camera.position == camera.target {
        return Err(format!(
            "the eye and the target are the same point in `{text}`"
        ));
    }
    Ok(camera)
}

/// Parses `WIDTHxHEIGHT`.
///
/// # Errors
/// A message when it is not two whole numbers from 1 to 8192.
pub fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let side = |s: &str| {
        s.trim()
            .parse::<u32>()
            .ok()
            .filter(|v| (1..=rebound_render::MAX_PICTURE_SIDE).contains(v))
    };
    text.split_once(['x', 'X'])
        .and_then(|(w, h)| Some((side(w)?, side(h)?)))
        .ok_or_else(|| {
            format!(
                "`{text}` is not WIDTHxHEIGHT with sides from 1 to {} pixels",
                rebound_render::MAX_PICTURE_SIDE
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cameras_parse_with_and_without_a_field_of_view() {
        let c = parse_camera("0,2,10:0,1.5,0:45").unwrap();
        assert_eq!(c.position, Vec3::new(0.0, 2.0, 10.0));
        assert_eq!(c.target, Vec3::new(0.0, 1.5, 0.0));
        assert_eq!(c.fov_degrees, Some(45.0));
        assert_eq!(parse_camera("1,1,1:0,0,0").unwrap().fov_degrees, None);
        assert!(parse_camera("1,1:0,0,0").is_err());
        assert!(parse_camera("1,1,1:1,1,1").is_err());
        assert!(parse_camera("1,1,1:0,0,0:200").is_err());
        assert!(parse_camera("1,NaN,1:0,0,0").is_err());
    }

    #[test]
    fn sizes_parse() {
        assert_eq!(parse_size("320x240"), Ok((320, 240)));
        assert!(parse_size("0x240").is_err());
        assert!(parse_size("320").is_err());
        assert!(parse_size("99999x2").is_err());
    }
}
