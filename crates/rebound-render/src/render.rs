//! `render`: a [`RenderScene`] seen from a [`Camera`], as an [`Image`].
//!
//! Three passes: the solids (each triangle placed in the world, faces of closed pieces turned away from the
//! camera skipped, flat Lambert shading from [`RenderOptions::light_direction`], clipped at the near plane,
//! depth-tested fill — see `raster.rs` for why a z-buffer), then the ground grid where the ground plane is
//! visible, then the contacts and joints over everything.
//!
//! Shading of a face with unit normal n (turned towards the camera for surfaces seen from behind):
//!
//! ```text
//! colour = base · (ambient + (1 − ambient) · max(0, n · l̂))      l̂ = light_direction / |light_direction|
//! ```

use rebound::prelude::Vec3;
use tiny_skia::Pixmap;

use crate::camera::{NEAR_PLANE, Projection};
use crate::raster::{DepthCanvas, ScreenVertex};
use crate::{Camera, Grid, Image, RenderError, RenderScene, Rgba, SceneObject, overlay};

/// How a picture is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RenderOptions {
    /// Colour where nothing is drawn (alpha ignored: pictures are opaque). Default: pale grey-blue.
    pub background: Rgba,
    /// Direction towards the light (world; any length > 0). Default: (0.4, 1.0, 0.6), above and to the
    /// front right.
    pub light_direction: Vec3,
    /// Share of a face's colour it keeps facing away from the light (dimensionless, 0–1). Default: 0.35.
    pub ambient: f32,
    /// The ground grid, or `None` for none. Default: [`Grid::default`].
    pub grid: Option<Grid>,
    /// Draw the scene's contact points and normals. Default: false.
    pub contacts: bool,
    /// Length of a drawn contact normal (m, ≥ 0). Default: 0.3.
    pub contact_normal_length: f32,
    /// Colour of contacts. Default: opaque red.
    pub contact_colour: Rgba,
    /// Draw the scene's joint segments. Default: true.
    pub joints: bool,
    /// Colour of joints. Default: opaque dark blue.
    pub joint_colour: Rgba,
}

impl Default for RenderOptions {
    fn default() -> Self {
        Self {
            background: Rgba::opaque(205, 215, 225),
            light_direction: Vec3::new(0.4, 1.0, 0.6),
            ambient: 0.35,
            grid: Some(Grid::default()),
            contacts: false,
            contact_normal_length: 0.3,
            contact_colour: Rgba::opaque(220, 20, 30),
            joints: true,
            joint_colour: Rgba::opaque(20, 40, 140),
        }
    }
}

impl RenderOptions {
    /// Checks the fields.
    ///
    /// # Errors
    /// [`RenderError::Options`] naming the first bad field: a zero or non-finite light direction, an ambient
    /// share outside 0–1, a negative or non-finite normal length, a bad [`Grid`].
    pub fn validate(&self) -> Result<(), RenderError> {
        let bad = |field, value: String, expected| {
            Err(RenderError::Options {
                field,
                value,
                expected,
            })
        };
        if !(self.light_direction.is_finite() && self.light_direction.length_squared() > 0.0) {
            return bad(
                "light_direction",
                self.light_direction.to_string(),
                "finite and non-zero",
            );
        }
        if !(0.0..=1.0).contains(&self.ambient) {
            return bad("ambient", self.ambient.to_string(), "in 0–1");
        }
        if !(self.contact_normal_length.is_finite() && self.contact_normal_length >= 0.0) {
            return bad(
                "contact_normal_length",
                self.contact_normal_length.to_string(),
                "finite and ≥ 0 m",
            );
        }
        self.grid.as_ref().map_or(Ok(()), Grid::validate)
    }
}

