//! The contact-constraint kernel: soft non-penetration with a push-out speed cap, Coulomb friction on two
//! tangents with a circular cone, and restitution. Stages: *prepare* → per substep *warm start*, *solve*
//! (bias on), *relax* (bias off) → *restitution* (once) → *store impulses*.
//!
//! Contacts arrive as plain data ([`Contact`]); the collision backend (or a test) makes them. Bodies are
//! referred to by their index into the solver arrays ([`SolverBody`], [`BodyParams`]).
//!
//! # The model (Box2D v3 soft step; Catto, "Solver2D", 2024)
//!
//! For a contact point with anchors `r_a`, `r_b`, normal `n` (from A to B) and the current separation
//!
//! ```text
//! s = s₀ + n·[(Δp_b + Δq_b·r_b − r_b) − (Δp_a + Δq_a·r_a − r_a)]     (negative = overlap)
//! v_n = n·[(v_b + ω_b × r_b) − (v_a + ω_a × r_a)]
//! ```
//!
//! the normal impulse is
//!
//! ```text
//! s > 0 (speculative):   bias = s/h,                       mass_scale = 1, impulse_scale = 0
//! s ≤ 0, bias on:        bias = max(bias_rate·s, −v_max),  soft coefficients (crate::Softness)
//! s ≤ 0, relax:          bias = 0,                         mass_scale = 1, impulse_scale = 0
//! Δλ = −m_n·mass_scale·(v_n + bias) − impulse_scale·λ,   λ ← max(λ + Δλ, 0)
//! ```
//!
//! so a speculative contact lets the bodies close exactly the gap in this substep and no more, an overlap is
//! pushed out softly at no more than `v_max`, and the relax pass removes the push-out velocity so that resting
//! bodies do not gain energy. Friction: `λ_t ← clamp_circle(λ_t − M_t·v_t, μ·λ)`. Restitution, once after
//! the substeps, drives `v_n` to `−C_r·v_n⁻` where `v_n⁻` is the approach speed — the most negative normal
//! velocity the bias passes met before applying their impulse, so a body that keeps falling for part of the
//! step rebounds from its speed at impact, not its speed when the step began — for contacts that approached
//! faster than the threshold and carried an impulse.

use crate::{BodyParams, Softness, SolverBody, StepContext};
use rebound_math::{Mat3, Vec2, Vec3, rotate_inverse};

mod wide;

/// A point closer than this (m) counts as touching for restitution: a speculative contact closes its gap to
/// rounding error, not always to exactly zero.
const BOUNCE_SLOP: f32 = 5e-3;

/// The most points a contact manifold carries (a face on a face needs four).
pub const MAX_CONTACT_POINTS: usize = 4;

/// Whether the solve applies the position-correcting bias (the two passes of a soft substep).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Bias {
    /// Solve with the soft bias: corrects overlap.
    On,
    /// Relax: solve the velocity constraint only, removing the bias velocity.
    Off,
}

/// One point of a contact manifold, as the collision stage reports it.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ContactPoint {
    /// The contact point relative to body A's centre of mass at the start of the step, world axes (m).
    pub anchor_a: Vec3,
    /// The contact point relative to body B's centre of mass at the start of the step, world axes (m).
    pub anchor_b: Vec3,
    /// Signed distance between the surfaces along the normal (m): negative when they overlap, positive for a
    /// speculative point not yet touching.
    pub separation: f32,
    /// Normal impulse (N·s): the warm-start value on input, the step's accumulated impulse after
    /// [`ContactSolver::store_impulses`].
    pub normal_impulse: f32,
    /// Friction impulse as a world vector (N·s), likewise. Stored as a vector so that it survives a change of
    /// tangent basis between steps.
    pub tangent_impulse: Vec3,
    /// Identifies the pair of features that touch, for matching points between steps (warm starting).
    pub feature_id: u32,
}

/// A contact manifold between two bodies, as the collision stage reports it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Contact {
    /// Index of body A in the solver arrays.
    pub body_a: usize,
    /// Index of body B in the solver arrays.
    pub body_b: usize,
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
    /// The points; only the first `point_count` are used.
    pub points: [ContactPoint; MAX_CONTACT_POINTS],
    /// How many points are in use (0 to [`MAX_CONTACT_POINTS`]).
    pub point_count: usize,
}

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
        Self {
            body_a,
            body_b,
            normal,
            friction,
            restitution,
            rolling_friction: 0.0,
            points: [ContactPoint::default(); MAX_CONTACT_POINTS],
            point_count: 0,
        }
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
    #[must_use]
    pub fn points(&self) -> &[ContactPoint] {
        &self.points[..self.point_count.min(MAX_CONTACT_POINTS)]
    }
}

