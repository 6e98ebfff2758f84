//! A batch of the wide contact path: up to four manifolds without a moving body in common, side by side in
//! the four lanes of a `Vec4`. Built in stage *prepare* with the scalar path's formulas, lane by lane; its
//! *warm start* and its passes (*solve*, *relax*) are the scalar path's equations in four lanes; its results
//! are read back per manifold for *store impulses* (`super::results`).
//!
//! Hot and cold: the passes stream every batch twelve times a step (four substeps of warm start, solve and
//! relax), so what they read — [`Batch`], its [`PatchX4`], its point slots and, for manifolds of two points or
//! more, its [`TwistX4`] — holds nothing else; what only the read-back needs (which manifolds, the patch
//! centre and spread) is in [`BatchInfo`]. Indices are `u32`.

use super::lanes::{LANES, LaneStates, Mask4, Mat3x4, PointLanes, Vec3x4, gather1, gather3};
use crate::contact::bias::Bias;
use crate::contact::manifold::ContactPoint;
use crate::contact::patch::patch_sums;
use crate::contact::prepared::{PrepareInput, PreparedContact};
use crate::{SolverBody, StepContext};
use rebound_math::{Disjoint, Mat3, Vec3, Vec4, par};

/// One point slot of a batch: a [`PreparedPoint`]'s solve data in each lane. Six cache lines (`align(64)`),
/// laid out so that *warm start* reads the first two only.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C, align(64))]
pub(crate) struct PointX4 {
    pub(crate) normal_impulse: Vec4,
    pub(crate) wn_a: Vec3x4,
    pub(crate) wn_b: Vec3x4,
    pub(crate) normal_mass: Vec4,
    pub(crate) rn_a: Vec3x4,
    pub(crate) separation: Vec4,
    pub(crate) rn_b: Vec3x4,
    pub(crate) max_normal_impulse: Vec4,
    pub(crate) anchor_a: Vec3x4,
    /// The point's distance from the patch centre (m): its lever against twist.
    pub(crate) twist_radius: Vec4,
    pub(crate) anchor_b: Vec3x4,
}

/// A batch's friction patch in each lane: two tangent rows at the centre of the manifold's points (the twist
/// row is [`TwistX4`]). One per batch, at the batch's index. Seven cache lines.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C, align(64))]
pub(crate) struct PatchX4 {
    pub(crate) tangent_impulse: [Vec4; 2],
    pub(crate) tangent_mass: [Vec4; 2],
    pub(crate) rt_a: [Vec3x4; 2],
    pub(crate) rt_b: [Vec3x4; 2],
    pub(crate) wt_a: [Vec3x4; 2],
    pub(crate) wt_b: [Vec3x4; 2],
}

impl PatchX4 {
    /// No patch: zero impulses and masses.
    pub(crate) const EMPTY: Self = Self {
        tangent_impulse: [Vec4::ZERO; 2],
        tangent_mass: [Vec4::ZERO; 2],
        rt_a: [Vec3x4::ZERO; 2],
        rt_b: [Vec3x4::ZERO; 2],
        wt_a: [Vec3x4::ZERO; 2],
        wt_b: [Vec3x4::ZERO; 2],
    };
}

/// A batch's twist row about the normal in each lane: only batches with a manifold of two points or more
/// have one (a lone point has no lever to resist twist with). Two cache lines.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C, align(64))]
pub(crate) struct TwistX4 {
    /// Accumulated twist impulse (N·m·s).
    pub(crate) impulse: Vec4,
    pub(crate) mass: Vec4,
    /// `I⁻¹·n` of each body.
    pub(crate) twist_a: Vec3x4,
    pub(crate) twist_b: Vec3x4,
}

impl TwistX4 {
    /// No twist row: zero impulse (what a batch without one reports).
    pub(crate) const EMPTY: Self = Self {
        impulse: Vec4::ZERO,
        mass: Vec4::ZERO,
        twist_a: Vec3x4::ZERO,
        twist_b: Vec3x4::ZERO,
    };
}

