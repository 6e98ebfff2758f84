//! A joint's validated, body-independent description ([`Joint`]: kind, local anchors and frames, break
//! limits), its persistent solver state ([`crate::JointState`]) and the pair of solver indices it connects
//! ([`JointBodies`]). Not part of a step stage: descriptions are checked where they enter, the step trusts them.

use crate::ball::BallJoint;
use crate::error::ConstraintError;
use crate::error::check_positive_or_infinite as check_break;
use crate::fixed::FixedJoint;
use crate::hinge::HingeJoint;
use crate::limits::Limits;
use crate::motor::Motor;
use crate::prismatic::PrismaticJoint;
use crate::rod::Rod;
use crate::rope::Rope;
use crate::six_dof::SixDofJoint;
use crate::soft_spring::JointSpring;
use crate::soft_spring::SoftSpring;
use crate::spring::Spring;
use crate::spring::SpringModel;
use crate::wheel::WheelJoint;
use rebound_math::validity::{check_direction, check_finite_vec3, check_rotation};
use rebound_math::{Mat3, Pose, Quat, Vec3};

/// The kind of a joint and its own parameters. One type per kind, each in its own module.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub enum JointKind {
    /// A spring with a rest length ([`Spring`]).
    Spring(Spring),
    /// A maximum distance ([`Rope`]).
    Rope(Rope),
    /// A fixed distance ([`Rod`]).
    Rod(Rod),
    /// A spherical joint ([`BallJoint`]).
    Ball(BallJoint),
    /// A revolute joint ([`HingeJoint`]).
    Hinge(HingeJoint),
    /// A weld ([`FixedJoint`]).
    Fixed(FixedJoint),
    /// A slider ([`PrismaticJoint`]).
    Prismatic(PrismaticJoint),
    /// A suspended, driven wheel ([`WheelJoint`]).
    Wheel(WheelJoint),
    /// A generic joint, each axis free, locked, limited or driven ([`SixDofJoint`]).
    SixDof(SixDofJoint),
}

impl JointKind {
    /// The kind's name in lower case (`"rope"`, `"hinge"`, …), as error messages use it.
    #[must_use]
    pub const fn name(&self) -> &'static str {
        match self {
            Self::Spring(_) => "spring",
            Self::Rope(_) => "rope",
            Self::Rod(_) => "rod",
            Self::Ball(_) => "ball",
            Self::Hinge(_) => "hinge",
            Self::Fixed(_) => "fixed",
            Self::Prismatic(_) => "prismatic",
            Self::Wheel(_) => "wheel",
            Self::SixDof(_) => "six_dof",
        }
    }

    /// Returns `self` if the kind's parameters pass the checks of its constructors and setters (each kind's
    /// `validated`): for values that bypassed them (deserialised, or a kind given to [`Joint::new`] whose
    /// parts were built by hand).
    ///
    /// # Errors
    /// The first invalid field.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        match self {
            Self::Spring(s) => {
                s.validated()?;
            }
            Self::Rope(r) => {
                r.validated()?;
            }
            Self::Rod(r) => {
                r.validated()?;
            }
            Self::Ball(b) => {
                b.validated()?;
            }
            Self::SixDof(j) => {
                j.validated()?;
            }
            Self::Fixed(_) => {}
            Self::Hinge(h) => {
                h.validated()?;
            }
            Self::Prismatic(p) => {
                p.validated()?;
            }
            Self::Wheel(w) => {
                w.validated()?;
            }
        }
        Ok(self)
    }

    fn unsupported(&self, feature: &'static str) -> ConstraintError {
        ConstraintError::Unsupported {
            kind: self.name(),
            feature,
        }
    }
}

macro_rules! kind_from {
    ($($ty:ident => $variant:ident),* $(,)?) => {
        $(impl From<$ty> for JointKind {
            fn from(value: $ty) -> Self {
                Self::$variant(value)
            }
        }
        impl From<$ty> for Joint {
            /// A joint of this kind with the defaults of [`Joint::new`].
            fn from(value: $ty) -> Self {
                Self::new(value)
            }
        })*
    };
}

kind_from!(Spring => Spring, Rope => Rope, Rod => Rod, BallJoint => Ball, HingeJoint => Hinge,
    FixedJoint => Fixed, PrismaticJoint => Prismatic, WheelJoint => Wheel, SixDofJoint => SixDof);

