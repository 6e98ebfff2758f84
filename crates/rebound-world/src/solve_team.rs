//! Stage *substeps* in one parallel section (`parallel` feature, a pool of more than one thread): the
//! substeps' passes as the phases of a team of the pool's threads (`rebound_math::team`), instead of a
//! fork and a join for every colour group of every pass.
//!
//! The plan lists the passes of every substep in the order of the one-thread loop (`solve.rs`), each as a
//! phase: integration split over the bodies; each colour group of the contacts' wide path split over its
//! batches (a group too small to split, one chunk); *apply forces* split over the joints when they share no
//! body; every other joint pass, the contacts' scalar path, the axis locks and the impulse sums one chunk,
//! consecutive ones merged into one phase. Passes that change nothing are left out (the joints' warm start
//! and passes when every joint is a spring), and *ranged* passes that follow one another share a phase:
//! integration (a body's reads that body alone) and *apply forces* when each chunk's joints have their
//! bodies in that chunk's range of bodies (a field of springs numbered pair by pair), so that a chunk
//! runs them back to back on its own bodies — a field of springs walks all its substeps in one phase.
//! Every barrier costs the team a hand-over between threads, which on a scene of a few hundred bodies is
//! as long as a phase's work. A chunk writes what it computes in place — a contact batch its dynamic bodies, a joint its two bodies, integration its bodies — and no two chunks of a phase share
//! anything they write (the colouring, the joints' plan, disjoint ranges), so every value is the one the
//! loop computes: the same bits for any number of threads.
#![allow(
    unsafe_code,
    reason = "the solver's arrays shared by the chunks of a team (rebound_math::Disjoint)"
)]

use crate::solve_parts::{lock_axes_in, summing};
use rebound_constraints::{JointSolver, JointTeam, Substep};
use rebound_dynamics::contact::Bias;
use rebound_dynamics::integrate::{integrate_position, integrate_velocity};
use rebound_dynamics::{
    BodyParams, ContactSolver, ContactTeam, MAX_CONTACT_POINTS, SolverBody, StepContext,
};
use rebound_math::{Disjoint, team};

/// Bodies per chunk below which integration is not split: a phase boundary hands the bodies from core to
/// core (their cache lines, and a barrier), which costs more than integrating a few hundred bodies on one
/// core. A smaller scene (a chain of 500 balls, a bridge) integrates in one chunk, which joins the phases
/// of one chunk around it: fewer barriers, and every body stays in the cache of the thread that solves it.
/// The split changes which thread integrates a body, never a value.
const BODIES_PER_CHUNK: usize = 256;

/// The substeps' phases, rebuilt every step (the buffers kept).
#[derive(Debug, Default)]
pub(crate) struct Plan {
    ops: Vec<Op>,
    phases: Vec<Phase>,
    /// The team's chunk numbering: the end of each phase's chunks.
    ends: Vec<u32>,
}

/// A phase: the ops `start..end`, each run whole (one chunk), or split into `chunks`: one op, or ranged
/// ops over the same ranges of bodies.
#[derive(Debug, Clone, Copy)]
struct Phase {
    start: u32,
    end: u32,
    chunks: u32,
    /// Whether chunk `k` of every op of the phase touches only the bodies of range `k` (integration; *apply
    /// forces* of joints within those ranges).
    ranged: bool,
}

/// One pass of a substep, as the one-thread loop runs it.
#[derive(Debug, Clone, Copy)]
enum Op {
    IntegrateVelocities,
    IntegratePositions,
    LockAxes,
    ApplyForces,
    JointWarmStart,
    JointPass(Bias, Substep),
    ContactWarmStart(usize),
    ContactPass(usize, Bias),
    ScalarWarmStart,
    ScalarPass(Bias),
    SumImpulses(bool),
}

impl Op {
    /// Whether the op integrates the bodies: each body read and written alone, so that chunks over the same
    /// ranges of bodies may run two such ops back to back.
    fn is_integration(self) -> bool {
        matches!(self, Self::IntegrateVelocities | Self::IntegratePositions)
    }
}

impl Plan {
    /// Adds `op` in `chunks` chunks ([`Plan::push_ranged`], ranged if it is integration).
    fn push(&mut self, op: Op, chunks: usize) {
        self.push_ranged(op, chunks, op.is_integration());
    }

