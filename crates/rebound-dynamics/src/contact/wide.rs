//! The contact solve four manifolds at a time (Box2D v3's graph-coloured wide solver; Catto, "Solver2D",
//! 2024).
//!
//! One manifold's rows form a chain of dependent arithmetic: each row reads the velocities the row before
//! it wrote. Solved one manifold after another, a pass waits on that chain; four manifolds that share no
//! moving body are independent, so they are solved side by side in the four lanes of a `Vec4` — the
//! equations of the scalar solve ([`super::ContactSolver::solve`]), lane by lane.
//!
//! *Colouring*: manifolds are given, in order, the first of [`COLORS`] colours in which neither of their
//! moving bodies appears yet (fixed and kinematic bodies are never changed by a contact, so any number of
//! lanes may read them); each colour's manifolds are grouped four by four into batches. Manifolds that fit
//! no colour, and those the wide path does not handle (restitution, rolling resistance), are solved by the
//! scalar path after the batches. The grouping is a function of the manifold order alone: deterministic.
//!
//! A batch has as many point slots as its largest manifold; the slots a smaller manifold leaves empty, and
//! the empty lanes of a colour's last batch, carry zero masses and so apply zero impulses.

use super::{ContactPoint, PatchShare, PrepareInput, PreparedContact, patch_sums};
use crate::{Bias, SolverBody, StepContext};
use rebound_math::glam::BVec4A;
use rebound_math::{Mat3, Mat4, Vec3, Vec4};

/// The number of colours tried before a manifold is left to the scalar path. A body touching more manifolds
/// than this overflows (Box2D v3 uses 24; a box in a pyramid touches 6, a ball in a pile about 12). At most
/// 32 (one bit each in a `u32` per body).
pub(super) const COLORS: usize = 24;

/// Lanes per batch.
const LANES: usize = 4;

/// Manifolds coloured together: the batches of the first `CHUNK` manifolds (colour by colour), then those of
/// the next `CHUNK`, and so on. A chunk's bodies stay in cache while its colours are solved one after the
/// other; coloured all at once, a pile of 16,384 balls swept its whole body array once per colour, in
/// *prepare* and in every solve pass. Scenes with fewer manifolds are one chunk (the solve order does not
/// change; stacks are sensitive to it). Each chunk's colours start afresh: the chunks are solved one after
/// the other, so a body may have one colour in each.
const CHUNK: usize = 4096;

/// A 3-vector in each of the four lanes (structure of arrays).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Vec3x4 {
    x: Vec4,
    y: Vec4,
    z: Vec4,
}

impl Vec3x4 {
    const ZERO: Self = Self {
        x: Vec4::ZERO,
        y: Vec4::ZERO,
        z: Vec4::ZERO,
    };

    /// The four lanes' vectors, transposed (one 4×4 transpose instead of twelve lane inserts).
    #[inline(always)]
    fn from_lanes(v: [Vec3; LANES]) -> Self {
        Self::rows(&transpose_lanes(&v, |v| v.extend(0.0)))
    }

    /// The first three rows of `m` (of a [`transpose_lanes`]): x, y and z in lanes.
    #[inline(always)]
    fn rows(m: &Mat4) -> Self {
        Self {
            x: m.x_axis,
            y: m.y_axis,
            z: m.z_axis,
        }
    }

    /// The vector of each lane.
    #[inline(always)]
    fn lanes(&self) -> [Vec3; LANES] {
        let m = Mat4::from_cols(self.x, self.y, self.z, Vec4::ZERO).transpose();
        [
            m.x_axis.truncate(),
            m.y_axis.truncate(),
            m.z_axis.truncate(),
            m.w_axis.truncate(),
        ]
    }

