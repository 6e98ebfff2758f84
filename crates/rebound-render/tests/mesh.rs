//! Tessellations checked against the shapes they stand for.

use rebound::ColliderShape;
use rebound::prelude::{Pose, Quat, Vec3};
use rebound_render::{Mesh, RenderError};

fn mesh(shape: &ColliderShape) -> Mesh {
    Mesh::from_shape(shape, 16).expect("valid shape")
}

/// Every triangle of a convex mesh is wound counter-clockwise seen from outside: its normal points away
/// from `inside`, and the mesh encloses it.
fn assert_outward(mesh: &Mesh, inside: Vec3) {
    assert!(mesh.triangle_count() > 0);
    let p = mesh.positions();
    for [a, b, c] in mesh.triangles() {
        let (a, b, c) = (p[a as usize], p[b as usize], p[c as usize]);
        let normal = (b - a).cross(c - a);
        assert!(normal.dot((a + b + c) / 3.0 - inside) > 0.0);
    }
}

#[test]
fn a_cuboid_is_twelve_outward_triangles_on_its_corners() {
    let h = Vec3::new(0.5, 1.0, 2.0);
    let m = mesh(&ColliderShape::Cuboid { half_extents: h });
    assert_eq!(m.triangle_count(), 12);
    for p in m.positions() {
        assert!((p.abs() - h).abs().max_element() < 1e-6, "corner {p}");
    }
    assert_outward(&m, Vec3::ZERO);
}

#[test]
fn round_shapes_lie_on_their_surfaces_and_face_out() {
    let r = 0.7;
    let ball = mesh(&ColliderShape::Ball { radius: r });
    for p in ball.positions() {
        assert!((p.length() - r).abs() < 1e-5);
    }
    assert_outward(&ball, Vec3::ZERO);
    let (radius, half_height) = (0.4, 0.9);
    let capsule = mesh(&ColliderShape::Capsule {
        radius,
        half_height,
    });
    for p in capsule.positions() {
        // Distance to the axis segment from (0, −h, 0) to (0, h, 0) is the radius.
        let on_axis = Vec3::new(0.0, p.y.clamp(-half_height, half_height), 0.0);
        assert!(((*p - on_axis).length() - radius).abs() < 1e-5);
    }
    assert_outward(&capsule, Vec3::ZERO);
    for shape in [
        ColliderShape::Cylinder {
            radius,
            half_height,
        },
        ColliderShape::Cone {
            radius,
            half_height,
        },
    ] {
        let m = mesh(&shape);
        for p in m.positions() {
            assert!(p.y.abs() <= half_height + 1e-6);
            assert!(p.x.hypot(p.z) <= radius + 1e-6);
        }
        assert_outward(&m, Vec3::new(0.0, -0.5 * half_height, 0.0));
    }
}

#[test]
fn a_hull_is_closed_and_outward_and_a_compound_places_its_parts() {
    let points = vec![
        Vec3::ZERO,
        Vec3::X,
        Vec3::Y,
        Vec3::Z,
        Vec3::new(0.2, 0.2, 0.2),
    ];
    let hull = mesh(&ColliderShape::ConvexHull { points });
    // The interior point is not a hull vertex: a tetrahedron, four faces.
    assert_eq!(hull.triangle_count(), 4);
    assert_outward(&hull, Vec3::splat(0.2));
    let cube = ColliderShape::Cuboid {
        half_extents: Vec3::splat(0.5),
    };
    let offset = Vec3::new(3.0, 0.0, 0.0);
    let compound = mesh(&ColliderShape::Compound {
        parts: vec![
            (Pose::IDENTITY, cube.clone()),
            (
                Pose {
                    position: offset,
                    rotation: Quat::from_rotation_y(0.5),
                },
                cube,
            ),
        ],
    });
    assert_eq!(compound.triangle_count(), 24);
    let far = compound.positions().iter().filter(|p| p.x > 2.0).count();
    assert_eq!(far, compound.positions().len() / 2);
}

#[test]
fn surfaces_keep_their_triangles() {
    let vertices = vec![Vec3::ZERO, Vec3::X, Vec3::Z, Vec3::new(1.0, 0.0, 1.0)];
    let indices = vec![[0, 2, 1], [1, 2, 3]];
    let m = mesh(&ColliderShape::TriMesh {
        vertices: vertices.clone(),
        indices: indices.clone(),
    });
    // The same triangles, corner for corner.
    let p = m.positions();
    let corners: Vec<[Vec3; 3]> = m.triangles().map(|t| t.map(|i| p[i as usize])).collect();
    let expected: Vec<[Vec3; 3]> = indices
        .iter()
        .map(|t| t.map(|i| vertices[i as usize]))
        .collect();
    assert_eq!(corners, expected);
    let field = mesh(&ColliderShape::HeightField {
        rows: 3,
        cols: 4,
        heights: vec![0.0; 12],
        scale: Vec3::new(3.0, 1.0, 2.0),
    });
    // (3 − 1)·(4 − 1) cells of two triangles, spanning x in ±1.5 and z in ±1.
    assert_eq!(field.triangle_count(), 12);
    for p in field.positions() {
        assert!(p.x.abs() <= 1.5 + 1e-6 && p.z.abs() <= 1.0 + 1e-6 && p.y.abs() < 1e-6);
    }
}

#[test]
fn a_bad_shape_or_index_is_refused() {
    let bad = Mesh::from_shape(&ColliderShape::Ball { radius: -1.0 }, 16);
    assert!(matches!(bad, Err(RenderError::Shape(_))), "{bad:?}");
    let bad = Mesh::from_triangles(vec![Vec3::ZERO, Vec3::X, Vec3::Y], &[[0, 1, 3]]);
    match bad {
        Err(RenderError::Options { field, value, .. }) => {
            assert_eq!((field, value.as_str()), ("triangles", "3"));
        }
        other => panic!("{other:?}"),
    }
}
