//! Paths brought within the rasteriser's safe range before they are drawn.
//!
//! tiny-skia rasterises in fixed point: a path whose coordinates reach millions of pixels (a
//! huge shape right in front of the camera, projected from a few centimetres away) overflows it
//! and panics inside the library. A path inside the guard band (the frame plus
//! [`GUARD_PX`] on every side) is drawn as it is. A path beyond it is flattened (curves to
//! chords within [`FLATNESS_PX`]) and cut to the guard band: fills by clipping each closed
//! contour to the band's rectangle (Sutherland–Hodgman, exact for the polygons drawn here),
//! strokes by clipping each segment. What lies in the frame is unchanged; what lies outside it
//! was never visible.

use std::borrow::Cow;

use tiny_skia::{Path, PathBuilder, PathSegment, Point};

/// The band beyond the frame's edges (px) that paths are cut to: wide enough that every path
/// of an ordinary view is drawn as it is (the ground grid's lines reach about 1e5 px; views are
/// byte for byte what they were before the cut), small enough that the rasteriser's fixed point
/// (coordinates times 256 in an i32 when anti-aliasing) never overflows.
pub const GUARD_PX: f32 = 1_048_576.0;

/// The largest distance (px) between a flattened curve and its chords.
pub const FLATNESS_PX: f32 = 0.25;

/// The most chords one curve becomes (a circle of a million pixels needs about 2000).
const MAX_CHORDS: usize = 4096;

/// The guard band's rectangle: `[min_x, min_y, max_x, max_y]`.
fn band(width: u32, height: u32) -> [f32; 4] {
    [
        -GUARD_PX,
        -GUARD_PX,
        width as f32 + GUARD_PX,
        height as f32 + GUARD_PX,
    ]
}

/// Whether every point of `path` is finite and inside the band.
fn inside(path: &Path, rect: [f32; 4]) -> bool {
    let b = path.bounds();
    b.left() >= rect[0] && b.top() >= rect[1] && b.right() <= rect[2] && b.bottom() <= rect[3]
}

/// `path` as drawn into a `width` × `height` frame by a fill: itself when it lies in the guard
/// band, else its contours flattened and clipped to the band; `None` when nothing is left.
pub fn for_fill(path: &Path, width: u32, height: u32) -> Option<Cow<'_, Path>> {
    let rect = band(width, height);
    if inside(path, rect) {
        return Some(Cow::Borrowed(path));
    }
    let mut pb = PathBuilder::new();
    for contour in contours(path) {
        let clipped = clip_polygon(&contour, rect);
        if let Some((first, rest)) = clipped.split_first() {
            pb.move_to(first.x, first.y);
            for p in rest {
                pb.line_to(p.x, p.y);
            }
            pb.close();
        }
    }
    pb.finish().map(Cow::Owned)
}

/// `path` as drawn by a stroke (see [`for_fill`]): each of its segments clipped to the band.
pub fn for_stroke(path: &Path, width: u32, height: u32) -> Option<Cow<'_, Path>> {
    let rect = band(width, height);
    if inside(path, rect) {
        return Some(Cow::Borrowed(path));
    }
    let mut pb = PathBuilder::new();
    for contour in contours(path) {
        for pair in contour.windows(2) {
            if let Some((a, b)) = clip_segment(pair[0], pair[1], rect) {
                pb.move_to(a.x, a.y);
                pb.line_to(b.x, b.y);
            }
        }
    }
    pb.finish().map(Cow::Owned)
}

/// The path's contours as polylines, curves flattened; a closed contour ends at its start.
/// Contours holding a non-finite point are left out.
fn contours(path: &Path) -> Vec<Vec<Point>> {
    let mut out: Vec<Vec<Point>> = Vec::new();
    let mut current: Vec<Point> = Vec::new();
    let mut finish = |current: &mut Vec<Point>| {
        if current.len() >= 2 && current.iter().all(|p| p.x.is_finite() && p.y.is_finite()) {
            out.push(std::mem::take(current));
        } else {
            current.clear();
        }
    };
    for segment in path.segments() {
        match segment {
            PathSegment::MoveTo(p) => {
                finish(&mut current);
                current.push(p);
            }
            PathSegment::LineTo(p) => current.push(p),
            PathSegment::QuadTo(c, p) => {
                let from = current.last().copied().unwrap_or(p);
                flatten(
                    &mut current,
                    |t| quad(from, c, p, t),
                    quad_chords(from, c, p),
                );
            }
            PathSegment::CubicTo(c1, c2, p) => {
                let from = current.last().copied().unwrap_or(p);
                let n = cubic_chords(from, c1, c2, p);
                flatten(&mut current, |t| cubic(from, c1, c2, p, t), n);
            }
            PathSegment::Close => {
                if let Some(&start) = current.first() {
                    current.push(start);
                }
                finish(&mut current);
            }
        }
    }
    finish(&mut current);
    out
}

fn flatten(out: &mut Vec<Point>, at: impl Fn(f32) -> Point, chords: usize) {
    for i in 1..=chords {
        out.push(at(i as f32 / chords as f32));
    }
}

fn quad(a: Point, c: Point, b: Point, t: f32) -> Point {
    let u = 1.0 - t;
    Point::from_xy(
        u * u * a.x + 2.0 * u * t * c.x + t * t * b.x,
        u * u * a.y + 2.0 * u * t * c.y + t * t * b.y,
    )
}

