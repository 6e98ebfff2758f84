//! Pictures of a run as it goes: frames of the world drawn by `rebound-render` from one camera, gathered
//! into an animated GIF and/or written as numbered PNG files.

use crate::cli::{PictureArgs, ViewArgs};
use crate::error::CliError;
use rebound::prelude::*;
use rebound_record::{FrameReader, Manifest, Recorder};
use rebound_render::{Camera, GifWriter, RenderOptions, RenderScene};
use rebound_scene::SceneCamera;
use std::fs::File;
use std::io::BufWriter;
use std::path::PathBuf;

/// Vertical field of view when neither the command line nor the scene gives one (degrees).
const DEFAULT_FOV_DEGREES: f32 = 45.0;

/// The camera for a run: the command line's, else the scene's, else one that frames the bodies.
///
/// # Errors
/// [`CliError::Render`] if the resulting camera is unusable (the picture size, checked by the renderer).
pub fn camera(
    view: &ViewArgs,
    scene: Option<SceneCamera>,
    bodies: &[(Vec3, bool)],
) -> Result<Camera, CliError> {
    let (width, height) = view.size;
    let (position, target, fov_degrees) = match (view.camera, scene) {
        (Some(c), scene) => (
            c.position,
            c.target,
            c.fov_degrees
                .or(scene.map(|s| s.fov_degrees))
                .unwrap_or(DEFAULT_FOV_DEGREES),
        ),
        (None, Some(s)) => (s.position, s.target, s.fov_degrees),
        (None, None) => framing(bodies),
    };
    let camera = Camera {
        position,
        target,
        fov_y: fov_degrees.to_radians(),
        width,
        height,
    };
    camera.projection()?;
    Ok(camera)
}

/// A view of every moving body (or of every body, if none moves), given as positions with whether the body
/// moves: looking at the centre of their positions from in front, above and to the right, far enough for
/// their spread to fit the default field of view.
fn framing(bodies: &[(Vec3, bool)]) -> (Vec3, Vec3, f32) {
    let any_moving = bodies.iter().any(|(_, moving)| *moving);
    let points: Vec<Vec3> = bodies
        .iter()
        .filter(|(_, moving)| *moving || !any_moving)
        .map(|(p, _)| *p)
        .collect();
    let (lo, hi) = points.iter().fold(
        (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(*p), hi.max(*p)),
    );
    let (centre, radius) = if points.is_empty() {
        (Vec3::ZERO, 5.0)
    } else {
        ((lo + hi) * 0.5, ((hi - lo).length() * 0.5).max(1.0) + 1.0)
    };
    let distance = radius / (0.5 * DEFAULT_FOV_DEGREES.to_radians()).tan();
    let direction = Vec3::new(0.35, 0.4, 1.0).normalize();
    (centre + direction * distance, centre, DEFAULT_FOV_DEGREES)
}

/// `--png-every K DIR` as a step interval and a folder.
fn png_every(args: &PictureArgs) -> Result<Option<(u32, PathBuf)>, CliError> {
    let Some(values) = &args.png_every else {
        return Ok(None);
    };
    let [k, dir] = values.as_slice() else {
        return Err(CliError::Argument {
            argument: "--png-every",
            message: "needs K and DIR".to_owned(),
        });
    };
    let k = k
        .parse::<u32>()
        .ok()
        .filter(|k| *k >= 1)
        .ok_or_else(|| CliError::Argument {
            argument: "--png-every",
            message: format!("K must be a whole number ≥ 1, got `{k}`"),
        })?;
    Ok(Some((k, PathBuf::from(dir))))
}

/// Where a run's pictures go.
pub struct Pictures {
    camera: Camera,
    options: RenderOptions,
    gif: Option<(PathBuf, GifWriter<BufWriter<File>>)>,
    /// Write a GIF frame every this many steps.
    gif_every: u32,
    png: Option<(u32, PathBuf)>,
    pngs_written: usize,
}