    /// Adds `op` in `chunks` chunks, `ranged` if its chunk `k` touches only the bodies of range `k`: an op
    /// of one chunk joins a phase of one chunk before it, and a ranged op a ranged phase in as many chunks.
    fn push_ranged(&mut self, op: Op, chunks: usize, ranged: bool) {
        self.ops.push(op);
        let end = self.ops.len() as u32;
        let chunks = chunks.max(1) as u32;
        match self.phases.last_mut() {
            Some(last) if last.chunks == chunks && (chunks == 1 || (ranged && last.ranged)) => {
                last.end = end;
                last.ranged &= ranged;
            }
            _ => self.phases.push(Phase {
                start: end - 1,
                end,
                chunks,
                ranged,
            }),
        }
    }

    /// How many phases (barriers) the last plan made: the team's hand-overs this step.
    #[cfg(test)]
    pub(crate) fn phase_count(&self) -> usize {
        self.phases.len()
    }
}

/// What the chunks share.
struct Shared<'a> {
    bodies: Disjoint<'a, SolverBody>,
    params: &'a [BodyParams],
    contacts: ContactTeam<'a>,
    joints: JointTeam<'a>,
    locked: &'a [usize],
    step_impulses: Disjoint<'a, Vec<[f32; MAX_CONTACT_POINTS]>>,
    ctx: &'a StepContext,
}

/// The solver's arrays the substeps read and write, and the plan's buffers (the world's `prepare::Solver`,
/// split by `Solver::team_arrays`).
pub(crate) struct Arrays<'a> {
    pub(crate) plan: &'a mut Plan,
    pub(crate) states: &'a mut [SolverBody],
    pub(crate) params: &'a [BodyParams],
    pub(crate) contact_solver: &'a mut ContactSolver,
    pub(crate) joint_solver: &'a mut JointSolver,
    pub(crate) step_impulses: &'a mut Vec<[f32; MAX_CONTACT_POINTS]>,
    pub(crate) locked: &'a [usize],
}

/// Stage *substeps* on the team; `false` (nothing done) if the contact solver was not prepared for it.
pub(crate) fn solve_substeps(arrays: Arrays<'_>, ctx: &StepContext) -> bool {
    let Arrays {
        plan,
        states,
        params,
        contact_solver,
        joint_solver,
        step_impulses,
        locked,
    } = arrays;
    let Some(contacts) = contact_solver.team() else {
        return false;
    };
    let joints = joint_solver.team();
    make_plan(
        plan,
        &contacts,
        &joints,
        states.len(),
        !locked.is_empty(),
        !step_impulses.is_empty(),
        ctx,
    );
    let shared = Shared {
        bodies: Disjoint::new(states),
        params,
        contacts,
        joints,
        locked,
        step_impulses: Disjoint::one(step_impulses),
        ctx,
    };
    let plan = &*plan;
    team::run(&plan.ends, &|phase, chunk| {
        let Some(&Phase {
            start, end, chunks, ..
        }) = plan.phases.get(phase)
        else {
            return;
        };
        for &op in &plan.ops[start as usize..end as usize] {
            // SAFETY: the team runs the chunks of one phase at once and the phases one after another; a
            // phase of several chunks holds one op, whose chunks write disjoint parts, or ranged ops, each
            // chunk on the same range of bodies (and its own joints) in every one of them (see `run`).
            unsafe { run(&shared, op, chunk as usize, chunks as usize) };
        }
    });
    true
}