/// A prepared contact point: anchors, effective masses, the angular Jacobian terms and the accumulated
/// impulses. The angular terms `r × d` and `I⁻¹·(r × d)` are computed once at prepare so that the solve loop
/// does no matrix products.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct PreparedPoint {
    anchor_a: Vec3,
    anchor_b: Vec3,
    separation: f32,
    /// The most negative normal relative velocity seen before an impulse in any pass of the step (m/s);
    /// negative when approaching. Restitution reverses it.
    relative_velocity: f32,
    /// Whether this point has bounced this step: a bounce is one event, applied once, after which the
    /// contact is an ordinary one (otherwise a ball that handed its momentum on would be pushed again).
    bounced: bool,
    normal_impulse: f32,
    tangent_impulse: Vec2,
    max_normal_impulse: f32,
    normal_mass: f32,
    tangent_mass: [f32; 2],
    rn_a: Vec3,
    rn_b: Vec3,
    wn_a: Vec3,
    wn_b: Vec3,
    rt_a: [Vec3; 2],
    rt_b: [Vec3; 2],
    wt_a: [Vec3; 2],
    wt_b: [Vec3; 2],
}

/// A prepared contact manifold. Its points live in the solver's flat point array (`first_point ..
/// first_point + point_count`), so a one-point manifold (a ball on the ground) costs one point, not four, and a
/// pass streams no unused slots.
#[derive(Debug, Clone, Copy, PartialEq)]
struct PreparedContact {
    /// Index of the source [`Contact`] in the slice given to `prepare`.
    source: usize,
    body_a: usize,
    body_b: usize,
    first_point: usize,
    point_count: usize,
    /// Index of the manifold's rolling-resistance block, or `None` without rolling friction.
    rolling: Option<usize>,
    normal: Vec3,
    tangents: [Vec3; 2],
    friction: f32,
    restitution: f32,
    inv_mass_a: f32,
    inv_mass_b: f32,
    softness: Softness,
    /// Whether both bodies are moved by the solver (not fixed or kinematic).
    both_dynamic: bool,
}

/// The rolling-resistance block of a manifold: an angular constraint `ω_b − ω_a = 0` whose accumulated
/// impulse is clamped to `rolling_friction × Σλ_n`. Effective mass `(I_a⁻¹ + I_b⁻¹)⁻¹`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Rolling {
    friction: f32,
    impulse: Vec3,
    mass: Mat3,
    inv_inertia_a: Mat3,
    inv_inertia_b: Mat3,
}

/// The contact solver: holds the prepared constraints between stages and reuses its buffer from step to
/// step (no allocation once it has grown to the scene's contact count).
#[derive(Debug, Clone, Default)]
pub struct ContactSolver {
    contacts: Vec<PreparedContact>,
    points: Vec<PreparedPoint>,
    rolling: Vec<Rolling>,
    /// The wide-solved manifolds, four at a time, colour after colour (see [`wide`]).
    batches: Vec<wide::Batch>,
    /// The batches' point slots.
    slots: Vec<wide::PointX4>,
    /// Indices of the manifolds the scalar path solves, after the batches.
    scalar: Vec<usize>,
    coloring: wide::Coloring,
}

impl ContactSolver {
    /// An empty solver.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The number of prepared manifolds.
    #[must_use]
    pub fn len(&self) -> usize {
        self.contacts.len()
    }

