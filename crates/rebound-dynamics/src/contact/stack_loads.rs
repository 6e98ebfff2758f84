//! [`StackLoads`]: the weight each resting manifold carries, from the contact graph, before the solve. The
//! bodies are levelled by the fewest resting manifolds to a fixed or kinematic one; from the top level
//! down, each body hands its weight and what rests on it to its supports (its manifolds to a lower level
//! whose normal points up), in equal shares. Exact for a column; for a body on several supports the shares
//! are a guess the soft contacts correct.
//!
//! The solve uses a manifold's load as a preload of its soft rows (`docs/physics.md`, "Contacts under
//! load"): their spring then holds that load at a fixed small overlap instead of at `load / stiffness`.

use super::manifold::Contact;
use crate::BodyParams;
use rebound_math::Vec3;

/// The level of a body no chain of resting manifolds connects to a fixed or kinematic one.
const UNREACHED: u32 = u32::MAX;

/// A manifold rests when a point started the step at least this close (m) and it pushed in the last
/// step.
const RESTING_GAP: f32 = 1e-3;

/// A support's normal points up by at least this cosine (45°).
const SUPPORT_COSINE: f32 = core::f32::consts::FRAC_1_SQRT_2;

/// The scratch buffers of the load propagation, reused from step to step: flat arrays indexed by body or
/// by link, so a step allocates nothing once they have grown, and a body no resting manifold touches costs
/// only its share of two fills.
#[derive(Debug, Clone, Default)]
pub struct StackLoads {
    /// Body → its level: 0 for fixed and kinematic bodies, else the fewest resting manifolds to one.
    level: Vec<u32>,
    /// Body → the weight (N) that rests on it, handed down from the bodies above.
    carried: Vec<f32>,
    /// Body → where its links start in `links`; the entry after the last body is the number of links.
    start: Vec<u32>,
    /// The resting manifolds of each body, body after body: manifold index and the body at its other end.
    links: Vec<Link>,
    /// The reached bodies in breadth-first order from the fixed and kinematic ones.
    queue: Vec<u32>,
    /// One body's supports: manifold, supporting body, upward cosine of the normal.
    supports: Vec<(u32, u32, f32)>,
    /// The resting manifolds, in order.
    resting: Vec<u32>,
}

/// One end of a resting manifold, seen from a body.
#[derive(Debug, Clone, Copy, Default)]
struct Link {
    /// The manifold (index into the contacts).
    manifold: u32,
    /// The body at the other end.
    other: u32,
}

/// Whether manifold `c` rests: a point started the step within [`RESTING_GAP`].
fn resting(c: &Contact) -> bool {
    c.points().iter().any(|p| p.separation < RESTING_GAP)
}

/// The upward cosine of manifold `c`'s normal seen from `other` towards `body` (the normal points from
/// `body_a` to `body_b`).
fn upward_cosine(c: &Contact, body: usize, up: Vec3) -> f32 {
    let cosine = c.normal.dot(up);
    if c.body_b == body { cosine } else { -cosine }
}

