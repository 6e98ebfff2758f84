#![doc = include_str!("../README.md")]

/// The dynamics layer this crate builds on.
pub use rebound_dynamics as dynamics;
