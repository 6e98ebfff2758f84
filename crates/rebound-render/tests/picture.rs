//! Pictures checked pixel by pixel against where the camera's closed form puts things.

use std::sync::Arc;

use rebound::ColliderShape;
use rebound::prelude::{Pose, Quat, Vec3};
use rebound_render::{
    Camera, ContactMark, DEFAULT_ROUND_SUBDIVISIONS, Grid, Image, JointSegment, Mesh, RenderError,
    RenderOptions, RenderScene, Rgba, render,
};

const BACKGROUND: Rgba = Rgba::opaque(10, 20, 30);

/// No grid, a known background, overlays off.
fn plain() -> RenderOptions {
    RenderOptions {
        background: BACKGROUND,
        grid: None,
        joints: false,
        ..RenderOptions::default()
    }
}

/// Looking from (0, 0, 10) at the origin.
fn front_camera() -> Camera {
    Camera {
        position: Vec3::new(0.0, 0.0, 10.0),
        target: Vec3::ZERO,
        fov_y: 0.8,
        width: 64,
        height: 48,
    }
}

fn mesh(shape: &ColliderShape) -> Arc<Mesh> {
    Arc::new(Mesh::from_shape(shape, DEFAULT_ROUND_SUBDIVISIONS).expect("valid shape"))
}

fn at(position: Vec3) -> Pose {
    Pose {
        position,
        rotation: Quat::IDENTITY,
    }
}

fn pixel(image: &Image, x: u32, y: u32) -> Rgba {
    image.pixel(x, y).expect("inside the picture")
}

/// Red channel high, green and blue zero: a shaded red face.
fn is_red(c: Rgba) -> bool {
    c.r > 60 && c.g == 0 && c.b == 0
}

/// Focal length in pixels of a camera: (height/2)/tan(fov_y/2).
fn focal(camera: &Camera) -> f32 {
    0.5 * camera.height as f32 / (0.5 * camera.fov_y).tan()
}

#[test]
fn an_empty_scene_without_grid_is_the_background_everywhere() {
    let image = render(&RenderScene::new(), &front_camera(), &plain()).expect("renders");
    assert_eq!((image.width(), image.height()), (64, 48));
    for y in 0..48 {
        for x in 0..64 {
            assert_eq!(pixel(&image, x, y), BACKGROUND, "pixel ({x}, {y})");
        }
    }
}

#[test]
fn a_red_ball_at_the_target_fills_the_centre_and_not_the_corners() {
    let camera = Camera {
        width: 640,
        height: 480,
        ..front_camera()
    };
    let mut scene = RenderScene::new();
    let radius = 1.0;
    scene.push(
        mesh(&ColliderShape::Ball { radius }),
        at(Vec3::ZERO),
        Rgba::RED,
    );
    let image = render(&scene, &camera, &plain()).expect("renders");
    for (x, y) in [(319, 239), (320, 239), (319, 240), (320, 240)] {
        assert!(is_red(pixel(&image, x, y)), "centre pixel ({x}, {y})");
    }
    for (x, y) in [(0, 0), (639, 0), (0, 479), (639, 479)] {
        assert_eq!(pixel(&image, x, y), BACKGROUND, "corner ({x}, {y})");
    }
    // The sphere's outline is a circle of radius focal·R/√(D² − R²) pixels about the centre. The tessellated
    // ball lies inside the sphere, within cos(π/8) of its radius (8 bands pole to pole).
    let distance = 10.0f32;
    let outline = focal(&camera) * radius / (distance * distance - radius * radius).sqrt();
    for (dx, dy) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
        let inside = (320.0 + dx * 0.85 * outline, 240.0 + dy * 0.85 * outline);
        let outside = (320.0 + dx * 1.05 * outline, 240.0 + dy * 1.05 * outline);
        assert!(
            is_red(pixel(&image, inside.0 as u32, inside.1 as u32)),
            "0.85 of the outline radius along ({dx}, {dy})"
        );
        assert_eq!(
            pixel(&image, outside.0 as u32, outside.1 as u32),
            BACKGROUND,
            "1.05 of the outline radius along ({dx}, {dy})"
        );
    }
}

