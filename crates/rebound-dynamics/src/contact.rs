//! The contact-constraint kernel: soft non-penetration with a push-out speed cap, Coulomb friction on each
//! manifold's patch (two tangents with a circular cone at the centre of the points, and twist about the
//! normal), and restitution as a bounce inside the solve. Stages: *prepare* → per substep *warm start*,
//! *solve* (bias on, bounces included), *relax* (bias off) → *store impulses*.
//!
//! Contacts arrive as plain data ([`Contact`]); the collision backend (or a test) makes them. Bodies are
//! referred to by their index into the solver arrays ([`SolverBody`](crate::SolverBody),
//! [`BodyParams`](crate::BodyParams)).
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
//! point and approach: when a point touches (or, between two moving bodies, closes its gap within the substep)
//! having approached faster than the threshold, one impulse sets its normal velocity to `+C_r·v_n⁻`, where
//! `v_n⁻` is the approach speed — the most negative normal velocity any pass met before an impulse acted, so
//! a body that keeps falling for part of the step rebounds from its speed at impact, not its speed when the
//! step began. The bounce is kept out of the accumulated impulse, so the later passes see a separating
//! contact and leave it alone; and since it happens within a Gauss–Seidel pass, an impulse passes along a row
//! of touching balls (Newton's cradle) instead of moving the row as one block.
//!
//! # Files
//!
//! - `manifold.rs`: [`Contact`] and [`ContactPoint`], the input and output of the stages.
//! - `bias.rs`: [`Bias`], which pass of a substep a solve is.
//! - `solver.rs`: [`ContactSolver`], the stages as the step calls them.
//! - `prepared.rs`: what *prepare* makes of a manifold for either path, and what it reads.
//! - `scalar.rs`: one manifold at a time, with the bounce and rolling resistance.
//! - `patch.rs`: the scalar path's friction patch, and how a patch's impulses are shared among its points.
//! - `stack_loads.rs`: [`StackLoads`], the weight each resting manifold carries, handed down the contact
//!   graph, which moves the rest point of its soft rows at preparation.
//! - `wide.rs` and `wide/`: four manifolds at a time in `Vec4` lanes — colouring, batches, lane arithmetic.
//! - `team.rs`: the passes as a team of threads runs them, a colour group's batches split among it.

mod bias;
mod manifold;
mod patch;
mod prepared;
mod scalar;
mod solver;
mod stack_loads;
mod team;
mod wide;

pub use bias::Bias;
pub use manifold::{Contact, ContactPoint, MAX_CONTACT_POINTS};
pub use solver::ContactSolver;
pub use stack_loads::{StackLoads, Support};
pub use team::ContactTeam;