    #[inline(always)]
    fn dot(&self, o: &Self) -> Vec4 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    #[inline(always)]
    fn cross(&self, o: &Self) -> Self {
        Self {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }

    #[inline(always)]
    fn add(&self, o: &Self) -> Self {
        Self {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }

    #[inline(always)]
    fn sub(&self, o: &Self) -> Self {
        Self {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }

    #[inline(always)]
    fn scale(&self, s: Vec4) -> Self {
        Self {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }

    /// The vector of lane `lane`.
    #[inline(always)]
    fn lane(&self, lane: usize) -> Vec3 {
        Vec3::new(self.x[lane], self.y[lane], self.z[lane])
    }

    /// The lanes of `self` where `mask` is set, zero elsewhere.
    #[inline(always)]
    fn select(&self, mask: BVec4A) -> Self {
        Self {
            x: Vec4::select(mask, self.x, Vec4::ZERO),
            y: Vec4::select(mask, self.y, Vec4::ZERO),
            z: Vec4::select(mask, self.z, Vec4::ZERO),
        }
    }

    /// `self += v·s`.
    #[inline(always)]
    fn add_scaled(&mut self, v: &Self, s: Vec4) {
        self.x += v.x * s;
        self.y += v.y * s;
        self.z += v.z * s;
    }

    /// `self −= v·s`.
    #[inline(always)]
    fn sub_scaled(&mut self, v: &Self, s: Vec4) {
        self.x -= v.x * s;
        self.y -= v.y * s;
        self.z -= v.z * s;
    }
}

/// A 3 × 3 matrix in each lane, by columns.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
struct Mat3x4 {
    x_axis: Vec3x4,
    y_axis: Vec3x4,
    z_axis: Vec3x4,
}

impl Mat3x4 {
    /// `M·v` in each lane, summed as glam's `Mat3 * Vec3` sums (x, then y, then z column).
    #[inline(always)]
    fn mul(&self, v: &Vec3x4) -> Vec3x4 {
        self.x_axis
            .scale(v.x)
            .add(&self.y_axis.scale(v.y))
            .add(&self.z_axis.scale(v.z))
    }
}

/// One point slot of a batch: a [`PreparedPoint`]'s solve data in each lane.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(super) struct PointX4 {
    anchor_a: Vec3x4,
    anchor_b: Vec3x4,
    separation: Vec4,
    normal_impulse: Vec4,
    max_normal_impulse: Vec4,
    normal_mass: Vec4,
    /// The point's distance from the patch centre (m): its lever against twist.
    twist_radius: Vec4,
    rn_a: Vec3x4,
    rn_b: Vec3x4,
    wn_a: Vec3x4,
    wn_b: Vec3x4,
}

/// A batch's friction patch in each lane: two tangent rows at the centre of the manifold's points and one
/// twist row about the normal.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct PatchX4 {
    /// The patch centre relative to body A's centre of mass (m).
    center_a: Vec3x4,
    /// `Σ|ρ|²` over the points, `ρ` a point's offset from the centre (m²).
    spread: Vec4,
    tangent_impulse: [Vec4; 2],
    tangent_mass: [Vec4; 2],
    rt_a: [Vec3x4; 2],
    rt_b: [Vec3x4; 2],
    wt_a: [Vec3x4; 2],
    wt_b: [Vec3x4; 2],
    twist_impulse: Vec4,
    twist_mass: Vec4,
    /// `I⁻¹·n` of each body.
    twist_a: Vec3x4,
    twist_b: Vec3x4,
}

impl PatchX4 {
    /// No patch: zero impulses (what a batch without one reports).
    const EMPTY: Self = Self {
        center_a: Vec3x4::ZERO,
        spread: Vec4::ZERO,
        tangent_impulse: [Vec4::ZERO; 2],
        tangent_mass: [Vec4::ZERO; 2],
        rt_a: [Vec3x4::ZERO; 2],
        rt_b: [Vec3x4::ZERO; 2],
        wt_a: [Vec3x4::ZERO; 2],
        wt_b: [Vec3x4::ZERO; 2],
        twist_impulse: Vec4::ZERO,
        twist_mass: Vec4::ZERO,
        twist_a: Vec3x4::ZERO,
        twist_b: Vec3x4::ZERO,
    };
}

/// Up to four manifolds without a moving body in common, solved side by side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Batch {
    /// Indices of the manifolds (into the solver's prepared contacts); `lanes` of them are used.
    contacts: [usize; LANES],
    lanes: usize,
    body_a: [usize; LANES],
    body_b: [usize; LANES],
    /// The batch's point slots in the solver's slot array: `first_slot .. first_slot + slots`, as many as
    /// its largest manifold has points.
    first_slot: usize,
    slots: usize,
    /// The batch's friction patch (index into the solver's patches).
    patch: usize,
    /// Whether some lane has two points or more (else no twist row).
    twist: bool,
    normal: Vec3x4,
    tangents: [Vec3x4; 2],
    friction: Vec4,
    inv_mass_a: Vec4,
    inv_mass_b: Vec4,
    bias_rate: Vec4,
    mass_scale: Vec4,
    impulse_scale: Vec4,
}

/// Whether the wide path solves this manifold exactly as the scalar path would: no bounce (restitution 0)
/// and no rolling block.
pub(super) fn is_wide(c: &PreparedContact) -> bool {
    c.restitution == 0.0 && c.rolling.is_none() && c.point_count > 0
}

/// The colouring's scratch.
#[derive(Debug, Clone, Default)]
pub(super) struct Coloring {
    /// Per body, bit `c` set when a manifold of colour `c` moves it.
    used: Vec<u32>,
    /// Manifold indices per colour, in manifold order, for the chunk being coloured (see [`CHUNK`]).
    members: [Vec<usize>; COLORS],
    /// Leave every manifold to the scalar path (tests compare the two paths).
    pub(super) scalar_only: bool,
}

impl Coloring {
    /// Colours the wide-eligible manifolds of `contacts` and groups them into `batches`; the others (and those
    /// that fit no colour) go to `scalar`, in manifold order.
    pub(super) fn build(
        &mut self,
        contacts: &[PreparedContact],
        input: &PrepareInput<'_>,
        batches: &mut Vec<Batch>,
        slots: &mut Vec<PointX4>,
        patches: &mut Vec<PatchX4>,
        scalar: &mut Vec<usize>,
    ) {
        let params = input.params;
        batches.clear();
        slots.clear();
        patches.clear();
        scalar.clear();
        self.used.clear();
        self.used.resize(params.len(), 0);
        for members in &mut self.members {
            members.clear();
        }
        for (chunk_index, chunk) in contacts.chunks(CHUNK).enumerate() {
            for (offset, c) in chunk.iter().enumerate() {
                let index = chunk_index * CHUNK + offset;
                if !is_wide(c) || self.scalar_only {
                    scalar.push(index);
                    continue;
                }
                // Fixed and kinematic bodies take no colour: any number of lanes may read them.
                let moves = |body: usize| params[body].is_dynamic();
                let used = |body: usize| if moves(body) { self.used[body] } else { 0 };
                // The first colour neither body is in.
                let color = (!(used(c.body_a) | used(c.body_b))).trailing_zeros() as usize;
                if color >= COLORS {
                    scalar.push(index);
                    continue;
                }
                for body in [c.body_a, c.body_b] {
                    if moves(body) {
                        self.used[body] |= 1 << color;
                    }
                }
                self.members[color].push(index);
            }
            self.flush(chunk, contacts, input, batches, slots, patches);
        }
    }

