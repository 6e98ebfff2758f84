//! The thread pool a [`PhysicsWorld`] steps on (the `parallel` feature). Not a step stage: the setting the
//! step reads before it starts.
//!
//! The step spreads its stages over the pool through `rebound_math::par`; its results are the same bits for
//! any number of threads, and the same as the serial build's (`docs/architecture.md`, "Threads").

use crate::{Error, PhysicsWorld};
use rebound_math::par::rayon::{ThreadPool, ThreadPoolBuilder};
use std::sync::Arc;

/// The default of [`PhysicsWorld::set_min_work_for_threads`]: bodies moved plus contact manifolds solved in
/// the last step below which a step runs on one thread. In a scene this small (a 500-link chain, a 150-body
/// bridge) a stage's halves are a few microseconds each, and handing them between cores costs more than the
/// second core gives (`docs/performance.md`, "Threads").
pub const MIN_WORK_FOR_THREADS: usize = 1024;

impl PhysicsWorld {
    /// Steps on `pool` from now on (shared with whatever else uses it), or with `None` on the pool current
    /// where [`PhysicsWorld::step`] is called: rayon's global pool (one thread per core), or the one a
    /// caller's `ThreadPool::install` put around the call. The results do not depend on the pool.
    pub fn set_thread_pool(&mut self, pool: Option<Arc<ThreadPool>>) {
        self.thread_pool = pool;
    }

    /// Steps on a pool of its own with `count` threads (1: the serial code path). The results do not depend on `count`.
    ///
    /// # Errors
    /// [`Error::ThreadPool`] if `count` is 0 or the threads cannot be started; the setting is then unchanged.
    pub fn set_thread_count(&mut self, count: usize) -> Result<(), Error> {
        if count == 0 {
            return Err(Error::ThreadPool {
                count,
                reason: "a pool needs a thread".to_owned(),
            });
        }
        let pool = ThreadPoolBuilder::new()
            .num_threads(count)
            .build()
            .map_err(|e| Error::ThreadPool {
                count,
                reason: e.to_string(),
            })?;
        self.thread_pool = Some(Arc::new(pool));
        Ok(())
    }

    /// Runs a step on the calling thread alone, even on a pool of several, when the step before moved
    /// fewer than `work` bodies and contact manifolds together (the first step: when the world has fewer
    /// bodies) (default [`MIN_WORK_FOR_THREADS`], 1,024; 0: every step on the pool). The results are the same
    /// bits either way; only the time differs.
    pub fn set_min_work_for_threads(&mut self, work: usize) {
        self.min_work_for_threads = work;
    }

    /// See [`PhysicsWorld::set_min_work_for_threads`].
    #[must_use]
    pub fn min_work_for_threads(&self) -> usize {
        self.min_work_for_threads
    }

    /// The pool set with [`PhysicsWorld::set_thread_pool`] or [`PhysicsWorld::set_thread_count`], if any.
    #[must_use]
    pub fn thread_pool(&self) -> Option<&Arc<ThreadPool>> {
        self.thread_pool.as_ref()
    }
}