/// The plan of this step's substeps: the one-thread loop's passes in its order (`solve::solve_substeps`),
/// those with nothing to do left out.
fn make_plan(
    plan: &mut Plan,
    contacts: &ContactTeam<'_>,
    joints: &JointTeam<'_>,
    body_count: usize,
    locks: bool,
    sums: bool,
    ctx: &StepContext,
) {
    plan.ops.clear();
    plan.phases.clear();
    let threads = team::size();
    let body_chunks = (body_count / BODIES_PER_CHUNK).clamp(1, threads);
    let groups = contacts.group_count();
    let scalar = contacts.has_scalar();
    let joint = !joints.is_idle();
    let joint_passes = joint && !joints.is_forces_only();
    let force_chunks = joints.force_chunks(threads);
    // SAFETY: no chunk runs yet (the team starts after the plan).
    let forces_ranged = force_chunks == body_chunks
        && unsafe { joints.forces_within_body_ranges(body_chunks, body_count) };
    let lock = |plan: &mut Plan| {
        if locks {
            plan.push(Op::LockAxes, 1);
        }
    };
    let contact_pass = |plan: &mut Plan, bias: Option<Bias>| {
        for g in 0..groups {
            let op = bias.map_or(Op::ContactWarmStart(g), |b| Op::ContactPass(g, b));
            plan.push(op, contacts.chunks_of(g, threads));
        }
        if scalar {
            plan.push(bias.map_or(Op::ScalarWarmStart, Op::ScalarPass), 1);
        }
    };
    for index in 0..ctx.substep_count {
        let substep = Substep::new(index, ctx.substep_count);
        plan.push(Op::IntegrateVelocities, body_chunks);
        lock(plan);
        if joint {
            plan.push_ranged(Op::ApplyForces, force_chunks, forces_ranged);
        }
        if joint_passes {
            plan.push(Op::JointWarmStart, 1);
        }
        contact_pass(plan, None);
        for bias in [Bias::On, Bias::Off] {
            if bias == Bias::Off {
                plan.push(Op::IntegratePositions, body_chunks);
            }
            if joint_passes {
                plan.push(Op::JointPass(bias, substep), 1);
                lock(plan);
            }
            contact_pass(plan, Some(bias));
            lock(plan);
        }
        if sums {
            plan.push(Op::SumImpulses(substep.is_last()), 1);
        }
    }
    plan.ends.clear();
    let mut end = 0;
    for phase in &plan.phases {
        end += phase.chunks;
        plan.ends.push(end);
    }
}