#[test]
fn a_box_left_of_the_target_lands_left_of_centre_where_the_projection_puts_it() {
    let camera = front_camera();
    let mut scene = RenderScene::new();
    let centre = Vec3::new(-3.0, 0.0, 0.0);
    scene.push(
        mesh(&ColliderShape::Cuboid {
            half_extents: Vec3::splat(0.5),
        }),
        at(centre),
        Rgba::RED,
    );
    let image = render(&scene, &camera, &plain()).expect("renders");
    let mut drawn = 0;
    for y in 0..camera.height {
        for x in 0..camera.width {
            if pixel(&image, x, y) != BACKGROUND {
                drawn += 1;
                assert!(
                    x < camera.width / 2,
                    "pixel ({x}, {y}) drawn right of centre"
                );
            }
        }
    }
    assert!(drawn > 0);
    // Closed form: x = w/2 + focal·(−3)/10 (the face nearest the camera is at depth 9.5, the centre at 10).
    let expected_x = 32.0 - focal(&camera) * 3.0 / 10.0;
    assert!(is_red(pixel(&image, expected_x as u32, 24)));
}

#[test]
fn projection_matches_the_pinhole_closed_form() {
    let camera = Camera {
        position: Vec3::ZERO,
        target: Vec3::new(0.0, 0.0, -1.0),
        fov_y: 1.0,
        width: 800,
        height: 600,
    };
    let projection = camera.projection().expect("valid camera");
    let f = 300.0 / 0.5f32.tan();
    assert!((projection.focal - f).abs() < 1e-3);
    for (theta, depth) in [(0.0f32, 1.0f32), (0.2, 5.0), (-0.35, 12.0), (0.45, 0.3)] {
        // A point at angle θ right of the axis and one θ above it.
        let right = Vec3::new(theta.tan() * depth, 0.0, -depth);
        let (x, y, d) = projection.project(right).expect("in front");
        assert!(
            (x - (400.0 + f * theta.tan())).abs() < 1e-2,
            "θ = {theta}: x = {x}"
        );
        assert!((y - 300.0).abs() < 1e-3);
        assert!((d - depth).abs() < 1e-5);
        let above = Vec3::new(0.0, theta.tan() * depth, -depth);
        let (x, y, _) = projection.project(above).expect("in front");
        assert!((x - 400.0).abs() < 1e-3);
        assert!(
            (y - (300.0 - f * theta.tan())).abs() < 1e-2,
            "θ = {theta}: y = {y}"
        );
    }
    // Half the field of view above the axis is the top edge of the picture.
    let top = Vec3::new(0.0, 0.5f32.tan(), -1.0);
    let (_, y, _) = projection.project(top).expect("in front");
    assert!(y.abs() < 1e-3, "top edge at y = {y}");
    // Behind the camera, or nearer than the near plane: not on the picture.
    assert!(projection.project(Vec3::new(0.0, 0.0, 1.0)).is_none());
    assert!(projection.project(Vec3::new(0.0, 0.0, -0.01)).is_none());
}

#[test]
fn the_target_projects_to_the_centre_from_any_camera() {
    for position in [
        Vec3::new(3.0, 7.0, -2.0),
        Vec3::new(-10.0, 0.5, 4.0),
        Vec3::new(0.0, 20.0, 0.0),
    ] {
        let camera = Camera {
            position,
            target: Vec3::new(1.0, 2.0, 3.0),
            ..Camera::default()
        };
        let projection = camera.projection().expect("valid camera");
        let (x, y, d) = projection.project(camera.target).expect("in front");
        assert!((x - 320.0).abs() < 1e-3 && (y - 240.0).abs() < 1e-3);
        assert!((d - (camera.target - position).length()).abs() < 1e-4);
        let axes = [projection.right, projection.up, projection.forward];
        for (i, a) in axes.iter().enumerate() {
            assert!((a.length() - 1.0).abs() < 1e-5);
            for b in &axes[i + 1..] {
                assert!(a.dot(*b).abs() < 1e-5);
            }
        }
    }
}

#[test]
fn the_nearer_solid_wins_whatever_the_drawing_order() {
    let cube = mesh(&ColliderShape::Cuboid {
        half_extents: Vec3::splat(1.0),
    });
    let near = (at(Vec3::new(0.0, 0.0, 2.0)), Rgba::RED);
    let far = (at(Vec3::new(0.3, 0.2, -2.0)), Rgba::BLUE);
    for order in [[near, far], [far, near]] {
        let mut scene = RenderScene::new();
        for (pose, colour) in order {
            scene.push(cube.clone(), pose, colour);
        }
        let image = render(&scene, &front_camera(), &plain()).expect("renders");
        assert!(is_red(pixel(&image, 32, 24)));
    }
}

