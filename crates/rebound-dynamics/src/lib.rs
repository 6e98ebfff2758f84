#![doc = include_str!("../README.md")]

/// The math layer this crate builds on.
pub use rebound_math as math;
