//! [`StackLoads`]: the weight each resting manifold carries, from the contact graph, before the solve. The
//! graph is the supports: resting manifolds whose normal points up within 45°, each a link from the body
//! below to the body above. The bodies are levelled up from the fixed and kinematic ones (the fewest
//! supports between a body and one of them); from the top level down each body hands its weight and what
//! rests on it to its supports on a lower level, in equal shares. Exact for a column; for a body on several
//! supports the shares are a guess the soft contacts correct.
//!
//! The caller hands over the resting manifolds as it builds them ([`StackLoads::begin`],
//! [`StackLoads::add`], [`StackLoads::finish`]), so finding them costs no pass of its own; a manifold that
//! is not a support is dropped there and then. Contact preparation turns a manifold's load into the rest
//! point of its soft rows (`docs/physics.md`, "Contacts under load"): their spring then holds that load at
//! a fixed small overlap instead of at `load / stiffness`.

use super::manifold::Contact;
use crate::BodyParams;
use rebound_math::Vec3;

/// The level of a body no chain of supports connects to a fixed or kinematic one.
const UNREACHED: u32 = u32::MAX;

/// A support's normal points up by at least this cosine (45°).
const SUPPORT_COSINE: f32 = core::f32::consts::FRAC_1_SQRT_2;

/// No link: the end of a body's list.
const NONE: u32 = u32::MAX;

/// The scratch buffers of the load propagation, reused from step to step: flat arrays indexed by body or
/// by link. Between calls every body is unreached and has no link, and a call restores that for the bodies
/// it touched only, so a body no resting manifold touches costs nothing and a step allocates nothing once
/// the buffers have grown.
#[derive(Debug, Clone, Default)]
pub struct StackLoads {
    /// Body → its level: 0 for fixed and kinematic bodies, else the fewest supports to one.
    level: Vec<u32>,
    /// Body → the weight (N) that rests on it, handed down from the bodies above (set when reached).
    carried: Vec<f32>,
    /// Body → how many of its supports are on the level below it (set when reached).
    support_count: Vec<u32>,
    /// Body → its last link to a body it supports, [`NONE`] if it has none.
    above: Vec<u32>,
    /// Body → its last link to a body that supports it, [`NONE`] if it has none.
    below: Vec<u32>,
    /// The supports, each in the lists of both its bodies.
    links: Vec<Link>,
    /// The reached bodies in breadth-first order from the fixed and kinematic ones.
    queue: Vec<u32>,
    /// The unit vector against gravity, zero while gravity has no direction (then nothing is linked).
    up: Vec3,
    /// `|g|` (m/s²) of the current call.
    g: f32,
}

/// A manifold found to be a support ([`StackLoads::support`]): its lower and upper bodies and the upward
/// cosine of its normal from the lower to the upper.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Support {
    lower: u32,
    upper: u32,
    cosine: f32,
}

/// A support: a resting manifold whose normal points up, seen as a link from the lower body to the upper.
#[derive(Debug, Clone, Copy)]
struct Link {
    /// The manifold (index into the contacts).
    manifold: u32,
    /// The supporting body.
    lower: u32,
    /// The supported body.
    upper: u32,
    /// The upward cosine of the normal, from the lower body to the upper one (≥ [`SUPPORT_COSINE`]).
    cosine: f32,
    /// The lower body's previous link in `above`, [`NONE`] if this is its first.
    next_above: u32,
    /// The upper body's previous link in `below`, [`NONE`] if this is its first.
    next_below: u32,
}

/// The links of one list, from its head `first`, each followed by `next`.
fn list(links: &[Link], first: u32, next: fn(&Link) -> u32) -> impl Iterator<Item = &Link> {
    core::iter::successors(links.get(first as usize), move |link| {
        links.get(next(link) as usize)
    })
}

/// Scales the warm-start impulses of `c`'s points so that they sum to its load over a substep `h` (s),
/// if none pushed (equal shares): the substeps start from the impulse that holds the load instead of
/// building it pass by pass, which a light body between a heavy one and the ground cannot do (a pass moves
/// the heavy body by about the mass ratio of the error).
fn warm_start_with_load(c: &mut Contact, h: f32) {
    let target = c.load * h;
    let count = c.point_count.min(c.points.len());
    let points = &mut c.points[..count];
    let total: f32 = points.iter().map(|p| p.normal_impulse.max(0.0)).sum();
    if total <= 0.0 && count > 0 {
        for p in points.iter_mut() {
            p.normal_impulse = target / count as f32;
        }
    }
}

