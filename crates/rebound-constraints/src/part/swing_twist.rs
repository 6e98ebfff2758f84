//! The swing–twist measure of two joint frames (Jolt's `SwingTwistConstraintPart`, written from its
//! description): the relative rotation split into a twist about A's X axis and a swing that tilts the X axis,
//! with the swing measured against an elliptical cone. The ball joint's limits use it, and so do the 6-DOF
//! joint's angular coordinates. The derivation is in `docs/physics.md`, "Swing–twist limits".
//!
//! ```text
//! q = F_a⁻¹·F_b = q_swing·q_twist     (w ≥ 0),  q_twist = (w, x, 0, 0)/√(w² + x²),  q_swing.x = 0
//! twist  θ = 2·atan2(q_twist.x, q_twist.w) ∈ [−π, π]
//!        θ̇ = j_t·(ω_b − ω_a),  j_t = (x_a + x_b)/(1 + x_a·x_b)       x_a = F_a·x̂, x_b = F_b·x̂ (world)
//! swing  φ = 2·atan2(|(y_s, z_s)|, w_s) = ∠(x_a, x_b),  u = (y_s, z_s)/|(y_s, z_s)|   (A frame, unit)
//!        φ̇ = (F_a·(0, u))·(ω_b − ω_a)                              exact
//! cone   φ_max(u) = 1/√((u_y/θ_y)² + (u_z/θ_z)²)                   θ_y, θ_z the half-angles about Y and Z
//!        n = ∇ of (s_y/θ_y)² + (s_z/θ_z)² at s = φ_max·u, normalised: (u_y/θ_y², u_z/θ_z²)/|·|
//!        C = (φ − φ_max(u))·(n·u) ≤ 0,   Ċ = j_s·(ω_b − ω_a)
//!        j_s = F_a·(c·(0, u) + (−r'·c + (φ − r)·c')·(cot φ·(0, w) − x̂))    r = φ_max(u), c = n·u,
//!              w = (u_z, −u_y), r' and c' their rates as u turns towards w (see docs/physics.md)
//! ```
//!
//! For a circular cone `n = u` and `j_s = F_a·(0, u)`. For an elliptical one `C` changes as `u` turns too,
//! also under a twist of B about A's X axis, which carries B's axis round the cone; `j_s` is `C`'s exact
//! rate, so that a Newton step of the position projection on the row converges as Newton does.

use rebound_math::{Quat, Vec2, Vec3, real};

/// Below this `|(y_s, z_s)|` (the sine of half the swing) the swing direction is taken as A's Y axis.
const MIN_SWING_SINE: f32 = 1e-7;

/// The smallest `sin φ` the swing row's rate divides by (see [`SwingTwist::cone_error`]).
const MIN_SWING_SINE_FOR_RATE: f32 = 1e-3;

/// Below this `1 + x_a·x_b` (the X axes nearly opposite, a swing near π) the twist has no defined rate and
/// its row is left out.
pub const MIN_TWIST_DENOMINATOR: f32 = 1e-3;

/// The relative rotation of two joint frames as a swing and a twist (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SwingTwist {
    /// The twist angle θ about the X axis (rad, in `[−π, π]`).
    pub twist: f32,
    /// The swing angle φ: the angle between the two frames' X axes (rad, in `[0, π]`).
    pub swing: f32,
    /// The unit swing direction `u` in A's joint frame's YZ plane (its Y and Z components).
    pub swing_direction: Vec2,
}

impl SwingTwist {
    /// The swing and twist of frame `frame_b` relative to `frame_a` (world orientations).
    #[inline]
    #[must_use]
    pub fn new(frame_a: Quat, frame_b: Quat) -> Self {
        let mut q = frame_a.conjugate() * frame_b;
        if q.w < 0.0 {
            q = -q;
        }
        let twist_len = (q.w * q.w + q.x * q.x).sqrt();
        let (twist, swing_quat) = if twist_len > MIN_SWING_SINE {
            let t = Quat::from_xyzw(q.x / twist_len, 0.0, 0.0, q.w / twist_len);
            (2.0 * real::atan2(t.x, t.w), q * t.conjugate())
        } else {
            // A swing of π: no twist can be told apart from the swing.
            (0.0, q)
        };
        let sine = Vec2::new(swing_quat.y, swing_quat.z);
        let sine_len = sine.length();
        let swing_direction = if sine_len > MIN_SWING_SINE {
            sine / sine_len
        } else {
            Vec2::X
        };
        Self {
            twist,
            swing: 2.0 * real::atan2(sine_len, swing_quat.w.abs()),
            swing_direction,
        }
    }

