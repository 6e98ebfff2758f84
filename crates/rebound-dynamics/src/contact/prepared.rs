//! What stage *prepare* makes of a manifold, shared by the scalar and the wide path: the manifold's header
//! ([`PreparedContact`]: bodies, tangent basis, masses, softness, where its points and patch live) and what
//! *prepare* reads ([`PrepareInput`]).

use super::manifold::Contact;
use crate::{BodyParams, Softness, SolverBody, StepContext};
use rebound_math::Vec3;

/// `first_point` of a manifold whose points live in a wide batch.
pub(crate) const NO_POINTS: usize = usize::MAX;

/// A prepared contact manifold. On the scalar path its points live in the solver's flat point array
/// (`first_point .. first_point + point_count`), so a one-point manifold (a ball on the ground) costs one
/// point, not four, and a pass streams no unused slots; on the wide path they live in its batch's lanes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct PreparedContact {
    /// Index of the source [`Contact`] in the slice given to `prepare`.
    pub(crate) source: usize,
    pub(crate) body_a: usize,
    pub(crate) body_b: usize,
    pub(crate) first_point: usize,
    pub(crate) point_count: usize,
    /// Index of the manifold's friction patch in the solver's patches (scalar path only).
    pub(crate) patch: usize,
    /// Index of the manifold's rolling-resistance block, or `None` without rolling friction.
    pub(crate) rolling: Option<usize>,
    pub(crate) normal: Vec3,
    pub(crate) tangents: [Vec3; 2],
    pub(crate) friction: f32,
    pub(crate) restitution: f32,
    pub(crate) inv_mass_a: f32,
    pub(crate) inv_mass_b: f32,
    pub(crate) softness: Softness,
    /// The push-out speed cap of this manifold (m/s): the step's, or the contact's if lower.
    pub(crate) max_push_out_speed: f32,
    /// Whether both bodies are moved by the solver (not fixed or kinematic).
    pub(crate) both_dynamic: bool,
    /// The depth (m) at which a point's soft row holds its share of the manifold's load
    /// ([`Contact::load`]), per unit of the point's inverse normal mass (kg·m; 0 without a load): see
    /// [`PreparedContact::load_shift`].
    pub(crate) load_depth: f32,
    /// Whether the contact has a surface velocity ([`Contact::surface_velocity`]): only the scalar path's
    /// patch drives friction to one.
    pub(crate) moving_surface: bool,
}

impl PreparedContact {
    /// The header of `contact` (index `source` in the slice given to `prepare`) between bodies with
    /// parameters `pa` and `pb`: a tangent basis for the normal, the bodies' inverse masses and the softness
    /// of a contact between two moving bodies or against a fixed one. Its points and patch are placed later
    /// (`first_point` and `patch` start as [`NO_POINTS`]).
    #[inline]
    pub(crate) fn new(
        source: usize,
        contact: &Contact,
        pa: &BodyParams,
        pb: &BodyParams,
        rolling: Option<usize>,
        ctx: &StepContext,
    ) -> Self {
        let normal = contact.normal;
        let (t1, t2) = normal.any_orthonormal_pair();
        let both_dynamic = pa.is_dynamic() && pb.is_dynamic();
        let softness = if both_dynamic {
            ctx.contact_softness
        } else {
            ctx.static_softness
        };
        let point_count = contact.points().len();
        Self {
            source,
            body_a: contact.body_a,
            body_b: contact.body_b,
            first_point: NO_POINTS,
            point_count,
            patch: NO_POINTS,
            rolling,
            normal,
            tangents: [t1, t2],
            friction: contact.friction,
            restitution: contact.restitution,
            inv_mass_a: pa.inv_mass,
            inv_mass_b: pb.inv_mass,
            softness,
            max_push_out_speed: ctx.max_push_out_speed.min(contact.push_out_speed),
            both_dynamic,
            moving_surface: contact.surface_velocity != Vec3::ZERO,
            load_depth: load_depth(contact.load, point_count, softness, ctx),
        }
    }

    /// How far (m) the rest point of a point's soft row moves into the overlap for its share of the load,
    /// given the point's inverse normal mass `k_normal` (1/kg): `max(d − ε, 0)` with `d` the depth at which
    /// the soft row holds the share (`load_depth·k_normal`) and `ε` the overlap it may keep
    /// ([`StepContext::resting_overlap`]). Prepare subtracts it from the point's separation, so the same
    /// spring, damping and push-out cap act about the overlap `min(ε, d)` instead of `d`: at rest
    /// (`v = 0`, `λ = λ₀`) the row balances there, never deeper than `ε` whatever the load. 0 without a
    /// load.
    #[inline]
    pub(crate) fn load_shift(&self, k_normal: f32, ctx: &StepContext) -> f32 {
        let overlap = ctx.resting_overlap.unwrap_or(0.0);
        let shift = self.load_depth * k_normal - overlap;
        if shift > 0.0 { shift } else { 0.0 }
    }

    /// The push-out speed cap (m/s) of a manifold whose points' rest points moved by at most `shift` (m,
    /// [`PreparedContact::load_shift`]): the cap on the bias `bias_rate·s` of the unmoved separation `s`
    /// becomes one on `bias_rate·(s − shift)`, `bias_rate·shift` further, so the load is held whatever the
    /// cap.
    #[inline]
    pub(crate) fn max_push_with_shift(&self, shift: f32) -> f32 {
        self.max_push_out_speed + self.softness.bias_rate * shift
    }
}

/// `PreparedContact::load_depth` of a manifold of `point_count` points carrying `load` (N) with softness
/// `soft`: a point's share `λ₀ = load·h/N` of the load over substep `h` balances the soft row's leak
/// `impulse_scale·λ₀` with the bias `bias_rate·d` where `m_n·mass_scale·bias_rate·d = impulse_scale·λ₀`,
/// at the depth `d = λ₀·impulse_scale/(mass_scale·bias_rate) · (1/m_n)` (that is `λ₀/(m_n·h·ω²)`, load over
/// stiffness). 0 without a load or without [`StepContext::resting_overlap`].
#[inline]
fn load_depth(load: f32, point_count: usize, soft: Softness, ctx: &StepContext) -> f32 {
    if !(load > 0.0 && ctx.resting_overlap.is_some()) {
        return 0.0;
    }
    let denominator = soft.mass_scale * soft.bias_rate * point_count as f32;
    if denominator > 0.0 {
        load * ctx.h * soft.impulse_scale / denominator
    } else {
        0.0
    }
}

/// What *prepare* reads: the contacts as given and the bodies' start-of-step state.
pub(crate) struct PrepareInput<'a> {
    pub(crate) contacts: &'a [Contact],
    pub(crate) bodies: &'a [SolverBody],
    pub(crate) params: &'a [BodyParams],
    pub(crate) ctx: &'a StepContext,
}