#[test]
fn a_horizontal_camera_sees_the_ground_below_the_centre_row_and_sky_above() {
    // The ground's top face spans the whole view and passes under the camera: clipped at the near plane.
    let camera = Camera {
        position: Vec3::new(0.0, 2.0, 0.0),
        target: Vec3::new(0.0, 2.0, -10.0),
        ..front_camera()
    };
    let mut scene = RenderScene::new();
    let ground = Rgba::opaque(0, 200, 0);
    scene.push(
        mesh(&ColliderShape::Cuboid {
            half_extents: Vec3::new(1000.0, 0.5, 1000.0),
        }),
        at(Vec3::new(0.0, -0.5, 0.0)),
        ground,
    );
    let image = render(&scene, &camera, &plain()).expect("renders");
    for x in [0, 20, 63] {
        // The horizon is the centre row (y = 24); the ground at 1000 m is 0.4 px below it.
        assert_eq!(pixel(&image, x, 22), BACKGROUND, "above the horizon");
        for y in [26, 35, 47] {
            let c = pixel(&image, x, y);
            assert!(
                c.g > 60 && c.r == 0 && c.b == 0,
                "ground at ({x}, {y}): {c:?}"
            );
        }
    }
}

#[test]
fn the_grid_shows_on_its_lines_and_not_between_them_nor_under_a_box() {
    let camera = Camera {
        position: Vec3::new(0.0, 10.0, 0.001),
        target: Vec3::ZERO,
        fov_y: 0.8,
        width: 200,
        height: 200,
    };
    let projection = camera.projection().expect("valid camera");
    let grid = Grid {
        colour: Rgba::WHITE,
        ..Grid::default()
    };
    let options = RenderOptions {
        grid: Some(grid),
        ..plain()
    };
    let at_ground = |x: f32, z: f32| {
        let (px, py, _) = projection.project(Vec3::new(x, 0.0, z)).expect("in view");
        (px as u32, py as u32)
    };
    let mut scene = RenderScene::new();
    // A ground face at the grid's height does not hide it; a box above the plane does.
    scene.push(
        mesh(&ColliderShape::Cuboid {
            half_extents: Vec3::new(50.0, 0.5, 50.0),
        }),
        at(Vec3::new(0.0, -0.5, 0.0)),
        Rgba::opaque(0, 0, 90),
    );
    scene.push(
        mesh(&ColliderShape::Cuboid {
            half_extents: Vec3::new(1.0, 0.5, 1.0),
        }),
        at(Vec3::new(2.0, 0.5, 2.0)),
        Rgba::RED,
    );
    let image = render(&scene, &camera, &options).expect("renders");
    let (x, y) = at_ground(1.0, 0.5);
    let line = pixel(&image, x, y);
    assert!(line.r > 150 && line.g > 150, "on the line x = 1: {line:?}");
    let (x, y) = at_ground(-1.5, -1.5);
    let cell = pixel(&image, x, y);
    assert!(cell.r == 0 && cell.g == 0, "in a cell: {cell:?}");
    // The line x = 2 runs under the box: its top face is seen there.
    let (x, y) = at_ground(2.0, 2.5);
    assert!(is_red(pixel(&image, x, y)));
}

#[test]
fn contacts_and_joints_are_drawn_over_the_solids_only_when_asked() {
    let mut scene = RenderScene::new();
    scene.push(
        mesh(&ColliderShape::Cuboid {
            half_extents: Vec3::splat(1.0),
        }),
        at(Vec3::ZERO),
        Rgba::BLUE,
    );
    scene.contacts.push(ContactMark {
        point: Vec3::new(0.0, 0.0, 1.0),
        normal: Vec3::Y,
    });
    scene.joints.push(JointSegment {
        anchor_a: Vec3::new(-3.0, -1.5, 1.0),
        anchor_b: Vec3::new(3.0, -1.5, 1.0),
    });
    let joint_colour = Rgba::GREEN;
    let options = RenderOptions {
        contacts: true,
        contact_colour: Rgba::RED,
        joints: true,
        joint_colour,
        ..plain()
    };
    let camera = front_camera();
    let image = render(&scene, &camera, &options).expect("renders");
    let (x, y, _) = camera
        .projection()
        .expect("valid camera")
        .project(Vec3::new(0.0, -1.5, 1.0))
        .expect("in view");
    let c = pixel(&image, x as u32, y as u32);
    assert!(c.g > 100 && c.r < 60, "joint segment: {c:?}");
    assert_eq!(pixel(&image, 32, 24), Rgba::RED, "contact dot");
    let options = RenderOptions {
        contacts: false,
        joints: false,
        ..options
    };
    let hidden = render(&scene, &camera, &options).expect("renders");
    let c = pixel(&hidden, 32, 24);
    assert!(c.b > 60 && c.r == 0, "the box, no dot: {c:?}");
}