    /// Ends a chunk: its batches, colour by colour (each colour's manifolds four at a time, in manifold
    /// order), then the colours of its bodies are freed for the next chunk.
    fn flush(
        &mut self,
        chunk: &[PreparedContact],
        contacts: &[PreparedContact],
        input: &PrepareInput<'_>,
        batches: &mut Vec<Batch>,
        slots: &mut Vec<PointX4>,
        patches: &mut Vec<PatchX4>,
    ) {
        for members in &mut self.members {
            for group in members.chunks(LANES) {
                batches.push(Batch::new(group, contacts, input, slots, patches));
            }
            members.clear();
        }
        for c in chunk {
            for body in [c.body_a, c.body_b] {
                if let Some(used) = self.used.get_mut(body) {
                    *used = 0;
                }
            }
        }
    }
}

impl Batch {
    /// The batch of the manifolds `group` (one to four indices into `contacts`); its point slots are pushed
    /// onto `slots`. The points are prepared in the lanes, with the scalar path's formulas in the same order of
    /// operations ([`PrepareInput::point`]: `r × n`, `I⁻¹·(r × n)`, `1/K`), so each lane holds bit for bit
    /// what the scalar path would compute.
    fn new(
        group: &[usize],
        contacts: &[PreparedContact],
        input: &PrepareInput<'_>,
        slots: &mut Vec<PointX4>,
        patches: &mut Vec<PatchX4>,
    ) -> Self {
        let lane = |i: usize| group.get(i).map(|&index| &contacts[index]);
        let lanes = [lane(0), lane(1), lane(2), lane(3)];
        let headers = lanes.map(|c| c.copied().unwrap_or(EMPTY_LANE));
        let first_slot = slots.len();
        let slot_count = lanes
            .iter()
            .flatten()
            .map(|c| c.point_count)
            .max()
            .unwrap_or(0);
        let normal = gather3(&headers, |c| c.normal);
        let tangents = [
            gather3(&headers, |c| c.tangents[0]),
            gather3(&headers, |c| c.tangents[1]),
        ];
        let inv_mass_a = gather1(&headers, |c| c.inv_mass_a);
        let inv_mass_b = gather1(&headers, |c| c.inv_mass_b);
        // Each lane's inverse world inertia, once per batch (every slot of a lane shares its bodies).
        let inertia = |body: fn(&PreparedContact) -> usize| {
            let m =
                lanes.map(|c| c.map_or(Mat3::ZERO, |c| input.params[body(c)].inv_inertia_world));
            Mat3x4 {
                x_axis: Vec3x4::from_lanes(m.map(|m| m.x_axis)),
                y_axis: Vec3x4::from_lanes(m.map(|m| m.y_axis)),
                z_axis: Vec3x4::from_lanes(m.map(|m| m.z_axis)),
            }
        };
        let (inertia_a, inertia_b) = (inertia(|c| c.body_a), inertia(|c| c.body_b));
        let mass_sum = inv_mass_a + inv_mass_b;
        let invert = |k: Vec4, present: BVec4A| {
            Vec4::select(k.cmpgt(Vec4::ZERO) & present, Vec4::ONE / k, Vec4::ZERO)
        };
        // The patch centres, and the friction the points carry from the last step, lane by lane; in a batch of
        // one-point manifolds (a pile of balls), the point itself and its friction — the same bits.
        let single = slot_count == 1;
        let mut sums = (!single).then(|| {
            let sums = lanes.map(|c| {
                c.map_or([Vec3::ZERO; 3], |c| {
                    patch_sums(input.contacts[c.source].points())
                })
            });
            [0, 1, 2].map(|k| gather3(&sums, |s| s[k]))
        });
        let present = gather1(&headers, |c| c.point_count as f32).cmpgt(Vec4::ZERO);
        let (mut spread, mut warm_twist) = (Vec4::ZERO, Vec4::ZERO);
        for slot in 0..slot_count {
            let points = lanes.map(|c| c.and_then(|c| input.contacts[c.source].points().get(slot)));
            let here = BVec4A::from_array(points.map(|p| p.is_some()));
            let PointLanes {
                anchor_a,
                anchor_b,
                separation,
                normal_impulse,
                friction,
            } = PointLanes::of(points.map(|p| p.unwrap_or(&NO_POINT)));
            let [center_a, _, _] = *sums.get_or_insert([anchor_a, anchor_b, friction]);
            let rn_a = anchor_a.cross(&normal);
            let rn_b = anchor_b.cross(&normal);
            let wn_a = inertia_a.mul(&rn_a);
            let wn_b = inertia_b.mul(&rn_b);
            let normal_mass = invert(mass_sum + rn_a.dot(&wn_a) + rn_b.dot(&wn_b), here);
            // A lone point is the centre: no lever, no spread.
            let rho2 = if single {
                Vec4::ZERO
            } else {
                let rho = anchor_a.sub(&center_a).select(here);
                warm_twist += rho.cross(&friction).dot(&normal);
                rho.dot(&rho)
            };
            spread += rho2;
            slots.push(PointX4 {
                anchor_a,
                anchor_b,
                separation,
                normal_impulse: if input.ctx.warm_starting {
                    normal_impulse
                } else {
                    Vec4::ZERO
                },
                max_normal_impulse: Vec4::ZERO,
                normal_mass,
                twist_radius: rho2.sqrt(),
                rn_a,
                rn_b,
                wn_a,
                wn_b,
            });
        }
        let [center_a, center_b, warm_linear] = sums.unwrap_or([Vec3x4::ZERO; 3]);
        let twist = lanes.iter().flatten().any(|c| c.point_count > 1);
        let mut patch = PatchX4 {
            center_a,
            spread,
            ..PatchX4::EMPTY
        };
        for (i, t) in tangents.iter().enumerate() {
            patch.rt_a[i] = center_a.cross(t);
            patch.rt_b[i] = center_b.cross(t);
            patch.wt_a[i] = inertia_a.mul(&patch.rt_a[i]);
            patch.wt_b[i] = inertia_b.mul(&patch.rt_b[i]);
            patch.tangent_mass[i] = invert(
                mass_sum + patch.rt_a[i].dot(&patch.wt_a[i]) + patch.rt_b[i].dot(&patch.wt_b[i]),
                present,
            );
        }
        // A batch of one-point manifolds has no twist row (no lever to resist twist with).
        if twist {
            patch.twist_a = inertia_a.mul(&normal);
            patch.twist_b = inertia_b.mul(&normal);
            patch.twist_mass = invert(
                normal.dot(&patch.twist_a) + normal.dot(&patch.twist_b),
                present,
            );
        }
        if input.ctx.warm_starting {
            patch.tangent_impulse = [warm_linear.dot(&tangents[0]), warm_linear.dot(&tangents[1])];
            patch.twist_impulse = warm_twist;
        }
        let patch_index = patches.len();
        patches.push(patch);
        Self {
            contacts: [0, 1, 2, 3].map(|i| group.get(i).copied().unwrap_or(0)),
            lanes: group.len(),
            body_a: headers.map(|c| c.body_a),
            body_b: headers.map(|c| c.body_b),
            first_slot,
            slots: slot_count,
            patch: patch_index,
            twist,
            normal,
            tangents,
            friction: gather1(&headers, |c| c.friction),
            inv_mass_a,
            inv_mass_b,
            bias_rate: gather1(&headers, |c| c.softness.bias_rate),
            mass_scale: gather1(&headers, |c| c.softness.mass_scale),
            impulse_scale: gather1(&headers, |c| c.softness.impulse_scale),
        }
    }

