#![doc = include_str!("../README.md")]

/// The constraints layer this crate builds on.
pub use rebound_constraints as constraints;
