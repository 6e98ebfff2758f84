//! The depth-tested triangle fill that draws the solids (the first pass of [`crate::render`]).
//!
//! Written here rather than drawn with tiny-skia: tiny-skia fills 2D paths and keeps no depth, so solids
//! drawn with it must be sorted back to front, and a painter's sort is wrong exactly where a physics picture
//! looks — a ground face spanning the whole view sorts in front of the boxes on it, and shapes that
//! interpenetrate at a contact have no correct order at all. A z-buffer of one `f32` per pixel resolves
//! both per pixel. The fill is the classic one: edge functions evaluated at pixel centres over the
//! triangle's bounding box, with inverse depth (linear in screen space) interpolated and tested.

use crate::Rgba;

/// A colour buffer (opaque RGBA, row-major, shared with tiny-skia's pixmap) and an inverse-depth buffer.
pub(crate) struct DepthCanvas<'a> {
    /// RGBA bytes, 4 per pixel.
    pub rgba: &'a mut [u8],
    /// 1/depth (1/m) per pixel; 0 where nothing is drawn (infinitely far).
    pub inv_depth: Vec<f32>,
    /// Width (pixels).
    pub width: usize,
    /// Height (pixels).
    pub height: usize,
}

/// A projected vertex: pixel coordinates and 1/depth (1/m).
#[derive(Debug, Clone, Copy)]
pub(crate) struct ScreenVertex {
    /// x (pixels).
    pub x: f32,
    /// y (pixels, downwards).
    pub y: f32,
    /// 1/depth (1/m).
    pub inv_depth: f32,
}

/// Twice the signed area of (a, b, p): positive when p is to one side of a→b.
fn edge(a: ScreenVertex, b: ScreenVertex, x: f32, y: f32) -> f32 {
    (b.x - a.x) * (y - a.y) - (b.y - a.y) * (x - a.x)
}

impl<'a> DepthCanvas<'a> {
    /// A canvas over `rgba` (`width × height × 4` bytes) with nothing drawn in depth.
    pub fn new(rgba: &'a mut [u8], width: usize, height: usize) -> Self {
        Self {
            rgba,
            inv_depth: vec![0.0; width * height],
            width,
            height,
        }
    }

    /// Fills the triangle (either winding) where it is nearer than what is drawn, in `colour` (opaque).
    /// Pixels whose centre lies on the triangle or its edges are covered.
    pub fn fill_triangle(&mut self, v: [ScreenVertex; 3], colour: Rgba) {
        let [a, mut b, mut c] = v;
        let mut area = edge(a, b, c.x, c.y);
        if !(area.is_finite() && area.abs() > f32::EPSILON) {
            return;
        }
        if area < 0.0 {
            std::mem::swap(&mut b, &mut c);
            area = -area;
        }
        let to_pixel = |t: f32, size: usize| t.clamp(0.0, size as f32) as usize;
        let x0 = to_pixel(a.x.min(b.x).min(c.x).floor(), self.width);
        let x1 = to_pixel(a.x.max(b.x).max(c.x).ceil(), self.width);
        let y0 = to_pixel(a.y.min(b.y).min(c.y).floor(), self.height);
        let y1 = to_pixel(a.y.max(b.y).max(c.y).ceil(), self.height);
        if x0 >= x1 || y0 >= y1 {
            return;
        }
        let inv_area = 1.0 / area;
        // wa is the weight of a (the edge b→c), and so on; each steps by a constant per pixel along a row.
        let (step_a, step_b, step_c) = (b.y - c.y, c.y - a.y, a.y - b.y);
        let px = x0 as f32 + 0.5;
        let pixel = [colour.r, colour.g, colour.b, 255];
        for y in y0..y1 {
            // Each row starts from the exact edge values, so stepping errors do not pile up down the triangle.
            let py = y as f32 + 0.5;
            let (mut wa, mut wb, mut wc) =
                (edge(b, c, px, py), edge(c, a, px, py), edge(a, b, px, py));
            let row = y * self.width;
            for x in x0..x1 {
                if wa >= 0.0 && wb >= 0.0 && wc >= 0.0 {
                    let z = (wa * a.inv_depth + wb * b.inv_depth + wc * c.inv_depth) * inv_area;
                    let i = row + x;
                    if let Some(depth) = self.inv_depth.get_mut(i)
                        && z > *depth
                    {
                        *depth = z;
                        if let Some(out) = self.rgba.get_mut(4 * i..4 * i + 4) {
                            out.copy_from_slice(&pixel);
                        }
                    }
                }
                wa += step_a;
                wb += step_b;
                wc += step_c;
            }
        }
    }
}
