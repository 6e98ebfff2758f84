//! A joint's persistent solver state ([`JointState`]): the impulses it carried in the last step, its reaction
//! and whether it broke. Read at *prepare* (warm starting), written at *store impulses*.

use crate::error::ConstraintError;
use rebound_math::glam::Vec3A;
use rebound_math::validity::{check_finite, check_finite_vec3, check_non_negative};
use rebound_math::{Vec3, Vec4};

rebound_math::checked_serde! { "JointState", JointState::validated;
/// The persistent solver state of one joint: the impulses accumulated over the last substep of the last step
/// (for warm starting the next step), the reaction it carried, and whether it has broken. The world keeps one
/// per joint; [`crate::JointSolver::prepare`] reads it and [`crate::JointSolver::store_impulses`] writes it.
///
/// Impulses are per substep (N·s for linear rows, N·m·s for angular ones); divide by the substep length `h`
/// for a force. Which fields a kind uses:
///
/// | field | spring | rope | rod | ball | hinge | fixed | prismatic | wheel |
/// |---|---|---|---|---|---|---|---|---|
/// | `linear_impulse` | | | | point | point | point | across (x, y) | across (x, y) |
/// | `angular_impulse` | | | | | axis (x, y) | rotation | rotation | axle (x, y) |
/// | `axial_impulse` | spring | | rod | | spring | | spring | suspension |
/// | `lower_impulse` (≥ 0) | | | | | limit | | limit | limit |
/// | `upper_impulse` (≤ 0) | | rope | | | limit | | limit | limit |
/// | `motor_impulse` | | | | | motor | | motor | drive |
#[derive(Debug, Clone, Copy, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct JointState {
    /// Impulse of the point block or the two rows across an axis (N·s). Default: 0.
    pub linear_impulse: Vec3,
    /// Impulse of the rotation lock or the two axis-alignment rows (N·m·s). Default: 0.
    pub angular_impulse: Vec3,
    /// Impulse of the spring or rod row (N·s or N·m·s; for [`crate::SpringModel::Force`] the force·h of the last
    /// substep, recorded, not warm-started). Default: 0.
    pub axial_impulse: f32,
    /// Impulse of the lower limit (≥ 0). Default: 0.
    pub lower_impulse: f32,
    /// Impulse of the upper limit or the rope (≤ 0). Default: 0.
    pub upper_impulse: f32,
    /// Impulse of the motor. Default: 0.
    pub motor_impulse: f32,
    /// Impulse of the long-range tether of the body this joint leads to, if it has one (N·s, ≤ 0; see
    /// [`crate::JointSettings::tethers`]). Default: 0.
    pub tether_impulse: f32,
    /// Magnitude of the constraint force the joint carried in the last substep of the last step (N).
    pub reaction_force: f32,
    /// Magnitude of the constraint torque it carried (N·m).
    pub reaction_torque: f32,
    /// Whether the joint has broken (exceeded its break force or torque). A broken joint is skipped until
    /// this is reset to `false`. Default: false.
    pub broken: bool,
}
}

impl JointState {
    /// Returns `self` if every impulse is finite and the reactions are finite and ≥ 0: what warm starting and
    /// the break check trust (for values from outside the solver: deserialised, or restored).
    ///
    /// # Errors
    /// The first non-finite or negative field, by name.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        check_finite_vec3("linear_impulse", self.linear_impulse)?;
        check_finite_vec3("angular_impulse", self.angular_impulse)?;
        for (field, value) in [
            ("axial_impulse", self.axial_impulse),
            ("lower_impulse", self.lower_impulse),
            ("upper_impulse", self.upper_impulse),
            ("motor_impulse", self.motor_impulse),
            ("tether_impulse", self.tether_impulse),
        ] {
            check_finite(field, value)?;
        }
        check_non_negative("reaction_force", self.reaction_force)?;
        check_non_negative("reaction_torque", self.reaction_torque)?;
        Ok(self)
    }

    /// The state with every impulse zeroed but the tether's (which the tethers keep, whatever the joint's
    /// kind): what a kind's *prepare* starts from before it keeps the impulses its rows use, so that a joint
    /// whose kind changed is not warm-started with another kind's impulses.
    #[inline]
    pub(crate) fn tether_only(&self) -> Self {
        Self {
            tether_impulse: self.tether_impulse,
            ..Self::default()
        }
    }

    /// Whether every number is finite: `x·0` is 0 for a finite `x` and NaN otherwise, so four comparisons
    /// side by side cover the thirteen numbers.
    #[inline]
    pub(crate) fn is_finite(&self) -> bool {
        let vectors =
            Vec3A::from(self.linear_impulse) * 0.0 + Vec3A::from(self.angular_impulse) * 0.0;
        let scalars = Vec4::new(
            self.axial_impulse,
            self.lower_impulse,
            self.upper_impulse,
            self.motor_impulse,
        ) * 0.0
            + Vec4::new(
                self.tether_impulse,
                self.reaction_force,
                self.reaction_torque,
                0.0,
            ) * 0.0;
        vectors.cmpeq(Vec3A::ZERO).all() & scalars.cmpeq(Vec4::ZERO).all()
    }
}

/// Where [`crate::JointSolver::store_impulses_to`] writes the joints' states back: joint `i` of the step (in
/// the order [`crate::JointSolver::prepare_from`] read them) to `state_mut(i)`. A slice is one; a world
/// writes straight into its stored joints.
pub trait JointStates {
    /// The state of joint `i` of the step, if it has one.
    fn state_mut(&mut self, i: usize) -> Option<&mut JointState>;
}

impl JointStates for [JointState] {
    fn state_mut(&mut self, i: usize) -> Option<&mut JointState> {
        self.get_mut(i)
    }
}
