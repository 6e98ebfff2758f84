//! Tests of the path solver: the factorisation, the sweeps and the active set against dense solves and
//! against each other, bit for bit.

#![allow(
    clippy::needless_range_loop,
    reason = "dense reference solves read as the formulas with indices"
)]

use super::factor::*;
use super::link::*;
use super::row::*;
use super::sweep::*;
use crate::part::{AnglePart, AxisPart, RowTarget};
use rebound_dynamics::{Softness, SolverBody};
use rebound_math::{Mat3, Quat, Vec3};

/// Solves `s·x = b` with the block path's factorisation: `x = L⁻ᵀ·D⁻¹·L⁻¹·b`.
fn ldl_solve<const N: usize>(s: &Block, b: [Real; MAX_ROWS]) -> [Real; MAX_ROWS] {
    let (mut l, mut inv_pivots) = (*s, [0.0; MAX_ROWS]);
    ldl_factor::<N>(&mut l, &mut inv_pivots);
    let mut x = b;
    forward_substitute::<N>(&l, &mut x);
    for (x, inv) in x.iter_mut().zip(&inv_pivots) {
        *x *= inv;
    }
    back_substitute::<N>(&l, &mut x);
    x
}

/// `m·x`.
fn product(m: &Block, x: &[Real; MAX_ROWS]) -> [Real; MAX_ROWS] {
    m.map(|line| line.iter().zip(x).map(|(a, x)| a * x).sum())
}

#[test]
fn ldl_solves_a_symmetric_positive_system_and_zeroes_a_row_of_zeros() {
    let s = [
        [4.0, 1.0, 0.5, 0.0, 0.2, 0.0],
        [1.0, 3.0, 0.2, 0.1, 0.0, 0.0],
        [0.5, 0.2, 2.0, 0.3, 0.0, 0.0],
        [0.0, 0.1, 0.3, 1.5, 0.1, 0.0],
        [0.2, 0.0, 0.0, 0.1, 2.5, 0.0],
        [0.0; MAX_ROWS],
    ];
    let x_true = [1.0, -2.0, 0.5, 3.0, -1.0, 0.0];
    let x = ldl_solve::<MAX_ROWS>(&s, product(&s, &x_true));
    for (row, (x, t)) in x.iter().zip(&x_true).enumerate() {
        assert!((x - t).abs() <= 1e-9 * t.abs().max(1.0), "{row}: {x:?}");
    }
    assert!(x[5] == 0.0, "{x:?}");
}

#[test]
fn ldl_gives_a_redundant_row_zero_and_solves_the_rest() {
    // `S = J·Jᵀ` with row 2 of `J` the sum of rows 0 and 1: rank 3 of 4, row 2 redundant.
    let j = [
        [1.0, 0.5, 0.0, 0.2],
        [0.0, 1.0, 0.3, 0.0],
        [1.0, 1.5, 0.3, 0.2],
        [0.1, 0.0, 0.0, 2.0],
    ];
    let mut s = [[0.0; MAX_ROWS]; MAX_ROWS];
    for r in 0..4 {
        for c in 0..4 {
            s[r][c] = (0..4).map(|k| j[r][k] * j[c][k]).sum();
        }
    }
    // A consistent right-hand side: `S·x₀` for some `x₀`.
    let b = product(&s, &[0.3, -1.0, 0.7, 2.0, 0.0, 0.0]);
    let x = ldl_solve::<4>(&s, b);
    assert!(x.iter().all(|x| x.is_finite()), "{x:?}");
    assert!(x[2] == 0.0, "{x:?}");
    let residual = product(&s, &x);
    for (row, (r, b)) in residual.iter().zip(&b).enumerate() {
        assert!(
            (r - b).abs() <= 1e-9 * b.abs().max(1.0),
            "{row}: {residual:?} vs {b:?}"
        );
    }
}

#[test]
fn ldl_solves_an_identity_row_to_its_right_hand_side_of_zero() {
    // Row 1 not in the system, given an identity row: it solves to 0, the others as without it.
    let s = [
        [2.0, 0.0, 0.4, 0.0, 0.0, 0.0],
        [0.0, 1.0, 0.0, 0.0, 0.0, 0.0],
        [0.4, 0.0, 0.5, 0.0, 0.0, 0.0],
        [0.0; MAX_ROWS],
        [0.0; MAX_ROWS],
        [0.0; MAX_ROWS],
    ];
    let x_true = [0.25, 0.0, -4.0, 0.0, 0.0, 0.0];
    let x = ldl_solve::<3>(&s, product(&s, &x_true));
    for (row, (x, t)) in x.iter().zip(&x_true).enumerate() {
        assert!((x - t).abs() <= 1e-9 * t.abs().max(1.0), "{row}: {x:?}");
    }
    assert!(x[1] == 0.0, "{x:?}");
}