fn cubic(a: Point, c1: Point, c2: Point, b: Point, t: f32) -> Point {
    let u = 1.0 - t;
    let (w0, w1, w2, w3) = (u * u * u, 3.0 * u * u * t, 3.0 * u * t * t, t * t * t);
    Point::from_xy(
        w0 * a.x + w1 * c1.x + w2 * c2.x + w3 * b.x,
        w0 * a.y + w1 * c1.y + w2 * c2.y + w3 * b.y,
    )
}

/// The chords that keep a curve within [`FLATNESS_PX`] of them, from a bound `dd` on its second
/// derivative: uniform steps of 1/n deviate by at most dd / (8 n²).
fn chords_for(dd: f32) -> usize {
    let n = (dd / (8.0 * FLATNESS_PX)).sqrt().ceil();
    if n.is_finite() {
        (n as usize).clamp(1, MAX_CHORDS)
    } else {
        MAX_CHORDS
    }
}

fn second_difference(a: Point, b: Point, c: Point) -> f32 {
    let (x, y) = (a.x - 2.0 * b.x + c.x, a.y - 2.0 * b.y + c.y);
    (x * x + y * y).sqrt()
}

fn quad_chords(a: Point, c: Point, b: Point) -> usize {
    chords_for(2.0 * second_difference(a, c, b))
}

fn cubic_chords(a: Point, c1: Point, c2: Point, b: Point) -> usize {
    chords_for(6.0 * second_difference(a, c1, c2).max(second_difference(c1, c2, b)))
}

/// A closed polygon (first point repeated last, or not) clipped to `rect` (Sutherland–Hodgman),
/// without the repeated point; fewer than 3 points when nothing is left.
fn clip_polygon(polygon: &[Point], rect: [f32; 4]) -> Vec<Point> {
    let mut points: Vec<Point> = polygon.to_vec();
    if points.len() >= 2 && points.first() == points.last() {
        points.pop();
    }
    // Each edge of the rectangle as (axis, limit, keep the side above the limit).
    for (axis, limit, keep_above) in [
        (0, rect[0], true),
        (0, rect[2], false),
        (1, rect[1], true),
        (1, rect[3], false),
    ] {
        let coord = |p: &Point| if axis == 0 { p.x } else { p.y };
        let keeps = |p: &Point| {
            if keep_above {
                coord(p) >= limit
            } else {
                coord(p) <= limit
            }
        };
        let mut next = Vec::with_capacity(points.len() + 4);
        for (i, p) in points.iter().enumerate() {
            let prev = points[(i + points.len() - 1) % points.len()];
            let (p_in, prev_in) = (keeps(p), keeps(&prev));
            if p_in != prev_in {
                let t = (limit - coord(&prev)) / (coord(p) - coord(&prev));
                next.push(Point::from_xy(
                    prev.x + t * (p.x - prev.x),
                    prev.y + t * (p.y - prev.y),
                ));
            }
            if p_in {
                next.push(*p);
            }
        }
        points = next;
        if points.is_empty() {
            break;
        }
    }
    if points.len() < 3 {
        points.clear();
    }
    points
}

/// The part of segment `a`–`b` inside `rect` (Liang–Barsky), if any.
fn clip_segment(a: Point, b: Point, rect: [f32; 4]) -> Option<(Point, Point)> {
    let (dx, dy) = (b.x - a.x, b.y - a.y);
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for (p, q) in [
        (-dx, a.x - rect[0]),
        (dx, rect[2] - a.x),
        (-dy, a.y - rect[1]),
        (dy, rect[3] - a.y),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then(|| {
        (
            Point::from_xy(a.x + t0 * dx, a.y + t0 * dy),
            Point::from_xy(a.x + t1 * dx, a.y + t1 * dy),
        )
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_path_in_the_band_is_drawn_as_it_is() {
        let path = PathBuilder::from_circle(10.0, 10.0, 5.0).expect("circle");
        assert!(matches!(for_fill(&path, 64, 64), Some(Cow::Borrowed(_))));
    }

    #[test]
    fn a_huge_circle_is_cut_to_the_band_and_keeps_its_edge_in_the_frame() {
        // A circle of radius 1e8 px whose edge crosses the frame at x = 32.
        let path = PathBuilder::from_circle(32.0 - 1e8, 32.0, 1e8).expect("circle");
        let cut = for_fill(&path, 64, 64).expect("something is left");
        let b = cut.bounds();
        assert!(b.left() >= -GUARD_PX && b.right() <= 40.0, "{b:?}");
        let stroke = for_stroke(&path, 64, 64).expect("something is left");
        assert!(stroke.bounds().top() >= -GUARD_PX, "{:?}", stroke.bounds());
    }

    #[test]
    fn a_polygon_wholly_outside_the_band_leaves_nothing() {
        let mut pb = PathBuilder::new();
        pb.move_to(1e8, 1e8);
        pb.line_to(1e8 + 10.0, 1e8);
        pb.line_to(1e8, 1e8 + 10.0);
        pb.close();
        let path = pb.finish().expect("path");
        assert!(for_fill(&path, 64, 64).is_none());
    }
}