/// Draws `scene` from `camera`.
///
/// # Errors
/// [`RenderError::Camera`] or [`RenderError::Options`] naming a bad field (nothing is drawn).
pub fn render(
    scene: &RenderScene,
    camera: &Camera,
    options: &RenderOptions,
) -> Result<Image, RenderError> {
    let projection = camera.projection()?;
    options.validate()?;
    let mut pixmap = Pixmap::new(camera.width, camera.height).ok_or(RenderError::Camera {
        field: "width",
        value: format!("{}×{}", camera.width, camera.height),
        expected: "a picture that fits in memory",
    })?;
    let b = options.background;
    pixmap.fill(Rgba::opaque(b.r, b.g, b.b).to_skia());
    let shading = Shading {
        light: options.light_direction.normalize(),
        ambient: options.ambient,
    };
    {
        let (width, height) = (camera.width as usize, camera.height as usize);
        let mut canvas = DepthCanvas::new(pixmap.data_mut(), width, height);
        let mut world = Vec::new();
        for object in &scene.objects {
            draw_object(&mut canvas, &projection, object, &shading, &mut world);
        }
        if let Some(grid) = &options.grid {
            grid.draw(&mut canvas, &projection);
        }
    }
    if options.joints {
        overlay::draw_joints(&mut pixmap, &projection, scene, options.joint_colour);
    }
    if options.contacts {
        overlay::draw_contacts(
            &mut pixmap,
            &projection,
            scene,
            options.contact_normal_length,
            options.contact_colour,
        );
    }
    Ok(Image { pixmap })
}

/// The light, checked.
struct Shading {
    /// Towards the light (unit, world).
    light: Vec3,
    /// Share of colour kept in shadow (0–1).
    ambient: f32,
}

/// Draws one object's triangles; `world` is scratch space for its vertices in the world.
fn draw_object(
    canvas: &mut DepthCanvas<'_>,
    projection: &Projection,
    object: &SceneObject,
    shading: &Shading,
    world: &mut Vec<Vec3>,
) {
    let pose = object.pose;
    if !(pose.position.is_finite() && pose.rotation.is_finite()) {
        return;
    }
    world.clear();
    world.extend(
        object
            .mesh
            .positions()
            .iter()
            .map(|&p| pose.transform_point(p)),
    );
    for &(triangle, closed) in object.mesh.triangles_closed() {
        let [Some(&a), Some(&b), Some(&c)] = triangle.map(|i| world.get(i as usize)) else {
            continue;
        };
        let mut normal = (b - a).cross(c - a);
        let facing = normal.dot(projection.position - a);
        if facing <= 0.0 {
            if closed {
                continue;
            }
            normal = -normal;
        }
        let lit = normal.normalize_or_zero().dot(shading.light).max(0.0);
        let colour = object
            .colour
            .scaled(shading.ambient + (1.0 - shading.ambient) * lit);
        fill_clipped(
            canvas,
            projection,
            [a, b, c].map(|p| projection.to_view(p)),
            colour,
        );
    }
}

/// Clips the view-space triangle to the near plane and fills what is left (a triangle or a quadrilateral).
fn fill_clipped(
    canvas: &mut DepthCanvas<'_>,
    projection: &Projection,
    view: [Vec3; 3],
    colour: Rgba,
) {
    let screen = |v: Vec3| {
        let (x, y) = projection.view_to_pixel(v);
        ScreenVertex {
            x,
            y,
            inv_depth: 1.0 / v.z,
        }
    };
    if view.iter().all(|v| v.z >= NEAR_PLANE) {
        canvas.fill_triangle(view.map(screen), colour);
        return;
    }
    // Sutherland–Hodgman against the one plane depth = NEAR_PLANE.
    let mut kept = [Vec3::ZERO; 4];
    let mut count = 0;
    for i in 0..3 {
        let (p, q) = (view[i], view[(i + 1) % 3]);
        if p.z >= NEAR_PLANE {
            kept[count] = p;
            count += 1;
        }
        if (p.z >= NEAR_PLANE) != (q.z >= NEAR_PLANE) {
            kept[count] = p.lerp(q, (NEAR_PLANE - p.z) / (q.z - p.z));
            count += 1;
        }
    }
    for i in 1..count.saturating_sub(1) {
        canvas.fill_triangle([kept[0], kept[i], kept[i + 1]].map(screen), colour);
    }
}