    /// One pass (solve or relax) over the batch: normal rows of every slot, then friction — the scalar
    /// solve's equations in four lanes.
    #[inline(never)]
    pub(super) fn solve(
        &self,
        slots: &mut [PointX4],
        patches: &mut [PatchX4],
        bodies: &mut [SolverBody],
        ctx: &StepContext,
        bias: Bias,
    ) {
        let points = &mut slots[self.first_slot..][..self.slots];
        let (sa, sb) = (
            self.states(&self.body_a, bodies),
            self.states(&self.body_b, bodies),
        );
        let (la, lb) = (LaneStates::of(&sa), LaneStates::of(&sb));
        let (mut va, mut wa, mut vb, mut wb) = (la.v, la.w, lb.v, lb.w);
        let normal = self.normal;
        // Separation terms, as in the scalar solve: n·(Δp_b − Δp_a) and Δq⁻¹·n − n per body.
        let shift = normal.dot(&lb.dp.sub(&la.dp));
        let turn_a = la.turn(&normal);
        let turn_b = lb.turn(&normal);
        let zero = Vec4::ZERO;
        let one = Vec4::ONE;
        let inv_h = Vec4::splat(ctx.inv_h);
        let max_push = Vec4::splat(-ctx.max_push_out_speed);
        let mut total = zero;
        let mut twist_total = zero;
        // The normal rows change the linear velocities only along n: the loop carries `u = n·(v_b − v_a)` and
        // the sum of the applied impulses, and the velocities take that sum once after it (fewer live
        // registers in the loop; the scalar path does the same).
        let mut u = normal.dot(&vb.sub(&va));
        let u_gain = (self.inv_mass_a + self.inv_mass_b) * normal.dot(&normal);
        let mut pushed = zero;
        for p in points.iter_mut() {
            let s = p.separation + shift + turn_b.dot(&p.anchor_b) - turn_a.dot(&p.anchor_a);
            let vn = u + wb.dot(&p.rn_b) - wa.dot(&p.rn_a);
            let speculative: BVec4A = s.cmpgt(zero);
            let (velocity_bias, mass_scale, impulse_scale) = match bias {
                Bias::On => (
                    Vec4::select(speculative, s * inv_h, (self.bias_rate * s).max(max_push)),
                    Vec4::select(speculative, one, self.mass_scale),
                    Vec4::select(speculative, zero, self.impulse_scale),
                ),
                Bias::Off => (Vec4::select(speculative, s * inv_h, zero), one, zero),
            };
            let delta = -p.normal_mass * mass_scale * (vn + velocity_bias)
                - impulse_scale * p.normal_impulse;
            let accumulated = (p.normal_impulse + delta).max(zero);
            let applied = accumulated - p.normal_impulse;
            p.normal_impulse = accumulated;
            total += accumulated;
            twist_total += accumulated * p.twist_radius;
            p.max_normal_impulse = p.max_normal_impulse.max(applied);
            pushed += applied;
            u += applied * u_gain;
            wa.sub_scaled(&p.wn_a, applied);
            wb.add_scaled(&p.wn_b, applied);
        }
        va.sub_scaled(&normal, pushed * self.inv_mass_a);
        vb.add_scaled(&normal, pushed * self.inv_mass_b);
        let [t0, t1] = self.tangents;
        // The patch's rows, limited by this pass's normal impulses.
        if let Some(p) = patches.get_mut(self.patch) {
            let dv = vb.sub(&va);
            let vt0 = t0.dot(&dv) + wb.dot(&p.rt_b[0]) - wa.dot(&p.rt_a[0]);
            let vt1 = t1.dot(&dv) + wb.dot(&p.rt_b[1]) - wa.dot(&p.rt_a[1]);
            let x = p.tangent_impulse[0] - p.tangent_mass[0] * vt0;
            let y = p.tangent_impulse[1] - p.tangent_mass[1] * vt1;
            // Clamp to the friction circle (glam's `clamp_length_max`, lane by lane).
            let limit = self.friction * total;
            let length_squared = x * x + y * y;
            let slipping = length_squared.cmpgt(limit * limit);
            // Most patches of a resting pile stick: the square root and division (a long dependency chain)
            // only when some lane slips. Multiplying by the kept lanes' 1 changes no bit, so this is the
            // unbranched clamp's result.
            let (x, y) = if slipping.any() {
                let scale = Vec4::select(slipping, limit / length_squared.sqrt(), one);
                (x * scale, y * scale)
            } else {
                (x, y)
            };
            let (ax, ay) = (x - p.tangent_impulse[0], y - p.tangent_impulse[1]);
            p.tangent_impulse = [x, y];
            let linear = t0.scale(ax).add(&t1.scale(ay));
            va.sub_scaled(&linear, self.inv_mass_a);
            vb.add_scaled(&linear, self.inv_mass_b);
            wa.sub_scaled(&p.wt_a[0], ax);
            wa.sub_scaled(&p.wt_a[1], ay);
            wb.add_scaled(&p.wt_b[0], ax);
            wb.add_scaled(&p.wt_b[1], ay);
            if self.twist {
                let spin = normal.dot(&wb.sub(&wa));
                let limit = self.friction * twist_total;
                let candidate = (p.twist_impulse - p.twist_mass * spin)
                    .max(-limit)
                    .min(limit);
                let applied = candidate - p.twist_impulse;
                p.twist_impulse = candidate;
                wa.sub_scaled(&p.twist_a, applied);
                wb.add_scaled(&p.twist_b, applied);
            }
        }
        self.scatter(bodies, &va, &wa, &vb, &wb);
    }

