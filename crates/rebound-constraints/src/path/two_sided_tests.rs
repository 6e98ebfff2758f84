//! Tests of the sweep from both ends of a long path: against the sweep from its first link on random
//! systems, and the same bits for any number of threads.

use super::elimination::{Stale, Sweep, TWO_SIDED_MIN_LINKS, meet_of};
use super::link::Link;
use super::row::{InvMass, JointRows, MAX_ROWS, Real, TargetRule, one_row};
use super::sweep::{block_sweep, solve_scalar_path};
use crate::part::{AnglePart, AxisPart, RowTarget};
use proptest::prelude::*;
use rebound_dynamics::{Softness, SolverBody};
use rebound_math::{Mat3, Quat, Vec3};

/// One body of a random path: inverse mass (1/kg), the principal inverse inertias' scale and a turn of
/// the principal axes (rad), a velocity and an angular velocity component.
type BodyParams = (f32, f32, f32, f32, f32);

/// A path of links between consecutive bodies `params` (link `i` joins bodies `i` and `i + 1`, its body B
/// being the next link's body A), each of `width` rows — a rope's row, the three point rows of a ball
/// joint, or a hinge's five rows — every row in the system with `softness`, the bodies with the given
/// masses, inertias and velocities.
fn random_path(
    width: usize,
    params: &[BodyParams],
    softness: impl Fn(usize) -> Softness,
) -> (Vec<Link>, Vec<SolverBody>) {
    let masses: Vec<InvMass> = params
        .iter()
        .map(|&(mass, inertia, turn, _, _)| {
            let m =
                Mat3::from_quat(Quat::from_rotation_y(turn) * Quat::from_rotation_x(1.0 - turn));
            let d = Mat3::from_diagonal(Vec3::new(inertia, 0.5 * inertia + 0.2, 2.0 * inertia));
            InvMass {
                mass,
                inertia: m * d * m.transpose(),
            }
        })
        .collect();
    let bodies = params
        .iter()
        .map(|&(_, _, turn, v, w)| SolverBody {
            linear_velocity: Vec3::new(v, -1.0, 0.5 * turn),
            angular_velocity: Vec3::new(w, 0.3 * v, -0.4),
            ..SolverBody::STATIC
        })
        .collect();
    let len = params.len() - 1;
    let links = (0..len)
        .map(|i| {
            let target = RowTarget {
                bias: 0.05,
                softness: softness(i),
            };
            let turn = params[i].2;
            let (r_a, r_b) = (Vec3::new(0.5, 0.1 * turn, 0.0), Vec3::new(-0.4, 0.0, 0.2));
            let axis = Vec3::new(1.0, 0.3 * turn, 0.1).normalize();
            let mut rows = JointRows::new(masses[i], masses[i + 1]);
            if width == 1 {
                rows.push(
                    AxisPart::row(axis, r_a, r_b, target),
                    0.0,
                    TargetRule::Equality,
                );
            } else {
                for direction in [Vec3::X, Vec3::Y, Vec3::Z] {
                    rows.push(
                        AxisPart::row(direction, r_a, r_b, target),
                        0.0,
                        TargetRule::Equality,
                    );
                }
                for direction in [
                    axis.any_orthonormal_vector(),
                    axis.cross(axis.any_orthonormal_vector()),
                ]
                .into_iter()
                .take(width.saturating_sub(3))
                {
                    rows.push(AnglePart::row(direction, target), 0.0, TargetRule::Equality);
                }
            }
            let lambda = core::array::from_fn(|k| -0.1 * (1 + i % 7 + k) as f32);
            let mut link = Link::new(rows, lambda);
            link.active[..rows.count].fill(true);
            link.shared_with_next = (i + 1 < len).then_some((true, false));
            link
        })
        .collect();
    (links, bodies)
}