rebound_math::checked_serde! { "Joint", Joint::validated;
/// A joint: its kind, where it attaches to each body, how its frame is oriented on each body, and when it
/// breaks. Body-independent: the world pairs it with two bodies ([`JointBodies`]).
///
/// * **Anchors** `local_anchor_a`, `local_anchor_b` (m) are points in each body's frame, relative to the body
///   origin (not the centre of mass). Default: the body origins.
/// * **Frames** `local_basis_a`, `local_basis_b` are unit quaternions orienting the joint frame in each body's
///   frame. Their X axis is the hinge axis, the slide axis or the wheel's axle; a wheel's suspension is A's Y
///   axis; fixed and prismatic joints keep the two frames aligned. Default: identity (X = the body's x axis).
///   Distance joints (spring, rope, rod) and the ball joint ignore them.
/// * **Break limits** (N and N·m; +∞ = unbreakable, the default): a joint whose reaction force or torque at the
///   end of a step exceeds them is disabled ([`crate::JointState::broken`]) and reported by
///   [`crate::JointSolver::store_impulses`].
///
/// A **world anchor** (drag and drop, a pendulum pivot, a camera boom) is a joint whose body A is a fixed body
/// at the origin with identity rotation: `local_anchor_a` is then the world point and `local_basis_a` the world
/// orientation of the frame.
///
/// ```
/// use rebound_constraints::{HingeJoint, Joint, Rope};
/// use rebound_math::Vec3;
/// // A 2 m rope from the world point (0, 5, 0) to the centre of body B.
/// let rope = Joint::new(Rope::new(2.0)?).with_local_anchors(Vec3::new(0.0, 5.0, 0.0), Vec3::ZERO)?;
/// // A hinge about z through B's origin, breaking above 500 N.
/// let hinge = Joint::new(HingeJoint::new())
///     .with_local_axes(Vec3::Z, Vec3::Z)?
///     .with_break_force(500.0)?;
/// assert_eq!(hinge.break_force(), 500.0);
/// assert!(Joint::new(HingeJoint::new()).with_local_axes(Vec3::ZERO, Vec3::Z).is_err());
/// # Ok::<(), rebound_constraints::ConstraintError>(())
/// ```
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize))]
pub struct Joint {
    kind: JointKind,
    // Missing anchors, frames and break limits take `Joint::new`'s values, so a scene file names only the kind
    // and what differs.
    #[cfg_attr(feature = "serde", serde(default))]
    local_anchor_a: Vec3,
    #[cfg_attr(feature = "serde", serde(default))]
    local_anchor_b: Vec3,
    #[cfg_attr(feature = "serde", serde(default))]
    local_basis_a: Quat,
    #[cfg_attr(feature = "serde", serde(default))]
    local_basis_b: Quat,
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::bounds::unbounded",
            default = "crate::bounds::unbounded::infinity"
        )
    )]
    break_force: f32,
    #[cfg_attr(
        feature = "serde",
        serde(
            with = "crate::bounds::unbounded",
            default = "crate::bounds::unbounded::infinity"
        )
    )]
    break_torque: f32,
}
}

impl Joint {
    /// A joint of `kind` anchored at both body origins, with identity frames, unbreakable.
    #[must_use]
    pub fn new(kind: impl Into<JointKind>) -> Self {
        Self {
            kind: kind.into(),
            local_anchor_a: Vec3::ZERO,
            local_anchor_b: Vec3::ZERO,
            local_basis_a: Quat::IDENTITY,
            local_basis_b: Quat::IDENTITY,
            break_force: f32::INFINITY,
            break_torque: f32::INFINITY,
        }
    }