    /// The twist's Jacobian axis `j_t = (x_a + x_b)/(1 + x_a·x_b)` (world, not unit: `θ̇ = j_t·(ω_b − ω_a)`),
    /// or `None` when the X axes are nearly opposite.
    #[inline]
    #[must_use]
    pub fn twist_axis(frame_a: Quat, frame_b: Quat) -> Option<Vec3> {
        let (x_a, x_b) = (frame_a * Vec3::X, frame_b * Vec3::X);
        let denominator = 1.0 + x_a.dot(x_b);
        (denominator > MIN_TWIST_DENOMINATOR).then(|| (x_a + x_b) / denominator)
    }

    /// The swing limit's error `C` (rad, ≤ 0 inside the cone) and its row's axis `j_s` (world, `Ċ = j_s·(ω_b −
    /// ω_a)`; unit for a circular cone) for the cone of half-angles `half_angles` = (θ_y, θ_z) (rad, each in
    /// `(0, π]`) in A's frame `frame_a`. See the module docs for `j_s`.
    #[inline]
    #[must_use]
    pub fn cone_error(&self, frame_a: Quat, half_angles: Vec2) -> (f32, Vec3) {
        let u = self.swing_direction;
        let phi = self.swing;
        let scaled = u / half_angles;
        let inv_r2 = scaled.length_squared();
        let max_swing = inv_r2.sqrt().recip();
        let m = scaled / half_angles;
        let m_len = m.length();
        let normal = (m / m_len).normalize_or(u);
        let cosine = normal.dot(u);
        let c = (phi - max_swing) * cosine;
        // The swing direction's angle β (u turning towards w = (u_z, −u_y)): C's rate along it.
        let inv2 = half_angles.recip() * half_angles.recip();
        let (d2, d4) = (inv2.x - inv2.y, inv2.x * inv2.x - inv2.y * inv2.y);
        let p = u.x * u.y;
        let dr = -max_swing * max_swing * max_swing * p * d2;
        let dc = if m_len > 0.0 {
            p * (2.0 * d2 * m_len * m_len - inv_r2 * d4) / (m_len * m_len * m_len)
        } else {
            0.0
        };
        let along_beta = -dr * cosine + (phi - max_swing) * dc;
        // cot φ, held where φ is far inside the cone or near a half turn (the direction, and C's rate along
        // it, are then undefined; such a row is far from acting).
        let phi_held = phi.max(0.5 * max_swing);
        let (sine, cosine_held) = real::sin_cos(phi_held);
        let cot = cosine_held / sine.max(MIN_SWING_SINE_FOR_RATE);
        let w = Vec3::new(0.0, u.y, -u.x);
        let axis = Vec3::new(0.0, u.x, u.y) * cosine + (w * cot - Vec3::X) * along_beta;
        (c, frame_a * axis)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use core::f32::consts::FRAC_PI_2;

    /// `B` turned by the small world rotation vector `delta` (rad).
    fn turned(frame_b: Quat, delta: Vec3) -> Quat {
        (Quat::from_scaled_axis(delta) * frame_b).normalize()
    }

    #[test]
    fn swing_and_twist_recompose_the_rotation() {
        let fa = Quat::from_rotation_y(0.3);
        for (twist, swing_axis, swing) in [
            (0.4f32, Vec3::Y, 0.7f32),
            (-1.2, Vec3::new(0.0, 1.0, 1.0).normalize(), 1.1),
            (2.9, Vec3::Z, 0.01),
        ] {
            let q = Quat::from_axis_angle(swing_axis, swing) * Quat::from_rotation_x(twist);
            let st = SwingTwist::new(fa, fa * q);
            assert!((st.twist - twist).abs() < 1e-5, "{} vs {twist}", st.twist);
            assert!((st.swing - swing).abs() < 1e-5, "{} vs {swing}", st.swing);
            let u = Vec3::new(0.0, st.swing_direction.x, st.swing_direction.y);
            assert!(u.abs_diff_eq(swing_axis, 1e-5));
        }
    }

    #[test]
    fn the_twist_and_swing_rates_are_their_jacobians() {
        // Central differences of θ and of a circular cone's C under small rotations of B, against j·δ.
        let fa = Quat::from_rotation_z(0.2);
        let fb =
            fa * Quat::from_axis_angle(Vec3::new(0.0, 0.6, 0.8), 0.9) * Quat::from_rotation_x(0.5);
        let half = Vec2::splat(0.6);
        let j_t = SwingTwist::twist_axis(fa, fb).unwrap();
        let (_, j_s) = SwingTwist::new(fa, fb).cone_error(fa, half);
        let eps = 1e-3;
        for delta in [Vec3::X, Vec3::Y, Vec3::Z, Vec3::new(0.3, -0.5, 0.8)] {
            let (plus, minus) = (turned(fb, delta * eps), turned(fb, -delta * eps));
            let (p, m) = (SwingTwist::new(fa, plus), SwingTwist::new(fa, minus));
            let twist_rate = (p.twist - m.twist) / (2.0 * eps);
            assert!(
                (twist_rate - j_t.dot(delta)).abs() < 2e-3,
                "{twist_rate} vs {}",
                j_t.dot(delta)
            );
            let swing_rate = (p.cone_error(fa, half).0 - m.cone_error(fa, half).0) / (2.0 * eps);
            assert!(
                (swing_rate - j_s.dot(delta)).abs() < 2e-3,
                "{swing_rate} vs {}",
                j_s.dot(delta)
            );
        }
    }

    #[test]
    fn an_elliptical_cones_swing_rate_is_its_jacobian_inside_on_and_past_the_cone() {
        // Central differences of C against j_s·δ, for small rotations of B about every axis (about A's X
        // too, which turns the swing direction), at swings inside and far past cones of aspect 1:3 (not
        // deeper inside than half the cone, where the row holds its rate, see `cone_error`).
        let fa = Quat::from_rotation_y(-0.4);
        let eps = 1e-3;
        for half in [Vec2::new(0.436, 1.31), Vec2::new(1.2, 0.4)] {
            for (direction, swing, twist) in [
                (Vec3::new(0.0, 1.0, 1.0), 0.7f32, 0.3f32),
                (Vec3::new(0.0, 1.0, 3.0), 1.6, -0.5),
                (Vec3::new(0.0, -3.0, 1.0), 0.9, 1.1),
                (Vec3::new(0.0, 0.2, -1.0), 0.9, 0.0),
            ] {
                let fb = fa
                    * Quat::from_axis_angle(direction.normalize(), swing)
                    * Quat::from_rotation_x(twist);
                let (_, j_s) = SwingTwist::new(fa, fb).cone_error(fa, half);
                for delta in [Vec3::X, Vec3::Y, Vec3::Z, fa * Vec3::X] {
                    let (plus, minus) = (turned(fb, delta * eps), turned(fb, -delta * eps));
                    let (p, m) = (SwingTwist::new(fa, plus), SwingTwist::new(fa, minus));
                    let rate = (p.cone_error(fa, half).0 - m.cone_error(fa, half).0) / (2.0 * eps);
                    assert!(
                        (rate - j_s.dot(delta)).abs() < 5e-3 * (1.0 + rate.abs()),
                        "half {half}, swing {swing} about {direction}: {rate} vs {}",
                        j_s.dot(delta)
                    );
                }
            }
        }
    }

    #[test]
    fn the_cone_error_is_zero_on_the_ellipse_along_each_axis() {
        let half = Vec2::new(0.5, 1.0);
        for (axis, limit) in [
            (Vec3::Y, 0.5f32),
            (Vec3::Z, 1.0),
            (-Vec3::Y, 0.5),
            (-Vec3::Z, 1.0),
        ] {
            let st = SwingTwist::new(Quat::IDENTITY, Quat::from_axis_angle(axis, limit));
            let (c, n) = st.cone_error(Quat::IDENTITY, half);
            assert!(c.abs() < 1e-5, "{c}");
            assert!(n.abs_diff_eq(axis, 1e-5));
        }
        // Inside and outside.
        let inside = SwingTwist::new(Quat::IDENTITY, Quat::from_rotation_y(0.4));
        assert!(inside.cone_error(Quat::IDENTITY, half).0 < 0.0);
        let outside = SwingTwist::new(Quat::IDENTITY, Quat::from_rotation_z(FRAC_PI_2));
        assert!(outside.cone_error(Quat::IDENTITY, half).0 > 0.0);
    }

    #[test]
    fn no_nan_at_zero_and_half_turn_swings() {
        for q in [Quat::IDENTITY, Quat::from_rotation_y(core::f32::consts::PI)] {
            let st = SwingTwist::new(Quat::IDENTITY, q);
            let (c, n) = st.cone_error(Quat::IDENTITY, Vec2::new(0.3, 0.7));
            assert!(st.twist.is_finite() && c.is_finite() && n.is_finite());
        }
        assert!(
            SwingTwist::twist_axis(Quat::IDENTITY, Quat::from_rotation_y(core::f32::consts::PI))
                .is_none()
        );
    }
}