/// A path of `widths.len()` links between consecutive bodies with inverse masses `masses` (link `i`'s body
/// B is link `i + 1`'s body A), link `i` with `widths[i]` rows — a rope's one row, else a hinge's rows cut to the
/// width — every row soft, in the system and carrying an impulse.
fn soft_path(widths: &[usize], masses: &[InvMass]) -> Vec<Link> {
    let soft = RowTarget {
        bias: 0.05,
        softness: Softness {
            bias_rate: 10.0,
            mass_scale: 0.9,
            impulse_scale: 0.1,
        },
    };
    widths
        .iter()
        .enumerate()
        .map(|(i, &width)| {
            let (r_a, r_b) = (Vec3::new(0.5, 0.1, 0.0), Vec3::new(-0.4, 0.0, 0.2));
            let axis = Vec3::new(1.0, 0.1 * i as f32, 0.0).normalize();
            let mut rows = if width == 1 {
                let mut rows = JointRows::new(masses[i], masses[i + 1]);
                let row = AxisPart::row(axis, r_a, r_b, soft).clamped(f32::NEG_INFINITY, 0.0);
                rows.push(row, 0.0, TargetRule::UpperLimit);
                rows
            } else {
                hinge_rows(r_a, r_b, axis, masses[i], masses[i + 1])
            };
            rows.count = width;
            for row in &mut rows.rows {
                row.target = soft;
            }
            let lambda = core::array::from_fn(|k| -0.1 * (1 + i + k) as f32);
            let mut link = Link::new(rows, lambda);
            link.active[..width].fill(true);
            link.shared_with_next = (i + 1 < widths.len()).then_some((true, false));
            link
        })
        .collect()
}

/// The inverse masses of eight bodies for [`soft_path`]: unequal, with unequal inertias.
fn path_masses() -> [InvMass; 8] {
    core::array::from_fn(|k| InvMass {
        mass: 0.5 + 0.25 * k as f32,
        inertia: Mat3::from_diagonal(Vec3::new(2.0 + k as f32, 1.0, 0.5)),
    })
}

/// Eight bodies moving and turning, each differently.
fn path_bodies() -> [SolverBody; 8] {
    core::array::from_fn(|k| SolverBody {
        linear_velocity: Vec3::new(0.3 * k as f32, -1.0, 0.5),
        angular_velocity: Vec3::new(0.2, 0.1 * k as f32, -0.4),
        ..SolverBody::STATIC
    })
}

#[test]
fn a_resumed_sweep_gives_the_bits_of_a_full_one() {
    // Rope chains (the scalar sweep) and hinge decks (the block sweep): solve, take a row out of the
    // system at link 3 as an active-set round does, then solve again resuming from link 2 and from
    // scratch.
    let (masses, bodies) = (path_masses(), path_bodies());
    let load = |i: usize| Some((&bodies[i], &bodies[i + 1]));
    for width in [1, MAX_ROWS] {
        let mut resumed = soft_path(&[width; 7], &masses);
        let mut full = resumed.clone();
        let (mut out_resumed, mut out_full) = (Vec::new(), Vec::new());
        let mut resume = Resume::default();
        solve_path(&mut resumed, load, &mut out_resumed, &mut resume);
        solve_path(&mut full, load, &mut out_full, &mut Resume::default());
        for links in [&mut resumed, &mut full] {
            links[3].active[0] = false;
            links[3].lambda[0] = 0.0;
        }
        resume.changed(3);
        solve_path(&mut resumed, load, &mut out_resumed, &mut resume);
        solve_path(&mut full, load, &mut out_full, &mut Resume::default());
        let bits = |out: &[[Real; MAX_ROWS]]| {
            out.iter()
                .flat_map(|x| x.map(Real::to_bits))
                .collect::<Vec<_>>()
        };
        assert_eq!(bits(&out_resumed), bits(&out_full), "width {width}");
        assert!(out_full.iter().any(|x| x[0] != 0.0), "width {width}");
    }
}