/// Runs chunk `chunk` of `chunks` of `op`.
///
/// # Safety
/// With one chunk, nothing else runs on `shared` meanwhile; with more, only the other chunks of the same op.
unsafe fn run(shared: &Shared<'_>, op: Op, chunk: usize, chunks: usize) {
    let (bodies, ctx) = (&shared.bodies, shared.ctx);
    let range = || bodies.len() * chunk / chunks..bodies.len() * (chunk + 1) / chunks;
    // SAFETY: per op: integration chunks take disjoint ranges of bodies; the contact and joint chunks'
    // contracts are the caller's; an op of one chunk has everything to itself.
    unsafe {
        match op {
            Op::IntegrateVelocities => {
                let r = range();
                for (state, p) in bodies
                    .slice_mut(r.clone())
                    .iter_mut()
                    .zip(&shared.params[r])
                {
                    integrate_velocity(state, p, ctx);
                }
            }
            Op::IntegratePositions => {
                let r = range();
                for (state, p) in bodies
                    .slice_mut(r.clone())
                    .iter_mut()
                    .zip(&shared.params[r])
                {
                    integrate_position(state, p, ctx);
                }
            }
            Op::LockAxes => lock_axes_in(bodies.all_mut(), shared.params, shared.locked),
            Op::ApplyForces => shared
                .joints
                .apply_forces_chunk((chunk, chunks), bodies, ctx),
            Op::JointWarmStart => shared.joints.solver_mut().warm_start(bodies.all_mut()),
            Op::JointPass(bias, substep) => {
                shared
                    .joints
                    .solver_mut()
                    .solve_substep(bodies.all_mut(), ctx, bias, substep);
            }
            Op::ContactWarmStart(g) => shared.contacts.warm_start_chunk(g, (chunk, chunks), bodies),
            Op::ContactPass(g, bias) => {
                shared
                    .contacts
                    .solve_chunk(g, (chunk, chunks), bodies, ctx, bias);
            }
            Op::ScalarWarmStart => shared.contacts.warm_start_scalar(bodies.all_mut()),
            Op::ScalarPass(bias) => shared.contacts.solve_scalar(bodies.all_mut(), ctx, bias),
            Op::SumImpulses(last) => {
                if let Some(sums) = shared.step_impulses.all_mut().first_mut() {
                    shared.contacts.for_each_normal_impulse(summing(sums, last));
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::{World, WorldSettings};
    use rebound_constraints::{Joint, Rope, SoftSpring, Spring, SpringModel};
    use rebound_dynamics::BodyDesc;
    use rebound_math::Vec3;
    use rebound_math::par::rayon;

    /// Steps `world` `steps` times on a pool of `threads` threads: the phases of its last plan and the
    /// state's digest.
    fn stepped_on_pool(mut world: World, threads: usize, steps: usize) -> (usize, u64) {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap_or_else(|e| panic!("no pool: {e}"));
        for _ in 0..steps {
            pool.install(|| world.step(1.0 / 60.0));
        }
        (
            world.scratch.solver.plan.phase_count(),
            world.state_digest(),
        )
    }

    /// A field of `pairs` separate springs (as the `springs` scene, stretched to 1.5 m of 1 m rest length),
    /// stepped `steps` times on a pool of `threads` threads: the phases of its last plan and the state's digest.
    fn spring_field(pairs: usize, threads: usize, steps: usize) -> (usize, u64) {
        let settings = WorldSettings {
            gravity: Vec3::ZERO,
            ..WorldSettings::default()
        };
        let mut world = World::new(settings).unwrap_or_else(|e| panic!("settings: {e}"));
        let model = SpringModel::Soft(SoftSpring::Stiffness {
            stiffness: 1.0e4,
            damping: 10.0,
        });
        let spring = Spring::new(1.0, model).unwrap_or_else(|e| panic!("spring: {e}"));
        for i in 0..pairs {
            let x = 4.0 * i as f32;
            let mut body = |dx: f32| {
                world
                    .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(x + dx, 0.0, 0.0)))
                    .unwrap_or_else(|e| panic!("body: {e}"))
            };
            let (a, b) = (body(-0.75), body(0.75));
            world
                .insert_joint(Joint::new(spring), a, b)
                .unwrap_or_else(|e| panic!("joint: {e}"));
        }
        stepped_on_pool(world, threads, steps)
    }

    #[test]
    fn a_field_of_springs_walks_its_substeps_in_one_phase() {
        // Integration and *apply forces* of each half of the bodies and of their joints back to back; the
        // joints' other passes do nothing.
        assert_eq!(spring_field(1_000, 2, 1).0, 1);
    }

    /// A horizontal chain of `links` balls on ropes from a world anchor (as the `chain` scene), stepped
    /// `steps` times on a pool of `threads` threads: the phases of its last plan and the state's digest.
    fn rope_chain(links: usize, threads: usize, steps: usize) -> (usize, u64) {
        let mut world =
            World::new(WorldSettings::default()).unwrap_or_else(|e| panic!("settings: {e}"));
        let mut previous = None;
        for i in 0..links {
            let ball = world
                .insert_body(&BodyDesc::dynamic().with_position(Vec3::new(
                    (i as f32 + 1.0) * 0.25,
                    0.0,
                    0.0,
                )))
                .unwrap_or_else(|e| panic!("body: {e}"));
            let rope = Joint::new(Rope::new(0.25).unwrap_or_else(|e| panic!("rope: {e}")));
            match previous {
                None => world.insert_world_joint(rope, ball),
                Some(p) => world.insert_joint(rope, p, ball),
            }
            .unwrap_or_else(|e| panic!("joint: {e}"));
            previous = Some(ball);
        }
        stepped_on_pool(world, threads, steps)
    }

    #[test]
    fn a_chain_of_500_balls_walks_its_substeps_in_one_phase() {
        // 500 bodies are integrated in one chunk (`BODIES_PER_CHUNK`), which joins the joints' passes of
        // one chunk: the team has no barrier to hand over, and the path's two halves are its only tasks.
        assert_eq!(rope_chain(500, 2, 1).0, 1);
        // 1,024 bodies are split: two integration phases a substep, between the joint passes.
        assert_eq!(rope_chain(1_024, 2, 1).0, 4 * 4);
    }

    #[test]
    fn a_chain_on_any_pool_gives_the_one_thread_bits() {
        let one = rope_chain(200, 1, 20).1;
        for threads in [2, 3, 8] {
            assert_eq!(rope_chain(200, threads, 20).1, one, "{threads} threads");
        }
    }

    #[test]
    fn a_field_of_springs_on_any_pool_gives_the_one_thread_bits() {
        let one = spring_field(300, 1, 20).1;
        for threads in [2, 3, 8] {
            assert_eq!(spring_field(300, threads, 20).1, one, "{threads} threads");
        }
    }
}