/// Solves the path with its sides meeting at `meet` (`None`: from the first link to the last), refactorising
/// every link; returns each link's solution.
fn sweep_with(
    links: &mut [Link],
    bodies: &[SolverBody],
    uniform: Option<Softness>,
    meet: Option<usize>,
) -> Vec<[Real; MAX_ROWS]> {
    let load = |i: usize| Some((&bodies[i], &bodies[i + 1]));
    let mut out = vec![[0.0; MAX_ROWS]; links.len()];
    let sweep = Sweep {
        load: &load,
        uniform,
        stale: Stale(Some((0, links.len()))),
        layout: 0,
    };
    let width = links.iter().map(|l| l.rows.count).max().unwrap_or(0);
    match width {
        1 => {
            solve_scalar_path(links, &mut out, &sweep, (0, meet));
        }
        3 => {
            block_sweep::<3, _>(links, &mut out, &sweep, (0, meet));
        }
        _ => {
            block_sweep::<MAX_ROWS, _>(links, &mut out, &sweep, (0, meet));
        }
    }
    out
}

/// `‖K·x − r‖∞` and `‖K‖∞·‖x‖∞ + ‖r‖∞` of a path of rigid rows, `K` from the blocks of a sweep from the
/// first link (`B`, and `C` with the next link) and `r` the rows' residuals.
fn residual(links: &[Link], bodies: &[SolverBody], x: &[[Real; MAX_ROWS]]) -> (Real, Real) {
    let (mut worst, mut k_norm, mut x_norm, mut r_norm): (Real, Real, Real, Real) =
        (0.0, 0.0, 0.0, 0.0);
    for (i, link) in links.iter().enumerate() {
        let r = if link.rows.count == 1 {
            one_row(link.row_residual(&link.rows.rows[0], &bodies[i], &bodies[i + 1]))
        } else {
            link.residual(&bodies[i], &bodies[i + 1])
        };
        for row in 0..link.rows.count {
            let (b, c) = if link.rows.count == 1 {
                (one_row(link.scalar.b), one_row(link.scalar.c))
            } else {
                (link.b_block[row], link.c_block[row])
            };
            let mut kx = 0.0;
            let mut norm = 0.0;
            for k in 0..MAX_ROWS {
                kx += b[k] * x[i][k];
                norm += b[k].abs() + c[k].abs();
                if let Some(next) = x.get(i + 1) {
                    kx += c[k] * next[k];
                }
                if let Some(prev) = i.checked_sub(1) {
                    let p = &links[prev];
                    let c_prev = if p.rows.count == 1 {
                        if k == 0 { p.scalar.c } else { 0.0 }
                    } else {
                        p.c_block[k][row]
                    };
                    kx += c_prev * x[prev][k];
                    norm += c_prev.abs();
                }
            }
            worst = worst.max((kx - r[row]).abs());
            k_norm = k_norm.max(norm);
            x_norm = x_norm.max(x[i][row].abs());
            r_norm = r_norm.max(r[row].abs());
        }
    }
    (worst, k_norm * x_norm + r_norm)
}

/// The largest difference of two solutions and the largest entry of the first.
fn difference(a: &[[Real; MAX_ROWS]], b: &[[Real; MAX_ROWS]]) -> (Real, Real) {
    a.iter()
        .zip(b)
        .flat_map(|(a, b)| a.iter().zip(b))
        .fold((0.0, 0.0), |(d, m), (a, b)| {
            (Real::max(d, (a - b).abs()), Real::max(m, a.abs()))
        })
}

