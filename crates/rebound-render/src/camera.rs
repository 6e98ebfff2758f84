//! `Camera` and its `Projection`: where a world point lands in a picture (a pinhole camera with square
//! pixels, looking from `position` at `target`, +Y up).
//!
//! ```text
//! forward = (target − position)/|target − position|,  right = forward × Y (normalised),  up = right × forward
//! view point (x, y, d) = ((p − position)·right, (p − position)·up, (p − position)·forward)
//! focal = (height/2) / tan(fov_y/2)                                           (pixels)
//! pixel = (width/2 + focal·x/d,  height/2 − focal·y/d)                        (d ≥ NEAR_PLANE)
//! ```
//!
//! Pixel (i, j) covers [i, i + 1) × [j, j + 1) with j growing downwards; the view axis meets the picture at
//! (width/2, height/2).

use rebound::prelude::Vec3;

use crate::RenderError;

/// The closest distance in front of the camera that is drawn (m): geometry nearer than this is clipped.
pub const NEAR_PLANE: f32 = 0.05;

/// The largest picture side (pixels).
pub const MAX_PICTURE_SIDE: u32 = 8_192;

/// A pinhole camera and the picture it makes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Camera {
    /// Where the camera is (m, world). Default: (0, 6, 18).
    pub position: Vec3,
    /// The point the camera looks at, shown at the picture's centre (m, world; ≠ `position`).
    /// Default: (0, 2, 0).
    pub target: Vec3,
    /// Vertical field of view (radians, in (0, π)). Default: 0.8 (about 46°).
    pub fov_y: f32,
    /// Picture width (pixels, 1 to [`MAX_PICTURE_SIDE`]). Default: 640.
    pub width: u32,
    /// Picture height (pixels, 1 to [`MAX_PICTURE_SIDE`]). Default: 480.
    pub height: u32,
}

impl Default for Camera {
    fn default() -> Self {
        Self {
            position: Vec3::new(0.0, 6.0, 18.0),
            target: Vec3::new(0.0, 2.0, 0.0),
            fov_y: 0.8,
            width: 640,
            height: 480,
        }
    }
}

/// The direction from the target to the camera that [`Camera::framing`] uses: in front (+z), a little to the
/// right and raised about 25° (unnormalised).
pub const FRAMING_DIRECTION: Vec3 = Vec3::new(0.3, 0.5, 1.0);

/// How much larger than the framed sphere [`Camera::framing`] makes the view (dimensionless).
pub const FRAMING_MARGIN: f32 = 1.1;

impl Camera {
    /// A camera of the default field of view looking at `centre` from [`FRAMING_DIRECTION`], as close as it
    /// can be while the sphere of `radius` (m) about `centre`, widened by [`FRAMING_MARGIN`], is wholly in a
    /// `width × height` picture:
    ///
    /// ```text
    /// distance = FRAMING_MARGIN · radius / sin(θ),   θ = min(fov_y/2, atan(tan(fov_y/2) · width/height))
    /// ```
    ///
    /// A radius that is not finite and positive is taken as 1 m; the result is checked when used.
    #[must_use]
    pub fn framing(centre: Vec3, radius: f32, width: u32, height: u32) -> Self {
        let fov_y = Self::default().fov_y;
        let radius = if radius.is_finite() && radius > 0.0 {
            radius
        } else {
            1.0
        };
        let half_y = 0.5 * fov_y;
        let aspect = width as f32 / height.max(1) as f32;
        let half = half_y.min((half_y.tan() * aspect).atan());
        let distance = FRAMING_MARGIN * radius / half.sin();
        Self {
            position: centre + FRAMING_DIRECTION.normalize() * distance,
            target: centre,
            fov_y,
            width,
            height,
        }
    }

