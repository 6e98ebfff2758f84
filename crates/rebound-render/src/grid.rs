//! `Grid`: the ground grid, drawn after the solids where the ground plane is not hidden by them.
//!
//! Computed per pixel rather than stroked with tiny-skia: each pixel's ray meets the plane y = `height` at
//! depth t, and the grid shows there only if nothing drawn is nearer (the depth buffer of the solids), so
//! boxes standing on the ground hide the lines behind them while a ground box's top face at the same height
//! does not. A line's coverage falls off linearly over one pixel's footprint on the plane, and the grid fades
//! out where a cell shrinks to a few pixels along the view, instead of turning into moiré.

use rebound::prelude::Vec3;

use crate::camera::Projection;
use crate::raster::DepthCanvas;
use crate::{RenderError, Rgba};

/// A square grid on a horizontal plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Grid {
    /// Distance between lines (m, > 0). Default: 1.
    pub spacing: f32,
    /// The grid covers |x| ≤ `half_extent` and |z| ≤ `half_extent` (m, > 0). Default: 50.
    pub half_extent: f32,
    /// Height of the plane (m, world y). Default: 0.
    pub height: f32,
    /// Line colour; its alpha is the lines' opacity. Default: dark grey at 60 %.
    pub colour: Rgba,
}

impl Default for Grid {
    fn default() -> Self {
        Self {
            spacing: 1.0,
            half_extent: 50.0,
            height: 0.0,
            colour: Rgba::new(60, 60, 60, 150),
        }
    }
}

/// How much nearer than the grid plane (relative depth) a solid must be to hide it: a ground face at the
/// plane's own height, drawn at the same depth up to rounding, does not.
const DEPTH_TOLERANCE: f32 = 1.0e-3;

impl Grid {
    /// Checks the fields.
    ///
    /// # Errors
    /// [`RenderError::Options`] naming the first non-finite or non-positive field.
    pub fn validate(&self) -> Result<(), RenderError> {
        for (field, value) in [
            ("grid.spacing", self.spacing),
            ("grid.half_extent", self.half_extent),
        ] {
            if !(value.is_finite() && value > 0.0) {
                return Err(RenderError::Options {
                    field,
                    value: value.to_string(),
                    expected: "finite and > 0 m",
                });
            }
        }
        if !self.height.is_finite() {
            return Err(RenderError::Options {
                field: "grid.height",
                value: self.height.to_string(),
                expected: "finite",
            });
        }
        Ok(())
    }

    /// Blends the grid into `canvas` where the plane is visible.
    pub(crate) fn draw(&self, canvas: &mut DepthCanvas<'_>, projection: &Projection) {
        let rise = self.height - projection.position.y;
        if rise == 0.0 {
            return;
        }
        let inv_rise = 1.0 / rise;
        let alpha = f32::from(self.colour.a) / 255.0;
        let line = [self.colour.r, self.colour.g, self.colour.b].map(f32::from);
        let inv_spacing = 1.0 / self.spacing;
        let nearest = 1.0 / crate::NEAR_PLANE;
        for y in 0..canvas.height {
            for x in 0..canvas.width {
                let ray = projection.ray(x as f32 + 0.5, y as f32 + 0.5);
                // 1/depth of the plane along this pixel's ray (the ray's forward component is 1): positive
                // where the ray meets the plane in front of the camera.
                let inv_t = ray.y * inv_rise;
                if !(inv_t > 0.0 && inv_t < nearest) {
                    continue;
                }
                let i = y * canvas.width + x;
                let hidden = canvas
                    .inv_depth
                    .get(i)
                    .is_none_or(|&solid| solid * (1.0 - DEPTH_TOLERANCE) > inv_t);
                if hidden {
                    continue;
                }
                let t = 1.0 / inv_t;
                let hit = projection.position + ray * t;
                if hit.x.abs() > self.half_extent || hit.z.abs() > self.half_extent {
                    continue;
                }
                let coverage = self.coverage(hit, ray, t, projection.focal, inv_spacing) * alpha;
                if coverage <= 0.0 {
                    continue;
                }
                if let Some(out) = canvas.rgba.get_mut(4 * i..4 * i + 3) {
                    for (channel, target) in out.iter_mut().zip(line) {
                        let c = f32::from(*channel);
                        *channel = (c + (target - c) * coverage).round() as u8;
                    }
                }
            }
        }
    }

    /// How much of the pixel whose ray `ray` meets the plane at `hit`, depth `t`, a grid line covers (0–1).
    fn coverage(&self, hit: Vec3, ray: Vec3, t: f32, focal: f32, inv_spacing: f32) -> f32 {
        let length = ray.length();
        // One pixel's width on the plane across the ray, and along it (stretched at grazing angles).
        let across = t * length / focal;
        let along = across * length / ray.y.abs();
        let fade = (1.5 - 2.0 * along * inv_spacing).clamp(0.0, 1.0);
        if fade <= 0.0 {
            return 0.0;
        }
        let to_line = |u: f32| {
            let cells = u * inv_spacing;
            (cells - cells.round()).abs() * self.spacing
        };
        let distance = to_line(hit.x).min(to_line(hit.z));
        (1.0 - distance / across).clamp(0.0, 1.0) * fade
    }
}
