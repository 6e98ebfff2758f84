//! The 6-DOF (generic) joint: each of the three linear and three angular axes of A's joint frame free,
//! locked, limited to a range, and optionally driven — by a velocity motor or a spring toward a position
//! target, both with a force cap (rapier's `GenericJoint`, Jolt's `SixDOFConstraint`, PhysX's D6). The
//! other joint kinds stay the presets most joints are; this one is for what they do not cover. Stages:
//! *prepare*, *warm start*, *solve* and *relax*.
//!
//! ```text
//! linear i:   x_i = t_i·d,  t_i = F_a·ê_i,  lever r_a + d for A    row J = [ −tᵀ  −((r_a + d) × t)ᵀ  tᵀ  (r_b × t)ᵀ ]
//!             (the prismatic joint's rows, see crate::prismatic)
//! angular:    all three locked: the rotation lock C = rotation_error(F_a, F_b) (crate::part::RotationPart)
//!             otherwise (θ, σ_y, σ_z) = (twist, φ·u_y, φ·u_z) of crate::part::SwingTwist, rows about
//!             j_t, F_a·ŷ, F_a·ẑ (the twist's exact, the swing components' exact at zero swing)
//! locked:     C = x = 0, joint softness in the bias pass                      → linear/angular_impulse[i]
//! limited:    x_min ≤ x ≤ x_max, the nearer bound's speculative row            → linear/angular_impulse[i]
//! velocity:   Ċ → v_target, |λ| ≤ F_max·h, both passes                          → the step's drive impulse
//! position:   C = x − x_target, the drive's own spring, |λ| ≤ F_max·h, bias pass only
//! ```
//!
//! Row order: drives and limits axis by axis, then the angular locks, then the linear locks (the prismatic
//! joint's order, so that a 6-DOF joint free along X alone steps as a prismatic joint does). Not solved on a
//! direct path. The drives' impulses are warm-started from substep to substep within a step, not from the
//! last step (the joint state keeps the locks' and limits'); the reaction includes them.

use crate::error::{ConstraintError, check_in_range, check_non_negative_or_infinite};
use crate::limits::Limits;
use crate::pair::BodyPair;
use crate::part::{
    AnglePart, RotationPart, Row, RowTarget, SwingTwist, block_target, rotation_error,
};
use crate::prismatic::SlideGeometry;
use crate::soft_spring::SoftSpring;
use crate::stage::Stage;
use crate::state::JointState;
use core::f32::consts::PI;
use rebound_dynamics::{Bias, Softness, SolverBody, StepContext};
use rebound_math::validity::check_finite;
use rebound_math::{Quat, Vec3};

/// One of the joint's six axes, in A's joint frame.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum Axis {
    /// Translation along X (m).
    LinearX,
    /// Translation along Y (m).
    LinearY,
    /// Translation along Z (m).
    LinearZ,
    /// The twist about X (rad).
    AngularX,
    /// The swing component about Y (rad).
    AngularY,
    /// The swing component about Z (rad).
    AngularZ,
}

impl Axis {
    /// The six axes in storage order.
    pub const ALL: [Self; 6] = [
        Self::LinearX,
        Self::LinearY,
        Self::LinearZ,
        Self::AngularX,
        Self::AngularY,
        Self::AngularZ,
    ];

    const fn index(self) -> usize {
        self as usize
    }

    const fn is_angular(self) -> bool {
        self.index() >= 3
    }

    /// The field names errors about this axis use.
    const fn fields(self) -> AxisFields {
        macro_rules! fields {
            ($name:literal) => {
                AxisFields {
                    lower: concat!($name, ".lower"),
                    upper: concat!($name, ".upper"),
                    target_speed: concat!($name, ".target_speed"),
                    target: concat!($name, ".target"),
                    max_force: concat!($name, ".max_force"),
                }
            };
        }
        match self {
            Self::LinearX => fields!("linear_x"),
            Self::LinearY => fields!("linear_y"),
            Self::LinearZ => fields!("linear_z"),
            Self::AngularX => fields!("angular_x"),
            Self::AngularY => fields!("angular_y"),
            Self::AngularZ => fields!("angular_z"),
        }
    }
}

