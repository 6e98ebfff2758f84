//! What every example shares: `--record FILE` writes a recording of the run (`docs/recording.md`), and
//! `--gif FILE` an animated GIF of it seen from the scene's camera, drawn from the recording's frames (so
//! joints show) at 30 frames a second.

use clap::Parser;
use rebound::prelude::*;
use rebound_record::Recorder;
use rebound_render::{Camera, GifWriter, RecordingScenes, RenderOptions};
use rebound_suite::demos::About;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::PathBuf;

/// An example's options.
#[derive(Debug, Parser)]
pub struct Args {
    /// Write a recording of the run (`.rrec`) here.
    #[arg(long, value_name = "FILE")]
    pub record: Option<PathBuf>,
    /// Write an animated GIF of the run here.
    #[arg(long, value_name = "FILE")]
    pub gif: Option<PathBuf>,
    /// GIF picture size in pixels, width and height.
    #[arg(long, num_args = 2, default_values_t = [480, 360])]
    pub size: Vec<u32>,
}

/// Steps between GIF frames at 60 steps a second: 30 frames a second.
const GIF_EVERY: u64 = 2;

type Failure = Box<dyn std::error::Error>;

/// The GIF being drawn.
struct Animation {
    scenes: RecordingScenes,
    camera: Camera,
    gif: GifWriter<BufWriter<File>>,
    path: PathBuf,
}

/// A run's recorder and GIF, both optional.
pub struct Output {
    recorder: Option<Recorder<Box<dyn Write>>>,
    animation: Option<Animation>,
    record: Option<PathBuf>,
}

impl Output {
    /// Reads the command line and starts the outputs it asks for on `world`, viewed from `about.camera`.
    ///
    /// # Errors
    /// A file that cannot be created, a bad picture size.
    pub fn start(world: &PhysicsWorld, about: &About) -> Result<Self, Failure> {
        let args = Args::parse();
        if args.record.is_none() && args.gif.is_none() {
            return Ok(Self {
                recorder: None,
                animation: None,
                record: None,
            });
        }
        let out: Box<dyn Write> = match &args.record {
            Some(path) => Box::new(BufWriter::new(File::create(path)?)),
            None => Box::new(std::io::sink()),
        };
        let animation = match &args.gif {
            Some(path) => {
                let [width, height] = args.size[..] else {
                    return Err("--size takes a width and a height".into());
                };
                let (position, target, fov) = about.camera;
                let camera = Camera {
                    position,
                    target,
                    fov_y: fov.to_radians(),
                    width,
                    height,
                };
                camera.projection()?;
                let header = Recorder::new(world, Vec::new())?.finish()?;
                let manifest = rebound_record::FrameReader::new(header.as_slice())?
                    .manifest()
                    .clone();
                let gif = GifWriter::new(
                    BufWriter::new(File::create(path)?),
                    width,
                    height,
                    GIF_EVERY as f32 / 60.0,
                )?;
                Some(Animation {
                    scenes: RecordingScenes::new(&manifest)?,
                    camera,
                    gif,
                    path: path.clone(),
                })
            }
            None => None,
        };
        let mut output = Self {
            recorder: Some(Recorder::new(world, out)?),
            animation,
            record: args.record,
        };
        if let Some(recorder) = &mut output.recorder {
            recorder.record(world)?;
        }
        output.draw()?;
        Ok(output)
    }

    /// Steps `world` by `dt`, recording and drawing the new state if asked.
    ///
    /// # Errors
    /// A recording or picture that cannot be written.
    pub fn step(&mut self, world: &mut PhysicsWorld, dt: f32) -> Result<StepReport, Failure> {
        let report = match &mut self.recorder {
            Some(recorder) => recorder.step(world, dt)?,
            None => world.step(dt),
        };
        self.draw()?;
        Ok(report)
    }

    fn draw(&mut self) -> Result<(), Failure> {
        let (Some(recorder), Some(animation)) = (&mut self.recorder, &mut self.animation) else {
            return Ok(());
        };
        let Some(frame) = recorder.last_frame() else {
            return Ok(());
        };
        if frame.step.is_multiple_of(GIF_EVERY) {
            let scene = animation.scenes.scene(frame)?;
            let image =
                rebound_render::render(&scene, &animation.camera, &RenderOptions::default())?;
            animation.gif.add_frame(&image)?;
        } else {
            animation.scenes.advance(frame)?;
        }
        Ok(())
    }

    /// Finishes the files and says what was written.
    ///
    /// # Errors
    /// A file that cannot be finished.
    pub fn finish(self) -> Result<Vec<String>, Failure> {
        let mut lines = Vec::new();
        if let Some(recorder) = self.recorder {
            let frames = recorder.frames_written();
            recorder.finish()?;
            if let Some(path) = self.record {
                lines.push(format!("wrote {} ({frames} frames)", path.display()));
            }
        }
        if let Some(animation) = self.animation {
            let frames = animation.gif.frame_count();
            animation.gif.finish()?;
            lines.push(format!(
                "wrote {} ({frames} frames)",
                animation.path.display()
            ));
        }
        Ok(lines)
    }
}