impl StackLoads {
    /// A manifold rests when one of its points starts the step closer than this (m).
    pub const RESTING_GAP: f32 = 1e-3;

    /// An empty propagation.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Starts a propagation under `gravity` (m/s²): forgets the last call's supports. Without a gravity
    /// direction (zero or not finite) [`StackLoads::add`] links nothing.
    pub fn begin(&mut self, gravity: Vec3) {
        self.links.clear();
        self.queue.clear();
        let g = gravity.length();
        (self.up, self.g) = if g > 0.0 && g.is_finite() {
            (-gravity / g, g)
        } else {
            (Vec3::ZERO, 0.0)
        };
    }

    /// Offers manifold `c` (index `manifold` into the contacts later given to [`StackLoads::finish`], body
    /// indices into `params`). It is linked if it is a support: it rests (a point within
    /// [`StackLoads::RESTING_GAP`]) and its normal points up within 45°, and its upper body is one the
    /// solver moves; otherwise (a body with itself too) it is dropped.
    #[inline]
    pub fn add(&mut self, manifold: usize, c: &Contact, params: &[BodyParams]) {
        if let Some(support) = self.support(c, params) {
            self.link(manifold, support, params);
        }
    }

    /// Whether manifold `c` is a support, as [`StackLoads::add`] judges it, and which way up: reads the
    /// manifold alone, so a caller may judge its manifolds on several threads and link the supports found
    /// in manifold order after ([`StackLoads::link`]). `None` before [`StackLoads::begin`].
    #[inline]
    #[must_use]
    pub fn support(&self, c: &Contact, params: &[BodyParams]) -> Option<Support> {
        let cosine = c.normal.dot(self.up);
        let (lower, upper, cosine) = if cosine >= SUPPORT_COSINE {
            (c.body_a, c.body_b, cosine)
        } else if -cosine >= SUPPORT_COSINE {
            (c.body_b, c.body_a, -cosine)
        } else {
            return None;
        };
        if !c.points().iter().any(|p| p.separation < Self::RESTING_GAP) {
            return None;
        }
        let pu = params.get(upper)?;
        if lower >= params.len() || lower == upper || pu.inv_mass <= 0.0 {
            // Nothing to hand down: no body, or one the solver does not move.
            return None;
        }
        Some(Support {
            lower: lower as u32,
            upper: upper as u32,
            cosine,
        })
    }

    /// Links manifold `manifold` as the support [`StackLoads::support`] found it to be (body indices into
    /// `params`): what [`StackLoads::add`] does with a support. The order of the calls is the order of the
    /// hand-down's sums.
    #[inline]
    pub fn link(&mut self, manifold: usize, support: Support, params: &[BodyParams]) {
        let Support {
            lower,
            upper,
            cosine,
        } = support;
        let (lower, upper) = (lower as usize, upper as usize);
        let Some(pl) = params.get(lower) else {
            return;
        };
        if self.level.len() < params.len() {
            self.grow(params.len());
        }
        if upper >= self.level.len() {
            return;
        }
        let index = self.links.len() as u32;
        self.links.push(Link {
            manifold: manifold as u32,
            lower: lower as u32,
            upper: upper as u32,
            cosine,
            next_above: self.above[lower],
            next_below: self.below[upper],
        });
        self.above[lower] = index;
        self.below[upper] = index;
        if pl.inv_mass <= 0.0 && self.level[lower] == UNREACHED {
            self.level[lower] = 0;
            self.carried[lower] = 0.0;
            self.queue.push(lower as u32);
        }
    }

    /// Room for `body_count` bodies, all unreached and unlinked.
    #[cold]
    fn grow(&mut self, body_count: usize) {
        self.level.resize(body_count, UNREACHED);
        self.above.resize(body_count, NONE);
        self.below.resize(body_count, NONE);
        self.carried.resize(body_count, 0.0);
        self.support_count.resize(body_count, 0);
    }