/// The names of an axis's fields in errors (`"angular_y.lower"`, …).
struct AxisFields {
    lower: &'static str,
    upper: &'static str,
    target_speed: &'static str,
    target: &'static str,
    max_force: &'static str,
}

/// How an axis may move.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum AxisMotion {
    /// Free. The default.
    #[default]
    Free,
    /// Held at 0.
    Locked,
    /// Kept in a range (m or rad; angular bounds within `[−π, π]`). `lower == upper` holds it there.
    Limited(Limits),
}

/// A drive on an axis.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum AxisDrive {
    /// A velocity motor: drives the axis's speed to `target_speed` (m/s or rad/s) with at most `max_force`
    /// (N or N·m; +∞ = unbounded).
    Velocity {
        /// Target speed (m/s or rad/s), finite.
        target_speed: f32,
        /// Force or torque cap (N or N·m), ≥ 0.
        #[cfg_attr(
            feature = "serde",
            serde(
                with = "crate::bounds::unbounded",
                default = "crate::bounds::unbounded::infinity"
            )
        )]
        max_force: f32,
    },
    /// A spring toward a position `target` (m or rad) with at most `max_force` (N or N·m; +∞ = unbounded).
    Position {
        /// Target position (m or rad; angular within `[−π, π]`).
        target: f32,
        /// Stiffness (Hz/ζ, or N/m and N·s/m, N·m/rad and N·m·s/rad).
        spring: SoftSpring,
        /// Force or torque cap (N or N·m), ≥ 0.
        #[cfg_attr(
            feature = "serde",
            serde(
                with = "crate::bounds::unbounded",
                default = "crate::bounds::unbounded::infinity"
            )
        )]
        max_force: f32,
    },
}

/// One axis's motion and drive.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default))]
pub struct AxisSettings {
    /// How the axis may move. Default: free.
    pub motion: AxisMotion,
    /// Its drive, if any. Default: none.
    pub drive: Option<AxisDrive>,
}

/// A 6-DOF joint (see the module docs). The axes are those of A's joint frame
/// ([`crate::Joint::local_basis_a`]), at the anchors.
///
/// # Examples
///
/// ```
/// use rebound_constraints::{Axis, AxisDrive, AxisMotion, Limits, SixDofJoint};
/// // A slider along X with a 0.5 m travel, driven at 0.2 m/s, everything else locked.
/// let slider = SixDofJoint::locked()
///     .with_motion(Axis::LinearX, AxisMotion::Limited(Limits::new(0.0, 0.5)?))?
///     .with_drive(Axis::LinearX, Some(AxisDrive::Velocity { target_speed: 0.2, max_force: 100.0 }))?;
/// assert_eq!(slider.axis(Axis::LinearY).motion, AxisMotion::Locked);
/// let bad = AxisDrive::Velocity { target_speed: f32::NAN, max_force: 1.0 };
/// let err = SixDofJoint::new().with_drive(Axis::AngularZ, Some(bad)).unwrap_err();
/// assert!(err.to_string().contains("angular_z.target_speed"));
/// # Ok::<(), rebound_constraints::ConstraintError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default))]
pub struct SixDofJoint {
    axes: [AxisSettings; 6],
}

impl SixDofJoint {
    /// All six axes free.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// All six axes locked (a weld, until axes are freed).
    #[must_use]
    pub fn locked() -> Self {
        Self {
            axes: [AxisSettings {
                motion: AxisMotion::Locked,
                drive: None,
            }; 6],
        }
    }

    /// Sets how `axis` may move; see [`SixDofJoint::set_motion`].
    ///
    /// # Errors
    /// As [`SixDofJoint::set_motion`].
    pub fn with_motion(mut self, axis: Axis, motion: AxisMotion) -> Result<Self, ConstraintError> {
        self.set_motion(axis, motion)?;
        Ok(self)
    }

    /// Sets or removes the drive of `axis`; see [`SixDofJoint::set_drive`].
    ///
    /// # Errors
    /// As [`SixDofJoint::set_drive`].
    pub fn with_drive(
        mut self,
        axis: Axis,
        drive: Option<AxisDrive>,
    ) -> Result<Self, ConstraintError> {
        self.set_drive(axis, drive)?;
        Ok(self)
    }

