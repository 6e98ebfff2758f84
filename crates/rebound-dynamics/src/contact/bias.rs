//! Which pass of a soft substep a contact solve is: *solve* with the position-correcting bias, or *relax*
//! without it.

/// Whether the solve applies the position-correcting bias (the two passes of a soft substep).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Bias {
    /// Solve with the soft bias: corrects overlap.
    On,
    /// Relax: solve the velocity constraint only, removing the bias velocity.
    Off,
}
