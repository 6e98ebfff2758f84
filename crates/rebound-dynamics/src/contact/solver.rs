//! [`ContactSolver`]: the contact stages as the step calls them — *prepare*, per substep *warm start*,
//! *solve* and *relax*, then *store impulses*. Each stage runs the wide batches first (`super::wide`), then
//! the manifolds left to the scalar path (`super::scalar`), in that order every pass.

use super::bias::Bias;
use super::manifold::Contact;
use super::patch::{Patch, PatchShare};
use super::prepared::{PrepareInput, PreparedContact};
use super::scalar::{self, PreparedPoint, Rolling};
use super::wide::{self, Batches, Coloring};
use crate::{BodyParams, SolverBody, StepContext};
use core::sync::atomic::{AtomicBool, Ordering};
use rebound_math::Vec3;
use rebound_math::par::{self, MIN_ITEMS_PER_TASK};

/// The contact solver: holds the prepared constraints between stages and reuses its buffer from step to
/// step (no allocation once it has grown to the scene's contact count).
#[derive(Debug, Clone, Default)]
pub struct ContactSolver {
    pub(crate) contacts: Vec<PreparedContact>,
    /// The scalar path's points, manifold after manifold.
    pub(crate) points: Vec<PreparedPoint>,
    /// The friction patches of the scalar path's manifolds.
    pub(crate) patches: Vec<Patch>,
    pub(crate) rolling: Vec<Rolling>,
    /// The wide-solved manifolds, four at a time, colour after colour, with their rows (see `super::wide`).
    pub(crate) batches: Batches,
    /// Indices of the manifolds the scalar path solves, after the batches.
    pub(crate) scalar: Vec<usize>,
    pub(crate) coloring: Coloring,
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
        let on_pool = par::is_parallel()
            && prepare_on_pool(contacts, params, body_count, ctx, &mut self.contacts);
        // One after the other where the pool did not prepare them.
        if !on_pool {
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
                let rolling = (contact.rolling_friction > 0.0).then(|| {
                    self.rolling
                        .push(Rolling::new(contact.rolling_friction, pa, pb));
                    self.rolling.len() - 1
                });
                self.contacts
                    .push(PreparedContact::new(source, contact, pa, pb, rolling, ctx));
            }
        }
        // Wide manifolds get their points straight into their batch's lanes; the scalar ones here.
        let input = PrepareInput {
            contacts,
            bodies,
            params,
            ctx,
        };
        self.coloring
            .build(&self.contacts, &input, &mut self.batches, &mut self.scalar);
        for &index in &self.scalar {
            let c = &mut self.contacts[index];
            let points = contacts[c.source].points();
            let patch = Patch::new(&input, c, points);
            c.first_point = self.points.len();
            c.patch = self.patches.len();
            // The deepest shift of a loaded point's rest point moves the manifold's push-out cap with it.
            let mut shift = 0.0_f32;
            for point in points {
                let prepared = PreparedPoint::with_approach(&input, c, point, patch.center_a);
                shift = shift.max(point.separation - prepared.separation);
                self.points.push(prepared);
            }
            c.max_push_out_speed = c.max_push_with_shift(shift);
            self.patches.push(patch);
        }
        skipped
    }

    /// Stage *warm start*: applies the accumulated impulses of the last substep (or the last step) again, so
    /// the iterations start from the previous answer.
    pub fn warm_start(&mut self, bodies: &mut [SolverBody]) {
        wide::warm_start_batches(&self.batches, bodies);
        self.warm_start_scalar(bodies);
    }

    /// Stage *warm start* of the manifolds the scalar path solves.
    pub(crate) fn warm_start_scalar(&self, bodies: &mut [SolverBody]) {
        for c in self.scalar.iter().map(|&i| &self.contacts[i]) {
            scalar::warm_start(
                c,
                &self.points[c.first_point..c.first_point + c.point_count],
                self.patches.get(c.patch),
                c.rolling.map(|i| &self.rolling[i]),
                bodies,
            );
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
        wide::solve_batches(&mut self.batches, bodies, ctx, bias);
        self.solve_scalar(bodies, ctx, bias);
    }

    /// Stages *solve* and *relax* of the manifolds the scalar path solves.
    pub(crate) fn solve_scalar(
        &mut self,
        bodies: &mut [SolverBody],
        ctx: &StepContext,
        bias: Bias,
    ) {
        for &index in &self.scalar {
            let c = &self.contacts[index];
            scalar::solve(
                c,
                &mut self.points[c.first_point..c.first_point + c.point_count],
                self.patches.get_mut(c.patch),
                c.rolling.map(|i| &mut self.rolling[i]),
                bodies,
                ctx,
                bias,
            );
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

    /// Calls `f(source, point, normal_impulse, bounce_impulse)` for every point of every prepared manifold: the
    /// index of its source contact, the point's index in it, its accumulated normal impulse now (N·s) and the
    /// impulse of its bounce this step (N·s, kept out of the accumulated one; 0 if it did not bounce).
    ///
    /// A substep applies its accumulated impulse (the warm start applies the last one, the passes change it),
    /// so the accumulated impulses after each substep, summed, plus the bounce, are what the point pushed with
    /// over the step: what contact force events report.
    pub fn for_each_normal_impulse(&self, mut f: impl FnMut(usize, usize, f32, f32)) {
        for &index in &self.scalar {
            let c = &self.contacts[index];
            for (k, p) in self.points[c.first_point..][..c.point_count]
                .iter()
                .enumerate()
            {
                f(c.source, k, p.normal_impulse, p.bounce_impulse);
            }
        }
        self.batches
            .for_each_normal_impulse(|source, k, normal| f(source, k, normal, 0.0));
    }

    /// Calls `f(source, point, normal_impulse, tangent_impulse, max_normal_impulse)` for every point of every
    /// prepared manifold: the index of its source contact, the point's index in it, its accumulated normal
    /// impulse (N·s), its friction impulse as a world vector (N·s) and the largest normal impulse it applied
    /// in one iteration this step (N·s) — what contact events report as the hit strength. For a caller that
    /// keeps its own contacts: one pass gives it everything [`ContactSolver::store_impulses`] writes and more.
    pub fn for_each_point_result(&self, mut f: impl FnMut(usize, usize, f32, Vec3, f32)) {
        self.scalar_point_results(&mut f);
        self.batches.for_each_point_result(f);
    }

    /// [`ContactSolver::for_each_point_result`] with the batched manifolds' points read back over the thread
    /// pool (the scalar path's first, on this thread): `f` is called once for every point, and all calls for
    /// one source contact are made on one thread, one after the other, so calls for different sources may
    /// write apart at once. The order of the calls is the pool's; what each is given is not.
    pub fn for_each_point_result_on_pool(
        &self,
        f: impl Fn(usize, usize, f32, Vec3, f32) + Sync + Send,
    ) {
        self.scalar_point_results(&mut |source, k, normal, tangent, max| {
            f(source, k, normal, tangent, max);
        });
        self.batches.for_each_point_result_on_pool(&f);
    }

    /// [`ContactSolver::for_each_point_result`] of the manifolds the scalar path solves.
    #[inline(always)]
    fn scalar_point_results(&self, f: &mut impl FnMut(usize, usize, f32, Vec3, f32)) {
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
    }
}

/// Every contact's [`PreparedContact`] into `out`, in order, over the pool, when none is malformed and none
/// has rolling resistance (whose rows are numbered in contact order): what the one-thread loop of
/// [`ContactSolver::prepare`] gives then. Returns `false`, with `out` empty, otherwise.
fn prepare_on_pool(
    contacts: &[Contact],
    params: &[BodyParams],
    body_count: usize,
    ctx: &StepContext,
    out: &mut Vec<PreparedContact>,
) -> bool {
    let plain = AtomicBool::new(true);
    par::map_collect_in_order(contacts, out, MIN_ITEMS_PER_TASK, |source, contact| {
        let (a, b) = (contact.body_a, contact.body_b);
        let (Some(pa), Some(pb)) = (params[..body_count].get(a), params[..body_count].get(b))
        else {
            plain.store(false, Ordering::Relaxed);
            return PreparedContact::new(
                source,
                contact,
                &BodyParams::WORLD,
                &BodyParams::WORLD,
                None,
                ctx,
            );
        };
        if a == b || !contact.normal.is_finite() || contact.rolling_friction > 0.0 {
            plain.store(false, Ordering::Relaxed);
        }
        PreparedContact::new(source, contact, pa, pb, None, ctx)
    });
    if plain.into_inner() {
        return true;
    }
    out.clear();
    false
}