/// What the read-back of a batch needs and its passes do not: which manifolds its lanes hold, and its patch's
/// centre and spread. One per batch, at the batch's index.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct BatchInfo {
    /// Indices of the manifolds (into the solver's prepared contacts); the batch's `lanes` first are used.
    pub(crate) contacts: [u32; LANES],
    /// Each lane's source contact (`PreparedContact::source`).
    pub(crate) sources: [u32; LANES],
    /// Each lane's number of points (0 in an empty lane).
    pub(crate) point_counts: [u32; LANES],
    /// The patch centre relative to body A's centre of mass (m).
    pub(crate) center_a: Vec3x4,
    /// `Σ|ρ|²` over the points, `ρ` a point's offset from the centre (m²).
    pub(crate) spread: Vec4,
}

/// Up to four manifolds without a moving body in common, solved side by side: what the passes read of them.
/// Five cache lines (`align(64)`): the last holds what only *solve* reads (the bias and the soft row's
/// scales), the first what every pass reads first (where the bodies and rows are).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
#[repr(C, align(64))]
pub(crate) struct Batch {
    pub(crate) body_a: [u32; LANES],
    pub(crate) body_b: [u32; LANES],
    /// The batch's point slots in the solver's slot array: `first_slot .. first_slot + slots`, as many as
    /// its largest manifold has points.
    pub(crate) first_slot: u32,
    /// The batch's twist row in the solver's twist rows if `twist`; else where the next batch's would go.
    pub(crate) first_twist: u32,
    pub(crate) slots: u16,
    /// The lanes used (1 to 4).
    pub(crate) lanes: u8,
    /// Whether some lane has two points or more (else no twist row).
    pub(crate) twist: bool,
    /// Bit `k` set when lane `k`'s body A is dynamic, bit `4 + k` when its body B is: the bodies a pass on
    /// several threads writes back (`super::groups`). Set only when [`Batches::moving`] is.
    pub(crate) moving: u8,
    pub(crate) friction: Vec4,
    pub(crate) normal: Vec3x4,
    pub(crate) inv_mass_a: Vec4,
    pub(crate) tangents: [Vec3x4; 2],
    pub(crate) inv_mass_b: Vec4,
    pub(crate) bias_rate: Vec4,
    pub(crate) mass_scale: Vec4,
    pub(crate) impulse_scale: Vec4,
    /// Minus each lane's push-out speed cap (m/s).
    pub(crate) max_push: Vec4,
}

const _: () = assert!(size_of::<PointX4>() == 6 * 64 && size_of::<Batch>() == 5 * 64);
const _: () = assert!(size_of::<PatchX4>() == 7 * 64 && size_of::<TwistX4>() == 2 * 64);

/// The wide path's arrays: the batches and, at each batch's index, its patch and its read-back info; the point
/// slots and twist rows the batches index. Reused from step to step.
#[derive(Debug, Clone, Default)]
pub(crate) struct Batches {
    pub(crate) batches: Vec<Batch>,
    pub(crate) patches: Vec<PatchX4>,
    pub(crate) infos: Vec<BatchInfo>,
    pub(crate) slots: Vec<PointX4>,
    pub(crate) twists: Vec<TwistX4>,
    /// Whether the batches' [`Batch::moving`] masks are set: prepared to be solved by a team of threads
    /// (the serial build and a pool of one thread do not need them).
    pub(crate) moving: bool,
}

impl Batches {
    /// Empties every array (keeping their storage).
    pub(crate) fn clear(&mut self) {
        self.batches.clear();
        self.patches.clear();
        self.infos.clear();
        self.slots.clear();
        self.twists.clear();
        self.moving = par::is_parallel();
    }

