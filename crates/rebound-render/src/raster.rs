//! The depth-tested triangle fill that draws the solids (the first pass of [`crate::render`]).
//!
//! Written here rather than drawn with tiny-skia: tiny-skia fills 2D paths and keeps no depth, so solids
//! drawn with it must be sorted back to front, and a painter's sort is wrong exactly where a physics picture
//! looks — a ground face spanning the whole view sorts in front of the boxes on it, and shapes that
//! interpenetrate at a contact have no correct order at all. A z-buffer of one `f32` per pixel resolves
//! both per pixel. The fill is the classic one: edge functions evaluated at pixel centres over the
//! triangle's rows, each row's covered span found from where its three edge values cross zero, with inverse
//! depth (linear in screen space) interpolated along it and tested.

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

/// Twice the signed area of (a, b, p): positive when p is to one side of a→b. In f64: a ground face
/// clipped at the near plane reaches pixel coordinates of 10⁵ and more, where f32 edge values along a shared
/// edge round to a negative on both sides and leave holes between the two triangles.
fn edge(a: ScreenVertex, b: ScreenVertex, x: f64, y: f64) -> f64 {
    let (ax, ay, bx, by) = (
        f64::from(a.x),
        f64::from(a.y),
        f64::from(b.x),
        f64::from(b.y),
    );
    (bx - ax) * (y - ay) - (by - ay) * (x - ax)
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
        let finite =
            |v: &ScreenVertex| v.x.is_finite() && v.y.is_finite() && v.inv_depth.is_finite();
        if !v.iter().all(finite) {
            return;
        }
        let [a, mut b, mut c] = v;
        let mut area = edge(a, b, f64::from(c.x), f64::from(c.y));
        if !(area.is_finite() && area.abs() > f64::from(f32::EPSILON)) {
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
        // wa is the weight of a (the edge b→c), and so on; along a row each is linear in the pixel index k
        // from x0: w(k) = w(0) + step·k, and so is the inverse depth (wa·za + wb·zb + wc·zc)/area.
        let steps = [
            f64::from(b.y) - f64::from(c.y),
            f64::from(c.y) - f64::from(a.y),
            f64::from(a.y) - f64::from(b.y),
        ];
        let z = [a, b, c].map(|v| f64::from(v.inv_depth));
        let z_step = (steps[0] * z[0] + steps[1] * z[1] + steps[2] * z[2]) * inv_area;
        let px = x0 as f64 + 0.5;
        let last = (x1 - x0 - 1) as f64;
        let pixel = [colour.r, colour.g, colour.b, 255];
        for y in y0..y1 {
            // Each row starts from the exact edge values, so no stepping error piles up down the triangle.
            let py = y as f64 + 0.5;
            let w = [edge(b, c, px, py), edge(c, a, px, py), edge(a, b, px, py)];
            // The pixels of the row inside all three edges: w(k) ≥ 0 bounds k from below where the edge
            // value grows along the row and from above where it falls.
            let (mut lo, mut hi) = (0.0f64, last);
            for (w, step) in w.iter().zip(steps) {
                if step > 0.0 {
                    lo = lo.max((-w / step).ceil());
                } else if step < 0.0 {
                    hi = hi.min((w / -step).floor());
                } else if *w < 0.0 {
                    hi = -1.0;
                }
            }
            if lo > hi {
                continue;
            }
            let (lo, hi) = (lo as usize, hi as usize);
            let z_row = (w[0] * z[0] + w[1] * z[1] + w[2] * z[2]) * inv_area;
            let start = y * self.width + x0;
            let (Some(depths), Some(colours)) = (
                self.inv_depth.get_mut(start + lo..=start + hi),
                self.rgba.get_mut(4 * (start + lo)..4 * (start + hi + 1)),
            ) else {
                continue;
            };
            for (k, (depth, out)) in depths
                .iter_mut()
                .zip(colours.chunks_exact_mut(4))
                .enumerate()
            {
                let inv_depth = (z_row + z_step * (lo + k) as f64) as f32;
                if inv_depth > *depth {
                    *depth = inv_depth;
                    out.copy_from_slice(&pixel);
                }
            }
        }
    }
}
