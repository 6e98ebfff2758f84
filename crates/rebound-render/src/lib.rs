//! Pictures and plots of a Rebound simulation: a [`RenderScene`] (shaded solids, contacts, joints) seen from
//! a [`Camera`] rendered to an [`Image`], saved as PNG or gathered into an animated GIF with
//! [`GifWriter`]; and energy, momentum, joint error and penetration against time as SVG with
//! [`plot_svg`]. A recording (`rebound-record`) gives its scenes through [`RecordingScenes`] and its plot
//! data through [`time_history`].
//!
//! ```no_run
//! use rebound_render::{Camera, RenderOptions, RenderScene, render};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! # let world = rebound::PhysicsWorld::new(Default::default())?;
//! let scene = RenderScene::from_world(&world)?;
//! let image = render(&scene, &Camera::default(), &RenderOptions::default())?;
//! image.save_png("frame.png")?;
//! # Ok(())
//! # }
//! ```

mod animation;
mod camera;
mod colour;
mod error;
mod grid;
mod image;
mod mesh;
mod overlay;
mod plot;
mod raster;
mod recording;
mod render;
mod scene;

pub use animation::{GifWriter, MAX_FRAME_INTERVAL, MIN_FRAME_INTERVAL};
pub use camera::{
    Camera, FRAMING_DIRECTION, FRAMING_MARGIN, MAX_PICTURE_SIDE, NEAR_PLANE, Projection,
};
pub use colour::Rgba;
pub use error::{PlotError, RenderError};
pub use grid::Grid;
pub use image::Image;
pub use mesh::{DEFAULT_ROUND_SUBDIVISIONS, MAX_ROUND_SUBDIVISIONS, MIN_ROUND_SUBDIVISIONS, Mesh};
pub use plot::{
    MAX_PLOT_MAGNITUDE, MAX_PLOT_SIDE, MIN_PLOT_SIDE, Panel, PlotOptions, Series, TimeHistory,
    plot_svg,
};
pub use recording::{RecordingScenes, time_history};
pub use render::{RenderOptions, render};
pub use scene::{
    ContactMark, FIXED_COLOUR, JointSegment, PALETTE, RenderScene, SLEEPING_SHADE, SceneObject,
    body_colour,
};
