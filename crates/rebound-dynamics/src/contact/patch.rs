//! A manifold's friction patch on the scalar path: two tangent rows at the centre of its points and one twist
//! row about the normal, built in stage *prepare*, applied again in *warm start*, solved after the normal rows
//! in *solve* and *relax*; and how the patch's impulses are shared out among the points ([`PatchShare`]) for
//! warm starting the next step and for reporting. The wide path holds the same rows in lanes
//! (`super::wide`), with the same equations.

use super::manifold::ContactPoint;
use super::prepared::{PrepareInput, PreparedContact};
use crate::SolverBody;
use rebound_math::{Vec2, Vec3};

/// A manifold's friction patch: two tangent rows at the centre of its points and one twist row about the
/// normal, in place of two tangent rows per point (`docs/physics.md`, Contacts, "Friction").
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Patch {
    /// The centre `c` of the points, relative to body A's centre of mass (m).
    pub(crate) center_a: Vec3,
    /// `Σ|ρ|²` over the points, `ρ = r_a − c` a point's offset from the centre (m²).
    pub(crate) spread: f32,
    /// Accumulated tangent impulse in the manifold's tangent basis (N·s).
    pub(crate) tangent_impulse: Vec2,
    pub(crate) tangent_mass: [f32; 2],
    pub(crate) rt_a: [Vec3; 2],
    pub(crate) rt_b: [Vec3; 2],
    pub(crate) wt_a: [Vec3; 2],
    pub(crate) wt_b: [Vec3; 2],
    /// Accumulated twist impulse about the normal (N·m·s).
    pub(crate) twist_impulse: f32,
    pub(crate) twist_mass: f32,
    /// `I_a⁻¹·n` and `I_b⁻¹·n`.
    pub(crate) twist_a: Vec3,
    pub(crate) twist_b: Vec3,
    /// The relative tangential velocity the tangent rows drive to, along the two tangents (m/s): the
    /// contact's surface velocity (zero for ordinary friction).
    pub(crate) target: Vec2,
}

impl Patch {
    /// Stage *prepare*: the friction patch of manifold `c` with points `points` — the centre of the points on
    /// each body, the tangent rows there, the twist row, and the warm-start impulses recovered from the
    /// points' stored friction impulses ([`PatchShare`] in reverse: their sum, and their moment about the
    /// centre).
    #[inline]
    pub(crate) fn new(
        input: &PrepareInput<'_>,
        c: &PreparedContact,
        points: &[ContactPoint],
    ) -> Self {
        let (pa, pb) = (&input.params[c.body_a], &input.params[c.body_b]);
        let normal = c.normal;
        let count = points.len() as f32;
        let [center_a, center_b, warm_linear] = patch_sums(points);
        let (mut spread, mut warm_twist) = (0.0, 0.0);
        for p in points {
            let rho = p.anchor_a - center_a;
            spread += rho.dot(rho);
            warm_twist += rho.cross(p.tangent_impulse).dot(normal);
        }
        let mass_sum = pa.inv_mass + pb.inv_mass;
        let invert = |k: f32| if k > 0.0 && count > 0.0 { 1.0 / k } else { 0.0 };
        let mut patch = Self {
            center_a,
            spread,
            twist_a: pa.inv_inertia_world * normal,
            twist_b: pb.inv_inertia_world * normal,
            ..Self::default()
        };
        for (i, t) in c.tangents.iter().enumerate() {
            patch.rt_a[i] = center_a.cross(*t);
            patch.rt_b[i] = center_b.cross(*t);
            patch.wt_a[i] = pa.inv_inertia_world * patch.rt_a[i];
            patch.wt_b[i] = pb.inv_inertia_world * patch.rt_b[i];
            patch.tangent_mass[i] = invert(
                mass_sum + patch.rt_a[i].dot(patch.wt_a[i]) + patch.rt_b[i].dot(patch.wt_b[i]),
            );
        }
        patch.twist_mass = invert(normal.dot(patch.twist_a) + normal.dot(patch.twist_b));
        if c.moving_surface {
            let surface = input.contacts[c.source].surface_velocity;
            patch.target = Vec2::new(surface.dot(c.tangents[0]), surface.dot(c.tangents[1]));
        }
        if input.ctx.warm_starting {
            patch.tangent_impulse = Vec2::new(
                warm_linear.dot(c.tangents[0]),
                warm_linear.dot(c.tangents[1]),
            );
            patch.twist_impulse = warm_twist;
        }
        patch
    }