fn body_params() -> impl Strategy<Value = BodyParams> {
    (
        0.2f32..3.0,
        0.2f32..4.0,
        -1.0f32..1.0,
        -2.0f32..2.0,
        -2.0f32..2.0,
    )
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    /// The sweep from both ends solves a path's system `K·x = r` (`K` symmetric positive definite,
    /// block-tridiagonal: ropes 1 × 1, ball joints 3 × 3, hinges 5 × 5) as the sweep from the first link
    /// does: both residuals within 10⁻¹² of `‖K‖·‖x‖ + ‖r‖` (f64, some 60 links), and the solutions within
    /// 10⁻⁶ of the largest entry (the systems' condition numbers stay below 10⁵).
    #[test]
    fn the_sweep_from_both_ends_solves_the_path_as_the_sweep_from_one_end(
        width in prop::sample::select(vec![1usize, 3, 5]),
        params in prop::collection::vec(body_params(), TWO_SIDED_MIN_LINKS + 1..70),
        meet_at in 0.0f64..1.0,
    ) {
        let rigid = Some(Softness::RIGID);
        let (mut one_sided, bodies) = random_path(width, &params, |_| Softness::RIGID);
        let mut two_sided = one_sided.clone();
        let len = one_sided.len();
        let x_one = sweep_with(&mut one_sided, &bodies, rigid, None);
        // Any meeting link: the middle one the solver takes, or another.
        let meet = ((meet_at * len as f64) as usize).min(len - 1);
        for meet in [meet_of(len), Some(meet)] {
            let x_two = sweep_with(&mut two_sided, &bodies, rigid, meet);
            let (worst_one, scale) = residual(&one_sided, &bodies, &x_one);
            let (worst_two, _) = residual(&one_sided, &bodies, &x_two);
            prop_assert!(worst_one <= 1e-12 * scale, "one-sided residual {worst_one} of {scale}");
            prop_assert!(worst_two <= 1e-12 * scale, "two-sided residual {worst_two} of {scale}, meet {meet:?}");
            let (d, largest) = difference(&x_one, &x_two);
            prop_assert!(largest > 1e-3 && d <= 1e-6 * largest, "{d} of {largest}, meet {meet:?}");
        }
    }

    /// With a softness that differs along the path (the right-hand side holds `K·λ`), the sweep from both
    /// ends gives the solution of the sweep from one end within 10⁻⁶ of its largest entry.
    #[test]
    fn the_sweep_from_both_ends_takes_the_soft_rows_impulses_as_the_sweep_from_one_end(
        width in prop::sample::select(vec![1usize, 5]),
        params in prop::collection::vec(body_params(), TWO_SIDED_MIN_LINKS + 1..50),
    ) {
        let softness = |i: usize| Softness {
            bias_rate: 10.0,
            mass_scale: if i.is_multiple_of(3) { 1.0 } else { 0.9 },
            impulse_scale: if i.is_multiple_of(3) { 0.0 } else { 0.1 },
        };
        let (mut one_sided, bodies) = random_path(width, &params, softness);
        let mut two_sided = one_sided.clone();
        let len = one_sided.len();
        let x_one = sweep_with(&mut one_sided, &bodies, None, None);
        let x_two = sweep_with(&mut two_sided, &bodies, None, meet_of(len));
        let (d, largest) = difference(&x_one, &x_two);
        prop_assert!(largest > 1e-3 && d <= 1e-6 * largest, "{d} of {largest}");
    }
}

#[test]
fn a_second_solve_of_a_long_path_keeps_every_factorisation() {
    // Ropes (the scalar sweep) and hinges (the block sweep), 40 links: solved once, then nothing is stale.
    use super::sweep::{Resume, path_shape, solve_path};
    let params: Vec<BodyParams> = (0..=40)
        .map(|k| (1.0, 1.0, 0.02 * k as f32, 0.1, -0.1))
        .collect();
    for width in [1, 5] {
        let (mut links, bodies) = random_path(width, &params, |_| Softness::RIGID);
        let load = |i: usize| Some((&bodies[i], &bodies[i + 1]));
        assert_eq!(
            path_shape(&links, 0).stale(&links),
            Stale(Some((0, links.len())))
        );
        solve_path(&mut links, load, &mut Vec::new(), &mut Resume::default());
        assert_eq!(
            path_shape(&links, 0).stale(&links),
            Stale(None),
            "width {width}"
        );
    }
}