    /// The motion and drive of `axis`.
    #[must_use]
    pub fn axis(&self, axis: Axis) -> AxisSettings {
        self.axes[axis.index()]
    }

    /// Sets how `axis` may move; nothing changes on error.
    ///
    /// # Errors
    /// Non-finite or inverted bounds; angular bounds outside `[−π, π]` (fields such as `angular_x.lower`).
    pub fn set_motion(&mut self, axis: Axis, motion: AxisMotion) -> Result<(), ConstraintError> {
        check_motion(axis, motion)?;
        self.axes[axis.index()].motion = motion;
        Ok(())
    }

    /// Sets or removes the drive of `axis`; nothing changes on error.
    ///
    /// # Errors
    /// A non-finite target speed or target (angular targets within `[−π, π]`), an invalid spring, a negative
    /// or NaN force cap (fields such as `linear_y.max_force`).
    pub fn set_drive(
        &mut self,
        axis: Axis,
        drive: Option<AxisDrive>,
    ) -> Result<(), ConstraintError> {
        if let Some(d) = drive {
            check_drive(axis, d)?;
        }
        self.axes[axis.index()].drive = drive;
        Ok(())
    }

    /// Returns `self` if every axis is valid (for values that bypassed the setters: deserialized ones).
    ///
    /// # Errors
    /// The first invalid field.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        for axis in Axis::ALL {
            let settings = self.axis(axis);
            check_motion(axis, settings.motion)?;
            if let Some(d) = settings.drive {
                check_drive(axis, d)?;
            }
        }
        Ok(self)
    }

    pub(crate) fn prepare(
        &self,
        pair: &BodyPair,
        ctx: &StepContext,
        state: &mut JointState,
    ) -> PreparedSixDof {
        let kept = *state;
        *state = kept.tether_only();
        let rotation_locked = self.axes[3..]
            .iter()
            .all(|a| a.motion == AxisMotion::Locked);
        for axis in Axis::ALL {
            let i = axis.index();
            let held = self.axes[i].motion != AxisMotion::Free;
            let (slot, kept_slot) = if axis.is_angular() {
                (&mut state.angular_impulse, kept.angular_impulse)
            } else {
                (&mut state.linear_impulse, kept.linear_impulse)
            };
            if held {
                slot[i % 3] = kept_slot[i % 3];
            }
        }
        let drive_softness = self.axes.map(|a| match a.drive {
            Some(AxisDrive::Position { spring, .. }) => spring.softness(0.0, ctx.h),
            _ => Softness::RIGID,
        });
        PreparedSixDof {
            joint: *self,
            rotation: rotation_locked.then(|| RotationPart::new(pair)),
            drive_softness,
            drive_impulse: [0.0; 6],
        }
    }
}

fn check_motion(axis: Axis, motion: AxisMotion) -> Result<(), ConstraintError> {
    let AxisMotion::Limited(l) = motion else {
        return Ok(());
    };
    let f = axis.fields();
    let limits = Limits::new(l.lower(), l.upper()).map_err(|e| rename_limits(e, &f))?;
    if axis.is_angular() {
        check_in_range(f.lower, limits.lower(), -PI, PI)?;
        check_in_range(f.upper, limits.upper(), -PI, PI)?;
    }
    Ok(())
}

/// A [`Limits`] error with the axis's field names in place of `lower` and `upper`.
fn rename_limits(error: ConstraintError, f: &AxisFields) -> ConstraintError {
    let rename = |field: &'static str| if field == "lower" { f.lower } else { f.upper };
    match error {
        ConstraintError::InvertedRange { lower, upper, .. } => ConstraintError::InvertedRange {
            lower_field: f.lower,
            lower,
            upper_field: f.upper,
            upper,
        },
        ConstraintError::Math(rebound_math::MathError::NonFinite { field, value }) => {
            ConstraintError::Math(rebound_math::MathError::NonFinite {
                field: rename(field),
                value,
            })
        }
        other => other,
    }
}

