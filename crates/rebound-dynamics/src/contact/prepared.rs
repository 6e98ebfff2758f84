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
    /// The normal force the manifold carries at rest (N, [`Contact::load`]).
    pub(crate) load: f32,
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
        Self {
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
            max_push_out_speed: ctx.max_push_out_speed.min(contact.push_out_speed),
            both_dynamic,
            moving_surface: contact.surface_velocity != Vec3::ZERO,
            load: contact.load,
        }
    }

    /// The preload of a point with normal mass `normal_mass` (kg), as a velocity bias (m/s) its soft row
    /// subtracts: the leak `impulse_scale·λ` of the row's share `λ₀ = load·h/N` of the manifold's load, made
    /// a bias (`λ₀·impulse_scale/(m_n·mass_scale)`), less the bias of the overlap `ε` it may keep
    /// ([`StepContext::resting_overlap`]). At rest (`v = 0`, `λ = λ₀`) the row then balances at the overlap
    /// `min(ε, λ₀/(m_n·h·ω²))` instead of `λ₀/(m_n·h·ω²)`: whatever the load, never deeper than `ε`. 0
    /// without a load or without `ε`.
    #[inline]
    pub(crate) fn preload(&self, normal_mass: f32, ctx: &StepContext) -> f32 {
        let (Some(resting_overlap), true) = (ctx.resting_overlap, self.load > 0.0) else {
            return 0.0;
        };
        let h = ctx.h;
        let soft = self.softness;
        let denominator = normal_mass * soft.mass_scale * self.point_count as f32;
        if !(self.load > 0.0 && denominator > 0.0) {
            return 0.0;
        }
        let leak = self.load * h * soft.impulse_scale / denominator;
        (leak - soft.bias_rate * resting_overlap).max(0.0)
    }
}

/// What *prepare* reads: the contacts as given and the bodies' start-of-step state.
pub(crate) struct PrepareInput<'a> {
    pub(crate) contacts: &'a [Contact],
    pub(crate) bodies: &'a [SolverBody],
    pub(crate) params: &'a [BodyParams],
    pub(crate) ctx: &'a StepContext,
}
