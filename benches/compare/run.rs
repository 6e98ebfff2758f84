//! Running a scene in Rebound: the timed step loop, the per-phase profile and the run's record, shared by the
//! comparison, Rebound alone and the scaling series.

use std::time::{Duration, Instant};

use rebound_suite::scenes::metrics::TimingStats;
use rebound_suite::scenes::{self, Scene, SceneOptions, Value};
use serde_json::Value as Json;

/// Steps excluded from the timing statistics (warm-up: the pile, stack or chain is still forming), as in
/// the rapier side.
pub(crate) const WARMUP_STEPS: usize = 60;

/// Where Rebound's step spends its time: the mean over steps 60..N of each `StepReport::profile` phase (ms),
/// plus the facade's own work after the world's step (query BVH refresh, sensors): measured wall time minus
/// the world's `total`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Phases {
    pub(crate) collide: f64,
    pub(crate) prepare: f64,
    pub(crate) solve: f64,
    pub(crate) restitution: f64,
    pub(crate) finalize: f64,
    /// `PhysicsWorld::step` beyond the world's step.
    pub(crate) facade: f64,
    /// The measured step (wall clock).
    pub(crate) wall: f64,
}

impl Phases {
    /// The phase names and values, in step order.
    pub(crate) fn entries(&self) -> [(&'static str, f64); 7] {
        [
            ("collide", self.collide),
            ("prepare", self.prepare),
            ("solve", self.solve),
            ("restitution", self.restitution),
            ("finalize", self.finalize),
            ("facade", self.facade),
            ("wall", self.wall),
        ]
    }

    /// The element-wise mean of several.
    pub(crate) fn mean(all: &[Self]) -> Self {
        let n = all.len().max(1) as f64;
        let sum = |f: fn(&Self) -> f64| all.iter().map(f).sum::<f64>() / n;
        Self {
            collide: sum(|p| p.collide),
            prepare: sum(|p| p.prepare),
            solve: sum(|p| p.solve),
            restitution: sum(|p| p.restitution),
            finalize: sum(|p| p.finalize),
            facade: sum(|p| p.facade),
            wall: sum(|p| p.wall),
        }
    }
}

/// One engine's run of one scene.
#[derive(Debug, Clone)]
pub(crate) struct Run {
    pub(crate) bodies: usize,
    pub(crate) joints: usize,
    pub(crate) timing: TimingStats,
    /// Metric name → JSON value, in the order the engine reported them.
    pub(crate) quality: Vec<(String, Json)>,
    /// Rebound only.
    pub(crate) phases: Option<Phases>,
}

/// Steps one Rebound scene `steps` times, timing only [`Scene::step`].
pub(crate) fn run_scene(scene: &mut dyn Scene, steps: usize) -> (TimingStats, Phases) {
    let mut step_ms = Vec::with_capacity(steps);
    let mut phases = Vec::with_capacity(steps);
    let ms = |d: Duration| d.as_secs_f64() * 1e3;
    for step in 1..=steps {
        let start = Instant::now();
        let report = scene.step();
        let wall = ms(start.elapsed());
        step_ms.push(wall);
        let p = report.profile;
        phases.push(Phases {
            collide: ms(p.collide),
            prepare: ms(p.prepare),
            solve: ms(p.solve),
            restitution: ms(p.restitution),
            finalize: ms(p.finalize),
            facade: wall - ms(p.total),
            wall,
        });
        scene.observe(step);
    }
    let warmup = if steps > WARMUP_STEPS {
        WARMUP_STEPS
    } else {
        0
    };
    (
        TimingStats::of(&step_ms[warmup..]),
        Phases::mean(&phases[warmup..]),
    )
}

/// Runs `f` on the current thread, or with `threads` inside a rayon pool of that many threads (the parallel
/// build; `parse_args` refuses `--threads` in the serial one).
pub(crate) fn on_threads<R: Send>(
    threads: Option<usize>,
    f: impl FnOnce() -> R + Send,
) -> Result<R, String> {
    match threads {
        #[cfg(feature = "parallel")]
        Some(threads) => Ok(rebound::math::par::rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .map_err(|e| format!("a pool of {threads} threads: {e}"))?
            .install(f)),
        _ => Ok(f()),
    }
}

/// Builds and runs a scene in Rebound: on the current thread, or with `threads` inside a rayon pool of that
/// many threads (the parallel build; `parse_args` refuses `--threads` in the serial one).
pub(crate) fn run_rebound(name: &str, steps: usize, threads: Option<usize>) -> Result<Run, String> {
    let mut scene = scenes::build(name, SceneOptions::default())
        .map_err(|e| format!("building `{name}` in Rebound: {e}"))?
        .ok_or_else(|| format!("unknown scene `{name}`"))?;
    let (timing, phases) = on_threads(threads, || run_scene(scene.as_mut(), steps))?;
    Ok(Run {
        bodies: scene.body_count(),
        joints: scene.joint_count(),
        timing,
        quality: quality_json(&scene.quality()),
        phases: Some(phases),
    })
}

/// A Rebound scene's metrics as (name, JSON value) pairs.
pub(crate) fn quality_json(quality: &[(&'static str, Value)]) -> Vec<(String, Json)> {
    quality
        .iter()
        .map(|&(name, value)| (name.to_owned(), value.to_json()))
        .collect()
}

/// The Rebound version of this build.
pub(crate) fn rebound_engine() -> String {
    format!("rebound {}", env!("CARGO_PKG_VERSION"))
}
