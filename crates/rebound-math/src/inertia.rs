//! Inertia: principal moments of the primitive solids, the parallel-axis theorem, and the world-space
//! inverse inertia `R·I⁻¹·Rᵀ` the solver uses every substep.
//!
//! Units: mass kg, lengths m, moments of inertia kg·m². Every solid is uniform (constant density) and its
//! symmetry axis, where it has one, is the local **y** axis (parry's convention). Moments are about the centre
//! of mass, in the order `(I_xx, I_yy, I_zz)`.
//!
//! The inertia tensor is stored as a symmetric [`Mat3`]: a dedicated symmetric type would save three floats
//! but make every product with glam types a conversion; the solver keeps the world-space inverse as a `Mat3`
//! anyway.
//!
//! | solid | principal moments about the centre of mass |
//! |---|---|
//! | sphere, radius r | `2/5·m·r²` on every axis |
//! | cuboid, half-extents (a, b, c) | `m/3·(b² + c²)`, `m/3·(a² + c²)`, `m/3·(a² + b²)` |
//! | cylinder, radius r, half-height h | `I_yy = m·r²/2`, `I_xx = I_zz = m·(3r² + 4h²)/12` |
//! | cone, radius r, half-height h (height H = 2h) | `I_yy = 3/10·m·r²`, `I_xx = I_zz = 3/20·m·r² + 3/80·m·H²` |
//! | capsule, radius r, half-height h of the cylinder | cylinder + two hemispheres, see [`capsule`] |

use crate::validity::{check_finite_vec3, check_non_negative, check_positive};
use crate::{Mat3, MathError, Quat, Vec3};
use core::f32::consts::PI;

/// Principal moments of a solid sphere of `mass` (kg) and `radius` (m): `2/5·m·r²` (kg·m²).
///
/// # Errors
/// `mass` and `radius` must be finite and > 0 ([`MathError::NotPositive`], [`MathError::NonFinite`]).
pub fn sphere(mass: f32, radius: f32) -> Result<Vec3, MathError> {
    check_positive("mass", mass)?;
    check_positive("radius", radius)?;
    Ok(Vec3::splat(0.4 * mass * radius * radius))
}

/// Principal moments of a solid cuboid of `mass` (kg) and `half_extents` (m) along x, y, z (kg·m²).
///
/// # Errors
/// `mass` and every half-extent must be finite and > 0 (field `mass` or `half_extents.x|y|z`).
pub fn cuboid(mass: f32, half_extents: Vec3) -> Result<Vec3, MathError> {
    check_positive("mass", mass)?;
    check_positive("half_extents.x", half_extents.x)?;
    check_positive("half_extents.y", half_extents.y)?;
    check_positive("half_extents.z", half_extents.z)?;
    let sq = half_extents * half_extents;
    Ok(mass / 3.0 * Vec3::new(sq.y + sq.z, sq.x + sq.z, sq.x + sq.y))
}

/// Principal moments of a solid cylinder along y, of `mass` (kg), `radius` (m) and `half_height` (m).
///
/// # Errors
/// All three must be finite and > 0.
pub fn cylinder(mass: f32, radius: f32, half_height: f32) -> Result<Vec3, MathError> {
    check_positive("mass", mass)?;
    check_positive("radius", radius)?;
    check_positive("half_height", half_height)?;
    let r2 = radius * radius;
    let transverse = mass * (3.0 * r2 + 4.0 * half_height * half_height) / 12.0;
    Ok(Vec3::new(transverse, 0.5 * mass * r2, transverse))
}

/// Principal moments of a solid cone along y about its **centre of mass**, of `mass` (kg), base `radius` (m)
/// and `half_height` (m). The cone's base is at `y = −half_height` and its apex at `+half_height` (parry's
/// convention); the centre of mass is at [`cone_center_of_mass`].
///
/// # Errors
/// All three must be finite and > 0.
pub fn cone(mass: f32, radius: f32, half_height: f32) -> Result<Vec3, MathError> {
    check_positive("mass", mass)?;
    check_positive("radius", radius)?;
    check_positive("half_height", half_height)?;
    let r2 = radius * radius;
    let height = 2.0 * half_height;
    let transverse = mass * (3.0 / 20.0 * r2 + 3.0 / 80.0 * height * height);
    Ok(Vec3::new(transverse, 0.3 * mass * r2, transverse))
}

/// The centre of mass of the cone of [`cone`]: a quarter of the height above the base, `(0, −h/2, 0)` (m).
#[must_use]
pub fn cone_center_of_mass(half_height: f32) -> Vec3 {
    Vec3::new(0.0, -0.5 * half_height, 0.0)
}