/// Scales the warm-start impulses of `c`'s points so that they sum to its load over a substep `h` (s),
/// keeping how they share it (equal shares if none pushed): the substeps start from the impulse that holds
/// the load instead of building it pass by pass, which a light body between a heavy one and the ground
/// cannot do (a pass moves the heavy body by about the mass ratio of the error).
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
    /// An empty propagation.
    #[must_use]
    pub fn new() -> Self {
        Self::default()
    }

    /// Sets [`Contact::load`] of every manifold in `contacts` (solver indices into `params`): the normal
    /// force (N) its resting bodies press it with under `gravity` (m/s²), 0 for a manifold that carries no
    /// body's weight. A loaded manifold's warm-start impulses are set to hold its load over a substep `h`
    /// (s) if none pushed.
    pub fn compute(
        &mut self,
        contacts: &mut [Contact],
        params: &[BodyParams],
        gravity: Vec3,
        h: f32,
    ) {
        let g = gravity.length();
        let rests = self.link(contacts, params, g > 0.0 && g.is_finite());
        if !rests {
            return;
        }
        let up = -gravity / g;
        self.carried.clear();
        self.carried.resize(params.len(), 0.0);
        self.level_bodies();
        // Disjoint borrows, so that the loops below keep the slices in registers.
        let Self {
            level,
            carried,
            start,
            links,
            queue,
            supports,
            ..
        } = self;
        let (level, start, links) = (&level[..], &start[..], &links[..]);
        // From the top level down: each body's weight and what rests on it to its supports, in equal
        // shares.
        for &body in queue.iter().rev() {
            let body = body as usize;
            let level_of_body = level[body];
            let p = &params[body];
            if level_of_body == 0 || p.inv_mass <= 0.0 {
                continue;
            }
            let weight = p.gravity_scale * g / p.inv_mass + carried[body];
            if weight.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) {
                continue;
            }
            supports.clear();
            for link in &links[start[body] as usize..start[body + 1] as usize] {
                if level[link.other as usize] >= level_of_body {
                    continue;
                }
                let cosine = upward_cosine(&contacts[link.manifold as usize], body, up);
                if cosine >= SUPPORT_COSINE {
                    supports.push((link.manifold, link.other, cosine));
                }
            }
            if supports.is_empty() {
                continue;
            }
            let share = weight / supports.len() as f32;
            for &(m, other, cosine) in supports.iter() {
                // Only the upper body of a manifold loads it: this is its one load.
                let c = &mut contacts[m as usize];
                c.load = share * cosine;
                warm_start_with_load(c, h);
                carried[other as usize] += share;
            }
        }
    }

    /// Clears every load and links the resting manifolds (when `gravity` has a direction) into rows per
    /// body; the fixed and kinematic bodies they touch start `queue` at level 0, every other body is
    /// unreached. Returns whether any manifold rests.
    fn link(&mut self, contacts: &mut [Contact], params: &[BodyParams], gravity: bool) -> bool {
        let body_count = params.len();
        let valid =
            |c: &Contact| c.body_a < body_count && c.body_b < body_count && c.body_a != c.body_b;
        // `start[b]` counts body b's links, then becomes where its row ends.
        self.start.clear();
        self.start.resize(body_count + 1, 0);
        self.resting.clear();
        let (start, rests) = (&mut self.start[..], &mut self.resting);
        for (m, c) in contacts.iter_mut().enumerate() {
            c.load = 0.0;
            if gravity && valid(c) && resting(c) {
                start[c.body_a] += 1;
                start[c.body_b] += 1;
                rests.push(m as u32);
            }
        }
        if self.resting.is_empty() {
            return false;
        }
        let mut total = 0;
        for end in &mut self.start {
            total += *end;
            *end = total;
        }
        self.links.clear();
        self.links.resize(total as usize, Link::default());
        self.level.clear();
        self.level.resize(body_count, UNREACHED);
        self.queue.clear();
        let (start, links, level) = (
            &mut self.start[..],
            &mut self.links[..],
            &mut self.level[..],
        );
        // Filled from each row's end back to its start, which `start` then holds.
        for &m in &self.resting {
            let c = &contacts[m as usize];
            for (body, other) in [(c.body_a, c.body_b), (c.body_b, c.body_a)] {
                start[body] -= 1;
                links[start[body] as usize] = Link {
                    manifold: m,
                    other: other as u32,
                };
                if level[body] == UNREACHED && params[body].inv_mass <= 0.0 {
                    level[body] = 0;
                    self.queue.push(body as u32);
                }
            }
        }
        true
    }

    /// Levels by breadth-first search from the fixed and kinematic bodies in `queue` over the links;
    /// `queue` keeps the order.
    fn level_bodies(&mut self) {
        let (level, start, links, queue) = (
            &mut self.level[..],
            &self.start[..],
            &self.links[..],
            &mut self.queue,
        );
        let mut head = 0;
        while let Some(&body) = queue.get(head) {
            head += 1;
            let body = body as usize;
            let next = level[body] + 1;
            for link in &links[start[body] as usize..start[body + 1] as usize] {
                let other = link.other as usize;
                if level[other] == UNREACHED {
                    level[other] = next;
                    queue.push(link.other);
                }
            }
        }
    }
}
