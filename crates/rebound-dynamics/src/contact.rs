//! The contact-constraint kernel: soft non-penetration with a push-out speed cap, Coulomb friction on each
//! manifold's patch (two tangents with a circular cone at the centre of the points, and twist about the
//! normal), and restitution as a bounce inside the solve. Stages: *prepare* → per substep *warm start*,
//! *solve* (bias on, bounces included), *relax* (bias off) → *store impulses*.
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
//! bodies do not gain energy. Friction, at the patch centre `c` (the mean of the points' anchors):
//! `λ_t ← clamp_circle(λ_t − M_t·v_t, μ·Σλ)`, and about the normal `τ ← clamp(τ − m_τ·n·(ω_b − ω_a),
//! ±μ·Σλ·|r − c|)` (`docs/physics.md`, "Contacts"). Restitution is a bounce inside the solve pass, once per
//! point and step: when a point touches (or, between two moving bodies, closes its gap within the substep)
//! having approached faster than the threshold, one impulse sets its normal velocity to `+C_r·v_n⁻`, where
//! `v_n⁻` is the approach speed — the most negative normal velocity any pass met before an impulse acted, so
//! a body that keeps falling for part of the step rebounds from its speed at impact, not its speed when the
//! step began. The bounce is kept out of the accumulated impulse, so the later passes see a separating
//! contact and leave it alone; and since it happens within a Gauss–Seidel pass, an impulse passes along a row
//! of touching balls (Newton's cradle) instead of moving the row as one block.

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
    max_normal_impulse: f32,
    normal_mass: f32,
    /// The point's distance from its manifold's patch centre (m): its lever against twist.
    twist_radius: f32,
    rn_a: Vec3,
    rn_b: Vec3,
    wn_a: Vec3,
    wn_b: Vec3,
}

