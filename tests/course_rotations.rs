//! The course's rotation items (COURSE.md 14–19), checked end to end through the public `rebound-math` API
//! with the course's own numbers.

use core::f32::consts::FRAC_PI_2;
use rebound_math::{EulerAngles, EulerRot, Mat3, Quat, Transform, Vec2, Vec3, quat, rotation2d};

const EPS: f32 = 1e-6;

#[test]
fn item_14_rotating_x_by_90_degrees_gives_y() {
    let r = rotation2d::rotation_2d(FRAC_PI_2);
    // The course's matrix for 90°: [[0, −1], [1, 0]].
    assert!(r.x_axis.abs_diff_eq(Vec2::new(0.0, 1.0), EPS));
    assert!(r.y_axis.abs_diff_eq(Vec2::new(-1.0, 0.0), EPS));
    assert!((r * Vec2::X).abs_diff_eq(Vec2::Y, EPS));
}

#[test]
fn item_15_zxy_euler_angles_and_gimbal_lock() {
    // "zxy": about z, then x, then y (fixed axes). 90° about z then 90° about x sends x̂ → ŷ → ẑ.
    let zxy = EulerAngles::new(EulerRot::ZXYEx, FRAC_PI_2, FRAC_PI_2, 0.0);
    assert!((zxy.to_quat() * Vec3::X).abs_diff_eq(Vec3::Z, EPS));
    // Gimbal lock: with the middle (x) angle at 90°, z and y line up; two different angle triples with the
    // same a + c give the same rotation — one degree of freedom is gone.
    let one = EulerAngles::new(EulerRot::ZXY, 0.5, FRAC_PI_2, 0.2).to_quat();
    let two = EulerAngles::new(EulerRot::ZXY, 0.2, FRAC_PI_2, 0.5).to_quat();
    assert!(quat::angle_between(one, two) < 1e-5);
    let decoded = EulerAngles::from_quat(EulerRot::ZXY, one).expect("a unit quaternion decodes");
    assert!(decoded.is_gimbal_locked(rebound_math::euler::GIMBAL_LOCK_TOLERANCE));
}

#[test]
fn item_16_quaternion_from_unit_axis_and_angle() {
    let theta = 1.2f32;
    let axis = Vec3::new(1.0, 2.0, 2.0) / 3.0;
    let q = quat::from_unit_axis_angle(axis, theta).expect("unit axis");
    let [w, i, j, k] = quat::to_wijk(q);
    let s = (theta / 2.0).sin();
    assert!((w - (theta / 2.0).cos()).abs() < EPS);
    assert!(
        (i - axis.x * s).abs() < EPS
            && (j - axis.y * s).abs() < EPS
            && (k - axis.z * s).abs() < EPS
    );
    assert!(quat::from_unit_axis_angle(Vec3::new(1.0, 2.0, 2.0), theta).is_err());
}

#[test]
fn item_17_product_applies_p_first_then_q() {
    let p = Quat::from_rotation_x(FRAC_PI_2); // ŷ → ẑ
    let q = Quat::from_rotation_y(FRAC_PI_2); // ẑ → x̂
    let qp = quat::course_mul(q, p);
    assert!((qp * Vec3::Y).abs_diff_eq(Vec3::X, EPS));
    // The other order is a different rotation.
    assert!(!(quat::course_mul(p, q) * Vec3::Y).abs_diff_eq(Vec3::X, 1e-3));
}

#[test]
fn item_18_the_course_matrix_is_the_transpose_of_the_column_vector_matrix() {
    let q = Quat::from_rotation_z(FRAC_PI_2);
    let course = quat::course_to_mat3(q);
    assert!(course.abs_diff_eq(Mat3::from_quat(q).transpose(), EPS));
    // Copied blindly into column-vector code it rotates the wrong way.
    assert!((course * Vec3::X).abs_diff_eq(-Vec3::Y, EPS));
    assert!((quat::to_mat3(q) * Vec3::X).abs_diff_eq(Vec3::Y, EPS));
}

#[test]
fn item_19_model_inverse_and_normal_matrices() {
    let t = Transform::try_new(
        Vec3::new(5.0, 0.0, 0.0),
        Quat::from_rotation_z(FRAC_PI_2),
        Vec3::new(1.0, 3.0, 1.0),
    )
    .expect("valid transform");
    // Model → world with homogeneous coordinates: (0, 1, 0) scales to (0, 3, 0), rotates to (−3, 0, 0),
    // translates to (2, 0, 0).
    let world = t.model_matrix() * Vec3::Y.extend(1.0);
    assert!(world.truncate().abs_diff_eq(Vec3::new(2.0, 0.0, 0.0), 1e-5));
    // Back with the inverse.
    let model = t.inverse_model_matrix() * world;
    assert!(model.truncate().abs_diff_eq(Vec3::Y, 1e-5));
    // Normals with the inverse-transpose: the normal of the plane x + y = 0 stays perpendicular to it.
    let normal = t.transform_normal(Vec3::new(1.0, 1.0, 0.0));
    let tangent = t.transform_vector(Vec3::new(1.0, -1.0, 0.0));
    assert!(normal.dot(tangent).abs() < 1e-5);
}