    /// A joint of `kind` placed in world space for bodies currently at `pose_a` and `pose_b`: anchors at the
    /// world points `world_anchor_a`, `world_anchor_b` (m) and the joint frame at the world orientation
    /// `world_basis` on both bodies (so a fixed joint welds the bodies where they are and a hinge starts at
    /// angle 0).
    ///
    /// # Errors
    /// Non-finite anchors; a non-unit `world_basis`; invalid poses.
    pub fn from_world(
        kind: impl Into<JointKind>,
        pose_a: Pose,
        pose_b: Pose,
        world_anchor_a: Vec3,
        world_anchor_b: Vec3,
        world_basis: Quat,
    ) -> Result<Self, ConstraintError> {
        let pose_a = Pose::try_new(pose_a.position, pose_a.rotation)?;
        let pose_b = Pose::try_new(pose_b.position, pose_b.rotation)?;
        check_finite_vec3("world_anchor_a", world_anchor_a)?;
        check_finite_vec3("world_anchor_b", world_anchor_b)?;
        let world_basis = check_rotation("world_basis", world_basis)?.normalize();
        let mut joint = Self::new(kind);
        joint.local_anchor_a = pose_a.inverse_transform_point(world_anchor_a);
        joint.local_anchor_b = pose_b.inverse_transform_point(world_anchor_b);
        joint.local_basis_a = (pose_a.rotation.conjugate() * world_basis).normalize();
        joint.local_basis_b = (pose_b.rotation.conjugate() * world_basis).normalize();
        Ok(joint)
    }

    /// Sets the anchors (m, body frames); see [`Joint::set_local_anchors`].
    ///
    /// # Errors
    /// Non-finite anchors.
    pub fn with_local_anchors(
        mut self,
        local_anchor_a: Vec3,
        local_anchor_b: Vec3,
    ) -> Result<Self, ConstraintError> {
        self.set_local_anchors(local_anchor_a, local_anchor_b)?;
        Ok(self)
    }

    /// Sets the joint axes (body frames); see [`Joint::set_local_axes`].
    ///
    /// # Errors
    /// Zero-length or non-finite axes.
    pub fn with_local_axes(mut self, axis_a: Vec3, axis_b: Vec3) -> Result<Self, ConstraintError> {
        self.set_local_axes(axis_a, axis_b)?;
        Ok(self)
    }

    /// Sets the joint frames (body frames); see [`Joint::set_local_bases`].
    ///
    /// # Errors
    /// Non-unit or non-finite quaternions.
    pub fn with_local_bases(
        mut self,
        basis_a: Quat,
        basis_b: Quat,
    ) -> Result<Self, ConstraintError> {
        self.set_local_bases(basis_a, basis_b)?;
        Ok(self)
    }

    /// Sets the break force (N, > 0, +∞ = unbreakable).
    ///
    /// # Errors
    /// NaN or not positive.
    pub fn with_break_force(mut self, break_force: f32) -> Result<Self, ConstraintError> {
        self.set_break_force(break_force)?;
        Ok(self)
    }

    /// Sets the break torque (N·m, > 0, +∞ = unbreakable).
    ///
    /// # Errors
    /// NaN or not positive.
    pub fn with_break_torque(mut self, break_torque: f32) -> Result<Self, ConstraintError> {
        self.set_break_torque(break_torque)?;
        Ok(self)
    }

    /// Returns `self` if every parameter is valid, checking it again field by field as the constructors do.
    /// Joints built through the constructors and setters always are; this is for values that bypassed them
    /// (deserialized snapshots with the `serde` feature, or files).
    ///
    /// # Errors
    /// The first invalid field, as the constructor or setter of that field would report it.
    pub fn validated(self) -> Result<Self, ConstraintError> {
        self.kind.validated()?;
        let mut checked = Self::new(self.kind);
        checked.set_local_anchors(self.local_anchor_a, self.local_anchor_b)?;
        checked.set_local_bases(self.local_basis_a, self.local_basis_b)?;
        checked.set_break_force(self.break_force)?;
        checked.set_break_torque(self.break_torque)?;
        Ok(self)
    }

    /// The kind and its parameters.
    #[must_use]
    pub fn kind(&self) -> &JointKind {
        &self.kind
    }

    /// The kind, to change its parameters through its own validated setters.
    #[must_use]
    pub fn kind_mut(&mut self) -> &mut JointKind {
        &mut self.kind
    }

    /// Anchor on body A (m, A's frame, relative to A's origin).
    #[must_use]
    pub fn local_anchor_a(&self) -> Vec3 {
        self.local_anchor_a
    }

    /// Anchor on body B (m, B's frame, relative to B's origin).
    #[must_use]
    pub fn local_anchor_b(&self) -> Vec3 {
        self.local_anchor_b
    }

