//! The collision seam: the plain-data [`ContactManifold`] a collision backend reports, and the
//! [`CollisionBackend`] trait the world calls once per step (stage 2, *collide*). No collision library here:
//! the `rebound` facade implements the trait with parry3d; [`crate::testing`] has a small one for tests.

use crate::{BodyHandle, BodySet, WorldSettings};
use rebound_math::{Pose, Quat, Vec3};

/// The most points a manifold carries.
pub const MAX_MANIFOLD_POINTS: usize = rebound_dynamics::MAX_CONTACT_POINTS;

/// One contact point of a manifold.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ManifoldPoint {
    /// The contact point on body A, in A's body frame (relative to its origin, m).
    pub local_anchor_a: Vec3,
    /// The contact point on body B, in B's body frame (m).
    pub local_anchor_b: Vec3,
    /// Signed distance between the surfaces along the normal (m): negative when overlapping, positive for a
    /// speculative point.
    pub separation: f32,
    /// Identifies the touching features, so the point can be matched next step (warm starting).
    pub feature_id: u32,
    /// Normal impulse of the last step (N·s), filled in by the world.
    pub normal_impulse: f32,
    /// Friction impulse of the last step as a world vector (N·s), filled in by the world.
    pub tangent_impulse: Vec3,
    /// The lever arms the solver uses for this point — from body A's and from body B's centre of mass to the
    /// contact point, world axes (m). Filled in by the world; a backend leaves it `None`. A point that
    /// persists from step to step keeps its lever arms while the fresh ones stay within
    /// [`LEVER_ARM_TOLERANCE`] of them (see [`ManifoldPoint::refresh_lever_arms`]). Default `None`.
    #[cfg_attr(feature = "serde", serde(default))]
    pub solver_lever_arms: Option<[Vec3; 2]>,
}

/// How far (m) a persisting contact point's fresh lever arm may move from the one the solver keeps using
/// before the lever arm is renewed: 1 cm, and at most [`LEVER_ARM_RELATIVE_TOLERANCE`] of the lever arm's
/// length, so that small bodies keep their lever arms as accurately as large ones.
///
/// Why keep lever arms at all: a contact constraint's Jacobian is `(n, r × n)`. Re-derived from the current
/// pose every step, it turns with every small tilt of a loaded box, and in a tall stack of soft contacts that
/// feedback grows: a column of 20 unit boxes with 30 Hz contacts falls over within 10 s; with kept lever arms
/// it stands within 2 cm, and the peer scenes' pyramid stays in its plane (`docs/performance.md`). rapier
/// freezes its contact lever arms between narrow-phase updates for the same reason. The cost is an error of
/// at most this tolerance in where a contact force acts. The lever arm of a ball on flat ground never changes
/// (the contact is always straight below the centre), so rolling is unaffected.
pub const LEVER_ARM_TOLERANCE: f32 = 0.01;

/// The largest fraction of a lever arm's length by which it may move before it is renewed (dimensionless):
/// 5 %. See [`LEVER_ARM_TOLERANCE`].
pub const LEVER_ARM_RELATIVE_TOLERANCE: f32 = 0.05;

/// The square of how far (m²) a kept lever arm may lie from the fresh lever arm `fresh` (see
/// [`LEVER_ARM_TOLERANCE`]): the smaller of the two tolerances, squared, with no square root taken.
fn tolerance_squared(fresh: Vec3) -> f32 {
    (LEVER_ARM_TOLERANCE * LEVER_ARM_TOLERANCE)
        .min(LEVER_ARM_RELATIVE_TOLERANCE * LEVER_ARM_RELATIVE_TOLERANCE * fresh.length_squared())
}

impl ManifoldPoint {
    /// The contact point in world space (m) for bodies A and B at `pose_a` and `pose_b`: the midpoint of the
    /// point's anchor on A and its anchor on B (which lie `separation` apart along the normal), as debug
    /// drawing and recordings show it.
    #[inline]
    #[must_use]
    pub fn world_point(&self, pose_a: Pose, pose_b: Pose) -> Vec3 {
        (pose_a.transform_point(self.local_anchor_a) + pose_b.transform_point(self.local_anchor_b))
            * 0.5
    }