/// Principal moments of a solid capsule along y: a cylinder of `radius` and `half_height` (m) capped by two
/// hemispheres, of total `mass` (kg), split between the parts by volume.
///
/// ```text
/// m_c = m·V_c/(V_c + V_s),  m_s = m − m_c,   V_c = 2π r² h,  V_s = 4/3 π r³
/// I_yy = m_c·r²/2 + 2/5·m_s·r²
/// I_xx = m_c·(r²/4 + h²/3) + m_s·(2/5·r² + h² + 3/4·h·r)
/// ```
///
/// The hemisphere term moves each hemisphere's own moment (`83/320·(m_s/2)·r²` about its centroid, `3r/8`
/// from its flat face) out to the capsule's centre by the parallel-axis theorem; the sum simplifies to the
/// bracket above.
///
/// # Errors
/// `mass` and `radius` must be finite and > 0; `half_height` finite and ≥ 0 (0 is a sphere).
pub fn capsule(mass: f32, radius: f32, half_height: f32) -> Result<Vec3, MathError> {
    check_positive("mass", mass)?;
    check_positive("radius", radius)?;
    check_non_negative("half_height", half_height)?;
    let (r, h) = (radius, half_height);
    let cylinder_volume = 2.0 * PI * r * r * h;
    let sphere_volume = 4.0 / 3.0 * PI * r * r * r;
    let cylinder_mass = mass * cylinder_volume / (cylinder_volume + sphere_volume);
    let spheres_mass = mass - cylinder_mass;
    let axial = 0.5 * cylinder_mass * r * r + 0.4 * spheres_mass * r * r;
    let transverse = cylinder_mass * (r * r / 4.0 + h * h / 3.0)
        + spheres_mass * (0.4 * r * r + h * h + 0.75 * h * r);
    Ok(Vec3::new(transverse, axial, transverse))
}

/// Volume (m³) of a sphere of `radius` (m): `4/3·π·r³`.
#[must_use]
pub fn sphere_volume(radius: f32) -> f32 {
    4.0 / 3.0 * PI * radius * radius * radius
}

/// Volume (m³) of a cuboid of `half_extents` (m): `8·a·b·c`.
#[must_use]
pub fn cuboid_volume(half_extents: Vec3) -> f32 {
    8.0 * half_extents.x * half_extents.y * half_extents.z
}

/// Volume (m³) of a cylinder: `2π·r²·h`.
#[must_use]
pub fn cylinder_volume(radius: f32, half_height: f32) -> f32 {
    2.0 * PI * radius * radius * half_height
}

/// Volume (m³) of a cone: `π·r²·H/3` with `H = 2h`.
#[must_use]
pub fn cone_volume(radius: f32, half_height: f32) -> f32 {
    PI * radius * radius * 2.0 * half_height / 3.0
}

/// Volume (m³) of a capsule: cylinder plus sphere.
#[must_use]
pub fn capsule_volume(radius: f32, half_height: f32) -> f32 {
    cylinder_volume(radius, half_height) + sphere_volume(radius)
}

/// Moves an inertia tensor about the centre of mass to a parallel set of axes through a point at `offset`
/// (m) from the centre of mass (parallel-axis theorem, Steiner):
///
/// ```text
/// I_P = I_cm + m·(|d|²·E − d·dᵀ)
/// ```
///
/// `mass` in kg; tensors in kg·m². Works in the other direction with a negative mass only for bookkeeping,
/// so it accepts any finite values and does not check.
#[must_use]
pub fn parallel_axis(inertia_about_com: Mat3, mass: f32, offset: Vec3) -> Mat3 {
    let d = offset;
    let outer = Mat3::from_cols(d * d.x, d * d.y, d * d.z);
    inertia_about_com + (Mat3::from_diagonal(Vec3::splat(d.length_squared())) - outer) * mass
}

/// Rotates a body-frame inertia tensor into the frame `rotation` maps to: `R·I·Rᵀ`. A multiple of the
/// identity (a ball's, a cube's tensor, or its inverse) is returned as it is: `R·(s·1)·Rᵀ = s·R·Rᵀ = s·1` for
/// every rotation, which the product would only round (and 110 flops for every such body every step).
#[inline]
#[must_use]
pub fn rotate_inertia(rotation: Quat, inertia: Mat3) -> Mat3 {
    if inertia == Mat3::from_diagonal(Vec3::splat(inertia.x_axis.x)) {
        return inertia;
    }
    let r = Mat3::from_quat(rotation);
    r * inertia * r.transpose()
}