#[test]
fn the_shape_scan_finds_the_first_stale_link_as_the_key_scan_does() {
    // Paths of ropes, of hinges, and mixed (a rope between hinges: blocks 5 wide), factorised at one
    // width; then links unkeyed, re-keyed at another width, their active set or link to the next changed.
    let (masses, bodies) = (path_masses(), path_bodies());
    let load = |i: usize| Some((&bodies[i], &bodies[i + 1]));
    let edits: [fn(&mut [Link]); 6] = [
        |_| {},
        |links| links[4].forget(),
        |links| links[2].active[0] = false,
        |links| links[5].shared_with_next = None,
        |links| {
            if let Some(key) = links[3].factored.as_mut() {
                key.width = 2;
            }
        },
        |links| {
            for link in links.iter_mut() {
                if let Some(key) = link.factored.as_mut() {
                    key.width = 3;
                }
            }
        },
    ];
    for widths in [[1; 7], [MAX_ROWS; 7], [5, 5, 1, 5, 5, 5, 5]] {
        for edit in edits {
            for start in [0, 1, 3, 6, 7] {
                let mut links = soft_path(&widths, &masses);
                let _ = solve_path(&mut links, load, &mut Vec::new(), &mut Resume::default());
                edit(&mut links);
                let shape = path_shape(&links, start);
                let width = shape.widest.max(1);
                assert_eq!(
                    shape.first_stale(),
                    first_stale(&links, width, start),
                    "widths {widths:?}, start {start}"
                );
                let left_out = links.iter().any(|link| link.left_out().contains(&true));
                assert_eq!(shape.left_out, left_out, "widths {widths:?}");
            }
        }
    }
}

#[test]
fn a_solve_reports_whether_its_solution_would_release_a_row() {
    // A rope chain pulled together (every rope would push: all released) and pulled apart (none).
    let masses: [InvMass; 6] = core::array::from_fn(|k| InvMass {
        mass: 1.0 + k as f32,
        inertia: Mat3::IDENTITY,
    });
    for (speed, released) in [(1.0, true), (-1.0, false)] {
        let bodies: [SolverBody; 6] = core::array::from_fn(|k| SolverBody {
            linear_velocity: Vec3::new(-speed * k as f32, 0.0, 0.0),
            ..SolverBody::STATIC
        });
        let load = |i: usize| Some((&bodies[i], &bodies[i + 1]));
        for widths in [[1; 5], [1, 1, 5, 1, 1]] {
            let mut links = soft_path(&widths, &masses);
            let mut out = Vec::new();
            let solved = solve_path(&mut links, load, &mut out, &mut Resume::default());
            let would = links
                .iter()
                .zip(&out)
                .any(|(link, x)| link.would_deactivate(x));
            assert_eq!(solved.released, would, "speed {speed}, widths {widths:?}");
            assert_eq!(would, released, "speed {speed}, widths {widths:?}");
        }
    }
}

#[test]
fn only_rows_bounded_at_zero_can_be_released() {
    let mass = InvMass {
        mass: 1.0,
        inertia: Mat3::IDENTITY,
    };
    let (r_a, r_b) = (Vec3::new(0.5, 0.0, 0.0), Vec3::new(-0.5, 0.0, 0.0));
    // A hinge's equality rows: no solution releases them, however it pushes.
    let mut link = Link::new(hinge_rows(r_a, r_b, Vec3::Z, mass, mass), [1.0; MAX_ROWS]);
    link.active = [true; MAX_ROWS];
    assert!(!link.rows.may_release);
    assert!(!link.would_deactivate(&[1e3; MAX_ROWS]));
    // A rope's row (upper bound 0) pushed after them: a solution that would make it push releases it.
    let rope =
        AxisPart::row(Vec3::X, r_a, r_b, RowTarget::speed(0.0)).clamped(f32::NEG_INFINITY, 0.0);
    let mut rows = JointRows::new(mass, mass);
    rows.push(rope, 0.0, TargetRule::UpperLimit);
    let mut link = Link::new(rows, one_row(-1.0));
    link.active[0] = true;
    assert!(link.rows.may_release);
    assert!(link.would_deactivate(&one_row(-2.0)));
    assert!(!link.would_deactivate(&one_row(0.5)));
    // Emptied for another joint: nothing left to release.
    link.reset(mass, mass);
    assert!(!link.rows.may_release);
}

/// A hinge's five rows between bodies with anchors `r_a`, `r_b` and hinge axis `axis`.
fn hinge_rows(r_a: Vec3, r_b: Vec3, axis: Vec3, mass_a: InvMass, mass_b: InvMass) -> JointRows {
    let mut rows = JointRows::new(mass_a, mass_b);
    for direction in [Vec3::X, Vec3::Y, Vec3::Z] {
        rows.push(
            AxisPart::row(direction, r_a, r_b, RowTarget::speed(0.0)),
            0.0,
            TargetRule::Equality,
        );
    }
    let axis = axis.normalize();
    let side = axis.any_orthonormal_vector();
    for perpendicular in [side, axis.cross(side)] {
        rows.push(
            AnglePart::row(perpendicular, RowTarget::speed(0.0)),
            0.0,
            TargetRule::Equality,
        );
    }
    rows
}