    /// Whether no manifold is prepared.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.contacts.is_empty()
    }

    /// Stage *prepare*: computes tangents, effective masses, angular terms and pre-step normal velocities of
    /// `contacts` against the bodies' start-of-step state. Warm-start impulses are taken from the points if
    /// `ctx.warm_starting`, else zeroed.
    ///
    /// Malformed contacts — a body index out of range, a body against itself, a normal that is not finite —
    /// are skipped, never solved; the return value counts them (0 when the collision stage is sound).
    pub fn prepare(
        &mut self,
        contacts: &[Contact],
        bodies: &[SolverBody],
        params: &[BodyParams],
        ctx: &StepContext,
    ) -> usize {
        self.contacts.clear();
        self.points.clear();
        self.rolling.clear();
        self.contacts.reserve(contacts.len());
        let body_count = bodies.len().min(params.len());
        let mut skipped = 0;
        for (source, contact) in contacts.iter().enumerate() {
            if contact.body_a >= body_count
                || contact.body_b >= body_count
                || contact.body_a == contact.body_b
                || !contact.normal.is_finite()
            {
                skipped += 1;
                continue;
            }
            let (pa, pb) = (&params[contact.body_a], &params[contact.body_b]);
            let normal = contact.normal;
            let (t1, t2) = normal.any_orthonormal_pair();
            let both_dynamic = pa.is_dynamic() && pb.is_dynamic();
            let rolling = (contact.rolling_friction > 0.0).then(|| {
                self.rolling.push(Rolling {
                    friction: contact.rolling_friction,
                    impulse: Vec3::ZERO,
                    mass: angular_mass(pa.inv_inertia_world + pb.inv_inertia_world),
                    inv_inertia_a: pa.inv_inertia_world,
                    inv_inertia_b: pb.inv_inertia_world,
                });
                self.rolling.len() - 1
            });
            self.contacts.push(PreparedContact {
                source,
                body_a: contact.body_a,
                body_b: contact.body_b,
                first_point: NO_POINTS,
                point_count: contact.points().len(),
                rolling,
                normal,
                tangents: [t1, t2],
                friction: contact.friction,
                restitution: contact.restitution,
                inv_mass_a: pa.inv_mass,
                inv_mass_b: pb.inv_mass,
                softness: if both_dynamic {
                    ctx.contact_softness
                } else {
                    ctx.static_softness
                },
                both_dynamic,
            });
        }
        // Wide manifolds get their points straight into their batch's lanes; the scalar ones here.
        let input = PrepareInput {
            contacts,
            bodies,
            params,
            ctx,
        };
        self.coloring.build(
            &self.contacts,
            &input,
            &mut self.batches,
            &mut self.slots,
            &mut self.scalar,
        );
        for &index in &self.scalar {
            let c = &mut self.contacts[index];
            c.first_point = self.points.len();
            for point in contacts[c.source].points() {
                self.points.push(input.scalar_point(c, point));
            }
        }
        skipped
    }

    /// Stage *warm start*: applies the accumulated impulses of the last substep (or the last step) again, so
    /// the iterations start from the previous answer.
    pub fn warm_start(&self, bodies: &mut [SolverBody]) {
        for batch in &self.batches {
            batch.warm_start(&self.slots, bodies);
        }
        for c in self.scalar.iter().map(|&i| &self.contacts[i]) {
            let (mut a, mut b) = (bodies[c.body_a], bodies[c.body_b]);
            for p in &self.points[c.first_point..c.first_point + c.point_count] {
                let linear = c.normal * p.normal_impulse
                    + c.tangents[0] * p.tangent_impulse.x
                    + c.tangents[1] * p.tangent_impulse.y;
                a.linear_velocity -= linear * c.inv_mass_a;
                b.linear_velocity += linear * c.inv_mass_b;
                a.angular_velocity -= p.wn_a * p.normal_impulse
                    + p.wt_a[0] * p.tangent_impulse.x
                    + p.wt_a[1] * p.tangent_impulse.y;
                b.angular_velocity += p.wn_b * p.normal_impulse
                    + p.wt_b[0] * p.tangent_impulse.x
                    + p.wt_b[1] * p.tangent_impulse.y;
            }
            if let Some(r) = c.rolling.map(|i| &self.rolling[i]) {
                a.angular_velocity -= r.inv_inertia_a * r.impulse;
                b.angular_velocity += r.inv_inertia_b * r.impulse;
            }
            write_pair(bodies, c.body_a, a, c.body_b, b);
        }
    }

    /// Stages *solve* (`Bias::On`) and *relax* (`Bias::Off`): one Gauss–Seidel pass over every contact,
    /// normal impulses first, then friction clamped to the circle of radius μ·λ_n.
    ///
    /// The current separation of a point is `s₀ + n·(Δp_b − Δp_a) + (Δq_b⁻¹·n − n)·r_b − (Δq_a⁻¹·n − n)·r_a`:
    /// `n·(Δq·r − r) = (Δq⁻¹·n − n)·r` for a rotation, so the two rotations are done once per manifold instead of
    /// once per point and body.
    ///
    /// Manifolds without restitution or rolling resistance are solved four at a time, in graph-coloured
    /// batches in `Vec4` lanes (`docs/physics.md`, Contacts); the rest one by one after them.
    pub fn solve(&mut self, bodies: &mut [SolverBody], ctx: &StepContext, bias: Bias) {
        for batch in &self.batches {
            batch.solve(&mut self.slots, bodies, ctx, bias);
        }
        for &index in &self.scalar {
            let c = &self.contacts[index];
            let (mut a, mut b) = (bodies[c.body_a], bodies[c.body_b]);
            let normal = c.normal;
            let points = &mut self.points[c.first_point..c.first_point + c.point_count];
            let shift = normal.dot(b.delta_position - a.delta_position);
            let turn_a = rotate_inverse(a.delta_rotation, normal) - normal;
            let turn_b = rotate_inverse(b.delta_rotation, normal) - normal;
            for p in points.iter_mut() {
                let s = p.separation + shift + turn_b.dot(p.anchor_b) - turn_a.dot(p.anchor_a);
                let vn = normal.dot(b.linear_velocity - a.linear_velocity)
                    + b.angular_velocity.dot(p.rn_b)
                    - a.angular_velocity.dot(p.rn_a);
                // The approach speed restitution reverses is the fastest seen before an impulse acted, in any
                // pass: a falling body keeps accelerating after the step began, and a ball struck by its
                // neighbour in a row approaches the next only once struck.
                p.relative_velocity = p.relative_velocity.min(vn);
                let approach = -p.relative_velocity;
                let bounce =
                    if !p.bounced && c.restitution > 0.0 && approach > ctx.restitution_threshold {
                        c.restitution * approach
                    } else {
                        0.0
                    };
                // A bounce starts when the bodies touch. Between two moving bodies it starts already in the
                // substep that will close the gap: a speculative impulse there would share momentum
                // inelastically before the bounce, and a row of balls (Newton's cradle) would move as one.
                // The price is a bounce up to |v|·h early, under 1 cm at 2 m/s and 4 substeps.
                let closes_now = c.both_dynamic && s + vn * ctx.h <= 0.0;
                if bounce > 0.0 && (s <= BOUNCE_SLOP || closes_now) {
                    // The bounce: one impulse that sets the normal velocity to +C_r·approach. It is kept out
                    // of the accumulated impulse (which restarts at 0), so the later passes of the step —
                    // relax, the next substeps' warm start — see a separating contact and leave it alone
                    // instead of taking the bounce back.
                    p.bounced = true;
                    p.normal_impulse = 0.0;
                    let impulse = (-p.normal_mass * (vn - bounce)).max(0.0);
                    p.max_normal_impulse = p.max_normal_impulse.max(impulse);
                    apply_normal(
                        &mut a,
                        &mut b,
                        c.inv_mass_a,
                        c.inv_mass_b,
                        normal,
                        p,
                        impulse,
                    );
                    continue;
                }
                let (velocity_bias, mass_scale, impulse_scale) = if s > 0.0 {
                    (s * ctx.inv_h, 1.0, 0.0)
                } else if bias == Bias::On {
                    (
                        (c.softness.bias_rate * s).max(-ctx.max_push_out_speed),
                        c.softness.mass_scale,
                        c.softness.impulse_scale,
                    )
                } else {
                    (0.0, 1.0, 0.0)
                };
                let delta = -p.normal_mass * mass_scale * (vn + velocity_bias)
                    - impulse_scale * p.normal_impulse;
                let accumulated = (p.normal_impulse + delta).max(0.0);
                let applied = accumulated - p.normal_impulse;
                p.normal_impulse = accumulated;
                p.max_normal_impulse = p.max_normal_impulse.max(applied);
                apply_normal(
                    &mut a,
                    &mut b,
                    c.inv_mass_a,
                    c.inv_mass_b,
                    normal,
                    p,
                    applied,
                );
            }
            for p in points.iter_mut() {
                let dv = b.velocity_at(p.anchor_b) - a.velocity_at(p.anchor_a);
                let vt = Vec2::new(dv.dot(c.tangents[0]), dv.dot(c.tangents[1]));
                let candidate = p.tangent_impulse
                    - Vec2::new(p.tangent_mass[0] * vt.x, p.tangent_mass[1] * vt.y);
                let limit = c.friction * p.normal_impulse;
                let accumulated = candidate.clamp_length_max(limit);
                let applied = accumulated - p.tangent_impulse;
                p.tangent_impulse = accumulated;
                let linear = c.tangents[0] * applied.x + c.tangents[1] * applied.y;
                a.linear_velocity -= linear * c.inv_mass_a;
                b.linear_velocity += linear * c.inv_mass_b;
                a.angular_velocity -= p.wt_a[0] * applied.x + p.wt_a[1] * applied.y;
                b.angular_velocity += p.wt_b[0] * applied.x + p.wt_b[1] * applied.y;
            }
            if let Some(r) = c.rolling.map(|i| &mut self.rolling[i]) {
                let total_normal: f32 = points.iter().map(|p| p.normal_impulse).sum();
                let candidate = r.impulse - r.mass * (b.angular_velocity - a.angular_velocity);
                let accumulated = candidate.clamp_length_max(r.friction * total_normal);
                let applied = accumulated - r.impulse;
                r.impulse = accumulated;
                a.angular_velocity -= r.inv_inertia_a * applied;
                b.angular_velocity += r.inv_inertia_b * applied;
            }
            write_pair(bodies, c.body_a, a, c.body_b, b);
        }
    }

    /// Stage *store impulses*: writes the accumulated impulses back into `contacts` (the slice given to
    /// [`ContactSolver::prepare`]) for warm starting the next step and for reporting.
    pub fn store_impulses(&self, contacts: &mut [Contact]) {
        self.for_each_point_result(|source, k, normal, tangent, _| {
            if let Some(point) = contacts.get_mut(source).and_then(|c| c.points.get_mut(k)) {
                point.normal_impulse = normal;
                point.tangent_impulse = tangent;
            }
        });
    }

    /// Calls `f(source, point, normal_impulse, tangent_impulse, max_normal_impulse)` for every point of every
    /// prepared manifold: the index of its source contact, the point's index in it, its accumulated normal
    /// impulse (N·s), its friction impulse as a world vector (N·s) and the largest normal impulse it applied
    /// in one iteration this step (N·s) — what contact events report as the hit strength. For a caller that
    /// keeps its own contacts: one pass gives it everything [`ContactSolver::store_impulses`] writes and more.
    pub fn for_each_point_result(&self, mut f: impl FnMut(usize, usize, f32, Vec3, f32)) {
        let basis = |c: &PreparedContact, [x, y]: [f32; 2]| c.tangents[0] * x + c.tangents[1] * y;
        for &index in &self.scalar {
            let c = &self.contacts[index];
            for (k, p) in self.points[c.first_point..][..c.point_count]
                .iter()
                .enumerate()
            {
                let tangent = basis(c, p.tangent_impulse.to_array());
                f(c.source, k, p.normal_impulse, tangent, p.max_normal_impulse);
            }
        }
        for batch in &self.batches {
            for (index, impulses) in batch.results(&self.slots, &self.contacts) {
                let c = &self.contacts[index];
                for (k, (normal, tangent, max)) in impulses.enumerate() {
                    f(c.source, k, normal, basis(c, tangent), max);
                }
            }
        }
    }
}