    /// Sets [`ManifoldPoint::solver_lever_arms`] from the fresh lever arms (`fresh[0]` from A's centre of mass,
    /// `fresh[1]` from B's, world axes, m) and last step's points of the same manifold: the kept lever arms of
    /// the old point with this point's feature id if both are within tolerance ([`LEVER_ARM_TOLERANCE`]) of
    /// the fresh ones, else those of the nearest old point whose lever arms are, else the fresh ones. Returns
    /// the old point to warm start from: the one with this point's feature id, else that nearest one, else
    /// `None`.
    ///
    /// The same feature comes first because it is the same point of contact — and because it is found with
    /// no distance computed: a resting box's four points each find their old selves, where a search for the
    /// nearest measured sixteen pairs of lever arms. The two choices differ only when two old points lie
    /// within the tolerance of one fresh point (two points less than 2 cm apart).
    pub fn refresh_lever_arms<'a>(
        &mut self,
        fresh: [Vec3; 2],
        previous: &'a [ManifoldPoint],
    ) -> Option<&'a ManifoldPoint> {
        let tolerance = [tolerance_squared(fresh[0]), tolerance_squared(fresh[1])];
        let distances = |kept: &[Vec3; 2]| {
            let d = [
                kept[0].distance_squared(fresh[0]),
                kept[1].distance_squared(fresh[1]),
            ];
            (d[0] <= tolerance[0] && d[1] <= tolerance[1]).then_some(d[0] + d[1])
        };
        let same = previous.iter().find(|p| p.feature_id == self.feature_id);
        if let Some(old) = same
            && let Some(kept) = old.solver_lever_arms
            && distances(&kept).is_some()
        {
            self.solver_lever_arms = Some(kept);
            return Some(old);
        }
        let mut best: Option<(f32, &ManifoldPoint)> = None;
        for old in previous {
            let Some(distance) = old.solver_lever_arms.as_ref().and_then(distances) else {
                continue;
            };
            if best.is_none_or(|(nearest, _)| distance < nearest) {
                best = Some((distance, old));
            }
        }
        self.solver_lever_arms = Some(
            best.and_then(|(_, old)| old.solver_lever_arms)
                .unwrap_or(fresh),
        );
        same.or(best.map(|(_, old)| old))
    }
}

/// Where a backend computed a manifold from scratch, so that it may *recycle* it while the bodies barely
/// move: B's body pose in A's body frame at that moment and the normal in A's body frame. Part of the
/// manifold (and so of every snapshot): a recycled manifold is a function of the world's state, and a
/// restored world steps as the one that never stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct ContactBasis {
    /// B's body orientation in A's body frame (unit quaternion).
    pub rotation: Quat,
    /// B's body origin in A's body frame (m).
    pub translation: Vec3,
    /// The contact normal in A's body frame (unit vector, from A to B).
    pub local_normal: Vec3,
}

/// Contact between two bodies as the backend reports it.
///
/// Laid out for the stages that read it once a step (the warm-start walk, *prepare*, *store*, the events):
/// what they all read first — bodies, key, point count, normal, materials — then the points in order, the
/// recycling basis last (`repr(C)`). A one-point manifold (a ball on anything) is read from its first 152
/// bytes (three or four cache lines of its seven) where the compiler's order spread them over five; a pile of
/// 16,384 balls holds some 50,000 manifolds twice (this step's and last step's), which no cache holds. Not
/// aligned to whole lines: copying a 64-byte-aligned manifold costs a `memcpy` call.
///
/// Only the first [`ContactManifold::point_count`] points are part of the manifold: a manifold written in
/// place over an older one ([`ManifoldWriter::begin`]) leaves the slots past them as they were, and
/// equality compares the points in use only.
#[derive(Debug, Clone, Copy)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[repr(C)]
pub struct ContactManifold {
    /// Body A.
    pub body_a: BodyHandle,
    /// Body B.
    pub body_b: BodyHandle,
    /// A key the backend keeps stable for this manifold from step to step (e.g. the collider pair), so that
    /// two manifolds between the same bodies are told apart when warm starting.
    pub key: u64,
    /// How many points are in use.
    pub point_count: usize,
    /// Unit normal in world space, from A to B.
    pub normal: Vec3,
    /// Combined friction coefficient (dimensionless, ≥ 0).
    pub friction: f32,
    /// Combined coefficient of restitution (dimensionless, in `[0, 1]`).
    pub restitution: f32,
    /// Rolling resistance lever arm (m, ≥ 0; see `rebound_dynamics::Contact::rolling_friction`).
    pub rolling_friction: f32,
    /// The velocity (m/s, world axes) B's surface slides at relative to A's in the contact plane — a
    /// conveyor belt (see `rebound_dynamics::Contact::surface_velocity`). Default: zero.
    #[cfg_attr(feature = "serde", serde(default))]
    pub surface_velocity: Vec3,
    /// The smallest total normal force (N, ≥ 0) of a step at which this manifold is reported in an
    /// [`Event::ContactForce`](crate::Event::ContactForce). Default `None`: never.
    #[cfg_attr(feature = "serde", serde(default))]
    pub force_event_threshold: Option<f32>,
    /// The points; only the first `point_count` are meaningful.
    pub points: [ManifoldPoint; MAX_MANIFOLD_POINTS],
    /// Where the backend computed these points from scratch, if it may recycle them (see [`ContactBasis`]).
    /// Default `None`: every step computes them again.
    #[cfg_attr(feature = "serde", serde(default))]
    pub basis: Option<ContactBasis>,
}