/// The world-space inverse inertia `R·diag(I⁻¹)·Rᵀ` (1/(kg·m²)) from the body's orientation and its principal
/// inverse moments (zero for an axis that cannot rotate, e.g. a fixed body).
///
/// This is what the solver multiplies angular impulses by: `Δω = I_w⁻¹·(r × J)`.
#[inline]
#[must_use]
pub fn world_inverse_inertia(rotation: Quat, local_inverse_principal: Vec3) -> Mat3 {
    rotate_inertia(rotation, Mat3::from_diagonal(local_inverse_principal))
}

/// Inverts principal moments, mapping a zero moment to a zero inverse (an axis that cannot rotate).
///
/// # Errors
/// [`MathError::NonFiniteVector`] for non-finite moments, [`MathError::Negative`] for a negative one
/// (field `inertia.x|y|z`).
pub fn inverse_principal(principal: Vec3) -> Result<Vec3, MathError> {
    check_finite_vec3("inertia", principal)?;
    check_non_negative("inertia.x", principal.x)?;
    check_non_negative("inertia.y", principal.y)?;
    check_non_negative("inertia.z", principal.z)?;
    let invert = |v: f32| if v > 0.0 { 1.0 / v } else { 0.0 };
    Ok(Vec3::new(
        invert(principal.x),
        invert(principal.y),
        invert(principal.z),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// Numerically integrates the inertia tensor of a solid given by an inside-test over its bounding box
    /// (midpoint rule on an n³ grid), about the centre of mass. Slow but independent of the formulas.
    fn numeric_inertia(
        inside: impl Fn(Vec3) -> bool,
        half_box: Vec3,
        mass: f32,
        n: usize,
    ) -> (Vec3, Vec3) {
        let cell = 2.0 * half_box / n as f32;
        let mut points = Vec::new();
        for i in 0..n {
            for j in 0..n {
                for k in 0..n {
                    let p = -half_box
                        + cell * Vec3::new(i as f32 + 0.5, j as f32 + 0.5, k as f32 + 0.5);
                    if inside(p) {
                        points.push(p);
                    }
                }
            }
        }
        let point_mass = mass / points.len() as f32;
        let com = points.iter().copied().sum::<Vec3>() / points.len() as f32;
        let mut moments = Vec3::ZERO;
        for p in &points {
            let d = *p - com;
            moments += point_mass
                * Vec3::new(
                    d.y * d.y + d.z * d.z,
                    d.x * d.x + d.z * d.z,
                    d.x * d.x + d.y * d.y,
                );
        }
        (moments, com)
    }

    fn assert_rel(actual: Vec3, expected: Vec3, rel: f32) {
        let err = ((actual - expected) / expected).abs().max_element();
        assert!(
            err < rel,
            "actual {actual}, expected {expected}, relative error {err}"
        );
    }

    #[test]
    fn closed_forms_match_numeric_integration() {
        let (m, r, h) = (3.0, 0.5, 0.8);
        let n = 120;
        let (numeric, _) = numeric_inertia(|p| p.length() <= r, Vec3::splat(r), m, n);
        assert_rel(sphere(m, r).unwrap(), numeric, 0.01);

        let half = Vec3::new(0.3, 0.7, 1.1);
        let (numeric, _) = numeric_inertia(|_| true, half, m, 60);
        assert_rel(cuboid(m, half).unwrap(), numeric, 0.01);

        let (numeric, _) =
            numeric_inertia(|p| p.x * p.x + p.z * p.z <= r * r, Vec3::new(r, h, r), m, n);
        assert_rel(cylinder(m, r, h).unwrap(), numeric, 0.01);

        // Cone: radius shrinks linearly from r at y = −h to 0 at y = +h.
        let (numeric, com) = numeric_inertia(
            |p| {
                let radius_here = r * (h - p.y) / (2.0 * h);
                p.x * p.x + p.z * p.z <= radius_here * radius_here
            },
            Vec3::new(r, h, r),
            m,
            n,
        );
        assert_rel(cone(m, r, h).unwrap(), numeric, 0.015);
        assert!(
            (com - cone_center_of_mass(h)).length() < 0.01,
            "cone com {com}"
        );

        let (numeric, _) = numeric_inertia(
            |p| {
                let axis_point = Vec3::new(0.0, p.y.clamp(-h, h), 0.0);
                (p - axis_point).length() <= r
            },
            Vec3::new(r, h + r, r),
            m,
            n,
        );
        assert_rel(capsule(m, r, h).unwrap(), numeric, 0.01);
    }

    #[test]
    fn capsule_of_zero_height_is_a_sphere() {
        assert_rel(
            capsule(2.0, 0.5, 0.0).unwrap(),
            sphere(2.0, 0.5).unwrap(),
            1e-6,
        );
    }

    #[test]
    fn bad_dimensions_are_errors() {
        assert!(matches!(
            sphere(0.0, 1.0),
            Err(MathError::NotPositive { field: "mass", .. })
        ));
        assert!(matches!(
            sphere(1.0, -1.0),
            Err(MathError::NotPositive {
                field: "radius",
                ..
            })
        ));
        assert!(matches!(
            cuboid(1.0, Vec3::new(1.0, 0.0, 1.0)),
            Err(MathError::NotPositive {
                field: "half_extents.y",
                ..
            })
        ));
        assert!(matches!(
            cylinder(1.0, 1.0, f32::NAN),
            Err(MathError::NonFinite {
                field: "half_height",
                ..
            })
        ));
        assert!(cone(f32::INFINITY, 1.0, 1.0).is_err());
        assert!(capsule(1.0, 1.0, -0.1).is_err());
        assert!(inverse_principal(Vec3::new(1.0, -1.0, 1.0)).is_err());
        assert_eq!(
            inverse_principal(Vec3::new(2.0, 0.0, 4.0)).unwrap(),
            Vec3::new(0.5, 0.0, 0.25)
        );
    }

    #[test]
    fn volumes() {
        assert!((sphere_volume(1.0) - 4.18879).abs() < 1e-4);
        assert!((cuboid_volume(Vec3::new(0.5, 1.0, 1.5)) - 6.0).abs() < 1e-6);
        assert!((cone_volume(1.0, 0.5) - PI / 3.0).abs() < 1e-6);
        assert!((capsule_volume(1.0, 0.0) - sphere_volume(1.0)).abs() < 1e-6);
    }

    /// `R·(s·1)·Rᵀ = s·1`: an isotropic tensor comes back unchanged, and within rounding of the product; any
    /// other tensor is the product `R·I·Rᵀ` itself.
    #[test]
    fn an_isotropic_tensor_is_returned_as_it_is() {
        let q = Quat::from_axis_angle(Vec3::new(0.3, -1.0, 0.7).normalize(), 2.2);
        let r = Mat3::from_quat(q);
        let ball = Mat3::from_diagonal(Vec3::splat(0.4));
        assert_eq!(rotate_inertia(q, ball), ball);
        let product = r * ball * r.transpose();
        assert!(product.abs_diff_eq(ball, 1e-6 * 0.4), "{product:?}");
        let plank = Mat3::from_diagonal(Vec3::new(0.1, 0.4, 0.5));
        assert_eq!(rotate_inertia(q, plank), r * plank * r.transpose());
    }

    #[test]
    fn parallel_axis_for_a_rod_end() {
        // A thin rod of length L about its end: m·L²/3 = m·L²/12 + m·(L/2)².
        let (m, l) = (2.0, 3.0);
        let about_com = Mat3::from_diagonal(Vec3::new(0.0, m * l * l / 12.0, m * l * l / 12.0));
        let about_end = parallel_axis(about_com, m, Vec3::new(l / 2.0, 0.0, 0.0));
        assert!((about_end.y_axis.y - m * l * l / 3.0).abs() < 1e-5);
        assert!((about_end.x_axis.x).abs() < 1e-6);
        // Off-diagonal products of inertia appear for a diagonal offset.
        let diagonal = parallel_axis(Mat3::ZERO, 1.0, Vec3::new(1.0, 1.0, 0.0));
        assert!((diagonal.x_axis.y + 1.0).abs() < 1e-6);
    }

    proptest! {
        #[test]
        fn world_inverse_inertia_inverts_world_inertia(
            x in 0.1f32..10.0, y in 0.1f32..10.0, z in 0.1f32..10.0,
            qx in -1.0f32..1.0, qy in -1.0f32..1.0, qz in -1.0f32..1.0, qw in 0.1f32..1.0,
        ) {
            let q = Quat::from_xyzw(qx, qy, qz, qw).normalize();
            let principal = Vec3::new(x, y, z);
            let world = rotate_inertia(q, Mat3::from_diagonal(principal));
            let inverse = world_inverse_inertia(q, inverse_principal(principal).unwrap());
            prop_assert!((world * inverse).abs_diff_eq(Mat3::IDENTITY, 1e-4));
            // Symmetric.
            prop_assert!(inverse.abs_diff_eq(inverse.transpose(), 1e-5));
        }
    }
}
