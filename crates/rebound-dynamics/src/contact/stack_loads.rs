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

/// No link: the end of a body's list.
const NONE: u32 = u32::MAX;

/// The scratch buffers of the load propagation, reused from step to step: flat arrays indexed by body or
/// by link. Between calls every body is unreached and has no link, and a call restores that for the bodies
/// it touched only, so a body no resting manifold touches costs nothing and a step allocates nothing once
/// the buffers have grown.
#[derive(Debug, Clone, Default)]
pub struct StackLoads {
    /// Body → its level: 0 for fixed and kinematic bodies, else the fewest resting manifolds to one.
    level: Vec<u32>,
    /// Body → the weight (N) that rests on it, handed down from the bodies above (set when reached).
    carried: Vec<f32>,
    /// Body → its last link in `links`, [`NONE`] if it has none.
    first: Vec<u32>,
    /// The ends of the resting manifolds, each in its body's list.
    links: Vec<Link>,
    /// The reached bodies in breadth-first order from the fixed and kinematic ones.
    queue: Vec<u32>,
    /// One body's supports: manifold, supporting body, upward cosine of the normal.
    supports: Vec<(u32, u32, f32)>,
}

/// One end of a resting manifold, seen from a body.
#[derive(Debug, Clone, Copy)]
struct Link {
    /// The manifold (index into the contacts).
    manifold: u32,
    /// The body at the other end.
    other: u32,
    /// The body's previous link, [`NONE`] if this is its first.
    next: u32,
}

/// The links of one body, from its entry of `first`.
fn list(links: &[Link], first: u32) -> impl Iterator<Item = &Link> {
    core::iter::successors(links.get(first as usize), |link| {
        links.get(link.next as usize)
    })
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
        if !self.link(contacts, params, g > 0.0 && g.is_finite()) {
            return;
        }
        self.level_bodies();
        self.hand_down(contacts, params, g, -gravity / g, h);
        // Back to unreached and unlinked for the next call.
        for &body in &self.queue {
            self.level[body as usize] = UNREACHED;
        }
        for link in &self.links {
            self.first[link.other as usize] = NONE;
        }
    }

    /// From the top level down: each body's weight (`g`·`s_g`·m, N) and what rests on it to its supports
    /// (against `up`), in equal shares; each loaded manifold's warm start for a substep `h` (s).
    fn hand_down(
        &mut self,
        contacts: &mut [Contact],
        params: &[BodyParams],
        g: f32,
        up: Vec3,
        h: f32,
    ) {
        let Self {
            level,
            carried,
            first,
            links,
            queue,
            supports,
        } = self;
        let (level, first, links) = (&level[..], &first[..], &links[..]);
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
            for link in list(links, first[body]) {
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

    /// Clears every load and links the resting manifolds (when `gravity` has a direction) into a list per
    /// body; the fixed and kinematic bodies they touch start `queue` at level 0. Returns whether any
    /// manifold rests.
    fn link(&mut self, contacts: &mut [Contact], params: &[BodyParams], gravity: bool) -> bool {
        let body_count = params.len();
        if self.level.len() < body_count {
            self.level.resize(body_count, UNREACHED);
            self.first.resize(body_count, NONE);
            self.carried.resize(body_count, 0.0);
        }
        self.links.clear();
        self.queue.clear();
        let valid =
            |c: &Contact| c.body_a < body_count && c.body_b < body_count && c.body_a != c.body_b;
        let (level, first, carried) = (
            &mut self.level[..],
            &mut self.first[..],
            &mut self.carried[..],
        );
        for (m, c) in contacts.iter_mut().enumerate() {
            c.load = 0.0;
            if !(gravity && valid(c) && resting(c)) {
                continue;
            }
            for (body, other) in [(c.body_a, c.body_b), (c.body_b, c.body_a)] {
                self.links.push(Link {
                    manifold: m as u32,
                    other: other as u32,
                    next: first[body],
                });
                first[body] = (self.links.len() - 1) as u32;
                if level[body] == UNREACHED && params[body].inv_mass <= 0.0 {
                    level[body] = 0;
                    carried[body] = 0.0;
                    self.queue.push(body as u32);
                }
            }
        }
        !self.links.is_empty()
    }

    /// Levels by breadth-first search from the fixed and kinematic bodies in `queue` over the links;
    /// `queue` keeps the order.
    fn level_bodies(&mut self) {
        let (level, carried, first, links, queue) = (
            &mut self.level[..],
            &mut self.carried[..],
            &self.first[..],
            &self.links[..],
            &mut self.queue,
        );
        let mut head = 0;
        while let Some(&body) = queue.get(head) {
            head += 1;
            let body = body as usize;
            let next = level[body] + 1;
            for link in list(links, first[body]) {
                let other = link.other as usize;
                if level[other] == UNREACHED {
                    level[other] = next;
                    carried[other] = 0.0;
                    queue.push(link.other);
                }
            }
        }
    }
}
