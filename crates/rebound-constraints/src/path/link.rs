//! One link of a path as the path solver sees it ([`Link`]): a joint's rows, its impulses in the system,
//! which rows take part, and what is kept from pass to pass (the rows' pose, the factorisation, the rows
//! carried from an earlier pose). Lives from *prepare* through every solve and relax pass to the projection,
//! and (its rows) into the next step.

use super::factor::Block;
use super::pose::{BuiltAt, PoseKey};
use super::row::{InvMass, JointRows, MAX_ROWS, Real};
use rebound_math::{Mat3, Vec4};

/// What a link's stored factorisation was made for: the sweep's layout (`width`: the block width, 1 for the
/// scalar sweep, plus, for a path solved from both ends, its length times 8 — the length places the meeting
/// link and so which way each link was eliminated, see [`super::elimination::layout`]), the rows in the
/// system and the sharing with the next link. Together with unchanged rows (the key is dropped when they are
/// built again) and the same key for every link of the path, the factorisation would come out the same
/// bits, so [`solve_path`] keeps it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) struct FactorKey {
    pub(super) width: usize,
    pub(super) active: [bool; MAX_ROWS],
    pub(super) shared: Option<(bool, bool)>,
}

impl FactorKey {
    /// The key of `link`'s current rows in the system, for a sweep of layout `width`.
    #[inline]
    pub(super) fn of(link: &Link, width: usize) -> Self {
        Self {
            width,
            active: link.active,
            shared: link.shared_with_next,
        }
    }
}

/// What a link's system is solved for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Mode {
    /// A velocity pass (solve, relax): `K·x = Ċ + bias`, and the result changes the bodies' velocities.
    Velocity,
    /// A position projection: the rows' biases hold their position errors `C`, `K·x = C`, and the result
    /// moves the bodies.
    Position,
}

/// Which step's inverse masses a link's rows are turned with. A path whose rows were kept from the last step
/// ([`Link::new_step`]) builds rows with the kept rows' inverse masses until its last relax pass
/// ([`Link::end_last_step`]), so that every link of the path turns a body by the same inverse inertia.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Masses {
    /// This step's: the bodies' inverse masses and inertias at its start.
    ThisStep,
    /// Those of the rows kept from the last step.
    LastStep,
}

/// What a pass at the bodies' current pose may keep of a link's rows ([`PoseKey`]s compare the bits of the
/// pose).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum RowsAt {
    /// Nothing: the next pass builds the rows (or carries rows built earlier, [`Link::carry`]).
    Unknown,
    /// The rows were built at the pose `at`: a pass there recomputes only their targets ([`Link::reuse`]).
    /// If they were carried since to the pose `carried_to` ([`Link::carry`]), a pass there recomputes the
    /// targets from the carried errors ([`Link::recarry`]).
    Built {
        /// The pose of the build.
        at: PoseKey,
        /// The pose the rows were last carried to, if any.
        carried_to: Option<PoseKey>,
    },
    /// Rows built at no pose of this step (kept from the last one) were carried to the pose `to`.
    Carried {
        /// The pose carried to.
        to: PoseKey,
    },
}

/// The rows whose residuals the block sweep computes four lanes wide ([`Link::residual`]).
pub(super) const LANES: usize = 4;