    /// Applies the accumulated friction impulses again (stage *warm start*).
    #[inline]
    pub(crate) fn warm_start(&self, c: &PreparedContact, a: &mut SolverBody, b: &mut SolverBody) {
        let [x, y] = self.tangent_impulse.to_array();
        self.apply_tangent(c, a, b, x, y);
        self.apply_twist(a, b, self.twist_impulse);
    }

    /// Applies the tangent impulses `x` and `y` (N·s, along the manifold's tangents) at the patch centre.
    #[inline]
    fn apply_tangent(
        &self,
        c: &PreparedContact,
        a: &mut SolverBody,
        b: &mut SolverBody,
        x: f32,
        y: f32,
    ) {
        let linear = c.tangents[0] * x + c.tangents[1] * y;
        a.linear_velocity -= linear * c.inv_mass_a;
        b.linear_velocity += linear * c.inv_mass_b;
        a.angular_velocity -= self.wt_a[0] * x;
        a.angular_velocity -= self.wt_a[1] * y;
        b.angular_velocity += self.wt_b[0] * x;
        b.angular_velocity += self.wt_b[1] * y;
    }

    /// Applies the twist impulse `impulse` (N·m·s, about the normal).
    #[inline]
    fn apply_twist(&self, a: &mut SolverBody, b: &mut SolverBody, impulse: f32) {
        a.angular_velocity -= self.twist_a * impulse;
        b.angular_velocity += self.twist_b * impulse;
    }

    /// One pass of the patch's rows after the normal rows: the tangent impulse clamped to the circle of radius
    /// `μ·Σλ_n` (`total`), then the twist impulse to `±μ·Σλ_n·|ρ|` (`twist_total`). The wide path's
    /// equations, in the same order of operations.
    #[inline]
    pub(crate) fn solve(
        &mut self,
        c: &PreparedContact,
        a: &mut SolverBody,
        b: &mut SolverBody,
        total: f32,
        twist_total: f32,
    ) {
        let [t0, t1] = c.tangents;
        let dv = b.linear_velocity - a.linear_velocity;
        // Relative to the surface velocity (exactly the plain relative velocity when it is zero).
        let vt0 = t0.dot(dv) + b.angular_velocity.dot(self.rt_b[0])
            - a.angular_velocity.dot(self.rt_a[0])
            - self.target.x;
        let vt1 = t1.dot(dv) + b.angular_velocity.dot(self.rt_b[1])
            - a.angular_velocity.dot(self.rt_a[1])
            - self.target.y;
        let mut x = self.tangent_impulse.x - self.tangent_mass[0] * vt0;
        let mut y = self.tangent_impulse.y - self.tangent_mass[1] * vt1;
        let limit = c.friction * total;
        let length_squared = x * x + y * y;
        if length_squared > limit * limit {
            let scale = limit / length_squared.sqrt();
            x *= scale;
            y *= scale;
        }
        let (ax, ay) = (x - self.tangent_impulse.x, y - self.tangent_impulse.y);
        self.tangent_impulse = Vec2::new(x, y);
        self.apply_tangent(c, a, b, ax, ay);
        if c.point_count > 1 {
            let spin = c.normal.dot(b.angular_velocity - a.angular_velocity);
            let limit = c.friction * twist_total;
            let candidate = (self.twist_impulse - self.twist_mass * spin)
                .max(-limit)
                .min(limit);
            let applied = candidate - self.twist_impulse;
            self.twist_impulse = candidate;
            self.apply_twist(a, b, applied);
        }
    }
}

/// The centre of `points` on each body — the mean of their anchors relative to body A's and body B's centre
/// of mass (zero without points) — and the sum of the friction impulses they carry from the last step.
pub(crate) fn patch_sums(points: &[ContactPoint]) -> [Vec3; 3] {
    let count = points.len() as f32;
    let per_point = if count > 0.0 { 1.0 / count } else { 0.0 };
    let (mut sum_a, mut sum_b, mut friction) = (Vec3::ZERO, Vec3::ZERO, Vec3::ZERO);
    for p in points {
        sum_a += p.anchor_a;
        sum_b += p.anchor_b;
        friction += p.tangent_impulse;
    }
    [sum_a * per_point, sum_b * per_point, friction]
}