#[test]
fn a_long_path_solved_again_after_a_change_gives_the_bits_of_a_fresh_solve() {
    // A row taken out of the system before, at and after the meeting link (20 of 40), as an active-set
    // round does: the solve that keeps what it may (the factorisations, the forward side's sweep before
    // the change) gives the bits of one that factorises everything again.
    use super::sweep::{Resume, solve_path};
    let params: Vec<BodyParams> = (0..=40)
        .map(|k| (0.5 + 0.01 * k as f32, 1.0, 0.02 * k as f32, 0.1, -0.1))
        .collect();
    for width in [1, 5] {
        for changed in [3, 19, 20, 21, 33, 39] {
            let (mut kept, bodies) = random_path(width, &params, |_| Softness::RIGID);
            let load = |i: usize| Some((&bodies[i], &bodies[i + 1]));
            let (mut out_kept, mut out_fresh) = (Vec::new(), Vec::new());
            let mut resume = Resume::default();
            solve_path(&mut kept, load, &mut out_kept, &mut resume);
            kept[changed].active[0] = false;
            kept[changed].lambda[0] = 0.0;
            let mut fresh = kept.clone();
            for link in &mut fresh {
                link.forget();
            }
            resume.changed(changed);
            solve_path(&mut kept, load, &mut out_kept, &mut resume);
            solve_path(&mut fresh, load, &mut out_fresh, &mut Resume::default());
            let bits = |out: &[[Real; MAX_ROWS]]| {
                out.iter()
                    .flat_map(|x| x.map(Real::to_bits))
                    .collect::<Vec<_>>()
            };
            assert_eq!(
                bits(&out_kept),
                bits(&out_fresh),
                "width {width}, link {changed}"
            );
            assert!(
                out_fresh[changed][0] == 0.0,
                "width {width}: a row left out solves to 0"
            );
        }
    }
}

#[test]
fn a_path_shorter_than_the_minimum_is_swept_from_one_end_and_a_longer_one_from_both() {
    assert_eq!(meet_of(TWO_SIDED_MIN_LINKS - 1), None);
    assert_eq!(meet_of(TWO_SIDED_MIN_LINKS), Some(TWO_SIDED_MIN_LINKS / 2));
    assert_eq!(meet_of(500), Some(250));
}

/// A solve of a long path, twice (the second keeping the factorisation), and the bits of both solutions.
#[cfg(feature = "parallel")]
fn solve_bits(width: usize, len: usize) -> Vec<u64> {
    use super::sweep::{Resume, solve_path};
    let params: Vec<BodyParams> = (0..=len)
        .map(|k| {
            let t = k as f32 / len as f32;
            (0.5 + t, 1.0 + 0.5 * t, t - 0.5, 2.0 * t - 1.0, 0.5 - t)
        })
        .collect();
    let soft = |i: usize| Softness {
        bias_rate: 10.0,
        mass_scale: if i == len / 3 { 1.0 } else { 0.9 },
        impulse_scale: if i == len / 3 { 0.0 } else { 0.1 },
    };
    let (mut links, bodies) = random_path(width, &params, soft);
    let load = |i: usize| Some((&bodies[i], &bodies[i + 1]));
    let mut bits = Vec::new();
    let mut out = Vec::new();
    for _ in 0..2 {
        solve_path(&mut links, load, &mut out, &mut Resume::default());
        bits.extend(out.iter().flat_map(|x| x.map(Real::to_bits)));
    }
    bits
}

/// A 500-rope chain's and a 101-hinge deck's solve give the same bits on 1, 2 and 3 threads (and the serial
/// build computes what one thread does: the same code without the pool).
#[cfg(feature = "parallel")]
#[test]
fn a_long_paths_solve_gives_the_same_bits_on_any_number_of_threads() {
    use rebound_math::par::rayon::ThreadPoolBuilder;
    for (width, len) in [(1, 500), (5, 101), (3, 64)] {
        let on = |threads: usize| {
            ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .map(|pool| pool.install(|| solve_bits(width, len)))
        };
        let (Ok(one), Ok(two), Ok(three)) = (on(1), on(2), on(3)) else {
            panic!("no thread pool");
        };
        assert!(
            one.iter().any(|&b| b != 0),
            "width {width}: the solve moved nothing"
        );
        assert_eq!(one, two, "width {width}: 1 and 2 threads");
        assert_eq!(one, three, "width {width}: 1 and 3 threads");
    }
}