    /// Orientation of the joint frame in A's frame (X = the joint axis).
    #[must_use]
    pub fn local_basis_a(&self) -> Quat {
        self.local_basis_a
    }

    /// Orientation of the joint frame in B's frame.
    #[must_use]
    pub fn local_basis_b(&self) -> Quat {
        self.local_basis_b
    }

    /// Break force (N); +∞ when unbreakable.
    #[must_use]
    pub fn break_force(&self) -> f32 {
        self.break_force
    }

    /// Break torque (N·m); +∞ when unbreakable.
    #[must_use]
    pub fn break_torque(&self) -> f32 {
        self.break_torque
    }

    /// Changes the anchors (m, body frames, relative to the body origins); nothing changes on error.
    ///
    /// # Errors
    /// Non-finite anchors (fields `local_anchor_a`, `local_anchor_b`).
    pub fn set_local_anchors(
        &mut self,
        local_anchor_a: Vec3,
        local_anchor_b: Vec3,
    ) -> Result<(), ConstraintError> {
        check_finite_vec3("local_anchor_a", local_anchor_a)?;
        check_finite_vec3("local_anchor_b", local_anchor_b)?;
        self.local_anchor_a = local_anchor_a;
        self.local_anchor_b = local_anchor_b;
        Ok(())
    }

    /// Sets the joint frames from their X axes (any length, normalised; body frames) with
    /// [`basis_from_axis`]: the frames are the shortest rotations taking x̂ onto each axis. Two bodies with the
    /// same orientation and the same axis get the same frame, so a hinge starts at angle 0. Use
    /// [`Joint::set_local_bases`] (or [`Joint::from_world`]) to choose the angle reference.
    ///
    /// # Errors
    /// Zero-length or non-finite axes (fields `axis_a`, `axis_b`).
    pub fn set_local_axes(&mut self, axis_a: Vec3, axis_b: Vec3) -> Result<(), ConstraintError> {
        let basis_a = basis_from_axis_named("axis_a", axis_a)?;
        let basis_b = basis_from_axis_named("axis_b", axis_b)?;
        self.local_basis_a = basis_a;
        self.local_basis_b = basis_b;
        Ok(())
    }

    /// Sets the joint frames (unit quaternions, body frames); nothing changes on error.
    ///
    /// # Errors
    /// Non-finite or non-unit quaternions (fields `local_basis_a`, `local_basis_b`).
    pub fn set_local_bases(&mut self, basis_a: Quat, basis_b: Quat) -> Result<(), ConstraintError> {
        check_rotation("local_basis_a", basis_a)?;
        check_rotation("local_basis_b", basis_b)?;
        self.local_basis_a = basis_a.normalize();
        self.local_basis_b = basis_b.normalize();
        Ok(())
    }

    /// Changes the break force (N, > 0, +∞ = unbreakable); nothing changes on error.
    ///
    /// # Errors
    /// NaN or not positive.
    pub fn set_break_force(&mut self, break_force: f32) -> Result<(), ConstraintError> {
        self.break_force = check_break("break_force", break_force)?;
        Ok(())
    }

    /// Changes the break torque (N·m, > 0, +∞ = unbreakable); nothing changes on error.
    ///
    /// # Errors
    /// NaN or not positive.
    pub fn set_break_torque(&mut self, break_torque: f32) -> Result<(), ConstraintError> {
        self.break_torque = check_break("break_torque", break_torque)?;
        Ok(())
    }

    /// Sets or removes the motor of a hinge, prismatic or wheel joint.
    ///
    /// # Errors
    /// [`ConstraintError::Unsupported`] for other kinds.
    pub fn set_motor(&mut self, motor: Option<Motor>) -> Result<(), ConstraintError> {
        match &mut self.kind {
            JointKind::Hinge(j) => j.set_motor(motor),
            JointKind::Prismatic(j) => j.set_motor(motor),
            JointKind::Wheel(j) => j.set_motor(motor),
            other => return Err(other.unsupported("motor")),
        }
        Ok(())
    }

