//! Rows kept from pass to pass: a pass at the pose a link's rows were built at recomputes only their
//! targets ([`Link::reuse`]); a pass at a new pose may carry a hinge's rows there to first order instead of
//! building them again ([`Link::carry`], [`Link::recarry`]). Runs at the start of every solve and relax pass.

use super::link::{LANES, Link, RowsAt};
use super::pose::PoseKey;
use super::row::JointRows;
use crate::part::rotation_error;
use crate::stage::Stage;
use rebound_math::{Quat, Vec3, Vec4};

impl Link {
    /// Starts a velocity pass of `stage` at the bodies' current pose — their joint `frames` (world) and the
    /// vector `relative` between their centres of mass; `now`, its key, is recorded with the carried errors
    /// for [`Link::recarry`] — with the rows built earlier (in this step or, kept, in the last one), if
    /// neither body has turned by more than `max_angle` (rad) since: the Jacobians, turned vectors and the
    /// factorisation stay, and each row's position error is carried to the current pose to first order,
    /// `C = C₀ + J·Δ`, with `Δ` the bodies' relative displacement and small rotations since the build
    /// ([`BuiltAt`]). Returns `false`, changing nothing, when the link holds no carried rows, `max_angle` is
    /// not positive or a body turned further. For rows whose Jacobians depend on the rotations alone and
    /// whose linear parts are opposite on the two bodies (a hinge's, a ball joint's: `J·Δ` then needs only
    /// the relative displacement): the solver carries hinges ([`CARRY_ANGLE`]).
    ///
    /// Carried to first order, the errors stay in the range of the rows' `J`: a bridge hung between two
    /// anchors has redundant rows (a singular `K`, kept solvable by [`REGULARIZATION`]), and errors measured
    /// exactly at the new pose but solved with the old rows have a component `K` cannot reach, which the
    /// regularisation turns into impulses a million times too large.
    pub fn carry(
        &mut self,
        frames: (Quat, Quat),
        relative: Vec3,
        now: &PoseKey,
        stage: &Stage,
        max_angle: f32,
    ) -> bool {
        let (Some(built), true) = (self.built, max_angle > 0.0) else {
            return false;
        };
        // The small rotations (rad, world) since the build: the rotation error from the built frames.
        let (ta, tb) = (
            rotation_error(built.frames.0, frames.0),
            rotation_error(built.frames.1, frames.1),
        );
        let limit = max_angle * max_angle;
        if ta.length_squared() > limit || tb.length_squared() > limit {
            return false;
        }
        let d = relative - built.relative;
        // The first [`LANES`] rows four lanes wide from the Jacobians in `lanes` while they are current (the
        // factorisation is: both are made again with the rows), each lane the operations of the row-by-row
        // line below — the same bits.
        let (lanes, in_lanes) = if self.factored.is_some() {
            let dot = |j: &[Vec4; 3], v: Vec3| (j[0] * v.x + j[1] * v.y) + j[2] * v.z;
            let l = &self.lanes;
            let moved = dot(&l[2], d) + (dot(&l[1], ta) + dot(&l[3], tb));
            (moved.to_array(), LANES)
        } else {
            ([0.0; LANES], 0)
        };
        let rows = &self.rows;
        for (k, ((row, &(c, _)), carried)) in rows
            .rows()
            .iter()
            .zip(&rows.errors)
            .zip(&mut self.carried)
            .enumerate()
        {
            let moved = match lanes.get(k) {
                Some(&moved) if k < in_lanes => moved,
                _ => row.b.linear.dot(d) + (row.a.angular.dot(ta) + row.b.angular.dot(tb)),
            };
            *carried = c + moved;
        }
        self.rows_at = match self.rows_at {
            RowsAt::Built { at, .. } => RowsAt::Built {
                at,
                carried_to: Some(*now),
            },
            RowsAt::Carried { .. } | RowsAt::Unknown => RowsAt::Carried { to: *now },
        };
        self.restart_carried(stage);
        true
    }

    /// Starts a pass of `stage` at the pose `now` the rows were last carried to ([`Link::carry`]), from the
    /// errors carried there: the targets [`Link::carry`] would compute again, bit for bit, without measuring
    /// the turn and the displacement again. Returns `false`, changing nothing, at any other pose.
    pub fn recarry(&mut self, now: &PoseKey, stage: &Stage) -> bool {
        let carried_to = match &self.rows_at {
            RowsAt::Built {
                carried_to: Some(to),
                ..
            }
            | RowsAt::Carried { to } => Some(to),
            _ => None,
        };
        if carried_to != Some(now) {
            return false;
        }
        self.restart_carried(stage);
        true
    }

    /// Starts a pass of `stage` with each row's target made from its carried error.
    pub(super) fn restart_carried(&mut self, stage: &Stage) {
        self.restart();
        let JointRows {
            rows,
            errors,
            count,
            ..
        } = &mut self.rows;
        for ((row, &(_, rule)), &carried) in rows
            .iter_mut()
            .zip(errors.iter())
            .zip(&self.carried)
            .take(*count)
        {
            row.target = rule.target(carried, stage);
        }
    }

    /// Records that the rows just built (after [`Link::reset`]) are those of the pose `pose`.
    pub fn built_at(&mut self, pose: Option<PoseKey>) {
        self.rows_at = pose.map_or(RowsAt::Unknown, |at| RowsAt::Built {
            at,
            carried_to: None,
        });
    }

    /// Starts a pass of `stage` at the pose the rows were built at (the caller has checked
    /// [`Link::is_built_at`]): the Jacobians, turned vectors and position errors stay, the targets are
    /// recomputed from the errors, and the factorisation stays for [`solve_path`] to reuse if the same rows
    /// end up in the system.
    pub fn reuse(&mut self, stage: &Stage) {
        self.restart();
        self.rows.retarget(stage);
    }
}