    /// Stage *warm start* for the batch's manifolds: applies their accumulated impulses again.
    pub(super) fn warm_start(
        &self,
        slots: &[PointX4],
        patches: &[PatchX4],
        bodies: &mut [SolverBody],
    ) {
        let ((mut va, mut wa), (mut vb, mut wb)) = (
            LaneStates::velocities(&self.states(&self.body_a, bodies)),
            LaneStates::velocities(&self.states(&self.body_b, bodies)),
        );
        // All normal impulses act along n: their sum moves the linear velocities once.
        let mut pushed = Vec4::ZERO;
        for p in &slots[self.first_slot..][..self.slots] {
            pushed += p.normal_impulse;
            wa.sub_scaled(&p.wn_a, p.normal_impulse);
            wb.add_scaled(&p.wn_b, p.normal_impulse);
        }
        va.sub_scaled(&self.normal, pushed * self.inv_mass_a);
        vb.add_scaled(&self.normal, pushed * self.inv_mass_b);
        if let Some(p) = patches.get(self.patch) {
            let [t0, t1] = self.tangents;
            let [x, y] = p.tangent_impulse;
            let linear = t0.scale(x).add(&t1.scale(y));
            va.sub_scaled(&linear, self.inv_mass_a);
            vb.add_scaled(&linear, self.inv_mass_b);
            wa.sub_scaled(&p.wt_a[0], x);
            wa.sub_scaled(&p.wt_a[1], y);
            wb.add_scaled(&p.wt_b[0], x);
            wb.add_scaled(&p.wt_b[1], y);
            if self.twist {
                wa.sub_scaled(&p.twist_a, p.twist_impulse);
                wb.add_scaled(&p.twist_b, p.twist_impulse);
            }
        }
        self.scatter(bodies, &va, &wa, &vb, &wb);
    }

    /// The lanes' bodies, by reference (read field by field: copying whole states cost a fifth of a pass);
    /// empty lanes see [`SolverBody::STATIC`].
    #[inline(always)]
    fn states<'a>(
        &self,
        index: &[usize; LANES],
        bodies: &'a [SolverBody],
    ) -> [&'a SolverBody; LANES] {
        let lane = |k: usize| {
            if k < self.lanes {
                bodies.get(index[k]).unwrap_or(&SolverBody::STATIC)
            } else {
                &SolverBody::STATIC
            }
        };
        [lane(0), lane(1), lane(2), lane(3)]
    }

    /// Writes the lanes' velocities back.
    #[inline(always)]
    fn scatter(
        &self,
        bodies: &mut [SolverBody],
        va: &Vec3x4,
        wa: &Vec3x4,
        vb: &Vec3x4,
        wb: &Vec3x4,
    ) {
        let (va, wa, vb, wb) = (va.lanes(), wa.lanes(), vb.lanes(), wb.lanes());
        for lane in 0..self.lanes {
            let a = &mut bodies[self.body_a[lane]];
            a.linear_velocity = va[lane];
            a.angular_velocity = wa[lane];
            let b = &mut bodies[self.body_b[lane]];
            b.linear_velocity = vb[lane];
            b.angular_velocity = wb[lane];
        }
    }

