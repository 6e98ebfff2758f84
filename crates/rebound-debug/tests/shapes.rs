//! Every shape kind's drawing against closed forms: the 12 edges of a box at their world points, round
//! shapes' points at their radius, closed surfaces whose volume is the tessellated solid's exact volume and
//! whose triangles face outwards, and bounding boxes that hold every drawn point and touch it.

use proptest::prelude::*;
use rebound::{ColliderShape, Pose, Quat, Vec3};
use rebound_debug::{Color, DebugDraw, Line, MAX_CIRCLE_SEGMENTS, shape_aabb};

/// Tolerance on drawn coordinates (m): a few ulps of the unit-sized numbers involved.
const EPS: f32 = 2e-6;

fn pose() -> Pose {
    Pose::new(
        Vec3::new(1.0, 2.0, -3.0),
        Quat::from_axis_angle(Vec3::new(1.0, 1.0, 0.5).normalize(), 0.7),
    )
}

fn outline(shape: &ColliderShape, pose: Pose, segments: u32) -> DebugDraw {
    let mut draw = DebugDraw::new();
    draw.shape(shape, pose, Color::WHITE, true, false, segments);
    draw
}

fn solid(shape: &ColliderShape, pose: Pose, segments: u32) -> DebugDraw {
    let mut draw = DebugDraw::new();
    draw.shape(shape, pose, Color::WHITE, false, true, segments);
    draw
}

fn endpoints(draw: &DebugDraw) -> impl Iterator<Item = Vec3> + '_ {
    draw.lines.iter().flat_map(|l| [l.a, l.b])
}

/// The volume enclosed by the triangles (divergence theorem: Σ a·(b × c) / 6); the exact volume of the
/// polyhedron if the surface is closed and every triangle is counter-clockwise seen from outside.
fn volume(draw: &DebugDraw) -> f64 {
    draw.triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.vertices.map(Vec3::as_dvec3);
            a.dot(b.cross(c)) / 6.0
        })
        .sum()
}

