//! The lane arithmetic of the wide contact path: a 3-vector and a 3 × 3 matrix in each of four lanes
//! (structure of arrays), and the transposes that load four bodies' states and four contact points into lanes
//! (16-byte groups of `#[repr(C)]` structs, one 4 × 4 transpose each) and store the velocities back.

use crate::SolverBody;
use crate::contact::manifold::ContactPoint;
use rebound_math::{Mat4, Vec3, Vec4};

/// The mask `Vec4`'s comparisons return: glam's `BVec4A` on its SIMD paths, `BVec4` under its `scalar-math`
/// (which the `enhanced-determinism` feature turns on).
#[cfg(not(feature = "enhanced-determinism"))]
pub(crate) type Mask4 = rebound_math::glam::BVec4A;
/// The mask `Vec4`'s comparisons return: glam's `BVec4A` on its SIMD paths, `BVec4` under its `scalar-math`
/// (which the `enhanced-determinism` feature turns on).
#[cfg(feature = "enhanced-determinism")]
pub(crate) type Mask4 = rebound_math::glam::BVec4;

/// Lanes per batch.
pub(crate) const LANES: usize = 4;

/// A 3-vector in each of the four lanes (structure of arrays).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Vec3x4 {
    pub(crate) x: Vec4,
    pub(crate) y: Vec4,
    pub(crate) z: Vec4,
}

impl Vec3x4 {
    pub(crate) const ZERO: Self = Self {
        x: Vec4::ZERO,
        y: Vec4::ZERO,
        z: Vec4::ZERO,
    };

    /// The four lanes' vectors, transposed (one 4×4 transpose instead of twelve lane inserts).
    #[inline(always)]
    pub(crate) fn from_lanes(v: [Vec3; LANES]) -> Self {
        Self::rows(&transpose_lanes(&v, |v| v.extend(0.0)))
    }

    /// The first three rows of `m` (of a [`transpose_lanes`]): x, y and z in lanes.
    #[inline(always)]
    pub(crate) fn rows(m: &Mat4) -> Self {
        Self {
            x: m.x_axis,
            y: m.y_axis,
            z: m.z_axis,
        }
    }

    /// The vector of each lane.
    #[inline(always)]
    pub(crate) fn lanes(&self) -> [Vec3; LANES] {
        let m = Mat4::from_cols(self.x, self.y, self.z, Vec4::ZERO).transpose();
        [
            m.x_axis.truncate(),
            m.y_axis.truncate(),
            m.z_axis.truncate(),
            m.w_axis.truncate(),
        ]
    }

    #[inline(always)]
    pub(crate) fn dot(&self, o: &Self) -> Vec4 {
        self.x * o.x + self.y * o.y + self.z * o.z
    }

    #[inline(always)]
    pub(crate) fn cross(&self, o: &Self) -> Self {
        Self {
            x: self.y * o.z - self.z * o.y,
            y: self.z * o.x - self.x * o.z,
            z: self.x * o.y - self.y * o.x,
        }
    }

    #[inline(always)]
    pub(crate) fn add(&self, o: &Self) -> Self {
        Self {
            x: self.x + o.x,
            y: self.y + o.y,
            z: self.z + o.z,
        }
    }

    #[inline(always)]
    pub(crate) fn sub(&self, o: &Self) -> Self {
        Self {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }

    #[inline(always)]
    pub(crate) fn scale(&self, s: Vec4) -> Self {
        Self {
            x: self.x * s,
            y: self.y * s,
            z: self.z * s,
        }
    }

    /// The vector of lane `lane`.
    #[cfg(test)]
    pub(crate) fn lane(&self, lane: usize) -> Vec3 {
        Vec3::new(self.x[lane], self.y[lane], self.z[lane])
    }

    /// The lanes of `self` where `mask` is set, zero elsewhere.
    #[inline(always)]
    pub(crate) fn select(&self, mask: Mask4) -> Self {
        Self {
            x: Vec4::select(mask, self.x, Vec4::ZERO),
            y: Vec4::select(mask, self.y, Vec4::ZERO),
            z: Vec4::select(mask, self.z, Vec4::ZERO),
        }
    }

    /// `self += v·s`.
    #[inline(always)]
    pub(crate) fn add_scaled(&mut self, v: &Self, s: Vec4) {
        self.x += v.x * s;
        self.y += v.y * s;
        self.z += v.z * s;
    }

    /// `self −= v·s`.
    #[inline(always)]
    pub(crate) fn sub_scaled(&mut self, v: &Self, s: Vec4) {
        self.x -= v.x * s;
        self.y -= v.y * s;
        self.z -= v.z * s;
    }
}

/// A 3 × 3 matrix in each lane, by columns.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub(crate) struct Mat3x4 {
    pub(crate) x_axis: Vec3x4,
    pub(crate) y_axis: Vec3x4,
    pub(crate) z_axis: Vec3x4,
}

impl Mat3x4 {
    /// `M·v` in each lane, summed as glam's `Mat3 * Vec3` sums (x, then y, then z column).
    #[inline(always)]
    pub(crate) fn mul(&self, v: &Vec3x4) -> Vec3x4 {
        self.x_axis
            .scale(v.x)
            .add(&self.y_axis.scale(v.y))
            .add(&self.z_axis.scale(v.z))
    }
}

/// One slot's contact points in lanes, read like [`LaneStates`]: a `#[repr(C)]` [`ContactPoint`] is
/// `[r_a, r_b.x]`, `[r_b.y, r_b.z, s, λ_n]`, `[λ_t, id]` — three 16-byte groups, three transposes.
pub(crate) struct PointLanes {
    pub(crate) anchor_a: Vec3x4,
    pub(crate) anchor_b: Vec3x4,
    pub(crate) separation: Vec4,
    pub(crate) normal_impulse: Vec4,
    pub(crate) friction: Vec3x4,
}

impl PointLanes {
    #[inline(always)]
    pub(crate) fn of(points: [&ContactPoint; LANES]) -> Self {
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
pub(crate) struct LaneStates {
    pub(crate) v: Vec3x4,
    pub(crate) w: Vec3x4,
    pub(crate) dp: Vec3x4,
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
    pub(crate) fn velocities(states: &[&SolverBody; LANES]) -> (Vec3x4, Vec3x4) {
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
    pub(crate) fn of(states: &[&SolverBody; LANES]) -> Self {
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
    pub(crate) fn turn(&self, normal: &Vec3x4) -> Vec3x4 {
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
pub(crate) fn gather3<T>(items: &[T; LANES], f: impl Fn(&T) -> Vec3) -> Vec3x4 {
    Vec3x4::from_lanes([f(&items[0]), f(&items[1]), f(&items[2]), f(&items[3])])
}

/// One number per lane.
#[inline(always)]
pub(crate) fn gather1<T>(items: &[T; LANES], f: impl Fn(&T) -> f32) -> Vec4 {
    Vec4::new(f(&items[0]), f(&items[1]), f(&items[2]), f(&items[3]))
}
