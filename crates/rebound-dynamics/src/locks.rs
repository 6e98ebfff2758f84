//! Axis locks: the world axes along which a body may not translate and about which it may not turn (2.5D
//! games, upright characters). Read by *prepare* (the locked inverse inertia, [`LockedAxes::inv_inertia`])
//! and by the substeps ([`LockedAxes::lock_velocities`] after integration and after every constraint pass),
//! so that a locked axis's velocity is zero, bit for bit, at every stage boundary.

use rebound_math::{Mat3, Vec3};

/// Which world axes of a body are locked. Default: none.
///
/// A rotation lock is exact in the constraints too: the body's inverse inertia is that of the body turning
/// about its free axes only (the inverse of its world inertia restricted to them, zero on the locked ones),
/// so no constraint impulse turns it about a locked axis. A translation lock is applied to the velocities:
/// after integration and after each constraint pass the locked components are set to zero, as is the
/// displacement along them; within one pass a constraint sees the body free along the axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
#[cfg_attr(feature = "serde", derive(serde::Serialize, serde::Deserialize))]
#[cfg_attr(feature = "serde", serde(default))]
pub struct LockedAxes {
    /// No translation along world x, y, z.
    pub translation: [bool; 3],
    /// No rotation about world x, y, z.
    pub rotation: [bool; 3],
}

impl LockedAxes {
    /// Nothing locked.
    pub const NONE: Self = Self {
        translation: [false; 3],
        rotation: [false; 3],
    };

    /// Every translation locked (the body may only turn).
    pub const ALL_TRANSLATION: Self = Self {
        translation: [true; 3],
        rotation: [false; 3],
    };

    /// Every rotation locked (the body may only translate: an upright character).
    pub const ALL_ROTATION: Self = Self {
        translation: [false; 3],
        rotation: [true; 3],
    };

    /// The locks of a body moving in the x–y plane: no translation along z, no rotation about x or y.
    pub const PLANE_XY: Self = Self {
        translation: [false, false, true],
        rotation: [true, true, false],
    };

    /// Whether any axis is locked.
    #[must_use]
    pub const fn is_any(self) -> bool {
        let [tx, ty, tz] = self.translation;
        let [rx, ry, rz] = self.rotation;
        // `|`, not `||`: one test instead of six branches (every body asks, every step).
        tx | ty | tz | rx | ry | rz
    }

    /// `v` with the components along locked translation axes set to `+0.0`.
    #[must_use]
    pub fn lock_linear(self, v: Vec3) -> Vec3 {
        mask(v, self.translation)
    }

    /// `omega` with the components about locked rotation axes set to `+0.0`.
    #[must_use]
    pub fn lock_angular(self, omega: Vec3) -> Vec3 {
        mask(omega, self.rotation)
    }

    /// The world inverse inertia of a body with world inertia `inertia_world` (kg·m²) and these rotation
    /// locks (1/(kg·m²)): the inverse of the inertia restricted to the free axes, zero rows and columns for
    /// the locked ones. With no rotation lock, `None` (the caller keeps its ordinary inverse). A singular
    /// restriction (a massless body) gives zero.
    #[must_use]
    pub fn inv_inertia(self, inertia_world: Mat3) -> Option<Mat3> {
        if !self.rotation.contains(&true) {
            return None;
        }
        // The free axes, without allocating (prepare runs this per locked body per step).
        let (mut free, mut count) = ([0usize; 3], 0);
        for axis in 0..3 {
            if !self.rotation[axis] {
                free[count] = axis;
                count += 1;
            }
        }
        let at = |m: &Mat3, row: usize, column: usize| m.col(column)[row];
        let mut inverse = [[0.0f32; 3]; 3];
        match &free[..count] {
            [i] => {
                let k = at(&inertia_world, *i, *i);
                if k > 0.0 && k.is_finite() {
                    inverse[*i][*i] = 1.0 / k;
                }
            }
            [i, j] => {
                let (a, b, d) = (
                    at(&inertia_world, *i, *i),
                    at(&inertia_world, *i, *j),
                    at(&inertia_world, *j, *j),
                );
                let det = a * d - b * b;
                if det > 0.0 && det.is_finite() {
                    inverse[*i][*i] = d / det;
                    inverse[*j][*j] = a / det;
                    inverse[*i][*j] = -b / det;
                    inverse[*j][*i] = -b / det;
                }
            }
            _ => {}
        }
        // `inverse[row][column]`; glam's matrices are built from columns.
        Some(Mat3::from_cols(
            Vec3::new(inverse[0][0], inverse[1][0], inverse[2][0]),
            Vec3::new(inverse[0][1], inverse[1][1], inverse[2][1]),
            Vec3::new(inverse[0][2], inverse[1][2], inverse[2][2]),
        ))
    }
}

/// `v` with the components where `locked` is set replaced by `+0.0`.
fn mask(v: Vec3, locked: [bool; 3]) -> Vec3 {
    Vec3::new(
        if locked[0] { 0.0 } else { v.x },
        if locked[1] { 0.0 } else { v.y },
        if locked[2] { 0.0 } else { v.z },
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_locked_inverse_inertia_inverts_the_free_block_and_zeroes_the_rest() {
        // A symmetric positive definite world inertia with off-diagonal terms.
        let inertia = Mat3::from_cols(
            Vec3::new(2.0, 0.3, 0.1),
            Vec3::new(0.3, 3.0, 0.2),
            Vec3::new(0.1, 0.2, 4.0),
        );
        assert_eq!(LockedAxes::NONE.inv_inertia(inertia), None);
        let only_z = LockedAxes::PLANE_XY
            .inv_inertia(inertia)
            .unwrap_or(Mat3::NAN);
        let expected = Mat3::from_cols(Vec3::ZERO, Vec3::ZERO, Vec3::new(0.0, 0.0, 0.25));
        assert!(only_z.abs_diff_eq(expected, 1e-7), "{only_z}");
        // Free x and z: the 2 × 2 block [[2, 0.1], [0.1, 4]] inverted; times the block gives its identity.
        let locks = LockedAxes {
            rotation: [false, true, false],
            ..LockedAxes::NONE
        };
        let m = locks.inv_inertia(inertia).unwrap_or(Mat3::NAN);
        let product = m * inertia;
        for (row, column, value) in [(0, 0, 1.0), (2, 2, 1.0), (0, 2, 0.0), (2, 0, 0.0)] {
            assert!((product.col(column)[row] - value).abs() < 1e-6, "{product}");
        }
        assert_eq!(m.col(1), Vec3::ZERO);
        assert_eq!(m.row(1), Vec3::ZERO);
        assert_eq!(
            LockedAxes::ALL_ROTATION.inv_inertia(inertia),
            Some(Mat3::ZERO)
        );
    }

    #[test]
    fn masks_set_locked_components_to_positive_zero() {
        let v = Vec3::new(-1.0, -2.0, -3.0);
        let locked = LockedAxes::PLANE_XY.lock_linear(v);
        assert_eq!(locked.z.to_bits(), 0.0f32.to_bits());
        assert_eq!(locked.truncate(), v.truncate());
        let w = LockedAxes::PLANE_XY.lock_angular(v);
        assert_eq!([w.x.to_bits(), w.y.to_bits()], [0, 0]);
        assert!(LockedAxes::PLANE_XY.is_any() && !LockedAxes::NONE.is_any());
    }
}
