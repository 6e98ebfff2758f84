//! Quality metrics and timing statistics of the peer scenes, in the same form as the rapier side
//! (`benches/peers/src/metrics.rs`): the same metric names, the same JSON values (an `f32` written in its
//! shortest decimal form, counts as integers, positions as `[x, y, z]`, a metric that does not exist as
//! `null`), so the two engines' numbers compare one to one. Not part of any step stage: everything here runs
//! outside the timed region.

use core::fmt;

use rebound::prelude::*;
use serde_json::json;

/// One metric value.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Value {
    /// A real number.
    Num(f64),
    /// A count.
    Count(u64),
    /// A yes/no verdict.
    Bool(bool),
    /// A position `[x, y, z]` (m).
    Vec3([f64; 3]),
    /// A number that does not exist for this run (a threshold never reached): JSON `null`.
    Missing,
}

impl Value {
    /// A real number from an `f32`, as the `f64` with the same shortest decimal form (0.4915, not
    /// 0.4914952218532562): the precision that was computed, as the rapier side writes it.
    #[must_use]
    pub fn f32(x: f32) -> Self {
        Self::Num(short(x))
    }

    /// A real number computed in `f64`.
    #[must_use]
    pub const fn f64(x: f64) -> Self {
        Self::Num(x)
    }

    /// A count.
    #[must_use]
    pub fn count(n: usize) -> Self {
        Self::Count(n as u64)
    }

    /// A position, each coordinate in its shortest `f32` form.
    #[must_use]
    pub fn vec3(v: Vec3) -> Self {
        Self::Vec3([short(v.x), short(v.y), short(v.z)])
    }

    /// The value as JSON (what the rapier side's `--json` line holds for the same metric).
    #[must_use]
    pub fn to_json(self) -> serde_json::Value {
        match self {
            Self::Num(x) => json!(x),
            Self::Count(n) => json!(n),
            Self::Bool(b) => json!(b),
            Self::Vec3(v) => json!(v),
            Self::Missing => serde_json::Value::Null,
        }
    }

    /// The number behind a real or a count (`None` for the other kinds).
    #[must_use]
    pub fn as_f64(self) -> Option<f64> {
        match self {
            Self::Num(x) => Some(x),
            Self::Count(n) => Some(n as f64),
            _ => None,
        }
    }
}

impl fmt::Display for Value {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", DisplayJson(&self.to_json()))
    }
}

/// Formats a metric's JSON value for a table: about five significant digits (scientific notation when very
/// small or large), counts as integers, verdicts as yes/no, positions as `(x, y, z)`, `null` as `-`. Used for
/// both engines' values, so the two columns read alike.
#[derive(Debug, Clone, Copy)]
pub struct DisplayJson<'a>(pub &'a serde_json::Value);

impl fmt::Display for DisplayJson<'_> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use serde_json::Value as J;
        match self.0 {
            J::Null => f.pad("-"),
            J::Bool(b) => f.pad(if *b { "yes" } else { "no" }),
            J::Number(n) => match (n.as_u64(), n.as_i64(), n.as_f64()) {
                (Some(u), _, _) => f.pad(&u.to_string()),
                (None, Some(i), _) => f.pad(&i.to_string()),
                (None, None, Some(x)) => f.pad(&sig(x)),
                _ => f.pad("?"),
            },
            J::Array(items) => {
                let parts: Vec<String> = items
                    .iter()
                    .map(|item| item.as_f64().map_or_else(|| item.to_string(), sig))
                    .collect();
                f.pad(&format!("({})", parts.join(", ")))
            }
            other => f.pad(&other.to_string()),
        }
    }
}

/// A number with about five significant digits, in scientific notation when very small or large (the rapier
/// side's table format).
#[must_use]
pub fn sig(x: f64) -> String {
    let a = x.abs();
    if a != 0.0 && a.is_finite() && !(1e-3..1e6).contains(&a) {
        format!("{x:.4e}")
    } else {
        format!("{x:.5}")
    }
}

/// An `f32` widened to the `f64` with the same shortest decimal form (0.005, not 0.004999999888241291).
#[must_use]
pub fn short(x: f32) -> f64 {
    x.to_string().parse().unwrap_or(f64::from(x))
}

/// Median and mean of a set of step times, in milliseconds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TimingStats {
    /// Median ms/step (mean of the two middle samples for an even count).
    pub median_ms: f64,
    /// Mean ms/step.
    pub mean_ms: f64,
}

