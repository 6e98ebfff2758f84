//! The direct solve of joint chains: the equality rows of a path of joints solved together, exactly, instead
//! of one joint after another.
//!
//! # Why
//!
//! A soft row settles where its spring force balances the load: `C = λ/(h²·m_eff·ω²)` per substep, with
//! `m_eff` the effective mass *of that row alone*. In a chain of light links carrying a heavy load — a rope of
//! 500 balls swinging, a bridge deck under its own weight — the load is many times the link mass, and solved
//! link by link every link stretches by `load / (m_link·ω²)`: 23 % for the SCENES.md chain. Solving the rows
//! of the whole path as one system (`K·x = Ċ + bias`, `K = J·M⁻¹·Jᵀ`) gives each row the effective mass of
//! the chain behind it, so the stretch no longer grows with the load (Baraff, "Linear-Time Dynamics using
//! Lagrange Multipliers", SIGGRAPH 1996; here specialised to paths, where `K` is block-tridiagonal).
//!
//! # How
//!
//! A path is a sequence of joints in which each consecutive pair shares one dynamic body and every inner
//! body belongs to exactly two joints of the path (fixed bodies couple nothing, so a deck hung between two
//! anchors is a path). With `Bᵢ` the diagonal blocks (`J·M⁻¹·Jᵀ` of joint `i`'s rows over both its bodies)
//! and `Cᵢ` the coupling of joint `i` to joint `i + 1` through their shared body, the block Thomas algorithm
//!
//! ```text
//! S₁ = B₁,                      C'₁ = S₁⁻¹·C₁,   r'₁ = S₁⁻¹·r₁
//! Sᵢ = Bᵢ − Cᵢ₋₁ᵀ·C'ᵢ₋₁,        C'ᵢ = Sᵢ⁻¹·Cᵢ,   r'ᵢ = Sᵢ⁻¹·(rᵢ − Cᵢ₋₁ᵀ·r'ᵢ₋₁)
//! xₙ = r'ₙ,                     xᵢ = r'ᵢ − C'ᵢ·xᵢ₊₁
//! ```
//!
//! solves `K·x = r` in O(n). A path of 32 links or more is swept from both ends at once, the two sides meeting
//! at its middle link, so that they can run on two threads (`elimination.rs`; the same bits on any pool). The soft step of all rows at once takes `r = mass_scale∘(Ċ + bias) +
//! impulse_scale∘(K·λ)` row by row and `Δλ = −x` (for one row this is exactly the Gauss–Seidel row update of
//! [`crate::part::solve_row`]; see `solve_path` for why not each row's soft step from one solve), clamped
//! to the bounds. A rope that is slack and not closing its slack this substep is left out of the system (its
//! row is released); after a solve, a rope the solution would make push is dropped, a rope left out that it
//! would stretch is added, and the system solved again (up to 4 rounds), so slack links never push and links
//! left out are not pulled past their length. The sweep runs in f64 (a 500-link chain's `K` has a condition
//! number near 10⁵), each row's diagonal gets a 10⁻⁶ relative regularisation and a vanishing pivot gives 0 —
//! a bridge hung from two anchors has redundant rows and a singular `K`. A path of one-row joints (a rope
//! chain) takes a scalar sweep.
//!
//! Each `Sᵢ` is symmetric positive semi-definite (a Schur complement of `K`), so it is factorised as
//! `L·D·Lᵀ` without pivoting (`ldl_factor`), and the sweep is carried in the factors: `Cᵢ₋₁ᵀ·C'ᵢ₋₁ =
//! Wᵀ·D⁻¹·W` with `W = L⁻¹·Cᵢ₋₁`, symmetric, so only its upper triangle is formed (see `block_sweep`). The
//! blocks are as wide as the path's widest joint (6 × 6 for fixed joints and limited hinges, 5 × 5 for hinges, 3 × 3 for ball joints), with fixed loop
//! bounds; rows of a narrower link, and rows not in the system, are zero rows and columns, whose pivots
//! vanish and whose unknowns are 0. `Bᵢ` is built from its upper triangle, with each row's `I⁻¹·J_angular`
//! turned once when the row is built (`JointRows::turned`), shared by `Bᵢ`, `Cᵢ` and the impulses' updates.
//!
//! # Positions
//!
//! The same machinery projects positions after the substeps (`JointSolver::project_positions`): with the
//! rows' biases set to their position errors `C`, the solve of `K·x = C` moves the bodies by `−M⁻¹·Jᵀ·x`
//! (`project_rows` is the one-joint Gauss–Seidel version used after it). Where that step kinks a pulled,
//! curved chain, it is solved again with each rope and rod stiffened against turning by two compliant rows
//! across it (`Link::stiffen`: the geometric stiffness, which makes a rope chain a path of 3-row links for
//! the block sweep). Derivations and measurements are in `docs/physics.md`, "Chains solved directly".
//!
//! # Rows and factorisations kept between passes
//!
//! A step runs `solve` (bias on), the world integrates positions, `relax` (bias off), per substep, then the
//! projection. Between a relax pass and the next substep's solve pass (and the projection after the last
//! one) only velocities change, so both passes see the same Jacobians and the same `K`. A `Link` therefore
//! stays with its joint from pass to pass (one per path member, in the solver) and records the pose its rows
//! were built at (`PoseKey`: the bits of both bodies' `delta_position` and `delta_rotation`, all that row
//! building reads of the bodies). At an unchanged pose the pass keeps the rows — Jacobians, turned vectors
//! and position errors `C` — and recomputes only the targets, which depend on the stage, from the stored
//! `C` with the functions that built them (`TargetRule`); any other pose, and the first pass of a step,
//! builds them again. The sweep then keeps each link's factorisation (`B`, `C`, `L`, `D⁻¹`, `W`, `V`) while
//! it and its neighbours have the rows and the rows in the system (`FactorKey`) it was made for — a rope
//! joining or leaving the system refactorises from the link before it on — and sweeps only the right-hand
//! side. Everything kept is what the same operations on the same values would give again, so a pass gives
//! the bits it gave when it rebuilt everything. Within a pass, an active-set round that changes the system
//! from some link on sweeps forward again only from the link before it (`Resume`).
//!
//! # Rows carried through the step
//!
//! A hinge's rows (3 point rows, 2 alignment rows) have Jacobians that depend on its bodies' rotations alone.
//! A velocity pass at a new pose therefore keeps a hinge's rows, and the factorisation, while neither body
//! has turned by more than `CARRY_ANGLE` (0.01 rad) since they were built this step, and carries only the
//! position errors to the new pose, to first order: `C = C₀ + J·Δ` (`Link::carry`). A deck whose planks
//! swing slowly then factorises once per step instead of at every pose (five times: the first solve pass
//! and each relax pass). Exact errors with the kept rows would not do: see `Link::carry`. The projection
//! always builds its rows at the pose (its Newton steps need the pose's Jacobians). Ball joints are not
//! carried: in a whipping spherical chain the balls turn with their links, and carried rows let the links
//! stretch far more than rows built at the pose.
//!
//! The rows outlive the step, too. The last relax pass of a step builds every hinge's rows at the step's
//! final pose for the projection; the next step's passes carry those rows (and their factorisation) from
//! there instead of building them again at the step's first pass, measuring the turn and the displacement
//! in world terms (`BuiltAt`: both joint frames and the vector between the centres of mass at the build).
//! A path keeps its rows only whole (same joints, same bodies, same inverse masses) and every link of it
//! keeps the inverse inertias its rows were turned with until the last relax pass builds them all again:
//! `K` must use one inverse inertia per body — a link built with the new step's next to links kept with
//! the last step's makes a bridge's singular `K` inconsistent, and the regularisation turns that into
//! impulses that blow the bridge up. The kept rows are state: a snapshot holds them ([`crate::KeptRows`]).

mod active_set;
mod components;
mod elimination;
mod factor;
mod graph;
mod link;
mod min_degree;
mod pose;
mod projection;
mod reuse;
mod row;
mod sparse_ldl;
mod sweep;
mod system;
#[cfg(test)]
mod tests;
pub mod tether;
pub(crate) mod topology;
#[cfg(test)]
mod two_sided_tests;

pub(crate) use active_set::activate_violations;
pub(crate) use graph::DirectGraph;
#[cfg(test)]
pub(crate) use link::empty_link;
pub(crate) use link::{Link, link_at, resize_links};
pub(crate) use pose::{BuiltAt, CARRY_ANGLE, PoseKey};
pub(crate) use projection::project_rows;
pub(crate) use row::{
    InvMass, JointRows, MAX_ROWS, Real, Row, Side, TargetRule, equality_violation, one_row,
};
pub(crate) use sweep::{Resume, solve_path};