/// One link of a path as the direct solve sees it: the joint's rows, which of its bodies it shares with the
/// next link (`true` = body B), its accumulated impulses and which rows take part.
///
/// Laid out hot fields first (`repr(C)`): what every pass reads of every link — impulses, active set, the
/// keys of the kept rows and factorisation, the scalar sweep's entries, then the rows ([`JointRows`], also
/// ordered so) — and the 6 × 6 blocks of the block sweep last. A link is about 2.5 kB; a 500-rope chain's links
/// are a megabyte, far more than the first-level cache, and each pass sweeps them several times (rows and
/// activation, forward and back substitution, the active-set check, the update): packed so, a one-row link's
/// reads sit in the record's first cache lines.
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C)]
pub(crate) struct Link {
    pub lambda: [f32; MAX_ROWS],
    pub active: [bool; MAX_ROWS],
    /// The side of this joint on the body shared with the next link, and the side of the next link on it.
    pub shared_with_next: Option<(bool, bool)>,
    /// What the pass solves for: velocities (solve, relax) or positions (the projection).
    pub(super) mode: Mode,
    /// Which step's inverse masses rows built now take ([`Masses`]).
    pub(super) masses: Masses,
    /// What the factorisation (`scalar`, or `factor`, `v`, `w`, `inv_pivot` and the blocks) was made for;
    /// `None` when it is stale.
    pub(super) factored: Option<FactorKey>,
    /// The scalar sweep's entries of a one-row link ([`solve_scalar_path`]).
    pub(super) scalar: ScalarEntries,
    /// The poses the rows were built at and carried to ([`RowsAt`]): what a pass at the bodies' pose may keep.
    pub(super) rows_at: RowsAt,
    /// Each row's position error at the pose the rows were last carried to, `C₀ + J·Δ` ([`Link::carry`]);
    /// meaningful while `rows_at` is [`RowsAt::Carried`].
    pub(super) carried: [f32; MAX_ROWS],
    pub rows: JointRows,
    /// Each row's compliance in a position projection (1/kg, added to its diagonal of `K`): that of the rows
    /// that stiffen a pulled rope or rod against turning ([`Link::stiffen`]), 0 for every other row. Set by
    /// [`Link::make_positional`] and read only in [`Mode::Position`].
    pub(super) compliance: [Real; MAX_ROWS],
    /// Scratch of the block Thomas sweep (see [`solve_block_path`]): the strictly lower part of the unit
    /// lower triangular `L` of `Sᵢ = L·D·Lᵀ` (with `Sᵢ`'s upper triangle above it, factorised in place by
    /// [`ldl_factor`]), then `V = D⁻¹·L⁻¹·Cᵢ`, stored transposed (`v_t[k]` is column
    /// `k` of `V`: the back substitution sweeps it a column at a time), and `y = D⁻¹·L⁻¹·r̃ᵢ`.
    pub(super) y: [Real; MAX_ROWS],
    pub(super) inv_pivot: [Real; MAX_ROWS],
    pub(super) factor: Block,
    pub(super) v_t: Block,
    /// The rest of the factorisation, kept for the next pass ([`FactorKey`]): the link's blocks `B` and `C`
    /// (`K·λ` of a soft row reads them), `W = L⁻¹·C` (the next link's forward step reads it) and `D⁻¹`
    /// (`inv_pivot`).
    pub(super) w: Block,
    pub(super) b_block: Block,
    pub(super) c_block: Block,
    /// The Jacobians of the first [`LANES`] rows four lanes wide, lane `k` holding row `k`: for `a.linear`,
    /// `a.angular`, `b.linear` and `b.angular` in turn, their x, y and z components. The block sweep's
    /// residuals read them ([`Link::residual`]); they are made with the blocks ([`Link::fill_lanes`]),
    /// which are made again whenever the rows are.
    pub(super) lanes: [[Vec4; 3]; 4],
    /// `M⁻¹·Jᵀ` of each row four lanes wide (w = 0), in the order `[m_a⁻¹·J_a,linear, I_a⁻¹·J_a,angular,
    /// m_b⁻¹·J_b,linear, I_b⁻¹·J_b,angular]`, zero for a row not in the system: the velocity change of a unit
    /// impulse along the row. Made with the blocks ([`Link::fill_blocks`]), whose `C` and `B` it serves;
    /// a velocity pass's update sums the rows' increments through it and changes each body once
    /// ([`Link::apply_solution`]).
    pub(super) impulse: [[Vec4; 4]; MAX_ROWS],
    /// Where the rows were built, in world terms ([`BuiltAt`]): what [`Link::carry`] measures the turn and
    /// the displacement from, in this step or a later one. `None` for rows that are not carried (a rope's,
    /// a ball joint's): the solver sets it where it builds a hinge's rows and clears it where a link starts
    /// from nothing ([`Link::drop_built`]); last, so that a rope's passes never touch it.
    pub built: Option<BuiltAt>,
}

/// The entries of the scalar Thomas sweep of a one-row link ([`solve_scalar_path`]): its row's regularised
/// `K` entry `b` (1 for a row not in the system), the coupling `c` with the next link, the reciprocal `1/s`
/// of the Schur complement `s` (0 for a vanishing pivot), `c' = c/s` and `r' = r̃/s`. All but `r'` are kept
/// while the link's [`FactorKey`] holds.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct ScalarEntries {
    pub(super) b: Real,
    pub(super) c: Real,
    pub(super) inv_s: Real,
    pub(super) c_prime: Real,
    pub(super) r_prime: Real,
}