    /// Changes the target speed of the joint's motor (rad/s or m/s); nothing changes on error.
    ///
    /// # Errors
    /// A non-finite speed; [`ConstraintError::Unsupported`] when the joint has no motor.
    pub fn set_motor_speed(&mut self, target_speed: f32) -> Result<(), ConstraintError> {
        let motor = match &self.kind {
            JointKind::Hinge(j) => j.motor(),
            JointKind::Prismatic(j) => j.motor(),
            JointKind::Wheel(j) => j.motor(),
            _ => None,
        };
        let Some(mut motor) = motor else {
            return Err(self.kind.unsupported("motor"));
        };
        motor.set_target_speed(target_speed)?;
        self.set_motor(Some(motor))
    }

    /// The limits of a hinge (rad), prismatic joint (m) or wheel suspension (m), if it has any; `None` for
    /// other kinds. See [`Joint::set_limits`].
    #[must_use]
    pub fn limits(&self) -> Option<Limits> {
        match &self.kind {
            JointKind::Hinge(j) => j.limits(),
            JointKind::Prismatic(j) => j.limits(),
            JointKind::Wheel(j) => j.suspension_limits(),
            _ => None,
        }
    }

    /// The length of a distance joint (m): a spring's rest length, a rope's maximum length or a rod's length;
    /// `None` for other kinds. See [`Joint::set_length`].
    #[must_use]
    pub fn length(&self) -> Option<f32> {
        match &self.kind {
            JointKind::Spring(s) => Some(s.rest_length()),
            JointKind::Rope(r) => Some(r.max_length()),
            JointKind::Rod(r) => Some(r.length()),
            _ => None,
        }
    }

    /// Sets or removes the limits of a hinge (rad, within `[−π, π]`), prismatic joint (m) or wheel suspension
    /// (m); nothing changes on error.
    ///
    /// # Errors
    /// Hinge bounds outside `[−π, π]`; [`ConstraintError::Unsupported`] for other kinds.
    pub fn set_limits(&mut self, limits: Option<Limits>) -> Result<(), ConstraintError> {
        match &mut self.kind {
            JointKind::Hinge(j) => j.set_limits(limits)?,
            JointKind::Prismatic(j) => j.set_limits(limits),
            JointKind::Wheel(j) => j.set_suspension_limits(limits),
            other => return Err(other.unsupported("limits")),
        }
        Ok(())
    }

    /// Changes the stiffness of the joint's soft spring: a [`Spring`] becomes [`SpringModel::Soft`]; a hinge's
    /// or prismatic joint's spring keeps its target (a joint without one gets one relaxed at 0); a wheel's
    /// suspension. Nothing changes on error.
    ///
    /// # Errors
    /// An invalid `spring`; [`ConstraintError::Unsupported`] for rope, rod, ball and fixed joints.
    pub fn set_spring(&mut self, spring: SoftSpring) -> Result<(), ConstraintError> {
        let spring = spring.validated()?;
        match &mut self.kind {
            JointKind::Spring(s) => s.set_model(SpringModel::Soft(spring))?,
            JointKind::Hinge(j) => {
                let target = j.spring().map_or(0.0, |s| s.target());
                j.set_spring(Some(JointSpring::new(target, spring)?));
            }
            JointKind::Prismatic(j) => {
                let target = j.spring().map_or(0.0, |s| s.target());
                j.set_spring(Some(JointSpring::new(target, spring)?));
            }
            JointKind::Wheel(j) => j.set_suspension(spring)?,
            other => return Err(other.unsupported("spring")),
        }
        Ok(())
    }

    /// Changes the length of a distance joint: a spring's rest length, a rope's maximum length or a rod's
    /// length (m) — a winch. Nothing changes on error.
    ///
    /// # Errors
    /// As the kinds' own setters; [`ConstraintError::Unsupported`] for other kinds.
    pub fn set_length(&mut self, length: f32) -> Result<(), ConstraintError> {
        match &mut self.kind {
            JointKind::Spring(s) => s.set_rest_length(length),
            JointKind::Rope(r) => r.set_max_length(length),
            JointKind::Rod(r) => r.set_length(length),
            other => Err(other.unsupported("length")),
        }
    }
}

fn basis_from_axis_named(field: &'static str, axis: Vec3) -> Result<Quat, ConstraintError> {
    let (unit, _) = check_direction(field, axis)?;
    Ok(Quat::from_rotation_arc(Vec3::X, unit))
}