    /// Sets [`Contact::load`] of every added manifold in `contacts` (body indices into `params`): the
    /// normal force (N) its resting bodies press it with, handed down from the top of the stack. A loaded
    /// manifold's warm-start impulses are set to hold its load over a substep `h` (s) if none pushed. The
    /// loads of manifolds not added are left as they are (0 as [`Contact::new`] makes them).
    pub fn finish(&mut self, contacts: &mut [Contact], params: &[BodyParams], h: f32) {
        if self.links.is_empty() {
            return;
        }
        self.level_bodies();
        self.hand_down(contacts, params, h);
        // Back to unreached and unlinked for the next call.
        for &body in &self.queue {
            self.level[body as usize] = UNREACHED;
        }
        for link in &self.links {
            self.above[link.lower as usize] = NONE;
            self.below[link.upper as usize] = NONE;
        }
        self.links.clear();
        self.queue.clear();
    }

    /// Sets [`Contact::load`] of every manifold in `contacts` (solver indices into `params`) under
    /// `gravity` (m/s²), 0 for a manifold that carries no body's weight: [`StackLoads::begin`], every
    /// manifold to [`StackLoads::add`], [`StackLoads::finish`] for substeps of `h` (s). For a caller
    /// that has its contacts at hand; one that builds them adds them as it goes instead.
    pub fn compute(
        &mut self,
        contacts: &mut [Contact],
        params: &[BodyParams],
        gravity: Vec3,
        h: f32,
    ) {
        self.begin(gravity);
        for (m, c) in contacts.iter_mut().enumerate() {
            c.load = 0.0;
            self.add(m, c, params);
        }
        self.finish(contacts, params, h);
    }

    /// Levels by breadth-first search up the supports from the fixed and kinematic bodies in `queue`, and
    /// counts each reached body's supports on the level below it; `queue` keeps the order.
    fn level_bodies(&mut self) {
        let (level, carried, support_count, above, links, queue) = (
            &mut self.level[..],
            &mut self.carried[..],
            &mut self.support_count[..],
            &self.above[..],
            &self.links[..],
            &mut self.queue,
        );
        let mut head = 0;
        while let Some(&body) = queue.get(head) {
            head += 1;
            let body = body as usize;
            let next = level[body] + 1;
            for link in list(links, above[body], |l| l.next_above) {
                let upper = link.upper as usize;
                if level[upper] == UNREACHED {
                    level[upper] = next;
                    carried[upper] = 0.0;
                    support_count[upper] = 1;
                    queue.push(link.upper);
                } else if level[upper] == next {
                    support_count[upper] += 1;
                }
            }
        }
    }

    /// From the top level down: each body's weight (`|g|`·`s_g`·m, N) and what rests on it to its supports
    /// on a lower level, in equal shares; each loaded manifold's warm start for a substep `h` (s).
    fn hand_down(&mut self, contacts: &mut [Contact], params: &[BodyParams], h: f32) {
        let (level, carried, support_count, below, links, queue, g) = (
            &self.level[..],
            &mut self.carried[..],
            &self.support_count[..],
            &self.below[..],
            &self.links[..],
            &self.queue[..],
            self.g,
        );
        for &body in queue.iter().rev() {
            let body = body as usize;
            let level_of_body = level[body];
            if level_of_body == 0 {
                // The fixed and kinematic bodies come first in the queue: none is left above them.
                break;
            }
            // Reached from below: one support or more, all on the level below.
            let count = support_count[body];
            let p = &params[body];
            let weight = p.gravity_scale * g / p.inv_mass + carried[body];
            if weight.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) {
                continue;
            }
            let share = weight / count as f32;
            let supports = list(links, below[body], |l| l.next_below)
                .filter(|link| level[link.lower as usize] < level_of_body);
            for link in supports {
                // Only the upper body of a manifold loads it: this is its one load.
                if let Some(c) = contacts.get_mut(link.manifold as usize) {
                    c.load = share * link.cosine;
                    warm_start_with_load(c, h);
                }
                carried[link.lower as usize] += share;
            }
        }
    }
}