impl TimingStats {
    /// Statistics of `samples_ms` (NaN for an empty slice).
    #[must_use]
    pub fn of(samples_ms: &[f64]) -> Self {
        Self {
            median_ms: median(samples_ms),
            mean_ms: if samples_ms.is_empty() {
                f64::NAN
            } else {
                samples_ms.iter().sum::<f64>() / samples_ms.len() as f64
            },
        }
    }
}

/// The median of `samples` (the mean of the two middle ones for an even count; NaN when empty).
#[must_use]
pub fn median(samples: &[f64]) -> f64 {
    if samples.is_empty() {
        return f64::NAN;
    }
    let mut sorted = samples.to_vec();
    sorted.sort_by(f64::total_cmp);
    let n = sorted.len();
    if n % 2 == 1 {
        sorted[n / 2]
    } else {
        0.5 * (sorted[n / 2 - 1] + sorted[n / 2])
    }
}

/// Largest speed (m/s) of any dynamic body.
#[must_use]
pub fn max_speed(world: &PhysicsWorld) -> f32 {
    world
        .bodies()
        .iter()
        .filter(|(_, body)| body.is_dynamic())
        .map(|(_, body)| body.linear_velocity().length())
        .fold(0.0, f32::max)
}

/// Number of body pairs with an active contact at the last step: a manifold point whose separation is below
/// the world's speculative margin (0.02 m by default). That is rapier's test for a solver contact
/// (`has_any_active_contact`: distance below its 0.02 m prediction distance), without rapier's extra term for
/// points closing in within the step; Rebound's backend reports points out to the margin *plus* the bodies'
/// travel, and counting all of them would count pairs still flying towards each other. The separations are
/// the ones the step solved with (measured before its solve), as in rapier. Every body of the peer scenes
/// has one collider, so a body pair is a collider pair.
#[must_use]
pub fn active_contact_pairs(world: &PhysicsWorld) -> usize {
    let margin = world.settings().speculative_margin;
    let mut pairs: Vec<(BodyHandle, BodyHandle)> = world
        .contacts()
        .iter()
        .filter(|manifold| {
            manifold.points[..manifold.point_count.min(manifold.points.len())]
                .iter()
                .any(|point| point.separation < margin)
        })
        .map(|manifold| (manifold.body_a, manifold.body_b))
        .collect();
    pairs.sort_unstable();
    pairs.dedup();
    pairs.len()
}

/// The largest distance (m), over `joints`, between a joint's two anchor points in world space (anchor A
/// on body A, or the world point of a world joint, and anchor B on body B): zero when every joint holds its
/// point exactly, so this is pure joint error for ball-and-socket-like joints (hinge, ball, fixed).
#[must_use]
pub fn max_joint_separation(world: &PhysicsWorld, joints: &[JointHandle]) -> f32 {
    joints
        .iter()
        .filter_map(|&handle| {
            let joint = world.joint(handle)?;
            let (a, b) = world.joint_bodies(handle)?;
            let anchor_a = match a {
                Some(a) => world
                    .body(a)?
                    .pose()
                    .transform_point(joint.local_anchor_a()),
                None => joint.local_anchor_a(),
            };
            let anchor_b = world
                .body(b)?
                .pose()
                .transform_point(joint.local_anchor_b());
            Some(anchor_a.distance(anchor_b))
        })
        .fold(0.0, f32::max)
}

#[cfg(test)]
mod tests {
    use super::{DisplayJson, TimingStats, Value, short};

    #[test]
    fn median_of_even_and_odd_counts() {
        assert!((TimingStats::of(&[3.0, 1.0, 2.0]).median_ms - 2.0).abs() < 1e-12);
        assert!((TimingStats::of(&[4.0, 1.0, 2.0, 3.0]).median_ms - 2.5).abs() < 1e-12);
        assert!((TimingStats::of(&[4.0, 1.0, 2.0, 3.0]).mean_ms - 2.5).abs() < 1e-12);
        assert!(TimingStats::of(&[]).median_ms.is_nan());
    }

    #[test]
    fn values_serialise_as_the_rapier_side_writes_them() {
        assert_eq!(Value::f32(0.005).to_json().to_string(), "0.005");
        assert!((short(0.1) - 0.1).abs() < 1e-18);
        assert_eq!(Value::count(3).to_json().to_string(), "3");
        assert_eq!(Value::Missing.to_json().to_string(), "null");
        assert_eq!(Value::Bool(true).to_string(), "yes");
        let json: serde_json::Value = serde_json::from_str("[1.5, -2, 0.25]").expect("valid JSON");
        assert_eq!(
            DisplayJson(&json).to_string(),
            "(1.50000, -2.00000, 0.25000)"
        );
    }
}