// The header and the first point within 192 bytes.
const _: () =
    assert!(core::mem::offset_of!(ContactManifold, points) + size_of::<ManifoldPoint>() <= 3 * 64);

impl ContactManifold {
    /// A manifold with no points yet.
    #[must_use]
    pub fn new(
        body_a: BodyHandle,
        body_b: BodyHandle,
        key: u64,
        normal: Vec3,
        friction: f32,
        restitution: f32,
    ) -> Self {
        Self {
            body_a,
            body_b,
            key,
            normal,
            friction,
            restitution,
            rolling_friction: 0.0,
            surface_velocity: Vec3::ZERO,
            force_event_threshold: None,
            points: [ManifoldPoint::default(); MAX_MANIFOLD_POINTS],
            point_count: 0,
            basis: None,
        }
    }

    /// Makes this manifold a new one with no points, as [`ContactManifold::new`] does, keeping only the
    /// storage of its old points (never read: only the first `point_count` are), so that a manifold written
    /// over an older one writes its header and its points, not four points' worth of slots.
    #[inline]
    pub fn renew(
        &mut self,
        body_a: BodyHandle,
        body_b: BodyHandle,
        key: u64,
        normal: Vec3,
        friction: f32,
        restitution: f32,
    ) {
        self.body_a = body_a;
        self.body_b = body_b;
        self.key = key;
        self.point_count = 0;
        self.normal = normal;
        self.friction = friction;
        self.restitution = restitution;
        self.rolling_friction = 0.0;
        self.surface_velocity = Vec3::ZERO;
        self.force_event_threshold = None;
        self.basis = None;
    }

    /// Becomes equal to `other`: its fields and its points in use written over this manifold's, the point
    /// slots past them left as they were (as after [`ContactManifold::renew`]).
    #[inline]
    pub fn renew_from(&mut self, other: &Self) {
        // Every field named, so that a field added to the manifold is not forgotten here.
        let Self {
            body_a,
            body_b,
            key,
            point_count,
            normal,
            friction,
            restitution,
            rolling_friction,
            surface_velocity,
            force_event_threshold,
            points,
            basis,
        } = other;
        let used = (*point_count).min(MAX_MANIFOLD_POINTS);
        self.body_a = *body_a;
        self.body_b = *body_b;
        self.key = *key;
        self.point_count = *point_count;
        self.normal = *normal;
        self.friction = *friction;
        self.restitution = *restitution;
        self.rolling_friction = *rolling_friction;
        self.surface_velocity = *surface_velocity;
        self.force_event_threshold = *force_event_threshold;
        self.points[..used].copy_from_slice(&points[..used]);
        self.basis = *basis;
    }

    /// Sets the point slots past [`ContactManifold::point_count`] to their default (for a snapshot, whose
    /// serialised form then does not depend on what the slots held before).
    pub fn clear_unused_points(&mut self) {
        let used = self.point_count.min(MAX_MANIFOLD_POINTS);
        self.points[used..].fill(ManifoldPoint::default());
    }