/// A patch's friction shared out among its points, for warm starting the next step and for reporting: point
/// `k` at offset `ρ_k` from the centre gets `f_k = λ_t/N + τ·(n × ρ_k)/Σ|ρ|²`. The shares add up to the
/// patch's tangent impulse `λ_t` (the `ρ_k` sum to zero) and their moment about the centre along `n` is its
/// twist impulse `τ` (`ρ × (n × ρ) = n·|ρ|²` for `ρ` in the contact plane), so the next step's patch recovers
/// both from the points, whichever of them persist.
pub(crate) struct PatchShare {
    normal: Vec3,
    linear: Vec3,
    twist: f32,
}

impl PatchShare {
    /// The share-out of tangent impulse `[x, y]` (in basis `tangents`) and twist impulse `twist` of a patch
    /// of `count` points with spread `spread`.
    pub(crate) fn new(
        normal: Vec3,
        tangents: [Vec3; 2],
        [x, y]: [f32; 2],
        twist: f32,
        spread: f32,
        count: usize,
    ) -> Self {
        let linear = tangents[0] * x + tangents[1] * y;
        if count <= 1 {
            // A lone point takes the whole patch and no twist.
            return Self {
                normal,
                linear,
                twist: 0.0,
            };
        }
        Self {
            normal,
            linear: linear / count as f32,
            twist: if spread > 0.0 { twist / spread } else { 0.0 },
        }
    }

    /// The friction impulse (world vector, N·s) of the point at offset `rho` from the patch centre.
    pub(crate) fn at(&self, rho: Vec3) -> Vec3 {
        if self.twist == 0.0 {
            self.linear
        } else {
            self.linear + self.normal.cross(rho) * self.twist
        }
    }
}

#[cfg(test)]
mod tests {
    use super::{ContactPoint, PatchShare, patch_sums};
    use proptest::prelude::*;
    use rebound_math::{Quat, Vec3};

    proptest! {
        /// The friction a patch shares out among its points (for warm starting and reporting) gives the patch
        /// back: the shares sum to its tangent impulse and their moment about the centre, along the normal, is
        /// its twist impulse — which is how the next step's patch recovers both from the points.
        #[test]
        fn shared_out_patch_friction_sums_to_the_patch_impulses(
            tilt in -1.5f32..1.5,
            offsets in prop::collection::vec((-1.0f32..1.0, -1.0f32..1.0), 2..=4),
            x in -2.0f32..2.0,
            y in -2.0f32..2.0,
            twist in -2.0f32..2.0,
        ) {
            let turn = Quat::from_rotation_x(tilt);
            let normal = turn * Vec3::Y;
            let tangents = [turn * Vec3::X, turn * Vec3::Z];
            let base = Vec3::new(0.3, -0.2, 0.1);
            let mut points: Vec<ContactPoint> = offsets
                .iter()
                .map(|&(u, v)| ContactPoint {
                    anchor_a: base + tangents[0] * u + tangents[1] * v,
                    ..ContactPoint::default()
                })
                .collect();
            let [center, _, _] = patch_sums(&points);
            let spread: f32 = points.iter().map(|p| (p.anchor_a - center).length_squared()).sum();
            prop_assume!(spread > 1e-2);
            let share = PatchShare::new(normal, tangents, [x, y], twist, spread, points.len());
            for p in &mut points {
                p.tangent_impulse = share.at(p.anchor_a - center);
            }
            let [_, _, total] = patch_sums(&points);
            let moment: f32 = points
                .iter()
                .map(|p| (p.anchor_a - center).cross(p.tangent_impulse).dot(normal))
                .sum();
            let linear = tangents[0] * x + tangents[1] * y;
            prop_assert!((total - linear).length() < 1e-5 * (1.0 + twist.abs() / spread), "{total} vs {linear}");
            prop_assert!((moment - twist).abs() < 1e-5, "{moment} vs {twist}");
        }
    }
}