    /// Checks the fields and computes the projection.
    ///
    /// # Errors
    /// [`RenderError::Camera`] naming the first bad field: a non-finite position or target, a target at the
    /// position, a field of view outside (0, π), a side of 0 or above [`MAX_PICTURE_SIDE`].
    pub fn projection(&self) -> Result<Projection, RenderError> {
        let bad = |field, value: String, expected| RenderError::Camera {
            field,
            value,
            expected,
        };
        if !self.position.is_finite() {
            return Err(bad("position", format!("{}", self.position), "finite"));
        }
        if !self.target.is_finite() {
            return Err(bad("target", format!("{}", self.target), "finite"));
        }
        let forward = (self.target - self.position).normalize_or_zero();
        if forward == Vec3::ZERO {
            return Err(bad(
                "target",
                format!("{}", self.target),
                "a point other than the position",
            ));
        }
        if !(self.fov_y > 0.0 && self.fov_y < std::f32::consts::PI) {
            return Err(bad("fov_y", format!("{}", self.fov_y), "in (0, π) radians"));
        }
        for (field, side) in [("width", self.width), ("height", self.height)] {
            if side == 0 || side > MAX_PICTURE_SIDE {
                return Err(bad(field, side.to_string(), "1 to 8192 pixels"));
            }
        }
        // Looking straight up or down, world Y gives no right vector: take world X.
        let right = forward.cross(Vec3::Y).try_normalize().unwrap_or(Vec3::X);
        let up = right.cross(forward);
        let focal = 0.5 * self.height as f32 / (0.5 * self.fov_y).tan();
        Ok(Projection {
            position: self.position,
            right,
            up,
            forward,
            focal,
            centre_x: 0.5 * self.width as f32,
            centre_y: 0.5 * self.height as f32,
            width: self.width,
            height: self.height,
        })
    }
}

/// A checked camera's projection (see the module docs for the formulas).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// The camera position (m, world).
    pub position: Vec3,
    /// The picture's x axis in the world (unit).
    pub right: Vec3,
    /// The picture's upward axis in the world (unit).
    pub up: Vec3,
    /// The viewing direction (unit).
    pub forward: Vec3,
    /// The focal length (pixels).
    pub focal: f32,
    /// Where the view axis meets the picture, x (pixels).
    pub centre_x: f32,
    /// Where the view axis meets the picture, y (pixels, downwards).
    pub centre_y: f32,
    /// Picture width (pixels).
    pub width: u32,
    /// Picture height (pixels).
    pub height: u32,
}

impl Projection {
    /// A world point in view coordinates: (right, up, depth along the view direction), all m.
    #[must_use]
    pub fn to_view(&self, point: Vec3) -> Vec3 {
        let d = point - self.position;
        Vec3::new(d.dot(self.right), d.dot(self.up), d.dot(self.forward))
    }

    /// A view point (depth > 0) on the picture: (x, y) in pixels, y downwards.
    #[must_use]
    pub fn view_to_pixel(&self, view: Vec3) -> (f32, f32) {
        let s = self.focal / view.z;
        (self.centre_x + view.x * s, self.centre_y - view.y * s)
    }

    /// A world point on the picture: (x pixels, y pixels downwards, depth m), or `None` if it is nearer than
    /// [`NEAR_PLANE`] (or behind the camera).
    #[must_use]
    pub fn project(&self, point: Vec3) -> Option<(f32, f32, f32)> {
        let view = self.to_view(point);
        (view.z >= NEAR_PLANE).then(|| {
            let (x, y) = self.view_to_pixel(view);
            (x, y, view.z)
        })
    }

    /// The world direction through the picture point (x, y) (pixels), scaled so that its component along
    /// [`Projection::forward`] is 1: a point `position + t·ray(x, y)` is at depth t.
    #[must_use]
    pub fn ray(&self, x: f32, y: f32) -> Vec3 {
        self.forward
            + self.right * ((x - self.centre_x) / self.focal)
            + self.up * ((self.centre_y - y) / self.focal)
    }
}
