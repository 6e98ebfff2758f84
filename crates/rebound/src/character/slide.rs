//! Move-and-slide: the shape goes along the desired translation until it comes `skin` short of a surface,
//! and the rest of the motion is turned along that surface; repeated for at most `max_iterations` hits.
//! How the rest is turned depends on the surface (`docs/physics.md`, "Character controller"):
//!
//! - **walkable** (`n·up ≥ cos(max_slope_angle)`): the motion across `up` is kept and the motion along `up`
//!   becomes whatever keeps it on the plane, `h + up·k` with `k = −(h·n)/(n·up)`: the character walks up
//!   and down slopes at the commanded horizontal speed, and pressing down (gravity) into the ground stops;
//! - **steep** (`0 ≤ n·up < cos(max_slope_angle)`, walls included): the horizontal motion into the surface
//!   is removed with the horizontal normal `n_h`, so it can never climb, and what still goes into the plane
//!   (a downward motion) is projected on it, so it slides down; a step in the way may be climbed first
//!   ([`super::autostep`]);
//! - **overhanging** (`n·up < 0`, ceilings): the motion into the plane is removed.
//!
//! Each rule leaves a motion already along the plane as it is, so meeting the same face twice changes
//! nothing. A motion turned along the second of two planes that would go back into the first follows their
//! crease.

use super::CharacterCollision;
use super::autostep;
use super::sweep::{Probe, SweepHit};
use rebound_math::Vec3;

/// Below this length (m) what is left of the motion is dropped.
const MIN_MOTION: f32 = 1.0e-6;

/// Below this sine of the angle between two planes' normals they are treated as one plane.
const MIN_CREASE_SIN: f32 = 0.045;

/// Where the slide ended and what it met.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Slide {
    /// The shape's final position (m).
    pub(crate) position: Vec3,
    /// Whether it touched a walkable surface on the way.
    pub(crate) touched_ground: bool,
    /// Whether it climbed a step.
    pub(crate) stepped: bool,
}

/// Slides the shape from `start` along `desired` (m), logging each hit in `collisions`. `ground`: the point
/// of the walkable ground it stands on at the start, if any (steps are climbed only from the ground, and
/// measured from it).
pub(crate) fn slide(
    probe: &Probe<'_>,
    start: Vec3,
    desired: Vec3,
    ground: Option<Vec3>,
    collisions: &mut Vec<CharacterCollision>,
) -> Slide {
    let up = probe.settings.up;
    let mut ground = ground;
    let mut out = Slide {
        position: start,
        touched_ground: false,
        stepped: false,
    };
    let mut remaining = desired;
    let mut previous_normal: Option<Vec3> = None;
    for _ in 0..probe.settings.max_iterations {
        let length = remaining.length();
        if length < MIN_MOTION {
            break;
        }
        let direction = remaining / length;
        let Some(hit) = probe.sweep(out.position, direction, length, None) else {
            out.position += remaining;
            break;
        };
        out.position += direction * hit.distance;
        remaining = direction * (length - hit.distance);
        collisions.push(CharacterCollision {
            collider: hit.collider,
            body: hit.body,
            point: hit.point,
            normal: hit.normal,
            translation_before: out.position - start,
            translation_remaining: remaining,
        });
        let walkable = probe.is_walkable(hit.normal);
        if walkable {
            out.touched_ground = true;
            ground = Some(hit.point);
        }
        let step_from = ground.filter(|_| !walkable && remaining.dot(up) <= MIN_MOTION);
        if let Some(stepped) = step_from.and_then(|ground_point| {
            autostep::try_step(probe, out.position, remaining, &hit, ground_point)
        }) {
            out.position = stepped;
            out.stepped = true;
            out.touched_ground = true;
            break;
        }
        let mut turned = turn_along(probe, remaining, &hit, walkable);
        if let Some(first) = previous_normal {
            turned = follow_crease(turned, first, hit.normal);
        }
        previous_normal = Some(hit.normal);
        remaining = turned;
    }
    out
}

/// The motion `remaining` turned along the surface of `hit` (the three cases of the module doc).
fn turn_along(probe: &Probe<'_>, remaining: Vec3, hit: &SweepHit, walkable: bool) -> Vec3 {
    let up = probe.settings.up;
    let n = hit.normal;
    let n_up = n.dot(up);
    let horizontal = probe.horizontal(remaining);
    if walkable {
        // n·up ≥ cos(max_slope_angle) > 0.
        return horizontal - up * (horizontal.dot(n) / n_up);
    }
    if n_up < 0.0 {
        return remaining - n * remaining.dot(n).min(0.0);
    }
    let along_wall = match probe.horizontal(n).try_normalize() {
        Some(n_h) => horizontal - n_h * horizontal.dot(n_h).min(0.0),
        None => horizontal,
    };
    let kept = along_wall + up * remaining.dot(up);
    // What still goes into the plane goes down it: `kept·n < 0` only through a downward part, and removing
    // `n·(kept·n)` takes back at most that much height.
    kept - n * kept.dot(n).min(0.0)
}

/// `motion` turned along the crease of planes `first` and `second` when it would go back into `first`. Two
/// planes less than about 2.6° apart (the same face met twice, with the normals a cast gives) have no
/// useful crease: the motion then only loses its part into `first`.
fn follow_crease(motion: Vec3, first: Vec3, second: Vec3) -> Vec3 {
    if motion.dot(first) >= 0.0 {
        return motion;
    }
    let cross = second.cross(first);
    if cross.length_squared() < MIN_CREASE_SIN * MIN_CREASE_SIN {
        return motion - first * motion.dot(first);
    }
    let crease = cross.normalize();
    crease * motion.dot(crease)
}