#[test]
fn a_bad_camera_or_option_is_refused_naming_the_field() {
    let scene = RenderScene::new();
    let cases = [
        (
            Camera {
                fov_y: 0.0,
                ..Camera::default()
            },
            "fov_y",
        ),
        (
            Camera {
                width: 0,
                ..Camera::default()
            },
            "width",
        ),
        (
            Camera {
                height: 100_000,
                ..Camera::default()
            },
            "height",
        ),
        (
            Camera {
                target: Camera::default().position,
                ..Camera::default()
            },
            "target",
        ),
        (
            Camera {
                position: Vec3::new(f32::NAN, 0.0, 0.0),
                ..Camera::default()
            },
            "position",
        ),
    ];
    for (camera, name) in cases {
        match render(&scene, &camera, &plain()) {
            Err(RenderError::Camera { field, .. }) => assert_eq!(field, name),
            other => panic!("{name}: {other:?}"),
        }
    }
    let options = [
        (
            RenderOptions {
                ambient: 1.5,
                ..plain()
            },
            "ambient",
        ),
        (
            RenderOptions {
                light_direction: Vec3::ZERO,
                ..plain()
            },
            "light_direction",
        ),
        (
            RenderOptions {
                grid: Some(Grid {
                    spacing: -1.0,
                    ..Grid::default()
                }),
                ..plain()
            },
            "grid.spacing",
        ),
    ];
    for (options, name) in options {
        match render(&scene, &front_camera(), &options) {
            Err(RenderError::Options { field, .. }) => assert_eq!(field, name),
            other => panic!("{name}: {other:?}"),
        }
    }
}

#[test]
fn a_non_finite_pose_draws_nothing_and_does_not_panic() {
    let mut scene = RenderScene::new();
    scene.push(
        mesh(&ColliderShape::Ball { radius: 1.0 }),
        at(Vec3::new(f32::NAN, 0.0, 0.0)),
        Rgba::RED,
    );
    let image = render(&scene, &front_camera(), &plain()).expect("renders");
    assert!(image.rgba().chunks(4).all(|p| p == [10, 20, 30, 255]));
}

#[test]
fn a_framed_sphere_fills_the_picture_to_the_margin() {
    let (centre, radius) = (Vec3::new(4.0, 2.0, -1.0), 3.0);
    for (width, height) in [(160, 120), (90, 160)] {
        let camera = Camera::framing(centre, radius, width, height);
        let mut scene = RenderScene::new();
        scene.push(mesh(&ColliderShape::Ball { radius }), at(centre), Rgba::RED);
        let image = render(&scene, &camera, &plain()).expect("renders");
        // The outline's radius is focal·r/√(D² − r²) pixels (as in the ball test); framing puts it inside the
        // shorter half-side by about the margin.
        let distance = (camera.position - centre).length();
        let outline = focal(&camera) * radius / (distance * distance - radius * radius).sqrt();
        let half_side = 0.5 * width.min(height) as f32;
        assert!(
            outline < half_side && outline > 0.85 * half_side,
            "{outline} of {half_side}"
        );
        let red = |x: u32, y: u32| is_red(pixel(&image, x, y));
        let row: Vec<u32> = (0..width).filter(|&x| red(x, height / 2)).collect();
        let column: Vec<u32> = (0..height).filter(|&y| red(width / 2, y)).collect();
        for extent in [row.len(), column.len()] {
            // Tessellated (inside the sphere by up to 1 − cos(π/8)) and pixel-rounded.
            let diameter = 2.0 * outline;
            assert!(extent as f32 <= diameter + 2.0 && extent as f32 >= 0.9 * diameter);
        }
        // Nothing of the ball on the picture's border.
        for x in 0..width {
            assert!(!red(x, 0) && !red(x, height - 1));
        }
        for y in 0..height {
            assert!(!red(0, y) && !red(width - 1, y));
        }
    }
}

#[test]
fn a_non_finite_contact_or_joint_is_left_out_and_the_others_drawn() {
    let mut scene = RenderScene::new();
    for point in [Vec3::NAN, Vec3::new(0.0, 0.0, 1.0)] {
        scene.contacts.push(ContactMark {
            point,
            normal: Vec3::Y,
        });
    }
    scene.joints.push(JointSegment {
        anchor_a: Vec3::new(f32::INFINITY, 0.0, 0.0),
        anchor_b: Vec3::ZERO,
    });
    let options = RenderOptions {
        contacts: true,
        joints: true,
        contact_colour: Rgba::RED,
        ..plain()
    };
    let image = render(&scene, &front_camera(), &options).expect("renders");
    assert_eq!(pixel(&image, 32, 24), Rgba::RED);
}