impl Link {
    /// A link for `rows` with accumulated impulses `lambda`.
    pub fn new(rows: JointRows, lambda: [f32; MAX_ROWS]) -> Self {
        Self {
            rows,
            lambda,
            active: [false; MAX_ROWS],
            shared_with_next: None,
            mode: Mode::Velocity,
            compliance: [0.0; MAX_ROWS],
            scalar: ScalarEntries::default(),
            factor: [[0.0; MAX_ROWS]; MAX_ROWS],
            v_t: [[0.0; MAX_ROWS]; MAX_ROWS],
            y: [0.0; MAX_ROWS],
            b_block: [[0.0; MAX_ROWS]; MAX_ROWS],
            c_block: [[0.0; MAX_ROWS]; MAX_ROWS],
            w: [[0.0; MAX_ROWS]; MAX_ROWS],
            inv_pivot: [0.0; MAX_ROWS],
            lanes: [[Vec4::ZERO; 3]; 4],
            impulse: [[Vec4::ZERO; 4]; MAX_ROWS],
            factored: None,
            rows_at: RowsAt::Unknown,
            carried: [0.0; MAX_ROWS],
            built: None,
            masses: Masses::ThisStep,
        }
    }

    /// Makes this (reused) link empty, for a joint whose bodies have the given inverse masses: no rows, no
    /// impulses, nothing kept from an earlier pass but the link to the next one (the path's shape). Reusing
    /// links keeps a pass from copying 2-kilobyte records around.
    pub fn reset(&mut self, mass_a: InvMass, mass_b: InvMass) {
        self.rows.mass_a = mass_a;
        self.rows.mass_b = mass_b;
        self.clear();
    }

    /// [`Link::reset`] keeping the inverse masses the link has.
    pub fn clear(&mut self) {
        self.rows.count = 0;
        self.rows.may_release = false;
        self.forget();
        self.restart();
    }

    /// Starts a pass with the rows as they are: no impulses, no row in the system, a velocity pass. The link
    /// to the next one (`shared_with_next`) stays: it is the path's shape, set once a step.
    pub(super) fn restart(&mut self) {
        self.lambda = [0.0; MAX_ROWS];
        self.active = [false; MAX_ROWS];
        self.mode = Mode::Velocity;
    }

    /// Drops what is kept from earlier passes (the pose of the rows, the factorisation): the next pass
    /// builds the rows and factorises again.
    pub fn forget(&mut self) {
        self.forget_poses();
        self.factored = None;
    }

    /// Forgets the poses the rows were built and carried at (they are rebuilt or carried at the next pass).
    pub(super) fn forget_poses(&mut self) {
        self.rows_at = RowsAt::Unknown;
    }

    /// Forgets everything kept ([`Link::forget`]), from the last step too ([`Link::end_last_step`]), and
    /// where the rows were built: a link that starts from nothing.
    pub fn drop_built(&mut self) {
        self.forget();
        self.end_last_step();
        self.built = None;
    }

    /// Starts a new step with the rows of the last one, kept to be carried ([`Link::carry`]) with the inverse
    /// masses they were built with: the poses of this step ([`PoseKey`], displacements since the step began)
    /// are unrelated to the last step's, so neither the build pose nor a carried one is reused as is.
    pub fn new_step(&mut self) {
        self.forget_poses();
        self.masses = Masses::LastStep;
    }

    /// Ends what [`Link::new_step`] started: rows built from now on take this step's inverse masses, and
    /// kept rows are built again at the next pass (the solver calls it for every link of a path at once:
    /// before the step's last relax pass, and for a path it does not keep).
    pub fn end_last_step(&mut self) {
        if self.masses == Masses::LastStep {
            self.forget_poses();
            self.masses = Masses::ThisStep;
        }
    }

    /// Whether the rows were built at the pose `pose`, as recorded by [`Link::built_at`] (never when none
    /// was, or it was forgotten). Compares in place: the key is 56 bytes, checked for every link of every pass.
    #[inline]
    pub fn is_built_at(&self, pose: &PoseKey) -> bool {
        matches!(&self.rows_at, RowsAt::Built { at, .. } if at == pose)
    }

    /// Whether rows built now take the inverse masses of the rows kept from the last step.
    #[inline]
    pub fn keeps_last_step_masses(&self) -> bool {
        self.masses == Masses::LastStep
    }
}

/// An empty link (no rows, no bodies), to grow a buffer of links with.
pub(crate) fn empty_link() -> Link {
    let zero = InvMass {
        mass: 0.0,
        inertia: Mat3::ZERO,
    };
    Link::new(JointRows::new(zero, zero), [0.0; MAX_ROWS])
}

/// Grows `links` to at least `len` links (it never shrinks: the buffer keeps the longest it has been, so
/// that a step allocates nothing once it has).
pub(crate) fn resize_links(links: &mut Vec<Link>, len: usize) {
    if links.len() < len {
        links.resize(len, empty_link());
    }
}

/// Link `k` of a pass, reused from earlier passes (the buffer grows to the longest path once).
pub(crate) fn link_at(links: &mut Vec<Link>, k: usize) -> &mut Link {
    resize_links(links, k + 1);
    &mut links[k]
}
