//! Drawing a joint: its anchors and the line between them (whose length is the joint's stretch or error),
//! its axes and its limits, from a [`JointView`] — the joint's world-space geometry, built from a live
//! [`rebound::Joint`] or from a recording's description.

use crate::{DebugDraw, DebugSettings, Layer};
use rebound::{Joint, JointKind, Pose, Quat, Vec3};

/// What a joint's drawing needs beyond its anchors: which axes it has and its limits.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum JointGeometry {
    /// Ball and fixed joints: anchors only.
    Point,
    /// Springs, ropes and rods: the anchors and the line between them.
    Distance,
    /// A hinge: the axis (A's joint-frame X) and the angle limits about it (rad), measured from A's frame Y
    /// towards its Z.
    Hinge {
        /// `(lower, upper)` angle (rad).
        limits: Option<(f32, f32)>,
    },
    /// A slider: the slide axis (A's joint-frame X) and the range along it from anchor A (m).
    Slider {
        /// `(lower, upper)` slide (m).
        limits: Option<(f32, f32)>,
    },
    /// A 6-DOF joint: the three axes of A's joint frame.
    Frame,
    /// A wheel: the axle (A's joint-frame X), the suspension axis (A's frame Y) and the travel along it (m).
    Wheel {
        /// `(lower, upper)` suspension travel (m).
        limits: Option<(f32, f32)>,
    },
}

/// A joint's geometry in world space.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JointView {
    /// Anchor on body A (or the world point of a world joint), world space (m).
    pub anchor_a: Vec3,
    /// Anchor on body B, world space (m).
    pub anchor_b: Vec3,
    /// The joint frame on A, world orientation (its X is the hinge axis, slide axis or axle).
    pub frame_a: Quat,
    /// The joint frame on B, world orientation.
    pub frame_b: Quat,
    /// Axes and limits.
    pub geometry: JointGeometry,
    /// Whether the joint has broken (drawn in [`crate::DebugColors::broken_joint`], without axes or limits).
    pub broken: bool,
}

impl JointView {
    /// The view of `joint` for body A at `pose_a` (`None`: a world joint) and body B at `pose_b`.
    #[must_use]
    pub fn new(joint: &Joint, pose_a: Option<Pose>, pose_b: Pose, broken: bool) -> Self {
        let pose_a = pose_a.unwrap_or(Pose::IDENTITY);
        let limits = joint.limits().map(|l| (l.lower(), l.upper()));
        let geometry = match joint.kind() {
            JointKind::Ball(_) | JointKind::Fixed(_) => JointGeometry::Point,
            JointKind::Spring(_) | JointKind::Rope(_) | JointKind::Rod(_) => {
                JointGeometry::Distance
            }
            JointKind::Hinge(_) => JointGeometry::Hinge { limits },
            JointKind::Prismatic(_) => JointGeometry::Slider { limits },
            JointKind::Wheel(_) => JointGeometry::Wheel { limits },
            JointKind::SixDof(_) => JointGeometry::Frame,
        };
        Self {
            anchor_a: pose_a.transform_point(joint.local_anchor_a()),
            anchor_b: pose_b.transform_point(joint.local_anchor_b()),
            frame_a: pose_a.rotation * joint.local_basis_a(),
            frame_b: pose_b.rotation * joint.local_basis_b(),
            geometry,
            broken,
        }
    }
}

impl DebugDraw {
    /// Draws a joint: with [`DebugSettings::joints`], a cross at each anchor and the line between them;
    /// with [`DebugSettings::joint_axes`], its axes (length [`DebugSettings::joint_axis_length`], centred
    /// on anchor A); with [`DebugSettings::joint_limits`], a hinge's limit arc (radius the axis length, with
    /// a radius to each bound) or a slider's or suspension's range as a segment from `anchor A + lower·axis`
    /// to `anchor A + upper·axis` with a tick at each end.
    pub fn joint(&mut self, view: &JointView, settings: &DebugSettings) {
        let colors = &settings.colors;
        let link = if view.broken {
            colors.broken_joint
        } else {
            colors.joint
        };
        if settings.joints {
            self.cross(view.anchor_a, settings.marker_size, link, Layer::Joint);
            self.cross(view.anchor_b, settings.marker_size, link, Layer::Joint);
            self.line(view.anchor_a, view.anchor_b, link, Layer::Joint);
        }
        if view.broken {
            return;
        }
        let length = settings.joint_axis_length;
        let (x, y, z) = (
            view.frame_a * Vec3::X,
            view.frame_a * Vec3::Y,
            view.frame_a * Vec3::Z,
        );
        // The axes to draw, and a range: its axis, the direction of its end ticks, its bounds.
        type Range = Option<(Vec3, Vec3, (f32, f32))>;
        let (axes, range): (&[Vec3], Range) = match view.geometry {
            JointGeometry::Point | JointGeometry::Distance => (&[], None),
            JointGeometry::Hinge { .. } => (&[x], None),
            JointGeometry::Frame => (&[x, y, z], None),
            JointGeometry::Slider { limits } => (&[x], limits.map(|l| (x, y, l))),
            JointGeometry::Wheel { limits } => (&[x, y], limits.map(|l| (y, x, l))),
        };
        if settings.joint_axes {
            for &axis in axes {
                let half = axis * (0.5 * length);
                self.line(
                    view.anchor_a - half,
                    view.anchor_a + half,
                    colors.joint_axis,
                    Layer::Joint,
                );
            }
        }
        if !settings.joint_limits {
            return;
        }
        let limit = colors.joint_limit;
        if let JointGeometry::Hinge {
            limits: Some((lower, upper)),
        } = view.geometry
        {
            let segments = ((settings.segments() as f32 * (upper - lower) / std::f32::consts::TAU)
                .ceil() as u32)
                .clamp(1, crate::MAX_CIRCLE_SEGMENTS);
            let at = |angle: f32| {
                let (sin, cos) = angle.sin_cos();
                view.anchor_a + (y * cos + z * sin) * length
            };
            self.line(view.anchor_a, at(lower), limit, Layer::Joint);
            self.line(view.anchor_a, at(upper), limit, Layer::Joint);
            let step = (upper - lower) / segments as f32;
            for k in 0..segments {
                let end = if k + 1 == segments {
                    upper
                } else {
                    lower + step * (k + 1) as f32
                };
                self.line(at(lower + step * k as f32), at(end), limit, Layer::Joint);
            }
        }
        if let Some((axis, tick, (lower, upper))) = range {
            let (from, to) = (view.anchor_a + axis * lower, view.anchor_a + axis * upper);
            self.line(from, to, limit, Layer::Joint);
            let across = tick * settings.marker_size;
            for end in [from, to] {
                self.line(end - across, end + across, limit, Layer::Joint);
            }
        }
    }
}