impl Pictures {
    /// Checks `args` and opens the outputs it asks for: the GIF file (a frame every whole number of steps of
    /// `dt`, as close to `args.fps` as that allows) and the PNG folder, creating the folder.
    ///
    /// # Errors
    /// A bad frame rate or `--png-every`, a file or folder that cannot be created, or a picture size the GIF
    /// cannot hold.
    pub fn open(
        camera: Camera,
        contacts: bool,
        args: &PictureArgs,
        dt: f32,
    ) -> Result<Self, CliError> {
        if !(args.fps.is_finite() && args.fps > 0.0) {
            return Err(CliError::Argument {
                argument: "--fps",
                message: format!("must be finite and > 0, got {}", args.fps),
            });
        }
        let png_every = png_every(args)?;
        // The cast saturates; at least one step per frame.
        let gif_every = ((1.0 / (args.fps * dt)).round() as u32).max(1);
        let gif = args
            .gif
            .as_deref()
            .map(|path| {
                let file = File::create(path).map_err(|source| CliError::Write {
                    path: path.to_owned(),
                    source,
                })?;
                let writer = GifWriter::new(
                    BufWriter::new(file),
                    camera.width,
                    camera.height,
                    gif_every as f32 * dt,
                )?;
                Ok::<_, CliError>((path.to_owned(), writer))
            })
            .transpose()?;
        if let Some((_, dir)) = &png_every {
            std::fs::create_dir_all(dir).map_err(|source| CliError::Write {
                path: dir.clone(),
                source,
            })?;
        }
        Ok(Self {
            camera,
            options: RenderOptions {
                contacts,
                ..RenderOptions::default()
            },
            gif,
            gif_every: gif_every.max(1),
            png: png_every,
            pngs_written: 0,
        })
    }

    /// Whether any picture is wanted at all.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.gif.is_none() && self.png.is_none()
    }

    /// Whether the picture after `step` steps (0 = the start) is wanted by any output.
    #[must_use]
    pub fn wants(&self, step: u64) -> bool {
        let (gif, png) = self.wanted_by(step);
        gif || png
    }

    /// Whether the GIF and whether the PNG folder want the picture after `step` steps.
    fn wanted_by(&self, step: u64) -> (bool, bool) {
        let gif = self.gif.is_some() && step.is_multiple_of(u64::from(self.gif_every));
        let png = self
            .png
            .as_ref()
            .is_some_and(|(k, _)| step.is_multiple_of(u64::from(*k)));
        (gif, png)
    }

    /// Draws `scene`, the state after `step` steps (0 = the start), into the outputs that want this step.
    ///
    /// # Errors
    /// A picture that cannot be drawn, encoded or written.
    pub fn capture(&mut self, step: u64, scene: &RenderScene) -> Result<(), CliError> {
        let (gif_wants, png_wants) = self.wanted_by(step);
        if !(gif_wants || png_wants) {
            return Ok(());
        }
        let image = rebound_render::render(scene, &self.camera, &self.options)?;
        if gif_wants && let Some((_, gif)) = &mut self.gif {
            gif.add_frame(&image)?;
        }
        if png_wants && let Some((_, dir)) = &self.png {
            image.save_png(dir.join(format!("step_{step:05}.png")))?;
            self.pngs_written += 1;
        }
        Ok(())
    }

    /// Finishes the GIF. Returns a line per output written, for the summary.
    ///
    /// # Errors
    /// The GIF cannot be finished.
    pub fn finish(self) -> Result<Vec<String>, CliError> {
        let mut lines = Vec::new();
        if let Some((path, gif)) = self.gif {
            let frames = gif.frame_count();
            gif.finish()?;
            lines.push(format!("wrote {} ({frames} frames)", path.display()));
        }
        if let Some((every, dir)) = self.png {
            lines.push(format!(
                "wrote {} PNG frames (every {every} steps) to {}",
                self.pngs_written,
                dir.display()
            ));
        }
        Ok(lines)
    }
}

/// The manifest a recording of `world` starts with (the descriptions of its bodies, colliders and joints),
/// read back from the header a recorder writes.
///
/// # Errors
/// [`CliError::Recording`] if the header cannot be written or read back (not for a valid world).
pub fn manifest_of(world: &PhysicsWorld) -> Result<Manifest, CliError> {
    let header = Recorder::new(world, Vec::new())?.finish()?;
    Ok(FrameReader::new(header.as_slice())?.manifest().clone())
}
