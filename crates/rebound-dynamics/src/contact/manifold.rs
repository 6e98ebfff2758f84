//! The contact manifold as the collision stage hands it to the solver: [`Contact`] (two bodies by solver
//! index, the normal, the combined material coefficients) and its up to [`MAX_CONTACT_POINTS`]
//! [`ContactPoint`]s, which carry the warm-start impulses in and the step's impulses out. Input and output of
//! the contact stages (*prepare* reads it, *store impulses* writes it).

use rebound_math::Vec3;

/// The most points a contact manifold carries (a face on a face needs four).
pub const MAX_CONTACT_POINTS: usize = 4;

/// One point of a contact manifold, as the collision stage reports it. `#[repr(C)]`: the contact lanes read
/// it in 16-byte groups, in this field order.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C)]
pub struct ContactPoint {
    /// The contact point relative to body A's centre of mass at the start of the step, world axes (m).
    pub anchor_a: Vec3,
    /// The contact point relative to body B's centre of mass at the start of the step, world axes (m).
    pub anchor_b: Vec3,
    /// Signed distance between the surfaces along the normal (m): negative when they overlap, positive for a
    /// speculative point not yet touching.
    pub separation: f32,
    /// Normal impulse (N·s): the warm-start value on input, the step's accumulated impulse after
    /// [`ContactSolver::store_impulses`](crate::ContactSolver::store_impulses).
    pub normal_impulse: f32,
    /// Friction impulse as a world vector (N·s), likewise. Stored as a vector so that it survives a change of
    /// tangent basis between steps.
    pub tangent_impulse: Vec3,
    /// Identifies the pair of features that touch, for matching points between steps (warm starting).
    pub feature_id: u32,
}

/// A contact manifold between two bodies, as the collision stage reports it.
///
/// Laid out for the stages that write and read it once a step (the world builds it in place over last
/// step's, *prepare* reads it): the header first, the point count with it, then the points in order, each
/// manifold on whole cache lines (`repr(C, align(64))`), so that a one-point manifold (a ball on anything)
/// is two lines of its five and its unused point slots are never touched.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(64))]
pub struct Contact {
    /// Index of body A in the solver arrays.
    pub body_a: usize,
    /// Index of body B in the solver arrays.
    pub body_b: usize,
    /// How many points are in use (0 to [`MAX_CONTACT_POINTS`]).
    pub point_count: usize,
    /// Unit normal from A to B.
    pub normal: Vec3,
    /// Combined friction coefficient μ (dimensionless, ≥ 0).
    pub friction: f32,
    /// Combined coefficient of restitution `C_r` (dimensionless, in `[0, 1]`).
    pub restitution: f32,
    /// Rolling resistance as a lever arm (m, ≥ 0): the relative angular velocity of the two bodies (rolling
    /// and spinning) is resisted by a torque of at most `rolling_friction × normal force`. Default: 0 (ideal
    /// rolling: a ball set rolling on flat ground rolls forever, as in rapier and Box2D's default).
    pub rolling_friction: f32,
    /// The velocity (m/s, world axes) B's surface should slide at relative to A's at the contact, in the
    /// contact plane — a conveyor belt's surface speed. Friction drives the relative tangential velocity to it
    /// instead of to zero; the part along the normal is ignored. Default: zero (ordinary friction).
    pub surface_velocity: Vec3,
    /// The fastest this manifold pushes its overlapping bodies apart (m/s); the step's
    /// `max_push_out_speed` if that is lower. A body in `k` overlaps gets `max_push_out_speed / k` on each
    /// from the world, so that it leaves them all at no more than `max_push_out_speed` together. Default: ∞
    /// (the step's).
    pub push_out_speed: f32,
    /// The normal force (N) the bodies resting on this manifold press it with — their weight handed down
    /// the stack ([`StackLoads`](crate::contact::StackLoads)). With a resting overlap set
    /// ([`StepContext::resting_overlap`](crate::StepContext::resting_overlap)), preparation moves the rest
    /// point of the soft rows by it, so that they hold it at that small overlap (`docs/physics.md`,
    /// "Contacts under load"). Default: 0 (the overlap at rest is load / stiffness).
    pub load: f32,
    /// The points; only the first `point_count` are used.
    pub points: [ContactPoint; MAX_CONTACT_POINTS],
}

// The header and the first point within two cache lines.
const _: () = assert!(core::mem::offset_of!(Contact, points) + size_of::<ContactPoint>() <= 2 * 64);

impl Contact {
    /// A manifold between bodies `body_a` and `body_b` with normal `normal` (unit, A → B) and no points yet.
    #[must_use]
    pub fn new(
        body_a: usize,
        body_b: usize,
        normal: Vec3,
        friction: f32,
        restitution: f32,
    ) -> Self {
        let mut contact = Self {
            body_a,
            body_b,
            point_count: 0,
            normal,
            friction,
            restitution,
            rolling_friction: 0.0,
            surface_velocity: Vec3::ZERO,
            push_out_speed: 0.0,
            load: 0.0,
            points: [ContactPoint::default(); MAX_CONTACT_POINTS],
        };
        // The defaults of the other fields are written once, in `renew`.
        contact.renew(body_a, body_b, normal, friction, restitution);
        contact
    }

    /// Makes this manifold a new one between bodies `body_a` and `body_b` with normal `normal` (unit, A → B),
    /// the given coefficients, the defaults of the other fields and no points, keeping only the storage of
    /// its old points (never read: only the first `point_count` are used), so that a reused list of
    /// manifolds is not written twice.
    #[inline]
    pub fn renew(
        &mut self,
        body_a: usize,
        body_b: usize,
        normal: Vec3,
        friction: f32,
        restitution: f32,
    ) {
        self.body_a = body_a;
        self.body_b = body_b;
        self.normal = normal;
        self.friction = friction;
        self.restitution = restitution;
        self.rolling_friction = 0.0;
        self.surface_velocity = Vec3::ZERO;
        self.push_out_speed = f32::INFINITY;
        self.load = 0.0;
        self.point_count = 0;
    }

    /// Sets the rolling resistance lever arm (m).
    #[must_use]
    pub fn with_rolling_friction(mut self, rolling_friction: f32) -> Self {
        self.rolling_friction = rolling_friction;
        self
    }

    /// Adds a point; returns `false` (and adds nothing) when the manifold is full.
    pub fn push_point(&mut self, point: ContactPoint) -> bool {
        if self.point_count == MAX_CONTACT_POINTS {
            return false;
        }
        self.points[self.point_count] = point;
        self.point_count += 1;
        true
    }

    /// The points in use.
    #[inline]
    #[must_use]
    pub fn points(&self) -> &[ContactPoint] {
        &self.points[..self.point_count.min(MAX_CONTACT_POINTS)]
    }
}
