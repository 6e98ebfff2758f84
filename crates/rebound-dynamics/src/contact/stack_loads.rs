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

/// The scratch buffers of the load propagation, reused from step to step.
#[derive(Debug, Clone, Default)]
pub struct StackLoads {
    /// Body → its level: 0 for fixed and kinematic bodies, else the fewest resting manifolds to one.
    level: Vec<u32>,
    /// Body → the weight it hands down (N): its own and what rests on it.
    weight: Vec<f32>,
    /// Body → where its resting manifolds start in `links` (one more entry than bodies).
    start: Vec<u32>,
    /// The resting manifolds of each body, body after body.
    links: Vec<u32>,
    /// Fill cursors of `links`.
    cursor: Vec<u32>,
    /// The bodies in breadth-first order from the fixed ones.
    queue: Vec<u32>,
    /// One body's supports: manifold, supporting body, upward cosine of the normal.
    supports: Vec<(u32, u32, f32)>,
    /// Manifold → whether it rests.
    resting: Vec<bool>,
}

/// Whether manifold `c` rests: it pushed in the last step and a point is within [`RESTING_GAP`].
fn resting(c: &Contact) -> bool {
    c.points().iter().any(|p| p.separation < RESTING_GAP)
}

/// Whether manifold `m` supports `body`: it leads to a body of a lower level and its normal, seen from
/// there towards `body`, points up by at least [`SUPPORT_COSINE`]. Gives the supporting body and that
/// cosine.
fn support(
    contacts: &[Contact],
    level: &[u32],
    body: usize,
    m: u32,
    up: Vec3,
) -> Option<(usize, f32)> {
    let c = &contacts[m as usize];
    let (other, n) = if c.body_b == body {
        (c.body_a, c.normal)
    } else {
        (c.body_b, -c.normal)
    };
    let cosine = n.dot(up);
    (level[other] < level[body] && cosine >= SUPPORT_COSINE).then_some((other, cosine))
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
    /// body's weight.
    pub fn compute(
        &mut self,
        contacts: &mut [Contact],
        params: &[BodyParams],
        gravity: Vec3,
        h: f32,
    ) {
        let g = gravity.length();
        if !(g > 0.0 && g.is_finite()) {
            for c in contacts.iter_mut() {
                c.load = 0.0;
            }
            return;
        }
        let up = -gravity / g;
        let body_count = params.len();
        let valid =
            |c: &Contact| c.body_a < body_count && c.body_b < body_count && c.body_a != c.body_b;
        self.resting.clear();
        self.resting.extend(contacts.iter_mut().map(|c| {
            c.load = 0.0;
            valid(c) && resting(c)
        }));
        self.link(contacts, body_count);
        self.level_bodies(contacts, params);
        self.weight.clear();
        self.weight.extend(params.iter().map(|p| {
            if p.inv_mass > 0.0 {
                p.gravity_scale * g / p.inv_mass
            } else {
                0.0
            }
        }));
        // From the top level down: each body's weight to its supports, in equal shares.
        for &body in self.queue.iter().rev() {
            let body = body as usize;
            let (level, weight) = (self.level[body], self.weight[body]);
            if level == 0 || weight.partial_cmp(&0.0) != Some(core::cmp::Ordering::Greater) {
                continue;
            }
            let row = self.start[body] as usize..self.start[body + 1] as usize;
            self.supports.clear();
            for &m in &self.links[row] {
                if let Some((other, cosine)) = support(contacts, &self.level, body, m, up) {
                    self.supports.push((m, other as u32, cosine));
                }
            }
            if self.supports.is_empty() {
                continue;
            }
            let share = weight / self.supports.len() as f32;
            for &(m, other, cosine) in &self.supports {
                contacts[m as usize].load += share * cosine;
                self.weight[other as usize] += share;
            }
        }
        for c in contacts.iter_mut().filter(|c| c.load > 0.0) {
            warm_start_with_load(c, h);
        }
    }

    /// Compressed rows of the resting manifolds, per body.
    fn link(&mut self, contacts: &[Contact], body_count: usize) {
        self.start.clear();
        self.start.resize(body_count + 1, 0);
        for (c, _) in contacts.iter().zip(&self.resting).filter(|(_, r)| **r) {
            self.start[c.body_a + 1] += 1;
            self.start[c.body_b + 1] += 1;
        }
        for i in 0..body_count {
            self.start[i + 1] += self.start[i];
        }
        self.links.clear();
        self.links.resize(self.start[body_count] as usize, 0);
        self.cursor.clear();
        self.cursor.extend_from_slice(&self.start[..body_count]);
        for (m, (c, _)) in contacts
            .iter()
            .zip(&self.resting)
            .enumerate()
            .filter(|(_, (_, r))| **r)
        {
            for body in [c.body_a, c.body_b] {
                self.links[self.cursor[body] as usize] = m as u32;
                self.cursor[body] += 1;
            }
        }
    }

    /// Levels by breadth-first search from the fixed and kinematic bodies over the linked manifolds;
    /// `queue` keeps the order.
    fn level_bodies(&mut self, contacts: &[Contact], params: &[BodyParams]) {
        self.level.clear();
        self.queue.clear();
        for (i, p) in params.iter().enumerate() {
            if p.inv_mass > 0.0 {
                self.level.push(UNREACHED);
            } else {
                self.level.push(0);
                self.queue.push(i as u32);
            }
        }
        let mut head = 0;
        while let Some(&body) = self.queue.get(head) {
            head += 1;
            let body = body as usize;
            let next = self.level[body] + 1;
            let row = self.start[body] as usize..self.start[body + 1] as usize;
            for &m in &self.links[row] {
                let c = &contacts[m as usize];
                let other = if c.body_a == body { c.body_b } else { c.body_a };
                if self.level[other] == UNREACHED {
                    self.level[other] = next;
                    self.queue.push(other as u32);
                }
            }
        }
    }
}