/// `first_point` of a manifold whose points live in a wide batch.
const NO_POINTS: usize = usize::MAX;

/// What *prepare* reads: the contacts as given and the bodies' start-of-step state.
struct PrepareInput<'a> {
    contacts: &'a [Contact],
    bodies: &'a [SolverBody],
    params: &'a [BodyParams],
    ctx: &'a StepContext,
}

impl PrepareInput<'_> {
    /// The prepared form of `point`, a point of manifold `c`: anchors, angular Jacobian terms, effective
    /// masses and the warm-start impulses in the manifold's tangent basis. The pre-step normal velocity,
    /// which only a bounce reads, is left at 0 (see [`PrepareInput::scalar_point`]).
    #[inline]
    fn point(&self, c: &PreparedContact, point: &ContactPoint) -> PreparedPoint {
        let (pa, pb) = (&self.params[c.body_a], &self.params[c.body_b]);
        let normal = c.normal;
        let (ra, rb) = (point.anchor_a, point.anchor_b);
        let rn_a = ra.cross(normal);
        let rn_b = rb.cross(normal);
        let wn_a = pa.inv_inertia_world * rn_a;
        let wn_b = pb.inv_inertia_world * rn_b;
        let k_normal = pa.inv_mass + pb.inv_mass + rn_a.dot(wn_a) + rn_b.dot(wn_b);
        let mut rt_a = [Vec3::ZERO; 2];
        let mut rt_b = [Vec3::ZERO; 2];
        let mut wt_a = [Vec3::ZERO; 2];
        let mut wt_b = [Vec3::ZERO; 2];
        let mut tangent_mass = [0.0; 2];
        for (i, t) in c.tangents.iter().enumerate() {
            rt_a[i] = ra.cross(*t);
            rt_b[i] = rb.cross(*t);
            wt_a[i] = pa.inv_inertia_world * rt_a[i];
            wt_b[i] = pb.inv_inertia_world * rt_b[i];
            let k = pa.inv_mass + pb.inv_mass + rt_a[i].dot(wt_a[i]) + rt_b[i].dot(wt_b[i]);
            tangent_mass[i] = if k > 0.0 { 1.0 / k } else { 0.0 };
        }
        let (normal_impulse, tangent_impulse) = if self.ctx.warm_starting {
            (
                point.normal_impulse,
                Vec2::new(
                    point.tangent_impulse.dot(c.tangents[0]),
                    point.tangent_impulse.dot(c.tangents[1]),
                ),
            )
        } else {
            (0.0, Vec2::ZERO)
        };
        PreparedPoint {
            anchor_a: ra,
            anchor_b: rb,
            separation: point.separation,
            relative_velocity: 0.0,
            bounced: false,
            normal_impulse,
            tangent_impulse,
            max_normal_impulse: 0.0,
            normal_mass: if k_normal > 0.0 { 1.0 / k_normal } else { 0.0 },
            tangent_mass,
            rn_a,
            rn_b,
            wn_a,
            wn_b,
            rt_a,
            rt_b,
            wt_a,
            wt_b,
        }
    }

    /// [`PrepareInput::point`] with the pre-step normal velocity, for the scalar path (which bounces).
    fn scalar_point(&self, c: &PreparedContact, point: &ContactPoint) -> PreparedPoint {
        let (sa, sb) = (&self.bodies[c.body_a], &self.bodies[c.body_b]);
        let dv = sb.velocity_at(point.anchor_b) - sa.velocity_at(point.anchor_a);
        PreparedPoint {
            relative_velocity: dv.dot(c.normal),
            ..self.point(c, point)
        }
    }
}