fn check_drive(axis: Axis, drive: AxisDrive) -> Result<(), ConstraintError> {
    let f = axis.fields();
    match drive {
        AxisDrive::Velocity {
            target_speed,
            max_force,
        } => {
            check_finite(f.target_speed, target_speed)?;
            check_non_negative_or_infinite(f.max_force, max_force)?;
        }
        AxisDrive::Position {
            target,
            spring,
            max_force,
        } => {
            if axis.is_angular() {
                check_in_range(f.target, target, -PI, PI)?;
            } else {
                check_finite(f.target, target)?;
            }
            spring.validated()?;
            check_non_negative_or_infinite(f.max_force, max_force)?;
        }
    }
    Ok(())
}

/// How many times one visit sweeps the rows of a joint whose angular limits or drives act beside held
/// linear axes.
const SWEEPS: usize = 3;

/// A 6-DOF joint ready for the substeps.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedSixDof {
    joint: SixDofJoint,
    /// The rotation lock, when all three angular axes are locked.
    rotation: Option<RotationPart>,
    /// Position drives' coefficients in frequency form.
    drive_softness: [Softness; 6],
    /// The drives' impulses accumulated this step (N·s or N·m·s), in axis order.
    drive_impulse: [f32; 6],
}

/// The angular coordinates and their rows' axes at one pose (when the rotation is not locked whole).
struct AngularGeometry {
    coordinates: [f32; 3],
    axes: [Option<Vec3>; 3],
}

impl AngularGeometry {
    fn new((fa, fb): (Quat, Quat)) -> Self {
        let st = SwingTwist::new(fa, fb);
        let sigma = st.swing_direction * st.swing;
        Self {
            coordinates: [st.twist, sigma.x, sigma.y],
            axes: [
                SwingTwist::twist_axis(fa, fb),
                Some(fa * Vec3::Y),
                Some(fa * Vec3::Z),
            ],
        }
    }
}

impl PreparedSixDof {
    /// The drives' accumulated impulses this step (for the reaction).
    pub(crate) fn drive_impulses(&self) -> [f32; 6] {
        self.drive_impulse
    }

    pub(crate) fn warm_start(
        &self,
        pair: &BodyPair,
        state: &JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
    ) {
        let g = SlideGeometry::new(pair, a, b);
        g.row(pair, 0)
            .apply(pair, a, b, state.linear_impulse.x + self.drive_impulse[0]);
        if self.rotation.is_some() {
            RotationPart::apply(pair, a, b, state.angular_impulse);
        } else {
            let angular = AngularGeometry::new((g.frame_a, g.frame_b));
            for i in 0..3 {
                if let Some(axis) = angular.axes[i] {
                    let impulse = state.angular_impulse[i] + self.drive_impulse[3 + i];
                    AnglePart::new(pair, axis).apply(a, b, impulse);
                }
            }
        }
        for i in 1..3 {
            g.row(pair, i)
                .apply(pair, a, b, state.linear_impulse[i] + self.drive_impulse[i]);
        }
    }

    /// Stages *solve* and *relax*: the joint's rows, swept [`SWEEPS`] times when an angular limit or drive
    /// acts beside held linear axes (as a limited ball joint's, see `crate::ball`: an angular row alone turns
    /// the body about its centre of mass, which the linear rows turn partly back), else once.
    pub(crate) fn solve(
        &mut self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        let angular_rows = self.joint.axes[3..]
            .iter()
            .any(|x| x.drive.is_some() || matches!(x.motion, AxisMotion::Limited(_)));
        let linear_held = self.joint.axes[..3]
            .iter()
            .any(|x| x.motion != AxisMotion::Free);
        let sweeps = if angular_rows && linear_held {
            SWEEPS
        } else {
            1
        };
        for _ in 0..sweeps {
            self.solve_once(pair, state, a, b, stage);
        }
    }