    /// Adds the batch of the manifolds `group` (one to four indices into `contacts`), with its patch, its
    /// point slots, its twist row if it has one and its read-back info. The points are prepared in the lanes,
    /// with the scalar path's formulas in the same order of operations (`PreparedPoint::new`: `r × n`,
    /// `I⁻¹·(r × n)`, `1/K`), so each lane holds bit for bit what the scalar path would compute.
    #[inline]
    pub(crate) fn push(
        &mut self,
        group: &[usize],
        contacts: &[PreparedContact],
        input: &PrepareInput<'_>,
    ) {
        let (first_slot, first_twist) = (self.slots.len(), self.twists.len() as u32);
        let moving = self.moving;
        build(
            group,
            contacts,
            input,
            (first_slot, first_twist),
            moving,
            self,
        );
    }
}

/// Where [`build`] puts a batch's parts, in the order it makes them: its point slots one by one, its twist
/// row if it has one, its patch, its read-back info, the batch.
pub(crate) trait BatchSink {
    fn slot(&mut self, slot: PointX4);
    fn twist(&mut self, row: TwistX4);
    fn patch(&mut self, patch: PatchX4);
    fn info(&mut self, info: BatchInfo);
    fn batch(&mut self, batch: Batch);
}

/// One thread's preparation: each part pushed onto its array.
impl BatchSink for Batches {
    #[inline(always)]
    fn slot(&mut self, slot: PointX4) {
        self.slots.push(slot);
    }
    #[inline(always)]
    fn twist(&mut self, row: TwistX4) {
        self.twists.push(row);
    }
    #[inline(always)]
    fn patch(&mut self, patch: PatchX4) {
        self.patches.push(patch);
    }
    #[inline(always)]
    fn info(&mut self, info: BatchInfo) {
        self.infos.push(info);
    }
    #[inline(always)]
    fn batch(&mut self, batch: Batch) {
        self.batches.push(batch);
    }
}