#[test]
fn the_block_sweep_solves_the_path_system_as_a_dense_solve_does() {
    // Four bodies, link i joins bodies i and i + 1 (its body B is the next link's body A). Link 1 is a
    // ball joint (3 rows, padded in the 5 × 5 sweep) with one row left out.
    let inertia = |k: f32| {
        let turn = Quat::from_rotation_y(0.3 * k) * Quat::from_rotation_x(0.2 + k);
        let m = Mat3::from_quat(turn);
        m * Mat3::from_diagonal(Vec3::new(2.0 + k, 1.0, 0.5 + 0.3 * k)) * m.transpose()
    };
    let masses: [InvMass; 4] = core::array::from_fn(|k| InvMass {
        mass: 0.5 + 0.25 * k as f32,
        inertia: inertia(k as f32),
    });
    let bodies: [SolverBody; 4] = core::array::from_fn(|k| SolverBody {
        linear_velocity: Vec3::new(0.3 * k as f32, -1.0, 0.5),
        angular_velocity: Vec3::new(0.2, 0.1 * k as f32, -0.4),
        ..SolverBody::STATIC
    });
    let r_a = Vec3::new(0.5, 0.1, 0.0);
    let r_b = Vec3::new(-0.4, 0.0, 0.2);
    let mut links = [0, 1, 2].map(|i| {
        let mut rows = hinge_rows(
            r_a,
            r_b,
            Vec3::new(0.1 * i as f32, 0.0, 1.0),
            masses[i],
            masses[i + 1],
        );
        if i == 1 {
            rows.count = 3;
        }
        let mut link = Link::new(rows, [0.0; MAX_ROWS]);
        link.active = [true; MAX_ROWS];
        link.active[rows.count..].fill(false);
        link.shared_with_next = (i < 2).then_some((true, false));
        link
    });
    links[1].active[1] = false;
    let mut out = Vec::new();
    solve_path(
        &mut links,
        |i| Some((&bodies[i], &bodies[i + 1])),
        &mut out,
        &mut Resume::default(),
    );

    // The dense system over the active rows: K = J·M⁻¹·Jᵀ (diagonal regularised), r = Ċ.
    let mut index = Vec::new();
    for (i, link) in links.iter().enumerate() {
        for k in 0..link.rows.count {
            if link.active[k] {
                index.push((i, k));
            }
        }
    }
    let n = index.len();
    // `J_p·M⁻¹·J_qᵀ` through one body, from scratch.
    let coupling = |p: &Side, m: &InvMass, q: &Side| {
        p.linear.dot(q.linear) * m.mass + p.angular.dot(m.inertia * q.angular)
    };
    let mut k_dense = vec![vec![0.0; n + 1]; n];
    for (p, &(i, a)) in index.iter().enumerate() {
        let row_p = &links[i].rows.rows[a];
        k_dense[p][n] = Real::from(row_p.velocity(&bodies[i], &bodies[i + 1]));
        for (q, &(j, b)) in index.iter().enumerate() {
            let row_q = &links[j].rows.rows[b];
            let value = if i == j {
                coupling(&row_p.a, &masses[i], &row_q.a)
                    + coupling(&row_p.b, &masses[i + 1], &row_q.b)
            } else if j == i + 1 {
                coupling(&row_p.b, &masses[j], &row_q.a)
            } else if i == j + 1 {
                coupling(&row_p.a, &masses[i], &row_q.b)
            } else {
                0.0
            };
            k_dense[p][q] = Real::from(value) * if p == q { 1.0 + REGULARIZATION } else { 1.0 };
        }
    }
    // Gauss–Jordan with partial pivoting.
    for c in 0..n {
        let pivot = (c..n)
            .max_by(|&x, &y| k_dense[x][c].abs().total_cmp(&k_dense[y][c].abs()))
            .unwrap_or(c);
        k_dense.swap(c, pivot);
        for r in 0..n {
            if r != c {
                let f = k_dense[r][c] / k_dense[c][c];
                for k in c..=n {
                    k_dense[r][k] -= f * k_dense[c][k];
                }
            }
        }
    }
    let largest = index
        .iter()
        .map(|&(i, k)| out[i][k].abs())
        .fold(0.0, Real::max);
    assert!(largest > 0.1, "{out:?}");
    for (p, &(i, k)) in index.iter().enumerate() {
        let dense = k_dense[p][n] / k_dense[p][p];
        assert!(
            (out[i][k] - dense).abs() <= 1e-7 * largest,
            "link {i} row {k}: {} vs {dense}",
            out[i][k]
        );
    }
    assert!(out[1][1] == 0.0, "a row left out solves to 0");
    assert!(out[1][3..].iter().all(|&x| x == 0.0), "padding solves to 0");
}