/// The effective mass of an angular constraint, `K⁻¹`; a singular `K` (both bodies unable to turn about some
/// axis) inverts per axis with zero for the locked directions.
fn angular_mass(k: Mat3) -> Mat3 {
    let det = k.determinant();
    if det > f32::MIN_POSITIVE && det.is_finite() {
        return k.inverse();
    }
    let invert = |v: f32| if v > 0.0 { 1.0 / v } else { 0.0 };
    Mat3::from_diagonal(Vec3::new(
        invert(k.x_axis.x),
        invert(k.y_axis.y),
        invert(k.z_axis.z),
    ))
}

#[inline]
fn apply_normal(
    a: &mut SolverBody,
    b: &mut SolverBody,
    inv_mass_a: f32,
    inv_mass_b: f32,
    normal: Vec3,
    p: &PreparedPoint,
    impulse: f32,
) {
    a.linear_velocity -= normal * (impulse * inv_mass_a);
    b.linear_velocity += normal * (impulse * inv_mass_b);
    a.angular_velocity -= p.wn_a * impulse;
    b.angular_velocity += p.wn_b * impulse;
}

/// Writes two solver bodies back. A fixed body's copy is written too, unchanged (its inverse mass and inertia
/// are zero, so nothing was added); when both indices are equal the second write wins, which is only
/// reachable with a malformed contact.
#[inline]
fn write_pair(bodies: &mut [SolverBody], ia: usize, a: SolverBody, ib: usize, b: SolverBody) {
    bodies[ia] = a;
    bodies[ib] = b;
}
