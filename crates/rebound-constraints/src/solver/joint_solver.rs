//! The joint solver's state ([`JointSolver`]: the prepared joints, the paths and their links, the tethers,
//! the scratch buffers every stage reuses) and the rows it keeps into the next step ([`KeptRows`]). The
//! stages themselves are in the sibling modules: `prepare`, `passes`, `path_pass` and `project`.

use super::dispatch::{JointRecord, PreparedJoint};
use super::pool::JointPool;
use crate::error::ConstraintError;
use crate::path::tether::{Edge, JointGraph, Tether};
use crate::path::topology::Topology;
use crate::path::{BuiltAt, CARRY_ANGLE, JointRows, Link, MAX_ROWS, Real, resize_links};
use crate::settings::JointSettings;
use rebound_dynamics::{Softness, SolverBody};

/// The rows a [`JointSolver`] keeps from one step to the next — a directly solved path's hinge rows, which
/// the next step carries instead of building them again (see [`crate::path`]) — as a snapshot holds
/// them. Restored into a solver ([`JointSolver::restore_kept_rows`]) before the next step, they make that
/// step the one the solver they were taken from would have taken, bit for bit.
#[derive(Debug, Clone, Default, PartialEq)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
pub struct KeptRows {
    /// Per link of the paths, in path order: its rows and where they were built (`None`: none kept).
    pub(super) links: Vec<Option<(JointRows, BuiltAt)>>,
}

impl KeptRows {
    /// The number of links whose rows are kept.
    #[must_use]
    pub fn len(&self) -> usize {
        self.links.iter().flatten().count()
    }

    /// Whether no rows are kept.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Whether every number is finite (impulse bounds may be infinite, never NaN) and every row count in
    /// range: what a solver restoring them trusts. A snapshot that was deserialised is checked with it.
    #[must_use]
    pub fn is_valid(&self) -> bool {
        self.links.iter().flatten().all(|(rows, built)| {
            let (a, b) = built.frames;
            rows.is_valid() && a.is_finite() && b.is_finite() && built.relative.is_finite()
        })
    }
}

/// The joint solver. Holds the prepared joints between stages and reuses its buffer from step to step.
///
/// See the crate README for a complete step loop.
#[derive(Debug, Clone)]
pub struct JointSolver {
    pub(super) settings: JointSettings,
    /// The prepared joints, what the passes read of them. The buffer keeps its slots from step to step, and
    /// *prepare* writes each joint's fields into its slot in place rather than building it and copying it in.
    pub(super) joints: Vec<PreparedJoint>,
    /// Per prepared joint, what only *prepare* and *store impulses* read (its break limits, its tether).
    pub(super) records: Vec<JointRecord>,
    /// The joints a Gauss–Seidel pass visits (indices into `joints`, in order): those on no direct path but
    /// springs, and hinges on one that have limit, motor or spring rows. A rope chain or a bridge solved
    /// directly has none, nor has a field of springs.
    pub(super) iterated: Vec<usize>,
    /// Long-range tethers of chains hanging from fixed bodies (see [`crate::path::tether`]).
    pub(super) tethers: Vec<Tether>,
    /// Scratch: the joints as graph edges, and the graph search's buffers.
    pub(super) edges: Vec<Edge>,
    pub(super) graph: JointGraph,
    /// The paths of joints solved directly ([`crate::path`]) and whether each is closed: all of its joints'
    /// rows are in the direct solve and no other joint or tether acts on its dynamic bodies (only the last
    /// relax pass of a step solves a closed path, see [`JointSolver::solve`]).
    pub(super) topology: Topology,
    /// The links of the direct solve, one per entry of `path_joints` (a path's links are the slice of its
    /// range), kept from pass to pass: a pass at the pose a link's rows were built at reuses them, and their
    /// factorisation if the rows in the system are also the same (see [`crate::path`]).
    pub(super) links: Vec<Link>,
    /// How many of `links` belong to the paths of the last prepared step (or of the restored [`KeptRows`]).
    pub(super) path_links: usize,
    pub(super) solution: Vec<[Real; MAX_ROWS]>,
    /// Scratch of the position projection: the path's bodies before a Newton step, and a link to measure
    /// errors with.
    pub(super) saved: Vec<(usize, SolverBody)>,
    pub(super) probe: Vec<Link>,
    /// Scratch of the position projection: per entry of the paths' joints, the position impulse (N·s·s) of
    /// its rope or rod row summed over the projection's accepted Newton steps.
    pub(super) position_impulses: Vec<f32>,
    /// Whether a prepared joint has a hinge, prismatic or wheel spring (*apply forces* visits the joints a
    /// second time for them only then).
    pub(super) coordinate_springs: bool,
    /// Whether a prepared joint may act in stage *restitution* (a rope with restitution, a ball joint with
    /// limits): the stage visits the joints only then.
    pub(super) restitution: bool,
    /// The joint softness of the prepared step.
    pub(super) joint_softness: Softness,
    /// The substep length of the prepared step (s).
    pub(super) h: f32,
    /// How far (rad) the bodies of a hinge on a path may turn before a velocity pass builds its rows again
    /// instead of carrying them ([`Link::carry`]); 0 builds them at every new pose.
    pub(super) carry_angle: f32,
    /// Relax passes since [`JointSolver::prepare`], for [`JointSolver::solve`], which does not name its
    /// substep.
    pub(super) relax_passes: u32,
    /// Whether *apply forces* runs on the thread pool this step, and its scratch.
    pub(super) pool: JointPool,
}

