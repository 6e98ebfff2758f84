//! The joint solver: the stages the world calls, dispatched on the joint kind with a `match` (no trait
//! objects in the hot loop; Box2D's `switch` in `joint.c`).
//!
//! ```text
//! prepare                         once per step: anchors, frames, masses, softness, warm-start impulses
//! for each substep:
//!     integrate velocities        (rebound-dynamics)
//!     apply_forces                SpringModel::Force: the explicit Hooke force as a velocity change
//!     warm_start                  the impulses of the last substep, again
//!     solve(Bias::On)             solve_iterations Gauss–Seidel passes, soft position correction
//!     integrate positions         (rebound-dynamics)
//!     solve(Bias::Off)            relax_iterations passes, no position correction (removes the bias velocity)
//!                                 (joint paths — chains, bridges — are solved as one system in each pass:
//!                                 crate::path; a pass at the pose of the one before it — a solve pass
//!                                 after a relax pass, the projection — keeps that pass's rows and, if the
//!                                 same rows are in the system, its factorisation; a hinge whose bodies
//!                                 turned less than 0.01 rad since its rows were built this step keeps
//!                                 them and its factorisation, with its errors carried to the pose)
//! project_positions               once: the positions of each joint path, so that its joints end the step closed
//! apply_restitution               once: ropes that snapped taut
//! store_impulses                  impulses back into the JointStates; break check
//! ```
//!
//! Buffers are reused from step to step: once the `Vec` of prepared joints has grown to the scene's joint
//! count, a step allocates nothing.

mod dispatch;
mod joint_solver;
mod passes;
mod path_pass;
mod prepare;
mod project;
#[cfg(test)]
mod tests;

pub use joint_solver::{JointSolver, KeptRows};