/// Every triangle faces away from `inside`.
fn faces_out(draw: &DebugDraw, inside: Vec3) -> bool {
    draw.triangles.iter().all(|t| {
        let centroid = (t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3.0;
        t.normal().dot(centroid - inside) > 0.0
    })
}

#[test]
fn a_unit_box_is_its_12_edges_at_the_expected_world_points() {
    let shape = ColliderShape::Cuboid {
        half_extents: Vec3::splat(0.5),
    };
    let pose = pose();
    let draw = outline(&shape, pose, 24);
    let corner = |i: usize| {
        let s = |bit: usize| if i & bit == 0 { -0.5 } else { 0.5 };
        pose.position + pose.rotation * Vec3::new(s(1), s(2), s(4))
    };
    // The edges of a box join the corners that differ in one coordinate: 12 pairs.
    let mut expected: Vec<(Vec3, Vec3)> = Vec::new();
    for i in 0..8usize {
        for bit in [1, 2, 4] {
            if i & bit == 0 {
                expected.push((corner(i), corner(i | bit)));
            }
        }
    }
    assert_eq!(expected.len(), 12);
    assert_eq!(draw.lines.len(), 12);
    let same = |l: &Line, (a, b): (Vec3, Vec3)| {
        (l.a.distance(a) < EPS && l.b.distance(b) < EPS)
            || (l.a.distance(b) < EPS && l.b.distance(a) < EPS)
    };
    for edge in &expected {
        let matches = draw.lines.iter().filter(|l| same(l, *edge)).count();
        assert_eq!(matches, 1, "edge {edge:?} drawn {matches} times");
    }
    assert!(draw.triangles.is_empty());
}

#[test]
fn a_box_surface_is_12_outward_triangles_enclosing_its_volume() {
    let half = Vec3::new(0.5, 0.25, 1.0);
    let draw = solid(&ColliderShape::Cuboid { half_extents: half }, pose(), 24);
    assert_eq!(draw.triangles.len(), 12);
    assert!(faces_out(&draw, pose().position));
    let exact = 8.0 * f64::from(half.x * half.y * half.z);
    assert!(
        (volume(&draw) - exact).abs() < 1e-5,
        "{} vs {exact}",
        volume(&draw)
    );
}

#[test]
fn a_ball_outline_is_three_great_circles_at_its_radius() {
    let r = 0.75;
    let pose = pose();
    let draw = outline(&ColliderShape::Ball { radius: r }, pose, 32);
    assert_eq!(draw.lines.len(), 3 * 32);
    for p in endpoints(&draw) {
        assert!(
            (p.distance(pose.position) - r).abs() < EPS,
            "{p} at {}",
            p.distance(pose.position)
        );
    }
    // Each circle lies in a plane through the centre spanned by two of the body's axes.
    for (k, normal) in [Vec3::Z, Vec3::X, Vec3::Y].into_iter().enumerate() {
        let n = pose.rotation * normal;
        for l in &draw.lines[k * 32..(k + 1) * 32] {
            assert!((l.a - pose.position).dot(n).abs() < EPS);
        }
    }
}

#[test]
fn a_ball_surface_has_its_vertices_at_its_radius_and_faces_out() {
    let r = 0.5;
    let draw = solid(&ColliderShape::Ball { radius: r }, pose(), 24);
    for t in &draw.triangles {
        for v in t.vertices {
            assert!((v.distance(pose().position) - r).abs() < EPS);
        }
    }
    assert!(faces_out(&draw, pose().position));
    // An inscribed polyhedron: less than the ball's volume, within the chord error of 24 segments.
    let ball = 4.0 / 3.0 * std::f64::consts::PI * f64::from(r).powi(3);
    let v = volume(&draw);
    assert!(v < ball && v > 0.95 * ball, "{v} vs {ball}");
}

#[test]
fn a_cylinder_is_two_rims_at_its_radius_and_a_prism_of_its_exact_volume() {
    let (r, h, n) = (0.4f32, 0.3f32, 16u32);
    let pose = pose();
    let axis = pose.rotation * Vec3::Y;
    let draw = outline(
        &ColliderShape::Cylinder {
            radius: r,
            half_height: h,
        },
        pose,
        n,
    );
    assert_eq!(draw.lines.len(), 2 * n as usize + 4);
    for p in endpoints(&draw) {
        let d = p - pose.position;
        let along = d.dot(axis);
        assert!((along.abs() - h).abs() < EPS, "height {along}");
        assert!(((d - axis * along).length() - r).abs() < EPS);
    }
    let draw = solid(
        &ColliderShape::Cylinder {
            radius: r,
            half_height: h,
        },
        pose,
        n,
    );
    assert!(faces_out(&draw, pose.position));
    // The inscribed n-gon prism: n triangles of area ½r²·sin(2π/n), height 2h.
    let prism = f64::from(n)
        * 0.5
        * f64::from(r * r)
        * (std::f64::consts::TAU / f64::from(n)).sin()
        * 2.0
        * f64::from(h);
    assert!(
        (volume(&draw) - prism).abs() < 1e-6,
        "{} vs {prism}",
        volume(&draw)
    );
}

#[test]
fn a_cone_is_a_base_rim_and_lines_to_its_apex_and_a_pyramid_of_its_exact_volume() {
    let (r, h, n) = (0.4f32, 0.5f32, 12u32);
    let pose = pose();
    let axis = pose.rotation * Vec3::Y;
    let apex = pose.position + axis * h;
    let draw = outline(
        &ColliderShape::Cone {
            radius: r,
            half_height: h,
        },
        pose,
        n,
    );
    assert_eq!(draw.lines.len(), n as usize + 4);
    for l in &draw.lines[..n as usize] {
        for p in [l.a, l.b] {
            let d = p - pose.position;
            assert!((d.dot(axis) + h).abs() < EPS);
            assert!(((d - axis * d.dot(axis)).length() - r).abs() < EPS);
        }
    }
    for l in &draw.lines[n as usize..] {
        assert!(l.b.distance(apex) < EPS);
    }
    let draw = solid(
        &ColliderShape::Cone {
            radius: r,
            half_height: h,
        },
        pose,
        n,
    );
    assert!(faces_out(&draw, pose.position));
    let pyramid = f64::from(n)
        * 0.5
        * f64::from(r * r)
        * (std::f64::consts::TAU / f64::from(n)).sin()
        * 2.0
        * f64::from(h)
        / 3.0;
    assert!(
        (volume(&draw) - pyramid).abs() < 1e-6,
        "{} vs {pyramid}",
        volume(&draw)
    );
}

#[test]
fn a_capsule_outline_lies_at_its_radius_from_its_segment() {
    let (r, h) = (0.3f32, 0.6f32);
    let pose = pose();
    let axis = pose.rotation * Vec3::Y;
    let draw = outline(
        &ColliderShape::Capsule {
            radius: r,
            half_height: h,
        },
        pose,
        24,
    );
    // Two rims (24 each), two half circles per cap in two planes (12 each), four side lines.
    assert_eq!(draw.lines.len(), 2 * 24 + 4 * 12 + 4);
    let to_segment = |p: Vec3| {
        let along = (p - pose.position).dot(axis).clamp(-h, h);
        p.distance(pose.position + axis * along)
    };
    for p in endpoints(&draw) {
        assert!((to_segment(p) - r).abs() < EPS, "{p}: {}", to_segment(p));
    }
    let draw = solid(
        &ColliderShape::Capsule {
            radius: r,
            half_height: h,
        },
        pose,
        24,
    );
    assert!(faces_out(&draw, pose.position));
    for t in &draw.triangles {
        for v in t.vertices {
            assert!((to_segment(v) - r).abs() < EPS);
        }
    }
    let capsule =
        std::f64::consts::PI * f64::from(r * r) * (2.0 * f64::from(h) + 4.0 / 3.0 * f64::from(r));
    assert!(volume(&draw) < capsule && volume(&draw) > 0.95 * capsule);
}

#[test]
fn a_cube_hull_draws_its_12_edges_and_no_face_diagonal() {
    let corners: Vec<Vec3> = (0..8)
        .map(|i| Vec3::new((i & 1) as f32, (i >> 1 & 1) as f32, (i >> 2) as f32))
        .collect();
    let shape = ColliderShape::ConvexHull { points: corners };
    let draw = outline(&shape, Pose::IDENTITY, 24);
    assert_eq!(draw.lines.len(), 12);
    for l in &draw.lines {
        assert!(
            (l.a.distance(l.b) - 1.0).abs() < EPS,
            "{l:?} is not an edge"
        );
    }
    let draw = solid(&shape, pose(), 24);
    assert_eq!(draw.triangles.len(), 12);
    assert!(faces_out(&draw, pose().transform_point(Vec3::splat(0.5))));
    assert!((volume(&draw) - 1.0).abs() < 1e-5);
}

#[test]
fn a_mesh_draws_each_edge_once_and_its_triangles_as_wound() {
    let shape = ColliderShape::TriMesh {
        vertices: vec![Vec3::ZERO, Vec3::X, Vec3::Z, Vec3::new(1.0, 0.0, 1.0)],
        indices: vec![[0, 2, 1], [1, 2, 3]],
    };
    let draw = outline(&shape, Pose::IDENTITY, 24);
    assert_eq!(draw.lines.len(), 5, "two triangles sharing an edge");
    let draw = solid(&shape, Pose::IDENTITY, 24);
    assert_eq!(draw.triangles.len(), 2);
    for t in &draw.triangles {
        assert!(
            (t.normal() - Vec3::Y).length() < EPS,
            "wound counter-clockwise from above"
        );
    }
}

#[test]
fn a_height_field_is_its_grid_at_the_documented_sample_points() {
    let (rows, cols) = (3usize, 4usize);
    let heights: Vec<f32> = (0..rows * cols).map(|i| i as f32 * 0.1).collect();
    let scale = Vec3::new(6.0, 2.0, 4.0);
    let shape = ColliderShape::HeightField {
        rows,
        cols,
        heights: heights.clone(),
        scale,
    };
    let draw = outline(&shape, Pose::IDENTITY, 24);
    assert_eq!(draw.lines.len(), rows * (cols - 1) + cols * (rows - 1));
    let sample = |row: usize, col: usize| {
        Vec3::new(
            (col as f32 / (cols - 1) as f32 - 0.5) * scale.x,
            heights[row * cols + col] * scale.y,
            (row as f32 / (rows - 1) as f32 - 0.5) * scale.z,
        )
    };
    for p in endpoints(&draw) {
        let found = (0..rows).any(|r| (0..cols).any(|c| sample(r, c).distance(p) < EPS));
        assert!(found, "{p} is not a sample point");
    }
    let draw = solid(&shape, Pose::IDENTITY, 24);
    assert_eq!(draw.triangles.len(), 2 * (rows - 1) * (cols - 1));
    assert!(
        draw.triangles.iter().all(|t| t.normal().y > 0.0),
        "facing up"
    );
}

#[test]
fn a_compound_is_its_parts_at_their_poses() {
    let part_pose = Pose::new(Vec3::new(1.0, 0.0, 0.0), Quat::from_rotation_z(0.4));
    let shape = ColliderShape::Compound {
        parts: vec![
            (Pose::IDENTITY, ColliderShape::Ball { radius: 0.3 }),
            (
                part_pose,
                ColliderShape::Cuboid {
                    half_extents: Vec3::splat(0.2),
                },
            ),
        ],
    };
    let pose = pose();
    let draw = outline(&shape, pose, 16);
    let ball = outline(&ColliderShape::Ball { radius: 0.3 }, pose, 16);
    let cube = outline(
        &ColliderShape::Cuboid {
            half_extents: Vec3::splat(0.2),
        },
        pose.mul_pose(&part_pose),
        16,
    );
    assert_eq!(draw.lines.len(), ball.lines.len() + cube.lines.len());
    assert_eq!(draw.lines[..ball.lines.len()], ball.lines[..]);
    assert_eq!(draw.lines[ball.lines.len()..], cube.lines[..]);
}

#[test]
fn segment_counts_are_clamped() {
    let ball = ColliderShape::Ball { radius: 1.0 };
    assert_eq!(outline(&ball, Pose::IDENTITY, 0).lines.len(), 3 * 3);
    assert_eq!(
        outline(&ball, Pose::IDENTITY, u32::MAX).lines.len(),
        3 * MAX_CIRCLE_SEGMENTS as usize
    );
}

/// Every shape kind, for the bounding-box checks.
fn shapes() -> Vec<ColliderShape> {
    vec![
        ColliderShape::Ball { radius: 0.5 },
        ColliderShape::Cuboid {
            half_extents: Vec3::new(0.5, 0.2, 0.8),
        },
        ColliderShape::Capsule {
            radius: 0.3,
            half_height: 0.5,
        },
        ColliderShape::Cylinder {
            radius: 0.4,
            half_height: 0.3,
        },
        ColliderShape::Cone {
            radius: 0.4,
            half_height: 0.6,
        },
        ColliderShape::ConvexHull {
            points: vec![Vec3::ZERO, Vec3::X, Vec3::Y, Vec3::Z, Vec3::splat(0.6)],
        },
        ColliderShape::TriMesh {
            vertices: vec![Vec3::ZERO, Vec3::X, Vec3::Z],
            indices: vec![[0, 2, 1]],
        },
        ColliderShape::HeightField {
            rows: 2,
            cols: 3,
            heights: vec![0.0, 0.5, 0.1, 0.2, 0.3, 0.0],
            scale: Vec3::ONE,
        },
        ColliderShape::Compound {
            parts: vec![
                (Pose::IDENTITY, ColliderShape::Ball { radius: 0.2 }),
                (
                    Pose::from_position(Vec3::X),
                    ColliderShape::Cone {
                        radius: 0.2,
                        half_height: 0.3,
                    },
                ),
            ],
        },
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    /// The closed-form box holds every drawn point (to rounding, 2e-5 m) and touches the drawn shape: no
    /// farther from the drawn bounds than the tessellation's error at 128 segments per circle. A vertex of
    /// a round surface lies within π/64 rad of any direction from its centre, so the drawn extreme falls
    /// short by at most r·(1 − cos(π/64)) = 1.2e-3·r, under the 1e-3 of the box's size (≥ 2r) allowed.
    #[test]
    fn bounding_boxes_hold_and_touch_the_drawn_shape(
        axis in (-1.0f32..1.0, -1.0f32..1.0, -1.0f32..1.0),
        angle in -3.1f32..3.1,
        position in (-10.0f32..10.0, -10.0f32..10.0, -10.0f32..10.0),
    ) {
        let axis = Vec3::new(axis.0, axis.1, axis.2).try_normalize().unwrap_or(Vec3::X);
        let pose = Pose::new(Vec3::new(position.0, position.1, position.2), Quat::from_axis_angle(axis, angle));
        for shape in shapes() {
            let (min, max) = shape_aabb(&shape, pose).unwrap();
            let mut draw = DebugDraw::new();
            draw.shape(&shape, pose, Color::WHITE, true, true, 128);
            let points = endpoints(&draw).chain(draw.triangles.iter().flat_map(|t| t.vertices));
            let (lo, hi) = points.fold((Vec3::INFINITY, Vec3::NEG_INFINITY), |(lo, hi), p| (lo.min(p), hi.max(p)));
            let hold = 2e-5;
            prop_assert!(lo.cmpge(min - hold).all() && hi.cmple(max + hold).all(),
                "{} escapes {min}..{max}: {lo}..{hi}", shape.kind_name());
            let touch = 1e-3 * (max - min).max_element();
            prop_assert!((lo - min).abs().max_element() < touch && (hi - max).abs().max_element() < touch,
                "{} box {min}..{max} is not tight on {lo}..{hi}", shape.kind_name());
        }
    }
}