    fn solve_once(
        &mut self,
        pair: &BodyPair,
        state: &mut JointState,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        let g = SlideGeometry::new(pair, a, b);
        let angular = self
            .rotation
            .is_none()
            .then(|| AngularGeometry::new((g.frame_a, g.frame_b)));
        // Drives and limits, axis by axis.
        for axis in Axis::ALL {
            let i = axis.index();
            let settings = self.joint.axes[i];
            let limited = matches!(settings.motion, AxisMotion::Limited(_));
            if settings.drive.is_none() && !limited {
                continue;
            }
            if axis.is_angular() {
                let Some(angular) = &angular else {
                    continue;
                };
                let Some(row_axis) = angular.axes[i - 3] else {
                    continue;
                };
                let row = AnglePart::new(pair, row_axis);
                let x = angular.coordinates[i - 3];
                let mut lock = state.angular_impulse[i - 3];
                self.solve_axis(&row, pair, i, x, &mut lock, a, b, stage);
                state.angular_impulse[i - 3] = lock;
            } else {
                let row = g.row(pair, i);
                let x = g.axes[i].dot(g.d);
                let mut lock = state.linear_impulse[i];
                self.solve_axis(&row, pair, i, x, &mut lock, a, b, stage);
                state.linear_impulse[i] = lock;
            }
        }
        // Angular locks.
        if let Some(rotation) = &self.rotation {
            let target = block_target(
                rotation_error(g.frame_a, g.frame_b),
                stage.bias,
                stage.joint_softness,
            );
            rotation.solve(pair, a, b, target, &mut state.angular_impulse);
        } else if let Some(angular) = &angular {
            for i in 0..3 {
                if self.joint.axes[3 + i].motion != AxisMotion::Locked {
                    continue;
                }
                let Some(row_axis) = angular.axes[i] else {
                    continue;
                };
                let target =
                    RowTarget::equality(angular.coordinates[i], stage.bias, stage.joint_softness);
                let mut lock = state.angular_impulse[i];
                AnglePart::new(pair, row_axis).solve_clamped(
                    pair,
                    a,
                    b,
                    target,
                    &mut lock,
                    f32::NEG_INFINITY,
                    f32::INFINITY,
                );
                state.angular_impulse[i] = lock;
            }
        }
        // Linear locks.
        for i in 0..3 {
            if self.joint.axes[i].motion != AxisMotion::Locked {
                continue;
            }
            let c = g.axes[i].dot(g.d);
            let target = RowTarget::equality(c, stage.bias, stage.joint_softness);
            let mut lock = state.linear_impulse[i];
            g.row(pair, i).solve_clamped(
                pair,
                a,
                b,
                target,
                &mut lock,
                f32::NEG_INFINITY,
                f32::INFINITY,
            );
            state.linear_impulse[i] = lock;
        }
    }

    /// The drive and limit rows of axis `i` at coordinate `x` (m or rad) on `row`.
    fn solve_axis<R: Row>(
        &mut self,
        row: &R,
        pair: &BodyPair,
        i: usize,
        x: f32,
        lock: &mut f32,
        a: &mut SolverBody,
        b: &mut SolverBody,
        stage: &Stage,
    ) {
        let settings = self.joint.axes[i];
        match settings.drive {
            Some(AxisDrive::Velocity {
                target_speed,
                max_force,
            }) => {
                let max = max_force * stage.h;
                let target = RowTarget::speed(target_speed);
                row.solve_clamped(pair, a, b, target, &mut self.drive_impulse[i], -max, max);
            }
            Some(AxisDrive::Position {
                target,
                spring,
                max_force,
            }) if stage.bias == Bias::On => {
                let softness = if spring.depends_on_mass() {
                    spring.softness(row.effective_mass(), stage.h)
                } else {
                    self.drive_softness[i]
                };
                let max = max_force * stage.h;
                let target = RowTarget::spring(x - target, softness);
                row.solve_clamped(pair, a, b, target, &mut self.drive_impulse[i], -max, max);
            }
            _ => {}
        }
        let AxisMotion::Limited(limits) = settings.motion else {
            return;
        };
        let (target, lower, upper) = if limits.upper() - limits.lower() <= 0.0 {
            let target = RowTarget::equality(x - limits.lower(), stage.bias, stage.joint_softness);
            (target, f32::NEG_INFINITY, f32::INFINITY)
        } else if x < 0.5 * (limits.lower() + limits.upper()) {
            let target = RowTarget::lower_limit(
                x - limits.lower(),
                stage.bias,
                stage.joint_softness,
                stage.inv_h,
            );
            (target, 0.0, f32::INFINITY)
        } else {
            let target = RowTarget::upper_limit(
                x - limits.upper(),
                stage.bias,
                stage.joint_softness,
                stage.inv_h,
            );
            (target, f32::NEG_INFINITY, 0.0)
        };
        row.solve_clamped(pair, a, b, target, lock, lower, upper);
    }
}