    /// Adds a point; returns `false` when the manifold is full.
    #[inline]
    pub fn push_point(&mut self, point: ManifoldPoint) -> bool {
        if self.point_count >= MAX_MANIFOLD_POINTS {
            return false;
        }
        self.points[self.point_count] = point;
        self.point_count += 1;
        true
    }

    /// The points in use.
    #[inline]
    #[must_use]
    pub fn points(&self) -> &[ManifoldPoint] {
        &self.points[..self.point_count.min(MAX_MANIFOLD_POINTS)]
    }

    /// Whether any point overlaps or touches (separation ≤ 0).
    #[must_use]
    pub fn is_touching(&self) -> bool {
        self.points().iter().any(|p| p.separation <= 0.0)
    }

    /// The sort key that orders manifolds deterministically: body pair, then the backend's key.
    #[must_use]
    pub fn order_key(&self) -> (BodyHandle, BodyHandle, u64) {
        (self.body_a, self.body_b, self.key)
    }
}

/// Equal when every field is and the points in use are: the slots past `point_count` are no part of the
/// manifold.
impl PartialEq for ContactManifold {
    fn eq(&self, other: &Self) -> bool {
        self.body_a == other.body_a
            && self.body_b == other.body_b
            && self.key == other.key
            && self.point_count == other.point_count
            && self.normal == other.normal
            && self.friction == other.friction
            && self.restitution == other.restitution
            && self.rolling_friction == other.rolling_friction
            && self.surface_velocity == other.surface_velocity
            && self.force_event_threshold == other.force_event_threshold
            && self.points() == other.points()
            && self.basis == other.basis
    }
}

/// Where a backend writes a step's manifolds: over the storage of a list of older ones, in order, so that a
/// manifold writes the cache lines of its header and of the points it has and leaves its unused point slots
/// untouched (a ball's manifold has one point of four; a pile of 16,384 balls writes some 50,000 manifolds a
/// step, far more than the caches hold). The list is cut to the manifolds written when the writer is
/// dropped.
#[derive(Debug)]
pub struct ManifoldWriter<'a> {
    list: &'a mut Vec<ContactManifold>,
    len: usize,
}

impl<'a> ManifoldWriter<'a> {
    /// A writer over `list`, whose manifolds it writes over from the first on (their contents are not read).
    #[must_use]
    pub fn new(list: &'a mut Vec<ContactManifold>) -> Self {
        Self { list, len: 0 }
    }

    /// How many manifolds were written.
    #[must_use]
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether no manifold was written.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The manifolds written, in order.
    #[must_use]
    #[inline]
    pub fn as_slice(&self) -> &[ContactManifold] {
        &self.list[..self.len]
    }

    /// The manifolds written, in order, to edit.
    #[must_use]
    #[inline]
    pub fn as_mut_slice(&mut self) -> &mut [ContactManifold] {
        &mut self.list[..self.len]
    }

    /// Starts the next manifold, with no points ([`ContactManifold::new`]'s fields), written over the next
    /// older one where the list has one ([`ContactManifold::renew`]); returns it to add points to.
    #[inline]
    pub fn begin(
        &mut self,
        body_a: BodyHandle,
        body_b: BodyHandle,
        key: u64,
        normal: Vec3,
        friction: f32,
        restitution: f32,
    ) -> &mut ContactManifold {
        let index = self.len;
        self.len += 1;
        if index < self.list.len() {
            let manifold = &mut self.list[index];
            manifold.renew(body_a, body_b, key, normal, friction, restitution);
            manifold
        } else {
            self.list.push(ContactManifold::new(
                body_a,
                body_b,
                key,
                normal,
                friction,
                restitution,
            ));
            &mut self.list[index]
        }
    }

    /// The next `count` manifolds at once, to be written over in place, in any order, each with
    /// [`ContactManifold::renew_from`] (or [`ContactManifold::renew`] and its points): the older manifolds
    /// where the list has them, else manifolds with no points. All of them count as written.
    pub fn next_slots(&mut self, count: usize) -> &mut [ContactManifold] {
        let start = self.len;
        self.len += count;
        if self.list.len() < self.len {
            let empty = ContactManifold::new(
                BodyHandle::invalid(),
                BodyHandle::invalid(),
                0,
                Vec3::ZERO,
                0.0,
                0.0,
            );
            self.list.resize(self.len, empty);
        }
        &mut self.list[start..self.len]
    }