/// A manifold's friction patch: two tangent rows at the centre of its points and one twist row about the
/// normal, in place of two tangent rows per point (`docs/physics.md`, Contacts, "Friction").
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Patch {
    /// The centre `c` of the points, relative to body A's centre of mass (m).
    center_a: Vec3,
    /// `Σ|ρ|²` over the points, `ρ = r_a − c` a point's offset from the centre (m²).
    spread: f32,
    /// Accumulated tangent impulse in the manifold's tangent basis (N·s).
    tangent_impulse: Vec2,
    tangent_mass: [f32; 2],
    rt_a: [Vec3; 2],
    rt_b: [Vec3; 2],
    wt_a: [Vec3; 2],
    wt_b: [Vec3; 2],
    /// Accumulated twist impulse about the normal (N·m·s).
    twist_impulse: f32,
    twist_mass: f32,
    /// `I_a⁻¹·n` and `I_b⁻¹·n`.
    twist_a: Vec3,
    twist_b: Vec3,
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
    /// Index of the manifold's friction patch in the solver's patches (scalar path only).
    patch: usize,
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
    /// The friction patches of the scalar path's manifolds.
    patches: Vec<Patch>,
    rolling: Vec<Rolling>,
    /// The wide-solved manifolds, four at a time, colour after colour (see [`wide`]).
    batches: Vec<wide::Batch>,
    /// The batches' point slots.
    slots: Vec<wide::PointX4>,
    /// The batches' friction patches.
    patches_x4: Vec<wide::PatchX4>,
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
        self.patches.clear();
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
                patch: NO_POINTS,
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
            &mut self.patches_x4,
            &mut self.scalar,
        );
        for &index in &self.scalar {
            let c = &mut self.contacts[index];
            let points = contacts[c.source].points();
            let patch = input.patch(c, points);
            c.first_point = self.points.len();
            c.patch = self.patches.len();
            for point in points {
                self.points
                    .push(input.scalar_point(c, point, patch.center_a));
            }
            self.patches.push(patch);
        }
        skipped
    }

    /// Stage *warm start*: applies the accumulated impulses of the last substep (or the last step) again, so
    /// the iterations start from the previous answer.
    pub fn warm_start(&self, bodies: &mut [SolverBody]) {
        for batch in &self.batches {
            batch.warm_start(&self.slots, &self.patches_x4, bodies);
        }
        for c in self.scalar.iter().map(|&i| &self.contacts[i]) {
            let (mut a, mut b) = (bodies[c.body_a], bodies[c.body_b]);
            // All normal impulses act along n: their sum moves the linear velocities once (as the wide path).
            let mut pushed = 0.0;
            for p in &self.points[c.first_point..c.first_point + c.point_count] {
                pushed += p.normal_impulse;
                a.angular_velocity -= p.wn_a * p.normal_impulse;
                b.angular_velocity += p.wn_b * p.normal_impulse;
            }
            a.linear_velocity -= c.normal * (pushed * c.inv_mass_a);
            b.linear_velocity += c.normal * (pushed * c.inv_mass_b);
            if let Some(patch) = self.patches.get(c.patch) {
                patch.warm_start(c, &mut a, &mut b);
            }
            if let Some(r) = c.rolling.map(|i| &self.rolling[i]) {
                a.angular_velocity -= r.inv_inertia_a * r.impulse;
                b.angular_velocity += r.inv_inertia_b * r.impulse;
            }
            write_pair(bodies, c.body_a, a, c.body_b, b);
        }
    }

    /// Stages *solve* (`Bias::On`) and *relax* (`Bias::Off`): one Gauss–Seidel pass over every contact,
    /// normal impulses first, then the friction patch: tangents clamped to the circle of radius μ·Σλ_n, twist
    /// to ±μ·Σλ_n·|ρ|.
    ///
    /// The current separation of a point is `s₀ + n·(Δp_b − Δp_a) + (Δq_b⁻¹·n − n)·r_b − (Δq_a⁻¹·n − n)·r_a`:
    /// `n·(Δq·r − r) = (Δq⁻¹·n − n)·r` for a rotation, so the two rotations are done once per manifold instead of
    /// once per point and body.
    ///
    /// Manifolds without restitution or rolling resistance are solved four at a time, in graph-coloured
    /// batches in `Vec4` lanes (`docs/physics.md`, Contacts); the rest one by one after them.
    pub fn solve(&mut self, bodies: &mut [SolverBody], ctx: &StepContext, bias: Bias) {
        for batch in &self.batches {
            batch.solve(&mut self.slots, &mut self.patches_x4, bodies, ctx, bias);
        }
        for &index in &self.scalar {
            let c = &self.contacts[index];
            let (mut a, mut b) = (bodies[c.body_a], bodies[c.body_b]);
            let normal = c.normal;
            let points = &mut self.points[c.first_point..c.first_point + c.point_count];
            let shift = normal.dot(b.delta_position - a.delta_position);
            let turn_a = rotate_inverse(a.delta_rotation, normal) - normal;
            let turn_b = rotate_inverse(b.delta_rotation, normal) - normal;
            // Σλ_n and Σλ_n·|ρ| after the normal rows: the friction patch's limits.
            let (mut total, mut twist_total) = (0.0, 0.0);
            // The normal rows change the linear velocities only along n: carry `u = n·(v_b − v_a)` and the
            // sum of the applied impulses, applied to the velocities once after the rows (as the wide path).
            let mut u = normal.dot(b.linear_velocity - a.linear_velocity);
            let u_gain = (c.inv_mass_a + c.inv_mass_b) * normal.dot(normal);
            let mut pushed = 0.0;
            for p in points.iter_mut() {
                let s = p.separation + shift + turn_b.dot(p.anchor_b) - turn_a.dot(p.anchor_a);
                let vn = u + b.angular_velocity.dot(p.rn_b) - a.angular_velocity.dot(p.rn_a);
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
                    pushed += impulse;
                    u += impulse * u_gain;
                    a.angular_velocity -= p.wn_a * impulse;
                    b.angular_velocity += p.wn_b * impulse;
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
                total += accumulated;
                twist_total += accumulated * p.twist_radius;
                p.max_normal_impulse = p.max_normal_impulse.max(applied);
                pushed += applied;
                u += applied * u_gain;
                a.angular_velocity -= p.wn_a * applied;
                b.angular_velocity += p.wn_b * applied;
            }
            a.linear_velocity -= normal * (pushed * c.inv_mass_a);
            b.linear_velocity += normal * (pushed * c.inv_mass_b);
            if let Some(patch) = self.patches.get_mut(c.patch) {
                patch.solve(c, &mut a, &mut b, total, twist_total);
            }
            if let Some(r) = c.rolling.map(|i| &mut self.rolling[i]) {
                let total_normal = total;
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
        for &index in &self.scalar {
            let c = &self.contacts[index];
            let patch = self.patches.get(c.patch).copied().unwrap_or_default();
            let share = PatchShare::new(
                c.normal,
                c.tangents,
                patch.tangent_impulse.to_array(),
                patch.twist_impulse,
                patch.spread,
                c.point_count,
            );
            for (k, p) in self.points[c.first_point..][..c.point_count]
                .iter()
                .enumerate()
            {
                let tangent = share.at(p.anchor_a - patch.center_a);
                f(c.source, k, p.normal_impulse, tangent, p.max_normal_impulse);
            }
        }
        for batch in &self.batches {
            for (index, impulses) in batch.results(&self.slots, &self.patches_x4, &self.contacts) {
                let c = &self.contacts[index];
                for (k, (normal, tangent, max)) in impulses.enumerate() {
                    f(c.source, k, normal, tangent, max);
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
    /// The prepared form of `point`, a point of manifold `c` whose patch centre is `center_a`: anchors, angular
    /// Jacobian terms, effective mass, twist lever and the warm-start normal impulse. The pre-step normal
    /// velocity, which only a bounce reads, is left at 0 (see [`PrepareInput::scalar_point`]).
    #[inline]
    fn point(&self, c: &PreparedContact, point: &ContactPoint, center_a: Vec3) -> PreparedPoint {
        let (pa, pb) = (&self.params[c.body_a], &self.params[c.body_b]);
        let normal = c.normal;
        let (ra, rb) = (point.anchor_a, point.anchor_b);
        let rn_a = ra.cross(normal);
        let rn_b = rb.cross(normal);
        let wn_a = pa.inv_inertia_world * rn_a;
        let wn_b = pb.inv_inertia_world * rn_b;
        let k_normal = pa.inv_mass + pb.inv_mass + rn_a.dot(wn_a) + rn_b.dot(wn_b);
        let rho = ra - center_a;
        PreparedPoint {
            anchor_a: ra,
            anchor_b: rb,
            separation: point.separation,
            relative_velocity: 0.0,
            bounced: false,
            normal_impulse: if self.ctx.warm_starting {
                point.normal_impulse
            } else {
                0.0
            },
            max_normal_impulse: 0.0,
            normal_mass: if k_normal > 0.0 { 1.0 / k_normal } else { 0.0 },
            twist_radius: rho.dot(rho).sqrt(),
            rn_a,
            rn_b,
            wn_a,
            wn_b,
        }
    }

    /// [`PrepareInput::point`] with the pre-step normal velocity, for the scalar path (which bounces).
    fn scalar_point(
        &self,
        c: &PreparedContact,
        point: &ContactPoint,
        center_a: Vec3,
    ) -> PreparedPoint {
        let (sa, sb) = (&self.bodies[c.body_a], &self.bodies[c.body_b]);
        let dv = sb.velocity_at(point.anchor_b) - sa.velocity_at(point.anchor_a);
        PreparedPoint {
            relative_velocity: dv.dot(c.normal),
            ..self.point(c, point, center_a)
        }
    }

    /// The friction patch of manifold `c` with points `points`: the centre of the points on each body, the
    /// tangent rows there, the twist row, and the warm-start impulses recovered from the points' stored
    /// friction impulses ([`PatchShare`] in reverse: their sum, and their moment about the centre).
    fn patch(&self, c: &PreparedContact, points: &[ContactPoint]) -> Patch {
        let (pa, pb) = (&self.params[c.body_a], &self.params[c.body_b]);
        let normal = c.normal;
        let count = points.len() as f32;
        let [center_a, center_b, warm_linear] = patch_sums(points);
        let (mut spread, mut warm_twist) = (0.0, 0.0);
        for p in points {
            let rho = p.anchor_a - center_a;
            spread += rho.dot(rho);
            warm_twist += rho.cross(p.tangent_impulse).dot(normal);
        }
        let mass_sum = pa.inv_mass + pb.inv_mass;
        let invert = |k: f32| if k > 0.0 && count > 0.0 { 1.0 / k } else { 0.0 };
        let mut patch = Patch {
            center_a,
            spread,
            twist_a: pa.inv_inertia_world * normal,
            twist_b: pb.inv_inertia_world * normal,
            ..Patch::default()
        };
        for (i, t) in c.tangents.iter().enumerate() {
            patch.rt_a[i] = center_a.cross(*t);
            patch.rt_b[i] = center_b.cross(*t);
            patch.wt_a[i] = pa.inv_inertia_world * patch.rt_a[i];
            patch.wt_b[i] = pb.inv_inertia_world * patch.rt_b[i];
            patch.tangent_mass[i] = invert(
                mass_sum + patch.rt_a[i].dot(patch.wt_a[i]) + patch.rt_b[i].dot(patch.wt_b[i]),
            );
        }
        patch.twist_mass = invert(normal.dot(patch.twist_a) + normal.dot(patch.twist_b));
        if self.ctx.warm_starting {
            patch.tangent_impulse = Vec2::new(
                warm_linear.dot(c.tangents[0]),
                warm_linear.dot(c.tangents[1]),
            );
            patch.twist_impulse = warm_twist;
        }
        patch
    }
}

impl Patch {
    /// Applies the accumulated friction impulses again (stage *warm start*).
    fn warm_start(&self, c: &PreparedContact, a: &mut SolverBody, b: &mut SolverBody) {
        let [x, y] = self.tangent_impulse.to_array();
        self.apply_tangent(c, a, b, x, y);
        self.apply_twist(a, b, self.twist_impulse);
    }

    /// Applies the tangent impulses `x` and `y` (N·s, along the manifold's tangents) at the patch centre.
    fn apply_tangent(
        &self,
        c: &PreparedContact,
        a: &mut SolverBody,
        b: &mut SolverBody,
        x: f32,
        y: f32,
    ) {
        let linear = c.tangents[0] * x + c.tangents[1] * y;
        a.linear_velocity -= linear * c.inv_mass_a;
        b.linear_velocity += linear * c.inv_mass_b;
        a.angular_velocity -= self.wt_a[0] * x;
        a.angular_velocity -= self.wt_a[1] * y;
        b.angular_velocity += self.wt_b[0] * x;
        b.angular_velocity += self.wt_b[1] * y;
    }

    /// Applies the twist impulse `impulse` (N·m·s, about the normal).
    fn apply_twist(&self, a: &mut SolverBody, b: &mut SolverBody, impulse: f32) {
        a.angular_velocity -= self.twist_a * impulse;
        b.angular_velocity += self.twist_b * impulse;
    }

    /// One pass of the patch's rows after the normal rows: the tangent impulse clamped to the circle of radius
    /// `μ·Σλ_n` (`total`), then the twist impulse to `±μ·Σλ_n·|ρ|` (`twist_total`). The wide path's
    /// equations, in the same order of operations.
    fn solve(
        &mut self,
        c: &PreparedContact,
        a: &mut SolverBody,
        b: &mut SolverBody,
        total: f32,
        twist_total: f32,
    ) {
        let [t0, t1] = c.tangents;
        let dv = b.linear_velocity - a.linear_velocity;
        let vt0 = t0.dot(dv) + b.angular_velocity.dot(self.rt_b[0])
            - a.angular_velocity.dot(self.rt_a[0]);
        let vt1 = t1.dot(dv) + b.angular_velocity.dot(self.rt_b[1])
            - a.angular_velocity.dot(self.rt_a[1]);
        let mut x = self.tangent_impulse.x - self.tangent_mass[0] * vt0;
        let mut y = self.tangent_impulse.y - self.tangent_mass[1] * vt1;
        let limit = c.friction * total;
        let length_squared = x * x + y * y;
        if length_squared > limit * limit {
            let scale = limit / length_squared.sqrt();
            x *= scale;
            y *= scale;
        }
        let (ax, ay) = (x - self.tangent_impulse.x, y - self.tangent_impulse.y);
        self.tangent_impulse = Vec2::new(x, y);
        self.apply_tangent(c, a, b, ax, ay);
        if c.point_count > 1 {
            let spin = c.normal.dot(b.angular_velocity - a.angular_velocity);
            let limit = c.friction * twist_total;
            let candidate = (self.twist_impulse - self.twist_mass * spin)
                .max(-limit)
                .min(limit);
            let applied = candidate - self.twist_impulse;
            self.twist_impulse = candidate;
            self.apply_twist(a, b, applied);
        }
    }
}

/// The centre of `points` on each body — the mean of their anchors relative to body A's and body B's centre
/// of mass (zero without points) — and the sum of the friction impulses they carry from the last step.
pub(crate) fn patch_sums(points: &[ContactPoint]) -> [Vec3; 3] {
    let count = points.len() as f32;
    let per_point = if count > 0.0 { 1.0 / count } else { 0.0 };
    let (mut sum_a, mut sum_b, mut friction) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
    for p in points {
        sum_a += p.anchor_a;
        sum_b += p.anchor_b;
        friction += p.tangent_impulse;
    }
    [sum_a * per_point, sum_b * per_point, friction]
}

/// A patch's friction shared out among its points, for warm starting the next step and for reporting: point
/// `k` at offset `ρ_k` from the centre gets `f_k = λ_t/N + τ·(n × ρ_k)/Σ|ρ|²`. The shares add up to the
/// patch's tangent impulse `λ_t` (the `ρ_k` sum to zero) and their moment about the centre along `n` is its
/// twist impulse `τ` (`ρ × (n × ρ) = n·|ρ|²` for `ρ` in the contact plane), so the next step's patch recovers
/// both from the points, whichever of them persist.
pub(crate) struct PatchShare {
    normal: Vec3,
    linear: Vec3,
    twist: f32,
}

impl PatchShare {
    /// The share-out of tangent impulse `[x, y]` (in basis `tangents`) and twist impulse `twist` of a patch
    /// of `count` points with spread `spread`.
    pub(crate) fn new(
        normal: Vec3,
        tangents: [Vec3; 2],
        [x, y]: [f32; 2],
        twist: f32,
        spread: f32,
        count: usize,
    ) -> Self {
        let linear = tangents[0] * x + tangents[1] * y;
        if count <= 1 {
            // A lone point takes the whole patch and no twist.
            return Self {
                normal,
                linear,
                twist: 0.0,
            };
        }
        Self {
            normal,
            linear: linear / count as f32,
            twist: if spread > 0.0 { twist / spread } else { 0.0 },
        }
    }

    /// The friction impulse (world vector, N·s) of the point at offset `rho` from the patch centre.
    pub(crate) fn at(&self, rho: Vec3) -> Vec3 {
        if self.twist == 0.0 {
            self.linear
        } else {
            self.linear + self.normal.cross(rho) * self.twist
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

/// Writes two solver bodies back. A fixed body's copy is written too, unchanged (its inverse mass and inertia
/// are zero, so nothing was added); when both indices are equal the second write wins, which is only
/// reachable with a malformed contact.
#[inline]
fn write_pair(bodies: &mut [SolverBody], ia: usize, a: SolverBody, ib: usize, b: SolverBody) {
    bodies[ia] = a;
    bodies[ib] = b;
}

#[cfg(test)]
mod tests {
    use super::{ContactPoint, PatchShare, patch_sums};
    use proptest::prelude::*;
    use rebound_math::{Quat, Vec3};

    proptest! {
        /// The friction a patch shares out among its points (for warm starting and reporting) gives the patch
        /// back: the shares sum to its tangent impulse and their moment about the centre, along the normal, is
        /// its twist impulse — which is how the next step's patch recovers both from the points.
        #[test]
        fn shared_out_patch_friction_sums_to_the_patch_impulses(
            tilt in -1.5f32..1.5,
            offsets in prop::collection::vec((-1.0f32..1.0, -1.0f32..1.0), 2..=4),
            x in -2.0f32..2.0,
            y in -2.0f32..2.0,
            twist in -2.0f32..2.0,
        ) {
            let turn = Quat::from_rotation_x(tilt);
            let normal = turn * Vec3::Y;
            let tangents = [turn * Vec3::X, turn * Vec3::Z];
            let base = Vec3::new(0.3, -0.2, 0.1);
            let mut points: Vec<ContactPoint> = offsets
                .iter()
                .map(|&(u, v)| ContactPoint {
                    anchor_a: base + tangents[0] * u + tangents[1] * v,
                    ..ContactPoint::default()
                })
                .collect();
            let [center, _, _] = patch_sums(&points);
            let spread: f32 = points.iter().map(|p| (p.anchor_a - center).length_squared()).sum();
            prop_assume!(spread > 1e-2);
            let share = PatchShare::new(normal, tangents, [x, y], twist, spread, points.len());
            for p in &mut points {
                p.tangent_impulse = share.at(p.anchor_a - center);
            }
            let [_, _, total] = patch_sums(&points);
            let moment: f32 = points
                .iter()
                .map(|p| (p.anchor_a - center).cross(p.tangent_impulse).dot(normal))
                .sum();
            let linear = tangents[0] * x + tangents[1] * y;
            prop_assert!((total - linear).length() < 1e-5 * (1.0 + twist.abs() / spread), "{total} vs {linear}");
            prop_assert!((moment - twist).abs() < 1e-5, "{moment} vs {twist}");
        }
    }
}