    /// For each lane: the manifold's index, and per point its accumulated normal impulse, its share of the
    /// patch's friction (world vector, [`PatchShare`]) and its largest applied normal impulse.
    pub(super) fn results<'a>(
        &'a self,
        slots: &'a [PointX4],
        patches: &'a [PatchX4],
        contacts: &'a [PreparedContact],
    ) -> impl Iterator<Item = (usize, impl Iterator<Item = (f32, Vec3, f32)> + 'a)> + 'a {
        let points = &slots[self.first_slot..][..self.slots];
        let patch = patches.get(self.patch).unwrap_or(&PatchX4::EMPTY);
        self.contacts[..self.lanes]
            .iter()
            .enumerate()
            .map(move |(lane, &index)| {
                let c = &contacts[index];
                let share = PatchShare::new(
                    c.normal,
                    c.tangents,
                    [
                        patch.tangent_impulse[0][lane],
                        patch.tangent_impulse[1][lane],
                    ],
                    patch.twist_impulse[lane],
                    patch.spread[lane],
                    c.point_count,
                );
                let center = patch.center_a.lane(lane);
                let impulses = points[..c.point_count].iter().map(move |w| {
                    (
                        w.normal_impulse[lane],
                        share.at(w.anchor_a.lane(lane) - center),
                        w.max_normal_impulse[lane],
                    )
                });
                (index, impulses)
            })
    }
}

/// What an empty lane holds: zero masses, so it applies zero impulses.
const EMPTY_LANE: PreparedContact = PreparedContact {
    source: 0,
    body_a: 0,
    body_b: 0,
    first_point: 0,
    point_count: 0,
    patch: 0,
    rolling: None,
    normal: Vec3::ZERO,
    tangents: [Vec3::ZERO; 2],
    friction: 0.0,
    restitution: 0.0,
    inv_mass_a: 0.0,
    inv_mass_b: 0.0,
    softness: crate::Softness::RIGID,
    both_dynamic: false,
};

/// What an empty lane's point reads: zeros.
const NO_POINT: ContactPoint = ContactPoint {
    anchor_a: Vec3::ZERO,
    anchor_b: Vec3::ZERO,
    separation: 0.0,
    normal_impulse: 0.0,
    tangent_impulse: Vec3::ZERO,
    feature_id: 0,
};

/// One slot's contact points in lanes, read like [`LaneStates`]: a `#[repr(C)]` [`ContactPoint`] is
/// `[r_a, r_b.x]`, `[r_b.y, r_b.z, s, λ_n]`, `[λ_t, id]` — three 16-byte groups, three transposes.
struct PointLanes {
    anchor_a: Vec3x4,
    anchor_b: Vec3x4,
    separation: Vec4,
    normal_impulse: Vec4,
    friction: Vec3x4,
}

impl PointLanes {
    #[inline(always)]
    fn of(points: [&ContactPoint; LANES]) -> Self {
        let a = transpose_lanes(&points, |p| {
            Vec4::new(p.anchor_a.x, p.anchor_a.y, p.anchor_a.z, p.anchor_b.x)
        });
        let b = transpose_lanes(&points, |p| {
            Vec4::new(p.anchor_b.y, p.anchor_b.z, p.separation, p.normal_impulse)
        });
        let t = transpose_lanes(&points, |p| p.tangent_impulse.extend(0.0));
        Self {
            anchor_a: Vec3x4::rows(&a),
            anchor_b: Vec3x4 {
                x: a.w_axis,
                y: b.x_axis,
                z: b.y_axis,
            },
            separation: b.z_axis,
            normal_impulse: b.w_axis,
            friction: Vec3x4::rows(&t),
        }
    }
}

/// The lanes' full solver states, transposed four floats at a time: each body's `[v, ω.x]`, `[ω.y, ω.z, Δp.x,
/// Δp.y]` and `Δq` are 16 contiguous bytes of a `#[repr(C)]` [`SolverBody`] (one load each), and a 4 × 4
/// transpose turns four bodies' into lanes; `Δp.z` is gathered alone.
struct LaneStates {
    v: Vec3x4,
    w: Vec3x4,
    dp: Vec3x4,
    /// `Δq`'s vector part and scalar part.
    dq: Vec3x4,
    dq_w: Vec4,
}

/// Four items' 16-byte groups `f`, transposed into lanes: row `k` holds component `k` of each lane.
#[inline(always)]
fn transpose_lanes<T>(items: &[T; LANES], f: impl Fn(&T) -> Vec4) -> Mat4 {
    Mat4::from_cols(f(&items[0]), f(&items[1]), f(&items[2]), f(&items[3])).transpose()
}

/// A body's `[v, ω.x]`.
#[inline(always)]
fn first_group(b: &SolverBody) -> Vec4 {
    Vec4::new(
        b.linear_velocity.x,
        b.linear_velocity.y,
        b.linear_velocity.z,
        b.angular_velocity.x,
    )
}

/// A body's `[ω.y, ω.z, Δp.x, Δp.y]`.
#[inline(always)]
fn second_group(b: &SolverBody) -> Vec4 {
    Vec4::new(
        b.angular_velocity.y,
        b.angular_velocity.z,
        b.delta_position.x,
        b.delta_position.y,
    )
}

impl LaneStates {
    /// The lanes' velocities (`v`, `ω`) alone.
    #[inline(always)]
    fn velocities(states: &[&SolverBody; LANES]) -> (Vec3x4, Vec3x4) {
        let (v, w, _) = Self::moving(states);
        (v, w)
    }

    /// The lanes' `v`, `ω` and `[Δp.x, Δp.y]`: the first two groups.
    #[inline(always)]
    fn moving(states: &[&SolverBody; LANES]) -> (Vec3x4, Vec3x4, [Vec4; 2]) {
        let a = transpose_lanes(states, |b| first_group(b));
        let c = transpose_lanes(states, |b| second_group(b));
        (
            Vec3x4::rows(&a),
            Vec3x4 {
                x: a.w_axis,
                y: c.x_axis,
                z: c.y_axis,
            },
            [c.z_axis, c.w_axis],
        )
    }