    /// Adds a whole manifold (every byte of it written).
    #[inline]
    pub fn push(&mut self, manifold: ContactManifold) {
        self.list.truncate(self.len);
        self.list.push(manifold);
        self.len += 1;
    }

    /// Adds whole manifolds with the list's own methods: `append` is handed the list cut to the manifolds
    /// written so far, and what it appends counts as written.
    #[inline]
    pub fn append_with(&mut self, append: impl FnOnce(&mut Vec<ContactManifold>)) {
        self.list.truncate(self.len);
        append(self.list);
        self.len = self.list.len();
    }

    /// Adds copies of `manifolds` (every byte of them written).
    pub fn extend_from_slice(&mut self, manifolds: &[ContactManifold]) {
        self.append_with(|list| list.extend_from_slice(manifolds));
    }

    /// Removes the last manifold written and returns it.
    #[inline]
    pub fn pop(&mut self) -> Option<ContactManifold> {
        let last = self.len.checked_sub(1)?;
        self.len = last;
        self.list.get(last).copied()
    }

    /// The last manifold written.
    #[inline]
    pub fn last_mut(&mut self) -> Option<&mut ContactManifold> {
        self.as_mut_slice().last_mut()
    }

    /// The manifold written at `index`.
    #[inline]
    pub fn get_mut(&mut self, index: usize) -> Option<&mut ContactManifold> {
        self.as_mut_slice().get_mut(index)
    }

    /// Keeps the first `len` manifolds written (no change if fewer were).
    #[inline]
    pub fn truncate(&mut self, len: usize) {
        self.len = self.len.min(len);
    }
}

/// The list keeps the manifolds written, and no older one.
impl Drop for ManifoldWriter<'_> {
    fn drop(&mut self) {
        self.list.truncate(self.len);
    }
}

/// Finds contacts between bodies. Called once per step with the current poses.
pub trait CollisionBackend {
    /// Writes the manifolds of the current poses into `out` (which starts empty). Impulses may be left at
    /// zero: the world matches points to last step's by body pair, key and feature id. The order of `out`
    /// must not depend on hashing or addresses; the world sorts by [`ContactManifold::order_key`] anyway.
    ///
    /// `previous` holds last step's manifolds, sorted by [`ContactManifold::order_key`]: a backend may
    /// recycle one whose [`ContactManifold::basis`] it set (the world's state only, so the result stays a
    /// function of the world's state).
    ///
    /// `dt` is the step about to be taken (s); a backend adds `|v|·dt` to
    /// [`WorldSettings::speculative_margin`] so fast bodies get their contacts before they arrive.
    ///
    /// A backend may skip the bodies [`BodySet::is_quarantined`] names (the world drops their manifolds
    /// anyway) and should keep at most [`crate::StepLimits::max_candidate_pairs`] candidate pairs.
    fn collide(
        &mut self,
        bodies: &BodySet,
        settings: &WorldSettings,
        dt: f32,
        previous: &[ContactManifold],
        out: &mut ManifoldWriter<'_>,
    );

    /// How many candidate pairs the last [`CollisionBackend::collide`] left out because of
    /// [`crate::StepLimits::max_candidate_pairs`] (reported in [`crate::StepReport::capped_pair_count`]).
    /// Default: 0, for a backend without such a cap.
    fn capped_pair_count(&self) -> usize {
        0
    }
}

/// A backend that finds nothing: for worlds of joints only.
#[derive(Debug, Clone, Copy, Default)]
pub struct NoCollision;

