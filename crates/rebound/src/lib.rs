#![doc = include_str!("../README.md")]

/// The collision library, re-exported so users get the same version Rebound uses.
pub use parry3d;

/// Rotations, transforms, inertia (`rebound-math`).
pub use rebound_math as math;

/// Bodies, mass, integration, impulses (`rebound-dynamics`).
pub use rebound_dynamics as dynamics;

/// Springs, ropes and joints (`rebound-constraints`).
pub use rebound_constraints as constraints;

/// The world and its step (`rebound-world`).
pub use rebound_world as world;