    #[inline(always)]
    fn of(states: &[&SolverBody; LANES]) -> Self {
        let (v, w, [dp_x, dp_y]) = Self::moving(states);
        let q = transpose_lanes(states, |b| Vec4::from(b.delta_rotation));
        Self {
            v,
            w,
            dp: Vec3x4 {
                x: dp_x,
                y: dp_y,
                z: gather1(states, |s| s.delta_position.z),
            },
            dq: Vec3x4::rows(&q),
            dq_w: q.w_axis,
        }
    }

    /// `Δq⁻¹·n − n` in each lane: the rotated normal whose dot with an anchor gives `n·(Δq·r − r)`.
    #[inline(always)]
    fn turn(&self, normal: &Vec3x4) -> Vec3x4 {
        // The conjugate's vector part; v' = v + w·t + u × t with t = 2·(u × v).
        let u = Vec3x4 {
            x: -self.dq.x,
            y: -self.dq.y,
            z: -self.dq.z,
        };
        let t = u.cross(normal).scale(Vec4::splat(2.0));
        t.scale(self.dq_w).add(&u.cross(&t))
    }
}

/// One vector per lane, transposed into lanes.
#[inline(always)]
fn gather3<T>(items: &[T; LANES], f: impl Fn(&T) -> Vec3) -> Vec3x4 {
    Vec3x4::from_lanes([f(&items[0]), f(&items[1]), f(&items[2]), f(&items[3])])
}

/// One number per lane.
#[inline(always)]
fn gather1<T>(items: &[T; LANES], f: impl Fn(&T) -> f32) -> Vec4 {
    Vec4::new(f(&items[0]), f(&items[1]), f(&items[2]), f(&items[3]))
}

#[cfg(test)]
mod tests {
    use super::super::{Contact, ContactPoint, ContactSolver};
    use crate::{Bias, BodyDesc, BodyParams, RigidBody, SolverBody, SolverSettings, StepContext};
    use rebound_math::{Quat, Vec3};

