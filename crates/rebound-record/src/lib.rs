#![doc = include_str!("../README.md")]

mod capture;
mod catalog;
mod contacts;
mod decode;
mod diagnostics;
mod encode;
mod error;
mod format;
mod frame;
mod handle_index;
mod manifest;
mod reader;
mod recorder;

pub use catalog::Catalog;
pub use diagnostics::{joint_error, spring_energy};
pub use error::RecordingError;
pub use format::{EXTENSION, FORMAT_NAME, MAGIC, NONE, VERSION};
pub use frame::{BodySample, ContactSample, Diagnostics, Frame, JointSample, RecordedEvent};
pub use manifest::{
    BodyEntry, BodyKind, Changes, ColliderEntry, JointEntry, JointKindName, LimitsEntry, Manifest,
};
pub use reader::{FrameReader, Recording};
pub use recorder::Recorder;
