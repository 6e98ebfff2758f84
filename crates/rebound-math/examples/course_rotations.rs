//! The course's rotation examples, worked by `rebound-math` and printed.
//!
//! Run: `cargo run -p rebound-math --example course_rotations`

#![allow(clippy::print_stdout, reason = "an example prints its results")]

use core::f32::consts::FRAC_PI_2;
use rebound_math::euler::GIMBAL_LOCK_TOLERANCE;
use rebound_math::{
    EulerAngles, EulerRot, MathError, Quat, Transform, Vec2, Vec3, quat, rotation2d,
};

fn main() -> Result<(), MathError> {
    println!("Rebound — the course's rotations, computed\n");

    // Course item 14: 2D rotation matrix.
    let v = rotation2d::rotate_2d(Vec2::X, FRAC_PI_2);
    println!(
        "2D: R(90°)·(1, 0) = ({:.3}, {:.3})   (course: (0, 1))",
        v.x, v.y
    );

    // Course item 16: quaternion from unit axis and angle.
    let q = quat::from_unit_axis_angle(Vec3::Z, FRAC_PI_2)?;
    let [w, i, j, k] = quat::to_wijk(q);
    println!("quaternion, 90° about z: (w, i, j, k) = ({w:.4}, {i:.4}, {j:.4}, {k:.4})");
    match quat::from_unit_axis_angle(Vec3::new(0.0, 2.0, 0.0), 1.0) {
        Ok(_) => println!("a non-unit axis was accepted (unexpected)"),
        Err(e) => println!("non-unit axis rejected: {e}"),
    }

    // Course item 17: q·p applies p first.
    let p = quat::from_unit_axis_angle(Vec3::X, FRAC_PI_2)?;
    let qp = quat::course_mul(q, p);
    let image = qp * Vec3::Y;
    println!(
        "q·p with p = 90° about x, q = 90° about z: y → ({:.3}, {:.3}, {:.3})   (p: y → z, then q keeps z)",
        image.x, image.y, image.z
    );

    // Course item 18: the course's matrix is the transpose of glam's.
    let glam_m = quat::to_mat3(q);
    let course_m = quat::course_to_mat3(q);
    println!(
        "matrix of q: glam's column-vector R·x = {:.3?}; the course's matrix·x = {:.3?} (transpose: it rotates row vectors)",
        (glam_m * Vec3::X).to_array(),
        (course_m * Vec3::X).to_array()
    );

    // Course item 15: Euler angles, the zxy convention, gimbal lock.
    let zxy = EulerAngles::new(EulerRot::ZXYEx, FRAC_PI_2, FRAC_PI_2, 0.0);
    let image = zxy.to_quat() * Vec3::X;
    println!(
        "zxy (about z by 90°, then x by 90°, then y by 0): x → ({:.3}, {:.3}, {:.3})",
        image.x, image.y, image.z
    );
    let locked = EulerAngles::from_quat(
        EulerRot::XYZ,
        Quat::from_rotation_y(FRAC_PI_2) * Quat::from_rotation_z(0.3),
    )?;
    println!(
        "XYZ angles of a rotation with pitch 90°: a = {:.4}, b = {:.4}, c = {:.4}; gimbal locked: {}",
        locked.a,
        locked.b,
        locked.c,
        locked.is_gimbal_locked(GIMBAL_LOCK_TOLERANCE)
    );

    // Course item 19: model matrix, inverse, normals through the inverse-transpose.
    let t = Transform::try_new(
        Vec3::new(1.0, 2.0, 3.0),
        Quat::IDENTITY,
        Vec3::new(4.0, 1.0, 1.0),
    )?;
    let normal = Vec3::new(1.0, 1.0, 0.0).normalize();
    let tangent = Vec3::new(1.0, -1.0, 0.0);
    let world_tangent = t.transform_vector(tangent).normalize();
    println!(
        "under scale (4, 1, 1): normal·tangent with the normal matrix = {:.2e}, with the model matrix = {:.3}",
        t.transform_normal(normal).dot(world_tangent),
        t.transform_vector(normal).normalize().dot(world_tangent)
    );
    let round_trip = t.inverse_transform_point(t.transform_point(Vec3::new(0.5, -0.5, 2.0)));
    println!(
        "model → world → model: (0.5, -0.5, 2) → {:.4?}",
        round_trip.to_array()
    );
    Ok(())
}