impl Default for JointSolver {
    fn default() -> Self {
        Self {
            settings: JointSettings::default(),
            joints: Vec::new(),
            records: Vec::new(),
            iterated: Vec::new(),
            tethers: Vec::new(),
            edges: Vec::new(),
            graph: JointGraph::default(),
            topology: Topology::default(),
            links: Vec::new(),
            path_links: 0,
            solution: Vec::new(),
            saved: Vec::new(),
            probe: Vec::new(),
            position_impulses: Vec::new(),
            coordinate_springs: false,
            restitution: false,
            joint_softness: Softness::RIGID,
            h: 0.0,
            carry_angle: CARRY_ANGLE,
            relax_passes: 0,
            pool: JointPool::default(),
        }
    }
}

impl JointSolver {
    /// A solver with [`crate::JointSettings::default`].
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// The rows this solver keeps for the next step ([`KeptRows`]), for a snapshot.
    #[must_use]
    pub fn kept_rows(&self) -> KeptRows {
        let links = self.links.get(..self.path_links).unwrap_or_default();
        KeptRows {
            links: links
                .iter()
                .map(|link| link.built.map(|built| (link.rows, built)))
                .collect(),
        }
    }

    /// Replaces the rows kept for the next step with `kept` (taken by [`JointSolver::kept_rows`]); rows kept
    /// for joints or bodies other than the next step's are dropped by it. Check a deserialised value with
    /// [`KeptRows::is_valid`] first.
    pub fn restore_kept_rows(&mut self, kept: &KeptRows) {
        resize_links(&mut self.links, kept.links.len());
        for (k, link) in self.links.iter_mut().enumerate() {
            link.drop_built();
            if let Some(&Some((rows, built))) = kept.links.get(k) {
                link.rows = rows;
                link.built = Some(built);
            }
        }
        self.path_links = kept.links.len();
    }

    /// A solver with `settings`.
    ///
    /// # Errors
    /// Invalid settings (see [`crate::JointSettings::validated`]).
    pub fn with_settings(settings: JointSettings) -> Result<Self, ConstraintError> {
        Ok(Self {
            settings: settings.validated()?,
            ..Self::default()
        })
    }

    /// The settings.
    #[must_use]
    pub fn settings(&self) -> &JointSettings {
        &self.settings
    }

    /// Replaces the settings (taking effect at the next [`JointSolver::prepare`]); nothing changes on error.
    ///
    /// # Errors
    /// Invalid settings.
    pub fn set_settings(&mut self, settings: JointSettings) -> Result<(), ConstraintError> {
        self.settings = settings.validated()?;
        Ok(())
    }

    /// The number of prepared joints.
    #[must_use]
    pub fn len(&self) -> usize {
        self.joints.len()
    }

    /// Whether no joint is prepared.
    #[must_use]
    pub fn is_empty(&self) -> bool {
        self.joints.is_empty()
    }

    /// Whether every row of joint `joint` (its index in the joints given to the last
    /// [`JointSolver::prepare`]) is in the direct solve of a path or graph ([`crate::path`]), none left to
    /// the Gauss–Seidel passes: what a test of a joint kind's direct rows checks. `false` for a joint
    /// skipped or not prepared.
    #[must_use]
    pub fn is_solved_directly(&self, joint: usize) -> bool {
        self.joints
            .iter()
            .find(|j| j.source == joint)
            .is_some_and(|j| j.path.is_some() && !j.kind.is_iterated(true))
    }
}
