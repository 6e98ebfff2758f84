//! Contacts and joints drawn over the solids with tiny-skia (anti-aliased strokes and dots, no depth test:
//! they are meant to be seen through what hides them). Segments crossing the near plane are clipped first;
//! points that are not finite are left out (tiny-skia refuses a whole path with one of them).

use rebound::prelude::Vec3;
use tiny_skia::{FillRule, Paint, PathBuilder, Pixmap, Stroke, Transform};

use crate::camera::{NEAR_PLANE, Projection};
use crate::{RenderScene, Rgba};

/// Dot radius of a contact point or joint anchor (pixels).
const DOT_RADIUS: f32 = 2.5;
/// Stroke width of normals and joint segments (pixels).
const LINE_WIDTH: f32 = 1.5;

/// The part of the world segment a→b in front of the near plane, on the picture (pixels).
fn clip_segment(projection: &Projection, a: Vec3, b: Vec3) -> Option<((f32, f32), (f32, f32))> {
    let (mut va, mut vb) = (projection.to_view(a), projection.to_view(b));
    if !(va.is_finite() && vb.is_finite()) || (va.z < NEAR_PLANE && vb.z < NEAR_PLANE) {
        return None;
    }
    if va.z < NEAR_PLANE {
        va = va.lerp(vb, (NEAR_PLANE - va.z) / (vb.z - va.z));
    } else if vb.z < NEAR_PLANE {
        vb = vb.lerp(va, (NEAR_PLANE - vb.z) / (va.z - vb.z));
    }
    Some((projection.view_to_pixel(va), projection.view_to_pixel(vb)))
}

/// Paint of `colour`, anti-aliased.
fn paint(colour: Rgba) -> Paint<'static> {
    let mut paint = Paint::default();
    paint.set_color(colour.to_skia());
    paint.anti_alias = true;
    paint
}

/// Draws `segments` (world, m) as strokes and `dots` (world, m) as filled circles in `colour`.
fn draw(
    pixmap: &mut Pixmap,
    projection: &Projection,
    segments: &[(Vec3, Vec3)],
    dots: &[Vec3],
    colour: Rgba,
) {
    let paint = paint(colour);
    let mut lines = PathBuilder::new();
    for &(a, b) in segments {
        if let Some(((xa, ya), (xb, yb))) = clip_segment(projection, a, b) {
            lines.move_to(xa, ya);
            lines.line_to(xb, yb);
        }
    }
    let stroke = Stroke {
        width: LINE_WIDTH,
        ..Stroke::default()
    };
    if let Some(path) = lines.finish() {
        pixmap.stroke_path(&path, &paint, &stroke, Transform::identity(), None);
    }
    let mut circles = PathBuilder::new();
    for &p in dots {
        if let Some((x, y, _)) = projection.project(p)
            && x.is_finite()
            && y.is_finite()
        {
            circles.push_circle(x, y, DOT_RADIUS);
        }
    }
    if let Some(path) = circles.finish() {
        pixmap.fill_path(
            &path,
            &paint,
            FillRule::Winding,
            Transform::identity(),
            None,
        );
    }
}

/// Draws the scene's contacts (dot and a normal `normal_length` m long) in `colour`.
pub(crate) fn draw_contacts(
    pixmap: &mut Pixmap,
    projection: &Projection,
    scene: &RenderScene,
    normal_length: f32,
    colour: Rgba,
) {
    let segments: Vec<_> = scene
        .contacts
        .iter()
        .map(|c| (c.point, c.point + c.normal * normal_length))
        .collect();
    let dots: Vec<_> = scene.contacts.iter().map(|c| c.point).collect();
    draw(pixmap, projection, &segments, &dots, colour);
}

/// Draws the scene's joints (segment and a dot at each anchor) in `colour`.
pub(crate) fn draw_joints(
    pixmap: &mut Pixmap,
    projection: &Projection,
    scene: &RenderScene,
    colour: Rgba,
) {
    let segments: Vec<_> = scene
        .joints
        .iter()
        .map(|j| (j.anchor_a, j.anchor_b))
        .collect();
    let dots: Vec<_> = scene
        .joints
        .iter()
        .flat_map(|j| [j.anchor_a, j.anchor_b])
        .collect();
    draw(pixmap, projection, &segments, &dots, colour);
}