impl CollisionBackend for NoCollision {
    fn collide(
        &mut self,
        _: &BodySet,
        _: &WorldSettings,
        _: f32,
        _: &[ContactManifold],
        _: &mut ManifoldWriter<'_>,
    ) {
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn kept(a: Vec3, b: Vec3) -> ManifoldPoint {
        kept_as(a, b, 7)
    }

    fn kept_as(a: Vec3, b: Vec3, feature_id: u32) -> ManifoldPoint {
        ManifoldPoint {
            solver_lever_arms: Some([a, b]),
            feature_id,
            ..ManifoldPoint::default()
        }
    }

    fn handles() -> (BodyHandle, BodyHandle) {
        (
            BodyHandle::from_raw_parts(1, 0),
            BodyHandle::from_raw_parts(2, 0),
        )
    }

    fn point(separation: f32) -> ManifoldPoint {
        ManifoldPoint {
            local_anchor_a: Vec3::new(separation, 1.0, 2.0),
            separation,
            feature_id: 9,
            normal_impulse: 0.5,
            ..ManifoldPoint::default()
        }
    }

    #[test]
    fn a_manifold_written_over_an_old_one_equals_a_new_one_and_the_list_keeps_only_those_written() {
        let (a, b) = handles();
        // An old list of three full manifolds with a basis and materials set.
        let mut old = ContactManifold::new(b, a, 3, Vec3::X, 0.9, 0.8);
        old.rolling_friction = 0.1;
        old.surface_velocity = Vec3::Z;
        old.force_event_threshold = Some(2.0);
        old.basis = Some(ContactBasis {
            rotation: Quat::IDENTITY,
            translation: Vec3::Y,
            local_normal: Vec3::X,
        });
        for k in 0..MAX_MANIFOLD_POINTS {
            assert!(old.push_point(point(-(k as f32))));
        }
        let mut list = vec![old; 3];
        let mut fresh = ContactManifold::new(a, b, 7, Vec3::Y, 0.5, 0.0);
        assert!(fresh.push_point(point(-0.01)));
        {
            let mut out = ManifoldWriter::new(&mut list);
            assert!(out.is_empty());
            let written = out.begin(a, b, 7, Vec3::Y, 0.5, 0.0);
            assert!(written.push_point(point(-0.01)));
            out.begin(a, b, 8, Vec3::Y, 0.5, 0.0);
            // A manifold made and taken back (no point within reach) leaves no trace.
            assert_eq!(out.pop().map(|m| m.key), Some(8));
            assert_eq!(out.len(), 1);
        }
        assert_eq!(list.len(), 1);
        assert_eq!(list[0], fresh);
        // The slots past the point count still hold the old points; a snapshot clears them.
        assert_eq!(list[0].points[1], old.points[1]);
        list[0].clear_unused_points();
        assert_eq!(list[0].points, fresh.points);
    }

    #[test]
    fn a_writer_appends_past_the_old_list_and_whole_manifolds_anywhere() {
        let (a, b) = handles();
        let mut list = vec![ContactManifold::new(a, b, 1, Vec3::Y, 0.5, 0.0)];
        let whole = ContactManifold::new(a, b, 2, Vec3::Y, 0.5, 0.0);
        {
            let mut out = ManifoldWriter::new(&mut list);
            out.begin(a, b, 1, Vec3::X, 0.5, 0.0);
            out.begin(a, b, 3, Vec3::X, 0.5, 0.0);
            out.push(whole);
            out.extend_from_slice(&[whole, whole]);
            assert_eq!(out.len(), 5);
            out.truncate(4);
            assert_eq!(out.last_mut().map(|m| m.key), Some(2));
            assert_eq!(out.get_mut(1).map(|m| m.key), Some(3));
        }
        let keys: Vec<u64> = list.iter().map(|m| m.key).collect();
        assert_eq!(keys, [1, 3, 2, 2]);
    }

    #[test]
    fn the_world_point_is_the_midpoint_of_the_two_anchors() {
        let point = ManifoldPoint {
            local_anchor_a: Vec3::new(0.0, -0.5, 0.0),
            local_anchor_b: Vec3::new(0.0, 0.5, 0.0),
            ..ManifoldPoint::default()
        };
        // A's anchor at (1, 0.5, 0), B's (rotated a half turn about z) at (1, 0.3, 0): 0.2 m of overlap.
        let pose_a = Pose::from_position(Vec3::new(1.0, 1.0, 0.0));
        let pose_b = Pose::new(
            Vec3::new(1.0, 0.8, 0.0),
            Quat::from_rotation_z(std::f32::consts::PI),
        );
        let p = point.world_point(pose_a, pose_b);
        assert!((p - Vec3::new(1.0, 0.4, 0.0)).length() < 1e-6, "{p}");
    }

    #[test]
    fn a_new_point_takes_its_fresh_lever_arms() {
        let mut point = ManifoldPoint::default();
        let fresh = [Vec3::new(0.5, -0.5, 0.5), Vec3::new(0.5, 0.5, 0.5)];
        assert!(point.refresh_lever_arms(fresh, &[]).is_none());
        assert_eq!(point.solver_lever_arms, Some(fresh));
    }

    #[test]
    fn lever_arms_within_tolerance_are_kept_and_the_nearest_point_wins() {
        let fresh = [Vec3::new(0.5, -0.5, 0.5), Vec3::new(0.5, 0.5, 0.5)];
        let nudge = Vec3::new(0.004, 0.0, 0.0);
        let near = kept_as(fresh[0] + nudge, fresh[1] - nudge, 1);
        let nearer = kept_as(fresh[0] + nudge * 0.5, fresh[1], 2);
        let mut point = ManifoldPoint::default();
        let previous = [near, nearer];
        let matched = point.refresh_lever_arms(fresh, &previous);
        assert_eq!(matched, Some(&nearer));
        assert_eq!(point.solver_lever_arms, nearer.solver_lever_arms);
    }

    #[test]
    fn the_same_feature_within_tolerance_wins_over_a_nearer_point() {
        let fresh = [Vec3::new(0.5, -0.5, 0.5), Vec3::new(0.5, 0.5, 0.5)];
        let nudge = Vec3::new(0.004, 0.0, 0.0);
        let same = kept_as(fresh[0] + nudge, fresh[1] - nudge, 3);
        let nearer = kept_as(fresh[0] + nudge * 0.5, fresh[1], 2);
        let mut point = ManifoldPoint {
            feature_id: 3,
            ..ManifoldPoint::default()
        };
        let previous = [nearer, same];
        assert_eq!(point.refresh_lever_arms(fresh, &previous), Some(&same));
        assert_eq!(point.solver_lever_arms, same.solver_lever_arms);
        // Beyond the tolerance the same feature still gives the warm start, the nearest point the lever arms.
        let moved = kept_as(fresh[0] + Vec3::X * 0.02, fresh[1], 3);
        let previous = [nearer, moved];
        assert_eq!(point.refresh_lever_arms(fresh, &previous), Some(&moved));
        assert_eq!(point.solver_lever_arms, nearer.solver_lever_arms);
        // Neither within tolerance: the fresh lever arms, and the same feature's impulses.
        let far = kept_as(fresh[0], fresh[1] + Vec3::Y * 0.02, 2);
        assert_eq!(point.refresh_lever_arms(fresh, &[far, moved]), Some(&moved));
        assert_eq!(point.solver_lever_arms, Some(fresh));
    }

    #[test]
    fn lever_arms_beyond_tolerance_are_renewed() {
        let fresh = [Vec3::new(0.5, -0.5, 0.5), Vec3::new(0.5, 0.5, 0.5)];
        // 1 cm + a little on body B alone is enough to renew both.
        let far = kept(
            fresh[0],
            fresh[1] + Vec3::new(0.0, 0.0, LEVER_ARM_TOLERANCE * 1.01),
        );
        let mut point = ManifoldPoint::default();
        assert!(point.refresh_lever_arms(fresh, &[far]).is_none());
        assert_eq!(point.solver_lever_arms, Some(fresh));
    }

    #[test]
    fn short_lever_arms_use_the_relative_tolerance() {
        // A 4 cm lever arm may move 2 mm (5 %), not 1 cm.
        let fresh = [Vec3::new(0.0, -0.04, 0.0), Vec3::new(0.0, 0.04, 0.0)];
        let mut point = ManifoldPoint::default();
        let within = kept(fresh[0] + Vec3::X * 0.0019, fresh[1]);
        assert!(point.refresh_lever_arms(fresh, &[within]).is_some());
        let beyond = kept(fresh[0] + Vec3::X * 0.0021, fresh[1]);
        assert!(point.refresh_lever_arms(fresh, &[beyond]).is_none());
        assert_eq!(point.solver_lever_arms, Some(fresh));
    }
}