    /// `n` dynamic bodies in a row over one fixed body (index `n`), each touching the ground with four
    /// points and its right neighbour with two, moving and spinning differently.
    fn scene(n: usize) -> (Vec<SolverBody>, Vec<BodyParams>, Vec<Contact>) {
        let mut bodies = Vec::new();
        let mut params = Vec::new();
        for i in 0..n {
            let f = i as f32;
            let body = RigidBody::new(
                &BodyDesc::dynamic()
                    .with_position(Vec3::new(f, 0.5, 0.0))
                    .with_rotation(Quat::from_rotation_y(0.1 * f))
                    .with_linear_velocity(Vec3::new(0.3 * f - 1.0, -2.0 + 0.1 * f, 0.2))
                    .with_angular_velocity(Vec3::new(0.1, 0.5 - 0.2 * f, 0.05 * f)),
            )
            .expect("valid body");
            let mut state = SolverBody::from_body(&body);
            // A substep already under way: the bodies have moved and turned since the step began.
            state.delta_position = Vec3::new(0.001 * f, -0.002, 0.0005);
            state.delta_rotation = Quat::from_rotation_z(0.01 + 0.002 * f);
            bodies.push(state);
            params.push(BodyParams::from_body(&body));
        }
        bodies.push(SolverBody::STATIC);
        params.push(BodyParams::WORLD);
        let mut contacts = Vec::new();
        for i in 0..n {
            let mut ground = Contact::new(n, i, Vec3::Y, 0.6, 0.0);
            for (k, (x, z)) in [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)]
                .into_iter()
                .enumerate()
            {
                ground.push_point(ContactPoint {
                    anchor_a: Vec3::new(i as f32 + x, 0.0, z),
                    anchor_b: Vec3::new(x, -0.5, z),
                    separation: -0.01 + 0.004 * k as f32,
                    normal_impulse: 0.05 * k as f32,
                    tangent_impulse: Vec3::new(0.01, 0.0, -0.02),
                    feature_id: k as u32,
                });
            }
            contacts.push(ground);
            if i + 1 < n {
                let mut side = Contact::new(i, i + 1, Vec3::X, 0.4, 0.0);
                for z in [-0.5, 0.5] {
                    side.push_point(ContactPoint {
                        anchor_a: Vec3::new(0.5, 0.0, z),
                        anchor_b: Vec3::new(-0.5, 0.0, z),
                        separation: 0.002 * z,
                        ..ContactPoint::default()
                    });
                }
                contacts.push(side);
            }
        }
        (bodies, params, contacts)
    }

    /// Runs one substep's contact passes, wide or all scalar.
    fn run(wide: bool, n: usize, only_ground: bool) -> (Vec<SolverBody>, Vec<Contact>) {
        let (mut bodies, params, mut contacts) = scene(n);
        if only_ground {
            contacts.retain(|c| c.body_a == n);
        }
        let ctx = StepContext::new(1.0 / 60.0, &SolverSettings::default());
        let mut solver = ContactSolver::new();
        solver.coloring.scalar_only = !wide;
        solver.prepare(&contacts, &bodies, &params, &ctx);
        assert_eq!(solver.batches.is_empty(), !wide);
        solver.warm_start(&mut bodies);
        solver.solve(&mut bodies, &ctx, Bias::On);
        solver.solve(&mut bodies, &ctx, Bias::Off);
        solver.store_impulses(&mut contacts);
        (bodies, contacts)
    }

    #[test]
    fn lanes_solve_the_scalar_equations() {
        // Manifolds without a moving body in common: the order does not matter, so the wide path must give
        // the scalar path's velocities and impulses to rounding.
        let (wide, wide_contacts) = run(true, 6, true);
        let (scalar, scalar_contacts) = run(false, 6, true);
        for (w, s) in wide.iter().zip(&scalar) {
            for (a, b) in [
                (w.linear_velocity, s.linear_velocity),
                (w.angular_velocity, s.angular_velocity),
            ] {
                assert!((a - b).length() <= 1e-5 * (1.0 + b.length()), "{a} vs {b}");
            }
        }
        for (w, s) in wide_contacts.iter().zip(&scalar_contacts) {
            for (p, q) in w.points().iter().zip(s.points()) {
                assert!((p.normal_impulse - q.normal_impulse).abs() <= 1e-5);
                assert!((p.tangent_impulse - q.tangent_impulse).length() <= 1e-5);
            }
        }
        // And they did push: the bodies fall at 2 m/s into the ground.
        assert!(
            wide_contacts
                .iter()
                .all(|c| c.points[0].normal_impulse > 0.0)
        );
    }

    #[test]
    fn lanes_are_prepared_bit_for_bit_as_the_scalar_points() {
        let (bodies, params, contacts) = scene(9);
        let ctx = StepContext::new(1.0 / 60.0, &SolverSettings::default());
        let mut solver = ContactSolver::new();
        solver.prepare(&contacts, &bodies, &params, &ctx);
        let input = super::PrepareInput {
            contacts: &contacts,
            bodies: &bodies,
            params: &params,
            ctx: &ctx,
        };
        let bits = |v: Vec3| v.to_array().map(f32::to_bits);
        let mut compared = 0;
        for batch in &solver.batches {
            for (l, &index) in batch.contacts[..batch.lanes].iter().enumerate() {
                let c = &solver.contacts[index];
                let points = contacts[c.source].points();
                let lane_of = |v: &super::Vec3x4| v.lane(l);
                let patch = input.patch(c, points);
                let x4 = &solver.patches_x4[batch.patch];
                assert_eq!(bits(lane_of(&x4.center_a)), bits(patch.center_a));
                assert_eq!(bits(lane_of(&x4.wt_a[0])), bits(patch.wt_a[0]));
                assert_eq!(bits(lane_of(&x4.wt_b[1])), bits(patch.wt_b[1]));
                assert_eq!(bits(lane_of(&x4.twist_b)), bits(patch.twist_b));
                for (wide, scalar) in [
                    (x4.spread, patch.spread),
                    (x4.tangent_mass[0], patch.tangent_mass[0]),
                    (x4.tangent_mass[1], patch.tangent_mass[1]),
                    (x4.tangent_impulse[0], patch.tangent_impulse.x),
                    (x4.tangent_impulse[1], patch.tangent_impulse.y),
                    (x4.twist_impulse, patch.twist_impulse),
                    (x4.twist_mass, patch.twist_mass),
                ] {
                    assert_eq!(wide[l].to_bits(), scalar.to_bits());
                }
                for (k, point) in points.iter().enumerate() {
                    let scalar = input.point(c, point, patch.center_a);
                    let slot = &solver.slots[batch.first_slot + k];
                    assert_eq!(bits(lane_of(&slot.wn_a)), bits(scalar.wn_a));
                    assert_eq!(bits(lane_of(&slot.wn_b)), bits(scalar.wn_b));
                    for (wide, scalar) in [
                        (slot.normal_mass, scalar.normal_mass),
                        (slot.normal_impulse, scalar.normal_impulse),
                        (slot.twist_radius, scalar.twist_radius),
                    ] {
                        assert_eq!(wide[l].to_bits(), scalar.to_bits());
                    }
                    compared += 1;
                }
            }
        }
        assert!(compared >= 9 * 4, "{compared} points compared");
    }

    #[test]
    fn no_batch_holds_a_moving_body_twice() {
        check_batches(9);
    }

    #[test]
    fn chunked_colouring_keeps_batches_independent() {
        // 2 · 2100 − 1 manifolds: more than one chunk, and a chunk boundary inside the run of bodies.
        let (_, _, contacts) = scene(2100);
        assert!(contacts.len() > super::CHUNK);
        check_batches(2100);
    }

    /// Every manifold of `scene(n)` solved exactly once (in a batch or by the scalar path), and no batch
    /// holding a moving body in two lanes.
    fn check_batches(n: usize) {
        let (bodies, params, contacts) = scene(n);
        let ctx = StepContext::new(1.0 / 60.0, &SolverSettings::default());
        let mut solver = ContactSolver::new();
        solver.prepare(&contacts, &bodies, &params, &ctx);
        let mut solved = vec![0; contacts.len()];
        for batch in &solver.batches {
            let lanes = &batch.body_a[..batch.lanes]
                .iter()
                .chain(&batch.body_b[..batch.lanes])
                .filter(|&&b| params[b].is_dynamic())
                .collect::<Vec<_>>();
            let mut unique = lanes.clone();
            unique.sort_unstable();
            unique.dedup();
            assert_eq!(unique.len(), lanes.len(), "a body twice in one batch");
            for &c in &batch.contacts[..batch.lanes] {
                solved[c] += 1;
            }
        }
        for &c in &solver.scalar {
            solved[c] += 1;
        }
        assert!(solved.iter().all(|&n| n == 1), "every manifold solved once");
        assert!(!solver.batches.is_empty());
    }
}
