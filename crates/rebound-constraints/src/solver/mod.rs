//! The joint solver: the stages the world calls. Each stage is in the file named after it and calls one
//! method of the prepared joint kind per joint, whose `match` over the kinds is in `dispatch.rs` (no trait
//! objects in the hot loop; Box2D's `switch` in `joint.c`). The paths of joints solved directly are handed
//! to the path solver ([`crate::path`]) as bodies and rows.
//!
//! ```text
//! prepare                        prepare.rs     once per step: anchors, frames, masses, softness, warm-start
//!                                               impulses; the paths, their kept links, the tethers
//! for each substep:
//!     integrate velocities                      (rebound-dynamics)
//!     apply_forces               passes.rs      SpringModel::Force: the explicit Hooke force as a velocity change
//!                                pool.rs        (joints that share no body: over the thread pool)
//!                                team.rs        (the same, and every pass, inside the substeps' one
//!                                               parallel section: JointTeam)
//!     warm_start                 passes.rs      the impulses of the last substep, again
//!     solve_substep(Bias::On)    passes.rs      solve_iterations Gauss–Seidel passes with soft position
//!                                               correction, then each path (path_pass.rs), then the tethers
//!     integrate positions                       (rebound-dynamics)
//!     solve_substep(Bias::Off)   passes.rs      relax_iterations passes without position correction; the last
//!                                               substep's also relaxes closed paths and builds every path's rows
//!                                               at the final pose
//! project_positions              project.rs     once: the positions of each path, so that its joints end the
//!                                               step closed; projection_velocity.rs: the velocities its
//!                                               displacement along turning rope and rod rows implies
//! apply_restitution              passes.rs      once: ropes that snapped taut
//! store_impulses                 passes.rs      impulses back into the JointStates; break check
//! ```
//!
//! Buffers are reused from step to step: once the `Vec` of prepared joints has grown to the scene's joint
//! count, a step allocates nothing.

mod dispatch;
mod joint_solver;
mod passes;
mod path_pass;
mod pool;
mod prepare;
mod project;
mod projection_velocity;
mod team;
#[cfg(test)]
mod tests;

pub use joint_solver::{JointSolver, KeptRows};
pub use team::JointTeam;