/// The frame whose X axis is `axis` (any non-zero length): the shortest rotation taking x̂ onto it.
///
/// # Errors
/// A zero-length or non-finite `axis`.
pub fn basis_from_axis(axis: Vec3) -> Result<Quat, ConstraintError> {
    basis_from_axis_named("axis", axis)
}

/// The frame whose X axis is `x_axis` and whose Y axis is `y_axis` made perpendicular to it (Gram–Schmidt):
/// for a wheel, X = the axle and Y = the suspension direction.
///
/// # Errors
/// Zero-length or non-finite axes; `y_axis` parallel to `x_axis` ([`ConstraintError::ParallelAxes`]).
pub fn basis_from_axes(x_axis: Vec3, y_axis: Vec3) -> Result<Quat, ConstraintError> {
    let (x, _) = check_direction("x_axis", x_axis)?;
    let (y_raw, _) = check_direction("y_axis", y_axis)?;
    let y = (y_raw - x * x.dot(y_raw))
        .try_normalize()
        .filter(|y| y.dot(y_raw) > 1e-4)
        .ok_or(ConstraintError::ParallelAxes { field: "y_axis" })?;
    let z = x.cross(y);
    Ok(Quat::from_mat3(&Mat3::from_cols(x, y, z)).normalize())
}

/// The two bodies of a joint as indices into the solver arrays (`SolverBody`, `BodyParams`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct JointBodies {
    /// Index of body A.
    pub a: usize,
    /// Index of body B.
    pub b: usize,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn limits_and_length_read_back_what_their_setters_set() {
        let mut hinge = Joint::new(HingeJoint::new());
        assert_eq!(hinge.limits(), None);
        let limits = Limits::new(-0.5, 0.25).unwrap();
        hinge.set_limits(Some(limits)).unwrap();
        assert_eq!(hinge.limits(), Some(limits));
        assert_eq!(hinge.length(), None);
        let mut rope = Joint::new(Rope::new(2.0).unwrap());
        rope.set_length(3.0).unwrap();
        assert_eq!(rope.length(), Some(3.0));
        assert_eq!(rope.limits(), None);
    }

    #[test]
    fn bases_put_x_on_the_axis_and_y_on_the_secondary_direction() {
        let q = basis_from_axes(Vec3::Z * 2.0, Vec3::new(0.0, 1.0, 1.0)).unwrap();
        assert!((q * Vec3::X).abs_diff_eq(Vec3::Z, 1e-6));
        assert!((q * Vec3::Y).abs_diff_eq(Vec3::Y, 1e-6));
        assert!(
            (q * Vec3::Z).abs_diff_eq(-Vec3::X, 1e-6),
            "right-handed: ẑ × ŷ = −x̂"
        );
        let r = basis_from_axis(Vec3::new(0.0, -3.0, 0.0)).unwrap();
        assert!((r * Vec3::X).abs_diff_eq(-Vec3::Y, 1e-6));
    }

    #[test]
    fn from_world_places_anchors_and_frames_in_the_body_frames() {
        let pose_a = Pose::new(Vec3::new(1.0, 2.0, 3.0), Quat::from_rotation_y(0.5));
        let pose_b = Pose::new(Vec3::new(-1.0, 0.0, 2.0), Quat::from_rotation_x(-1.2));
        let (anchor_a, anchor_b) = (Vec3::new(0.5, 0.5, 0.5), Vec3::new(0.0, -1.0, 0.0));
        let basis = Quat::from_rotation_z(0.3);
        let j =
            Joint::from_world(BallJoint::new(), pose_a, pose_b, anchor_a, anchor_b, basis).unwrap();
        assert!(
            pose_a
                .transform_point(j.local_anchor_a())
                .abs_diff_eq(anchor_a, 1e-5)
        );
        assert!(
            pose_b
                .transform_point(j.local_anchor_b())
                .abs_diff_eq(anchor_b, 1e-5)
        );
        assert!((pose_a.rotation * j.local_basis_a()).abs_diff_eq(basis, 1e-5));
        assert!((pose_b.rotation * j.local_basis_b()).abs_diff_eq(basis, 1e-5));
    }
}
