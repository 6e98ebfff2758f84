//! Quality metrics and timing statistics.
//!
//! A scene reports its metrics as an ordered [`Quality`] list (the order of docs/scenes.md), which serialises to a
//! JSON object with the keys in that order. The helpers here are the measurements shared by several scenes.

use std::fmt;

use rapier3d::prelude::*;
use serde::ser::{Serialize, SerializeMap, Serializer};

use crate::world::World;

/// One metric value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// A real number.
    Num(f64),
    /// A count.
    Count(u64),
    /// A yes/no verdict.
    Bool(bool),
    /// A position `[x, y, z]`.
    Vec3([f64; 3]),
    /// A number that does not exist for this run (e.g. a threshold never reached): JSON `null`.
    Missing,
}

impl Serialize for Value {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match *self {
            Self::Num(x) => serializer.serialize_f64(x),
            Self::Count(n) => serializer.serialize_u64(n),
            Self::Bool(b) => serializer.serialize_bool(b),
            Self::Vec3(v) => v.serialize(serializer),
            Self::Missing => serializer.serialize_none(),
        }
    }
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Self::Num(x) => write!(f, "{}", Sig(x)),
            Self::Count(n) => write!(f, "{n}"),
            Self::Bool(b) => write!(f, "{}", if b { "yes" } else { "no" }),
            Self::Vec3([x, y, z]) => write!(f, "({}, {}, {})", Sig(x), Sig(y), Sig(z)),
            Self::Missing => write!(f, "-"),
        }
    }
}

/// Formats a number with about five significant digits, in scientific notation when very small or large.
struct Sig(f64);

impl fmt::Display for Sig {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let x = self.0;
        let a = x.abs();
        if a != 0.0 && a.is_finite() && !(1e-3..1e6).contains(&a) {
            write!(f, "{x:.4e}")
        } else {
            write!(f, "{x:.5}")
        }
    }
}

/// A metric's number as it goes into JSON: an `f64` as it is, an `f32` as the `f64` with the same shortest
/// decimal form (0.4915, not 0.4914952218532562), so the output shows the precision that was computed.
pub trait MetricNumber {
    /// The value to report.
    fn to_metric(self) -> f64;
}

impl MetricNumber for f64 {
    fn to_metric(self) -> f64 {
        self
    }
}

impl MetricNumber for f32 {
    fn to_metric(self) -> f64 {
        short(self)
    }
}

/// An `f32` widened to the `f64` with the same shortest decimal form (0.005, not 0.004999999888241291).
pub fn short(x: f32) -> f64 {
    x.to_string().parse().unwrap_or(f64::from(x))
}

/// A scene's quality metrics, in the order docs/scenes.md lists them.
#[derive(Debug, Clone, Default)]
pub struct Quality(Vec<(&'static str, Value)>);

impl Quality {
    /// An empty list.
    pub fn new() -> Self {
        Self::default()
    }

    /// Appends a real-valued metric.
    pub fn num(&mut self, name: &'static str, x: impl MetricNumber) -> &mut Self {
        self.0.push((name, Value::Num(x.to_metric())));
        self
    }

    /// Appends a count.
    pub fn count(&mut self, name: &'static str, n: usize) -> &mut Self {
        self.0.push((name, Value::Count(n as u64)));
        self
    }

    /// Appends a verdict.
    pub fn flag(&mut self, name: &'static str, b: bool) -> &mut Self {
        self.0.push((name, Value::Bool(b)));
        self
    }

    /// Appends a position.
    pub fn vec3(&mut self, name: &'static str, v: Vector) -> &mut Self {
        let v = [short(v.x), short(v.y), short(v.z)];
        self.0.push((name, Value::Vec3(v)));
        self
    }

    /// Appends a metric that may be absent (`null` in JSON).
    pub fn optional_count(&mut self, name: &'static str, n: Option<usize>) -> &mut Self {
        let value = n.map_or(Value::Missing, |n| Value::Count(n as u64));
        self.0.push((name, value));
        self
    }

    /// The metrics, in order.
    pub fn entries(&self) -> &[(&'static str, Value)] {
        &self.0
    }
}

impl Serialize for Quality {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        let mut map = serializer.serialize_map(Some(self.0.len()))?;
        for (name, value) in &self.0 {
            map.serialize_entry(name, value)?;
        }
        map.end()
    }
}

/// Median and mean of a set of step times, in milliseconds.
#[derive(Debug, Clone, Copy)]
pub struct TimingStats {
    /// Median ms/step (mean of the two middle samples for an even count).
    pub median_ms: f64,
    /// Mean ms/step.
    pub mean_ms: f64,
}

impl TimingStats {
    /// Statistics of `samples_ms` (NaN for an empty slice).
    pub fn of(samples_ms: &[f64]) -> Self {
        if samples_ms.is_empty() {
            return Self {
                median_ms: f64::NAN,
                mean_ms: f64::NAN,
            };
        }
        let mut sorted = samples_ms.to_vec();
        sorted.sort_by(f64::total_cmp);
        let n = sorted.len();
        let median_ms = if n % 2 == 1 {
            sorted[n / 2]
        } else {
            0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
        };
        let mean_ms = sorted.iter().sum::<f64>() / n as f64;
        Self { median_ms, mean_ms }
    }
}

/// The largest distance, over all joints, between the joint's two anchor points in world space (`pose1 ·
/// anchor1` and `pose2 · anchor2`): zero when every joint is exactly satisfied, so this is pure joint error
/// for ball-and-socket-like joints (revolute, spherical, fixed).
pub fn max_joint_separation(world: &World) -> f32 {
    world
        .impulse_joints
        .iter()
        .map(|(_, joint)| {
            let p1 = world.bodies[joint.body1()]
                .position()
                .transform_point(joint.data.local_anchor1());
            let p2 = world.bodies[joint.body2()]
                .position()
                .transform_point(joint.data.local_anchor2());
            p1.distance(p2)
        })
        .fold(0.0, f32::max)
}

/// Largest speed of any dynamic body.
pub fn max_speed(world: &World) -> f32 {
    world
        .bodies
        .iter()
        .filter(|(_, b)| b.is_dynamic())
        .map(|(_, b)| b.linvel().length())
        .fold(0.0, f32::max)
}

/// Number of narrow-phase contact pairs with at least one active contact (a contact the solver sees).
pub fn active_contact_pairs(world: &World) -> usize {
    world
        .narrow_phase
        .contact_pairs()
        .filter(|pair| pair.has_any_active_contact())
        .count()
}

#[cfg(test)]
mod tests {
    use super::{Quality, TimingStats};

    #[test]
    fn median_of_even_and_odd_counts() {
        assert!((TimingStats::of(&[3.0, 1.0, 2.0]).median_ms - 2.0).abs() < 1e-12);
        assert!((TimingStats::of(&[4.0, 1.0, 2.0, 3.0]).median_ms - 2.5).abs() < 1e-12);
        assert!((TimingStats::of(&[4.0, 1.0, 2.0, 3.0]).mean_ms - 2.5).abs() < 1e-12);
    }

    #[test]
    fn quality_serialises_in_insertion_order() {
        let mut q = Quality::new();
        q.num("z", 1.5).count("a", 3).flag("m", true);
        q.optional_count("n", None);
        let json = serde_json::to_string(&q).expect("serialisable");
        assert_eq!(json, r#"{"z":1.5,"a":3,"m":true,"n":null}"#);
    }
}
