//! Pictures of a run as it goes: frames of the world drawn by `rebound-render` from one camera, gathered
//! into an animated GIF and/or written as numbered PNG files.

use crate::cli::ViewArgs;
use crate::error::CliError;
use rebound::prelude::*;
use rebound_render::{Camera, GifWriter, RenderOptions, RenderScene};
use rebound_scene::SceneCamera;
use std::fs::File;
use std::io::BufWriter;
use std::path::{Path, PathBuf};

/// Vertical field of view when neither the command line nor the scene gives one (degrees).
const DEFAULT_FOV_DEGREES: f32 = 45.0;

/// The camera for a run: the command line's, else the scene's, else one that frames the bodies.
///
/// # Errors
/// [`CliError::Render`] if the resulting camera is unusable (the picture size, checked by the renderer).
pub fn camera(view: &ViewArgs, scene: Option<SceneCamera>, world: &PhysicsWorld) -> Result<Camera, CliError> {
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
        (None, None) => framing(world),
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

/// A view of every moving body (or of every body, if none moves): looking at the centre of their positions
/// from in front, above and to the right, far enough for their spread to fit the default field of view.
fn framing(world: &PhysicsWorld) -> (Vec3, Vec3, f32) {
    let moving: Vec<Vec3> = world
        .bodies()
        .iter()
        .filter(|(_, b)| b.body_type() != BodyType::Fixed)
        .map(|(_, b)| b.position())
        .collect();
    let points = if moving.is_empty() {
        world.bodies().iter().map(|(_, b)| b.position()).collect()
    } else {
        moving
    };
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
    /// Opens the outputs: the GIF file (a frame every `gif_every` steps of `dt`) and the PNG folder (every
    /// `png_every.0` steps), creating the folder.
    ///
    /// # Errors
    /// A file or folder that cannot be created, or a picture size the GIF cannot hold.
    pub fn open(
        camera: Camera,
        contacts: bool,
        gif: Option<&Path>,
        gif_every: u32,
        dt: f32,
        png_every: Option<(u32, PathBuf)>,
    ) -> Result<Self, CliError> {
        let gif = gif
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

    /// Draws `world` after `step` steps (0 = the start) into the outputs that want this step.
    ///
    /// # Errors
    /// A picture that cannot be drawn, encoded or written.
    pub fn capture(&mut self, step: u32, world: &PhysicsWorld) -> Result<(), CliError> {
        let gif_wants = self.gif.is_some() && step % self.gif_every == 0;
        let png_wants = self.png.as_ref().is_some_and(|(k, _)| step % k == 0);
        if !(gif_wants || png_wants) {
            return Ok(());
        }
        let scene = RenderScene::from_world(world)?;
        let image = rebound_render::render(&scene, &self.camera, &self.options)?;
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
