//! Drawing a height field: its cells around the camera's target as flat-shaded quads, far
//! first, and the 1 m grid draped over them.
//!
//! A height grid can hold a million heights; a frame draws the cells within
//! [`TERRAIN_HALF_M`] of the camera's target, grouped into quads at least [`NEAR_QUAD_M`] across
//! (twice that beyond [`NEAR_RADIUS_M`]), each shaded by how its slope faces the light and
//! tinted by its height, so bumps, slopes and steps read at a glance. Quads are filled without
//! anti-aliasing so that neighbours meet without seams, in order of distance from the camera
//! (painter's algorithm), so nearer relief hides what is behind it.

use hyq_physics::HeightGrid;
use hyq_physics::na::{Point3, Vector3};

use crate::camera::Camera;

/// Half the side (m) of the square of terrain drawn around the camera's target.
pub(crate) const TERRAIN_HALF_M: f64 = 7.0;
/// The smallest quad drawn near the target (m): finer cells are grouped.
pub(crate) const NEAR_QUAD_M: f64 = 0.1;
/// Beyond this distance (m) from the target quads are twice as large.
pub(crate) const NEAR_RADIUS_M: f64 = 3.0;
/// How far (m) shadows, discs and rings are drawn above the surface, so none sinks into it.
pub(crate) const LIFT_M: f64 = 0.003;

/// One quad of the surface: its four corners (counter-clockwise seen from above), its shade
/// and its distance from the camera.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Quad {
    pub(crate) corners: [Point3<f64>; 4],
    /// Brightness in [0.5, 1.1] from how the quad faces the light, then tinted by height.
    pub(crate) shade: f32,
    /// How much lighter than the base colour, from the quad's height in [0, 0.35].
    pub(crate) tint: f32,
    pub(crate) depth: f64,
}

/// The quads to draw around `target`, far first, into `out` (cleared first).
pub(crate) fn quads(
    grid: &HeightGrid,
    cam: &Camera,
    target: &Point3<f64>,
    light: &Vector3<f64>,
    out: &mut Vec<Quad>,
) {
    out.clear();
    let [dx, dy] = grid.spacing();
    let near = ((NEAR_QUAD_M / dx).ceil() as usize).max(1);
    let near_y = ((NEAR_QUAD_M / dy).ceil() as usize).max(1);
    let (columns, rows) = grid.cells_in(
        [target.x - TERRAIN_HALF_M, target.x + TERRAIN_HALF_M],
        [target.y - TERRAIN_HALF_M, target.y + TERRAIN_HALF_M],
    );
    let (low, high) = (grid.min_height(), grid.max_height());
    let span = (high - low).max(1e-9);
    let last_c = grid.columns() - 1;
    let last_k = grid.rows() - 1;
    // Quads start on multiples of the near stride so that the pattern does not crawl as the
    // camera moves. Blocks of 2 × 2 near quads whose corner is beyond NEAR_RADIUS_M are drawn
    // as one far quad, so near and far quads tile without gaps.
    let mut k = rows.start - rows.start % near_y;
    while k < rows.end.min(last_k) {
        let mut c = columns.start - columns.start % near;
        while c < columns.end.min(last_c) {
            let (cb, kb) = (c - c % (2 * near), k - k % (2 * near_y));
            let block = grid.point(cb, kb);
            let far = (block.x - target.x).hypot(block.y - target.y) > NEAR_RADIUS_M;
            if far && (c != cb || k != kb) {
                c += near;
                continue;
            }
            let (sc, sk) = if far {
                (2 * near, 2 * near_y)
            } else {
                (near, near_y)
            };
            let (c1, k1) = ((c + sc).min(last_c), (k + sk).min(last_k));
            let p = [
                grid.point(c, k),
                grid.point(c1, k),
                grid.point(c1, k1),
                grid.point(c, k1),
            ];
            out.push(quad(p, cam, light, low, span));
            c += near;
        }
        k += near_y;
    }
    out.sort_unstable_by(|a, b| b.depth.total_cmp(&a.depth));
}

/// The quad of corners `p`, shaded and tinted (heights `low` .. `low + span`).
fn quad(p: [Point3<f64>; 4], cam: &Camera, light: &Vector3<f64>, low: f64, span: f64) -> Quad {
    let normal = (p[2] - p[0]).cross(&(p[3] - p[1]));
    let facing = normal
        .try_normalize(1e-12)
        .map_or(1.0, |n| n.dot(light).max(0.0));
    let centre = Point3::from((p[0].coords + p[1].coords + p[2].coords + p[3].coords) * 0.25);
    Quad {
        corners: p,
        shade: (0.55 + 0.55 * facing) as f32,
        tint: (0.35 * (centre.z - low) / span) as f32,
        depth: cam.depth(&centre),
    }
}

/// The points of a straight world line from `a` to `b` (x and y) laid on the surface, at most
/// `step` apart.
pub(crate) fn draped(
    grid: &HeightGrid,
    a: [f64; 2],
    b: [f64; 2],
    step: f64,
    out: &mut Vec<Point3<f64>>,
) {
    out.clear();
    let length = (b[0] - a[0]).hypot(b[1] - a[1]);
    let n = ((length / step).ceil() as usize).clamp(1, 4096);
    for i in 0..=n {
        let t = i as f64 / n as f64;
        let (x, y) = (a[0] + (b[0] - a[0]) * t, a[1] + (b[1] - a[1]) * t);
        out.push(Point3::new(x, y, grid.height_at(x, y) + LIFT_M));
    }
}
