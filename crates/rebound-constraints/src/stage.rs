//! The pass type: what one solve pass of the joint solver needs besides the bodies — bias or relax, the
//! substep length and the joint softness ([`Stage`]) — and which substep of the step a pass runs in
//! ([`Substep`], given by the step). Every stage of the step that solves rows (solve, relax, the position
//! projection) hands a [`Stage`] to the joints and to the path solver.

use rebound_dynamics::{Bias, Softness};

/// What one solve pass needs besides the bodies.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Stage {
    /// Bias pass or relax pass.
    pub bias: Bias,
    /// Substep length (s).
    pub h: f32,
    /// 1/h (1/s).
    pub inv_h: f32,
    /// Softness of hard parts in the bias pass.
    pub joint_softness: Softness,
}

impl Stage {
    /// The stage of the position projection for substeps of `h` (s): a bias rate of 1 and `inv_h` = 1 make
    /// every row's bias its position error `C` (m or rad), slack ropes included (their speculative bias is
    /// `C·inv_h`).
    pub(crate) fn projection(h: f32) -> Self {
        Self {
            bias: Bias::On,
            h,
            inv_h: 1.0,
            joint_softness: Softness {
                bias_rate: 1.0,
                mass_scale: 1.0,
                impulse_scale: 0.0,
            },
        }
    }
}

/// Which substep of the step a solve or relax pass runs in, as the step counts them: substep `index` of
/// `count` (0-based). The last substep's relax pass builds every path's rows at the step's final pose and
/// is the one that relaxes closed paths (see [`crate::JointSolver::solve_substep`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct Substep {
    index: u32,
    count: u32,
}

impl Substep {
    /// Substep `index` (0-based) of a step of `count` substeps.
    #[must_use]
    pub const fn new(index: u32, count: u32) -> Self {
        Self { index, count }
    }

    /// The substep's index in the step (0-based).
    #[must_use]
    pub const fn index(self) -> u32 {
        self.index
    }

    /// Whether this is the step's last substep (also for an index past the count).
    #[must_use]
    pub const fn is_last(self) -> bool {
        self.index.saturating_add(1) >= self.count
    }
}
