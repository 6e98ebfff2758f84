//! The thread pool a [`PhysicsWorld`] steps on (the `parallel` feature). Not a step stage: the setting the
//! step reads before it starts.
//!
//! The step spreads its stages over the pool through `rebound_math::par`; its results are the same bits for
//! any number of threads, and the same as the serial build's (`docs/architecture.md`, "Threads").

use crate::{Error, PhysicsWorld};
use rebound_math::par::rayon::{ThreadPool, ThreadPoolBuilder};
use std::sync::Arc;

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

    /// The pool set with [`PhysicsWorld::set_thread_pool`] or [`PhysicsWorld::set_thread_count`], if any.
    #[must_use]
    pub fn thread_pool(&self) -> Option<&Arc<ThreadPool>> {
        self.thread_pool.as_ref()
    }
}
