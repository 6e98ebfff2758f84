#![doc = include_str!("../README.md")]

mod color;
mod contact;
mod draw;
mod joint;
mod recording;
mod settings;
mod shape;
mod world;

pub use color::Color;
pub use draw::{DebugDraw, Layer, Line, Triangle};
pub use joint::{JointGeometry, JointView};
pub use recording::draw_frame;
pub use settings::{DebugColors, DebugSettings};
pub use shape::{MAX_CIRCLE_SEGMENTS, shape_aabb};
pub use world::{body_color, draw_world};
