//! Small geometry helpers for the renderer: near-plane clipping, 2-D convex hulls and circle
//! outlines. They write into caller-owned buffers so that a frame reuses its allocations.

use hyq_physics::na::Vector3;

use crate::camera::NEAR_PLANE_M;

/// Clips a polygon given in camera coordinates (z = depth) to the half-space in front of the
/// near plane (Sutherland–Hodgman against one plane). `out` is cleared first; it holds fewer
/// than 3 points when nothing of the polygon is in front of the camera.
pub(crate) fn clip_polygon_near(polygon: &[Vector3<f64>], out: &mut Vec<Vector3<f64>>) {
    out.clear();
    let Some(&last) = polygon.last() else {
        return;
    };
    let inside = |p: &Vector3<f64>| p.z >= NEAR_PLANE_M;
    let mut prev = last;
    for &cur in polygon {
        match (inside(&prev), inside(&cur)) {
            (true, true) => out.push(cur),
            (true, false) => out.push(near_crossing(&prev, &cur)),
            (false, true) => {
                out.push(near_crossing(&prev, &cur));
                out.push(cur);
            }
            (false, false) => {}
        }
        prev = cur;
    }
}

/// Clips a segment given in camera coordinates to the near plane; `None` if it lies wholly
/// behind it.
pub(crate) fn clip_segment_near(
    a: Vector3<f64>,
    b: Vector3<f64>,
) -> Option<(Vector3<f64>, Vector3<f64>)> {
    match (a.z >= NEAR_PLANE_M, b.z >= NEAR_PLANE_M) {
        (true, true) => Some((a, b)),
        (true, false) => Some((a, near_crossing(&a, &b))),
        (false, true) => Some((near_crossing(&a, &b), b)),
        (false, false) => None,
    }
}

/// The point where segment a–b crosses the near plane (one end in front of it, one behind).
fn near_crossing(a: &Vector3<f64>, b: &Vector3<f64>) -> Vector3<f64> {
    let t = (NEAR_PLANE_M - a.z) / (b.z - a.z);
    a + (b - a) * t
}

/// The convex hull of `points` in counter-clockwise order (x right, y up), by Andrew's
/// monotone chain. `points` is sorted in place; `out` is cleared first.
pub(crate) fn convex_hull(points: &mut [[f64; 2]], out: &mut Vec<[f64; 2]>) {
    out.clear();
    points.sort_unstable_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    if points.len() < 3 {
        out.extend_from_slice(points);
        return;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    // Lower hull, left to right.
    for &p in points.iter() {
        while out.len() >= 2 && cross(out[out.len() - 2], out[out.len() - 1], p) <= 0.0 {
            out.pop();
        }
        out.push(p);
    }
    // Upper hull, right to left; the last point repeats the first and is dropped.
    let lower_len = out.len() + 1;
    for &p in points.iter().rev().skip(1) {
        while out.len() >= lower_len && cross(out[out.len() - 2], out[out.len() - 1], p) <= 0.0 {
            out.pop();
        }
        out.push(p);
    }
    out.pop();
}

/// Appends `n` points of the circle of `radius` around `centre`, counter-clockwise from angle 0.
pub(crate) fn push_circle_points(centre: [f64; 2], radius: f64, n: usize, out: &mut Vec<[f64; 2]>) {
    for i in 0..n {
        let a = std::f64::consts::TAU * i as f64 / n as f64;
        out.push([centre[0] + radius * a.cos(), centre[1] + radius * a.sin()]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hull_of_a_square_with_an_inner_point_is_the_square_counter_clockwise() {
        let mut pts = [[0.0, 0.0], [1.0, 1.0], [0.5, 0.5], [1.0, 0.0], [0.0, 1.0]];
        let mut hull = Vec::new();
        convex_hull(&mut pts, &mut hull);
        assert_eq!(hull, vec![[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]]);
    }

    #[test]
    fn polygon_straddling_the_near_plane_is_cut_at_it() {
        let square = [
            Vector3::new(-1.0, 0.0, -1.0),
            Vector3::new(1.0, 0.0, -1.0),
            Vector3::new(1.0, 0.0, 1.0),
            Vector3::new(-1.0, 0.0, 1.0),
        ];
        let mut out = Vec::new();
        clip_polygon_near(&square, &mut out);
        assert_eq!(out.len(), 4);
        assert!(out.iter().all(|p| p.z >= NEAR_PLANE_M - 1e-12));
        assert!(out.iter().any(|p| (p.z - NEAR_PLANE_M).abs() < 1e-12));
        let behind: Vec<_> = square
            .iter()
            .map(|p| p - Vector3::new(0.0, 0.0, 5.0))
            .collect();
        clip_polygon_near(&behind, &mut out);
        assert!(out.is_empty());
    }
}