/// The batch of the manifolds `group` (one to four indices into `contacts`) whose point slots start at
/// `first_slot` and whose twist row, if it has one, is `first_twist`, into `sink` ([`Batches::push`]);
/// with its [`Batch::moving`] mask when `moving` ([`Batches::moving`]).
#[inline(always)]
pub(crate) fn build(
    group: &[usize],
    contacts: &[PreparedContact],
    input: &PrepareInput<'_>,
    (first_slot, first_twist): (usize, u32),
    moving: bool,
    sink: &mut impl BatchSink,
) {
    let lane = |i: usize| group.get(i).map(|&index| &contacts[index]);
    let lanes = [lane(0), lane(1), lane(2), lane(3)];
    // Read in place; an empty lane reads `EMPTY_LANE`.
    let headers: [&PreparedContact; LANES] = lanes.map(|c| c.unwrap_or(&EMPTY_LANE));
    let slot_count = lanes
        .iter()
        .flatten()
        .map(|c| c.point_count)
        .max()
        .unwrap_or(0);
    let twist = lanes.iter().flatten().any(|c| c.point_count > 1);
    let normal = gather3(&headers, |c| c.normal);
    let tangents = [
        gather3(&headers, |c| c.tangents[0]),
        gather3(&headers, |c| c.tangents[1]),
    ];
    let inv_mass_a = gather1(&headers, |c| c.inv_mass_a);
    let inv_mass_b = gather1(&headers, |c| c.inv_mass_b);
    // Each lane's inverse world inertia, once per batch (every slot of a lane shares its bodies).
    let inertia = |body: fn(&PreparedContact) -> usize| {
        let m = lanes.map(|c| c.map_or(Mat3::ZERO, |c| input.params[body(c)].inv_inertia_world));
        Mat3x4 {
            x_axis: Vec3x4::from_lanes(m.map(|m| m.x_axis)),
            y_axis: Vec3x4::from_lanes(m.map(|m| m.y_axis)),
            z_axis: Vec3x4::from_lanes(m.map(|m| m.z_axis)),
        }
    };
    let (inertia_a, inertia_b) = (inertia(|c| c.body_a), inertia(|c| c.body_b));
    let mass_sum = inv_mass_a + inv_mass_b;
    let invert = |k: Vec4, present: Mask4| {
        Vec4::select(k.cmpgt(Vec4::ZERO) & present, Vec4::ONE / k, Vec4::ZERO)
    };
    // The patch centres, and the friction the points carry from the last step, lane by lane; in a batch of
    // one-point manifolds (a pile of balls), the point itself and its friction — the same bits.
    let single = slot_count == 1;
    let loaded = headers.iter().any(|c| c.load_depth > 0.0);
    // The deepest shift of a loaded point's rest point in each lane (`PreparedContact::load_shift`).
    let mut load_shift = Vec4::ZERO;
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
        let here = Mask4::from_array(points.map(|p| p.is_some()));
        let PointLanes {
            anchor_a,
            anchor_b,
            mut separation,
            normal_impulse,
            friction,
        } = PointLanes::of(points.map(|p| p.unwrap_or(&NO_POINT)));
        let [center_a, _, _] = *sums.get_or_insert([anchor_a, anchor_b, friction]);
        let rn_a = anchor_a.cross(&normal);
        let rn_b = anchor_b.cross(&normal);
        let wn_a = inertia_a.mul(&rn_a);
        let wn_b = inertia_b.mul(&rn_b);
        let k_normal = mass_sum + rn_a.dot(&wn_a) + rn_b.dot(&wn_b);
        let normal_mass = invert(k_normal, here);
        if loaded {
            let k = k_normal.to_array();
            let shift = Vec4::select(
                here,
                Vec4::from_array(core::array::from_fn(|i| {
                    headers[i].load_shift(k[i], input.ctx)
                })),
                Vec4::ZERO,
            );
            // As the scalar path: the cap follows what the separation lost.
            let unshifted = separation;
            separation -= shift;
            load_shift = load_shift.max(unshifted - separation);
        }
        // A lone point is the centre: no lever, no spread.
        let rho2 = if single {
            Vec4::ZERO
        } else {
            let rho = anchor_a.sub(&center_a).select(here);
            warm_twist += rho.cross(&friction).dot(&normal);
            rho.dot(&rho)
        };
        spread += rho2;
        sink.slot(PointX4 {
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
    let mut patch = PatchX4::EMPTY;
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
    if input.ctx.warm_starting {
        patch.tangent_impulse = [warm_linear.dot(&tangents[0]), warm_linear.dot(&tangents[1])];
    }
    // A batch of one-point manifolds has no twist row (no lever to resist twist with).
    if twist {
        let twist_a = inertia_a.mul(&normal);
        let twist_b = inertia_b.mul(&normal);
        sink.twist(TwistX4 {
            impulse: if input.ctx.warm_starting {
                warm_twist
            } else {
                Vec4::ZERO
            },
            mass: invert(normal.dot(&twist_a) + normal.dot(&twist_b), present),
            twist_a,
            twist_b,
        });
    }
    sink.patch(patch);
    let index = |i: usize| group.get(i).map_or(0, |&index| index as u32);
    sink.info(BatchInfo {
        contacts: [0, 1, 2, 3].map(index),
        sources: headers.map(|c| c.source as u32),
        point_counts: headers.map(|c| c.point_count as u32),
        center_a,
        spread,
    });
    sink.batch(Batch {
        normal,
        tangents,
        friction: gather1(&headers, |c| c.friction),
        inv_mass_a,
        inv_mass_b,
        bias_rate: gather1(&headers, |c| c.softness.bias_rate),
        mass_scale: gather1(&headers, |c| c.softness.mass_scale),
        impulse_scale: gather1(&headers, |c| c.softness.impulse_scale),
        max_push: if loaded {
            let shift = load_shift.to_array();
            Vec4::from_array(core::array::from_fn(|i| {
                -headers[i].max_push_with_shift(shift[i])
            }))
        } else {
            gather1(&headers, |c| -c.max_push_out_speed)
        },
        body_a: headers.map(|c| c.body_a as u32),
        body_b: headers.map(|c| c.body_b as u32),
        first_slot: first_slot as u32,
        first_twist,
        slots: slot_count as u16,
        lanes: group.len() as u8,
        twist,
        moving: if cfg!(feature = "parallel") && moving {
            let dynamic = |body: usize| input.params[body].is_dynamic();
            lanes.iter().enumerate().fold(0, |mask, (k, c)| {
                c.map_or(mask, |c| {
                    mask | u8::from(dynamic(c.body_a)) << k | u8::from(dynamic(c.body_b)) << (4 + k)
                })
            })
        } else {
            0
        },
    });
}

/// How many point slots the batch of the manifolds `group` has (as many as its largest manifold has
/// points), and whether it has a twist row (some manifold has two points or more).
#[inline(always)]
pub(crate) fn shape(group: &[usize], contacts: &[PreparedContact]) -> (usize, bool) {
    let counts = group.iter().map(|&index| contacts[index].point_count);
    let slot_count = counts.clone().max().unwrap_or(0);
    (slot_count, counts.into_iter().any(|n| n > 1))
}

impl Batch {
    /// One pass (solve or relax) over the batch: normal rows of every slot, then friction — the scalar
    /// solve's equations in four lanes.
    #[inline(never)]
    pub(crate) fn solve(
        &self,
        patch: &mut PatchX4,
        slots: &mut [PointX4],
        twists: &mut [TwistX4],
        bodies: &mut [SolverBody],
        ctx: &StepContext,
        bias: Bias,
    ) {
        let rows = self.rows(patch, slots, twists);
        let lanes = (
            self.states(&self.body_a, bodies),
            self.states(&self.body_b, bodies),
        );
        let velocities = self.solve_lanes(rows, lanes, ctx, bias);
        self.scatter(bodies, &velocities);
    }

    /// The batch's rows in the solver's arrays: its `patch`, its slots of `slots` and its twist row of
    /// `twists`.
    #[inline(always)]
    pub(crate) fn rows<'a>(
        &self,
        patch: &'a mut PatchX4,
        slots: &'a mut [PointX4],
        twists: &'a mut [TwistX4],
    ) -> Rows<'a> {
        Rows {
            points: &mut slots[self.first_slot as usize..][..usize::from(self.slots)],
            patch,
            twist: if self.twist {
                twists.get_mut(self.first_twist as usize)
            } else {
                None
            },
        }
    }

    /// [`Batch::solve`] up to the write-back: the lanes' new velocities, from the batch's rows and its lanes'
    /// bodies A and B (`sa`, `sb`).
    #[inline(always)]
    pub(crate) fn solve_lanes(
        &self,
        rows: Rows<'_>,
        (sa, sb): LaneBodies<'_>,
        ctx: &StepContext,
        bias: Bias,
    ) -> LaneVelocities {
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
        let max_push = self.max_push;
        let mut total = zero;
        let mut twist_total = zero;
        // The normal rows change the linear velocities only along n: the loop carries `u = n·(v_b − v_a)` and
        // the sum of the applied impulses, and the velocities take that sum once after it (fewer live
        // registers in the loop; the scalar path does the same).
        let mut u = normal.dot(&vb.sub(&va));
        let u_gain = (self.inv_mass_a + self.inv_mass_b) * normal.dot(&normal);
        let mut pushed = zero;
        let Rows {
            points,
            patch: p,
            twist,
        } = rows;
        for p in points.iter_mut() {
            let s = p.separation + shift + turn_b.dot(&p.anchor_b) - turn_a.dot(&p.anchor_a);
            let vn = u + wb.dot(&p.rn_b) - wa.dot(&p.rn_a);
            let speculative: Mask4 = s.cmpgt(zero);
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
        if let Some(r) = twist {
            let spin = normal.dot(&wb.sub(&wa));
            let limit = self.friction * twist_total;
            let candidate = (r.impulse - r.mass * spin).max(-limit).min(limit);
            let applied = candidate - r.impulse;
            r.impulse = candidate;
            wa.sub_scaled(&r.twist_a, applied);
            wb.add_scaled(&r.twist_b, applied);
        }
        LaneVelocities { va, wa, vb, wb }
    }

    /// Stage *warm start* for the batch's manifolds: applies their accumulated impulses again.
    pub(crate) fn warm_start(
        &self,
        patch: &PatchX4,
        slots: &[PointX4],
        twists: &[TwistX4],
        bodies: &mut [SolverBody],
    ) {
        let points = &slots[self.first_slot as usize..][..usize::from(self.slots)];
        let twist = self
            .twist
            .then(|| twists.get(self.first_twist as usize))
            .flatten();
        let lanes = (
            self.states(&self.body_a, bodies),
            self.states(&self.body_b, bodies),
        );
        let velocities = self.warm_start_lanes(points, patch, twist, lanes);
        self.scatter(bodies, &velocities);
    }

    /// [`Batch::warm_start`] up to the write-back: the lanes' new velocities, from its lanes' bodies A and B.
    #[inline(always)]
    pub(crate) fn warm_start_lanes(
        &self,
        points: &[PointX4],
        p: &PatchX4,
        twist: Option<&TwistX4>,
        (sa, sb): LaneBodies<'_>,
    ) -> LaneVelocities {
        let ((mut va, mut wa), (mut vb, mut wb)) =
            (LaneStates::velocities(&sa), LaneStates::velocities(&sb));
        // All normal impulses act along n: their sum moves the linear velocities once.
        let mut pushed = Vec4::ZERO;
        for p in points {
            pushed += p.normal_impulse;
            wa.sub_scaled(&p.wn_a, p.normal_impulse);
            wb.add_scaled(&p.wn_b, p.normal_impulse);
        }
        va.sub_scaled(&self.normal, pushed * self.inv_mass_a);
        vb.add_scaled(&self.normal, pushed * self.inv_mass_b);
        let [t0, t1] = self.tangents;
        let [x, y] = p.tangent_impulse;
        let linear = t0.scale(x).add(&t1.scale(y));
        va.sub_scaled(&linear, self.inv_mass_a);
        vb.add_scaled(&linear, self.inv_mass_b);
        wa.sub_scaled(&p.wt_a[0], x);
        wa.sub_scaled(&p.wt_a[1], y);
        wb.add_scaled(&p.wt_b[0], x);
        wb.add_scaled(&p.wt_b[1], y);
        if let Some(r) = twist {
            wa.sub_scaled(&r.twist_a, r.impulse);
            wb.add_scaled(&r.twist_b, r.impulse);
        }
        LaneVelocities { va, wa, vb, wb }
    }

    /// The lanes' bodies, by reference (the transposes read the 16-byte groups they need, not whole states).
    /// An empty lane reads body 0 (its indices are [`EMPTY_LANE`]'s): with zero masses, normal and rows it
    /// applies no impulse, whatever it reads, and its velocities are never written back, so no lane's result
    /// depends on what an empty one reads, and no branch per lane is needed (an empty lane's own rows may
    /// then hold any value; nothing reads lanes past the batch's `lanes`). [`Batch::shared_states`] keeps the
    /// branch: there another thread may be writing body 0 while the lane reads it.
    #[inline(always)]
    fn states<'a>(
        &self,
        index: &[u32; LANES],
        bodies: &'a [SolverBody],
    ) -> [&'a SolverBody; LANES] {
        index.map(|i| bodies.get(i as usize).unwrap_or(&SolverBody::STATIC))
    }

    /// [`Batch::states`] of bodies that other threads may be writing: bodies A and B of every lane.
    ///
    /// # Safety
    /// No other thread writes a body of the batch while the references live: within a colour group each
    /// dynamic body is in one batch only, and fixed and kinematic bodies are never written by a group.
    #[inline(always)]
    #[expect(
        unsafe_code,
        reason = "reads the bodies other batches of the group write (Disjoint)"
    )]
    pub(crate) unsafe fn shared_states<'a>(
        &self,
        bodies: &'a Disjoint<'_, SolverBody>,
    ) -> LaneBodies<'a> {
        let lanes = |index: &[u32; LANES]| {
            let lane = |k: usize| {
                if k < usize::from(self.lanes) {
                    // SAFETY: the caller keeps writers off the batch's bodies.
                    unsafe { bodies.get(index[k] as usize) }.unwrap_or(&SolverBody::STATIC)
                } else {
                    &SolverBody::STATIC
                }
            };
            [lane(0), lane(1), lane(2), lane(3)]
        };
        (lanes(&self.body_a), lanes(&self.body_b))
    }

    /// Writes the lanes' velocities back into their dynamic bodies ([`Batch::moving`]), never into a fixed
    /// or kinematic one: what [`Batch::scatter`] writes, as the velocity a lane computes for a body of zero
    /// inverse mass and inertia is the one it read (see `super::groups`).
    ///
    /// # Safety
    /// No other reference to a dynamic body of the batch lives: within a colour group each dynamic body is in
    /// one batch only.
    #[inline(always)]
    #[expect(
        unsafe_code,
        reason = "writes the batch's own bodies of a shared array (Disjoint)"
    )]
    pub(crate) unsafe fn scatter_moving(
        &self,
        bodies: &Disjoint<'_, SolverBody>,
        velocities: &LaneVelocities,
    ) {
        let LaneVelocities { va, wa, vb, wb } = velocities;
        let (va, wa, vb, wb) = (va.lanes(), wa.lanes(), vb.lanes(), wb.lanes());
        for lane in 0..usize::from(self.lanes) {
            if self.moving & (1 << lane) != 0 {
                // SAFETY: the batch's own dynamic body (the caller's contract).
                if let Some(a) = unsafe { bodies.get_mut(self.body_a[lane] as usize) } {
                    a.linear_velocity = va[lane];
                    a.angular_velocity = wa[lane];
                }
            }
            if self.moving & (1 << (4 + lane)) != 0 {
                // SAFETY: as above.
                if let Some(b) = unsafe { bodies.get_mut(self.body_b[lane] as usize) } {
                    b.linear_velocity = vb[lane];
                    b.angular_velocity = wb[lane];
                }
            }
        }
    }

    /// Writes the lanes' velocities back.
    #[inline(always)]
    pub(crate) fn scatter(&self, bodies: &mut [SolverBody], velocities: &LaneVelocities) {
        let LaneVelocities { va, wa, vb, wb } = velocities;
        let (va, wa, vb, wb) = (va.lanes(), wa.lanes(), vb.lanes(), wb.lanes());
        for lane in 0..usize::from(self.lanes) {
            let a = &mut bodies[self.body_a[lane] as usize];
            a.linear_velocity = va[lane];
            a.angular_velocity = wa[lane];
            let b = &mut bodies[self.body_b[lane] as usize];
            b.linear_velocity = vb[lane];
            b.angular_velocity = wb[lane];
        }
    }
}

/// The bodies A and B of a batch's four lanes, as the passes read them.
pub(crate) type LaneBodies<'a> = ([&'a SolverBody; LANES], [&'a SolverBody; LANES]);

/// A pass's rows of one batch: its point slots, its patch and its twist row if it has one.
pub(crate) struct Rows<'a> {
    pub(crate) points: &'a mut [PointX4],
    pub(crate) patch: &'a mut PatchX4,
    pub(crate) twist: Option<&'a mut TwistX4>,
}

/// A pass's result for a batch before it is written back: each lane's new linear and angular velocities of
/// body A and body B (m/s, rad/s).
#[derive(Debug, Clone, Copy, Default)]
pub(crate) struct LaneVelocities {
    pub(crate) va: Vec3x4,
    pub(crate) wa: Vec3x4,
    pub(crate) vb: Vec3x4,
    pub(crate) wb: Vec3x4,
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
    max_push_out_speed: 0.0,
    both_dynamic: false,
    moving_surface: false,
    load_depth: 0.0,
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
