//! Micro-benchmarks of the math the solver leans on: quaternion products, orientation integration, transforms
//! of points and normals, Euler conversion. Run: `cargo bench -p rebound-math`.
//!
//! Each bench works on a batch of 1,024 inputs so the loop, not call overhead, is measured; criterion reports
//! the time per batch.

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rebound_math::{EulerAngles, EulerRot, Quat, RotationIntegrator, Transform, Vec3, quat};
use std::hint::black_box;

const N: usize = 1024;

/// Deterministic pseudo-random inputs (a tiny LCG: the benches need variety, not statistics).
fn inputs() -> (Vec<Quat>, Vec<Vec3>) {
    let mut state = 0x1234_5678_u32;
    let mut next = move || {
        state = state.wrapping_mul(1_664_525).wrapping_add(1_013_904_223);
        (state >> 8) as f32 / (1u32 << 24) as f32 * 2.0 - 1.0
    };
    let quats = (0..N)
        .map(|_| Quat::from_xyzw(next(), next(), next(), next() + 2.0).normalize())
        .collect();
    let vectors = (0..N)
        .map(|_| Vec3::new(next(), next(), next()) * 5.0)
        .collect();
    (quats, vectors)
}

fn quaternion_product(c: &mut Criterion) {
    let (q, _) = inputs();
    let mut group = c.benchmark_group("quat_product");
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function("glam_simd", |b| {
        b.iter(|| {
            q.windows(2)
                .map(|w| w[0] * w[1])
                .fold(Quat::IDENTITY, |acc, x| acc + x)
        });
    });
    group.bench_function("course_components", |b| {
        b.iter(|| {
            q.windows(2)
                .map(|w| quat::course_mul(w[0], w[1]))
                .fold(Quat::IDENTITY, |acc, x| acc + x)
        });
    });
    group.finish();
}

fn orientation_integration(c: &mut Criterion) {
    let (q, w) = inputs();
    let mut group = c.benchmark_group("integrate_rotation");
    group.throughput(Throughput::Elements(N as u64));
    for (name, method) in [
        ("first_order", RotationIntegrator::FirstOrder),
        ("exact", RotationIntegrator::Exact),
    ] {
        group.bench_function(name, |b| {
            let mut out = vec![Quat::IDENTITY; N];
            b.iter(|| {
                for ((o, q), w) in out.iter_mut().zip(&q).zip(&w) {
                    *o = quat::integrate_rotation(*q, *w, black_box(1.0 / 240.0), method);
                }
                black_box(&out);
            });
        });
    }
    group.finish();
}

fn transforms(c: &mut Criterion) {
    let (q, v) = inputs();
    let transforms: Vec<Transform> = q
        .iter()
        .zip(&v)
        .map(|(q, v)| {
            Transform::try_new(*v, *q, Vec3::new(2.0, 1.0, 0.5)).expect("valid bench input")
        })
        .collect();
    let mut group = c.benchmark_group("transform");
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function("point", |b| {
        let mut out = vec![Vec3::ZERO; N];
        b.iter(|| {
            for ((o, t), p) in out.iter_mut().zip(&transforms).zip(&v) {
                *o = t.transform_point(*p);
            }
            black_box(&out);
        });
    });
    group.bench_function("normal", |b| {
        let mut out = vec![Vec3::ZERO; N];
        b.iter(|| {
            for ((o, t), n) in out.iter_mut().zip(&transforms).zip(&v) {
                *o = t.transform_normal(*n);
            }
            black_box(&out);
        });
    });
    group.bench_function("point_via_model_matrix", |b| {
        let matrices: Vec<_> = transforms.iter().map(Transform::model_matrix).collect();
        let mut out = vec![Vec3::ZERO; N];
        b.iter(|| {
            for ((o, m), p) in out.iter_mut().zip(&matrices).zip(&v) {
                *o = m.transform_point3(*p);
            }
            black_box(&out);
        });
    });
    group.finish();
}

fn euler_conversion(c: &mut Criterion) {
    let (q, _) = inputs();
    let mut group = c.benchmark_group("euler");
    group.throughput(Throughput::Elements(N as u64));
    group.bench_function("from_quat_xyz", |b| {
        b.iter(|| {
            q.iter()
                .map(|q| EulerAngles::from_quat(EulerRot::XYZ, *q).map_or(0.0, |e| e.a + e.b + e.c))
                .sum::<f32>()
        });
    });
    group.bench_function("to_quat_xyz", |b| {
        b.iter(|| {
            q.iter()
                .map(|q| EulerAngles::new(EulerRot::XYZ, q.x, q.y, q.z).to_quat())
                .fold(Quat::IDENTITY, |acc, x| acc + x)
        });
    });
    group.finish();
}

criterion_group!(
    benches,
    quaternion_product,
    orientation_integration,
    transforms,
    euler_conversion
);
criterion_main!(benches);
