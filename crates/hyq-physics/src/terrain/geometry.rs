//! How far a shape is above the ground: exact for points and spheres, bounded from both sides
//! for the other primitives.
//!
//! On flat ground a shape's clearance is its lowest point's height
//! ([`Shape::lowest_z`](crate::Shape::lowest_z)). Over a height field it is the shortest
//! distance between the shape and the triangulated surface (negative when the shape reaches
//! below it): exact for a point or a sphere (the feet), and for a box, capsule or cylinder
//! bracketed by a lower and an upper bound ([`Clearance`]) that meet when the shape is over a
//! flat patch. A test that a contact flag is off needs the lower bound above the contact
//! distance; a test that it is on needs the upper bound at or below zero; a simulator that
//! adds contacts within the contact distance (DART) uses the upper bound, so it never adds one
//! for a shape farther away.

use nalgebra::{Isometry3, Point3, Vector3};

use super::{HeightGrid, Terrain};
use crate::model::Shape;

/// How far a shape is above the ground (m): the true clearance lies in [lower, upper].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Clearance {
    /// At most the true clearance.
    pub lower: f64,
    /// At least the true clearance.
    pub upper: f64,
}

impl Clearance {
    fn exact(value: f64) -> Self {
        Self {
            lower: value,
            upper: value,
        }
    }
}

/// How far (m) beyond a shape's horizontal extent the lower bound first looks for ground:
/// ground farther out than this is at least this far away.
const LOWER_BOUND_REACH_M: f64 = 0.02;

impl Terrain {
    /// The clearance of `shape` at `pose` (world frame) above this ground.
    pub fn clearance(&self, shape: &Shape, pose: &Isometry3<f64>) -> Clearance {
        match self {
            Terrain::Flat => Clearance::exact(shape.lowest_z(pose)),
            Terrain::Field(grid) => grid.clearance(shape, pose),
        }
    }
}

impl Terrain {
    /// Whether `shape` at `pose` is surely within `distance` (m) of this ground: its
    /// clearance's upper bound is at most `distance` (on flat ground: its lowest point is at
    /// most `distance` high). Quick when the shape is above the field's highest point.
    pub fn within(&self, shape: &Shape, pose: &Isometry3<f64>, distance: f64) -> bool {
        match self {
            Terrain::Flat => shape.lowest_z(pose) <= distance,
            Terrain::Field(grid) => {
                let lowest = shape.lowest_z(pose);
                if lowest - grid.max_height() > distance {
                    return false;
                }
                if let Shape::Sphere { radius } = *shape {
                    let centre = Point3::from(pose.translation.vector);
                    return grid.point_distance(&centre) - radius <= distance;
                }
                grid.lower_clearance(shape, pose, lowest) <= distance
                    && grid.upper_clearance(shape, pose) <= distance
            }
        }
    }
}

impl HeightGrid {
    /// The signed distance (m) from `p` to the surface: positive above it, negative below.
    /// Outside the grid's rectangle, the distance to the surface's nearest part.
    pub fn point_distance(&self, p: &Point3<f64>) -> f64 {
        let [x0, y0] = self.origin();
        let [sx, sy] = self.size();
        let nearest_xy = [p.x.clamp(x0, x0 + sx), p.y.clamp(y0, y0 + sy)];
        let h = self.height_at(nearest_xy[0], nearest_xy[1]);
        let surface_point = Point3::new(nearest_xy[0], nearest_xy[1], h);
        // Some surface point is this close, so no nearer one lies farther out horizontally.
        let reach = (p - surface_point).norm();
        let (columns, rows) = self.cells_in([p.x - reach, p.x + reach], [p.y - reach, p.y + reach]);
        let mut best = reach;
        for k in rows {
            for c in columns.clone() {
                for [a, b, t] in self.cell_triangles(c, k) {
                    best = best.min((p - closest_on_triangle(p, &a, &b, &t)).norm());
                }
            }
        }
        if p.z >= h { best } else { -best }
    }

    /// The highest height among the cells meeting the rectangle [x] × [y].
    pub fn max_height_in(&self, x: [f64; 2], y: [f64; 2]) -> f64 {
        let (columns, rows) = self.cells_in(x, y);
        let mut top = f64::NEG_INFINITY;
        for k in rows.start..=rows.end {
            for c in columns.start..=columns.end {
                top = top.max(self.height(c, k));
            }
        }
        top
    }

    /// See [`Terrain::clearance`].
    fn clearance(&self, shape: &Shape, pose: &Isometry3<f64>) -> Clearance {
        if let Shape::Sphere { radius } = *shape {
            let centre = Point3::from(pose.translation.vector);
            return Clearance::exact(self.point_distance(&centre) - radius);
        }
        let lower = self.lower_clearance(shape, pose, shape.lowest_z(pose));
        let upper = self.upper_clearance(shape, pose);
        Clearance {
            lower: lower.min(upper),
            upper,
        }
    }

    /// A lower bound on a shape's clearance (`lowest`: its lowest point's height): ground
    /// beyond [`LOWER_BOUND_REACH_M`] of its horizontal extent is at least that far away, and
    /// the ground within it at most as high as its highest sample there.
    fn lower_clearance(&self, shape: &Shape, pose: &Isometry3<f64>, lowest: f64) -> f64 {
        let (lo, hi) = horizontal_extent(shape, pose);
        let mut reach = LOWER_BOUND_REACH_M;
        let mut bound = f64::NEG_INFINITY;
        // A shape higher above the ground than the reach can look farther out; the ground's
        // top only rises with the reach, so the bound only improves while the gap exceeds it.
        for _ in 0..3 {
            let top =
                self.max_height_in([lo.x - reach, hi.x + reach], [lo.y - reach, hi.y + reach]);
            bound = bound.max((lowest - top).min(reach));
            if lowest - top <= reach {
                break;
            }
            reach = lowest - top;
        }
        bound
    }

    /// An upper bound on a shape's clearance: the smallest height above the surface of the
    /// points of the shape where it may come closest to it.
    fn upper_clearance(&self, shape: &Shape, pose: &Isometry3<f64>) -> f64 {
        sample_points(shape, pose, self)
            .iter()
            .map(|p| self.gap(p))
            .fold(f64::INFINITY, f64::min)
    }

    /// An upper bound on the signed distance from `p` to the surface: its height above the
    /// surface point under it (over the grid), else the distance to the nearest edge point.
    fn gap(&self, p: &Point3<f64>) -> f64 {
        if self.contains(p.x, p.y) {
            return p.z - self.height_at(p.x, p.y);
        }
        let [x0, y0] = self.origin();
        let [sx, sy] = self.size();
        let (x, y) = (p.x.clamp(x0, x0 + sx), p.y.clamp(y0, y0 + sy));
        let h = self.height_at(x, y);
        let d = (p - Point3::new(x, y, h)).norm();
        if p.z >= h { d } else { -d }
    }
}

/// The shape's horizontal bounding rectangle: its lowest and highest x and y (z unused).
fn horizontal_extent(shape: &Shape, pose: &Isometry3<f64>) -> (Point3<f64>, Point3<f64>) {
    let lo = Point3::new(
        support(shape, pose, &-Vector3::x()).x,
        support(shape, pose, &-Vector3::y()).y,
        0.0,
    );
    let hi = Point3::new(
        support(shape, pose, &Vector3::x()).x,
        support(shape, pose, &Vector3::y()).y,
        0.0,
    );
    (lo, hi)
}

/// The point of `shape` at `pose` farthest along `dir` (a support point).
pub(crate) fn support(shape: &Shape, pose: &Isometry3<f64>, dir: &Vector3<f64>) -> Point3<f64> {
    let local = pose.rotation.inverse() * dir;
    let sign = |v: f64| if v >= 0.0 { 1.0 } else { -1.0 };
    let radial = |v: Vector3<f64>| v.try_normalize(1e-12).unwrap_or_else(Vector3::zeros);
    let p: Vector3<f64> = match *shape {
        Shape::Sphere { radius } => radial(local) * radius,
        Shape::Box { half_extents } => Vector3::new(
            sign(local.x) * half_extents.x,
            sign(local.y) * half_extents.y,
            sign(local.z) * half_extents.z,
        ),
        Shape::Capsule {
            radius,
            half_length,
        } => Vector3::new(0.0, 0.0, sign(local.z) * half_length) + radial(local) * radius,
        Shape::Cylinder {
            radius,
            half_length,
        } => {
            Vector3::new(0.0, 0.0, sign(local.z) * half_length)
                + radial(Vector3::new(local.x, local.y, 0.0)) * radius
        }
    };
    pose * Point3::from(p)
}

/// Points on `shape`'s surface where it may come closest to the ground: its lowest point, a
/// box's corners and the points of its bottom above each grid height beneath it, a capsule's
/// and a cylinder's lowest points along their length at the grid's spacing.
fn sample_points(shape: &Shape, pose: &Isometry3<f64>, grid: &HeightGrid) -> Vec<Point3<f64>> {
    let mut points = vec![support(shape, pose, &-Vector3::z())];
    let [dx, dy] = grid.spacing();
    let step = 0.5 * dx.min(dy);
    match *shape {
        Shape::Box { half_extents } => {
            for i in 0..8 {
                let corner = Vector3::new(
                    if i & 1 == 0 { -1.0 } else { 1.0 } * half_extents.x,
                    if i & 2 == 0 { -1.0 } else { 1.0 } * half_extents.y,
                    if i & 4 == 0 { -1.0 } else { 1.0 } * half_extents.z,
                );
                points.push(pose * Point3::from(corner));
            }
            box_bottom_over_grid(&half_extents, pose, grid, &mut points);
        }
        Shape::Capsule {
            radius,
            half_length,
        } => {
            // Each point of the axis carries a sphere whose lowest point is `radius` below it.
            for axis_point in axis_points(half_length, step, pose) {
                points.push(axis_point - Vector3::z() * radius);
            }
        }
        Shape::Cylinder {
            radius,
            half_length,
        } => {
            // Each point of the axis carries a disc whose lowest point is `radius` away from it,
            // straight down within the disc's plane.
            let axis = pose.rotation * Vector3::z();
            let down = -Vector3::z();
            let radial = (down - axis * axis.dot(&down))
                .try_normalize(1e-12)
                .unwrap_or_else(Vector3::zeros);
            for axis_point in axis_points(half_length, step, pose) {
                points.push(axis_point + radial * radius);
            }
        }
        Shape::Sphere { .. } => {}
    }
    points
}

/// Points along a shape's local z axis from −`half_length` to +`half_length`, at most `step`
/// apart (at most 1001 of them), in the world.
fn axis_points(half_length: f64, step: f64, pose: &Isometry3<f64>) -> Vec<Point3<f64>> {
    let n = ((2.0 * half_length / step).ceil() as usize).clamp(1, 1000);
    (0..=n)
        .map(|i| {
            pose * Point3::new(
                0.0,
                0.0,
                -half_length + 2.0 * half_length * i as f64 / n as f64,
            )
        })
        .collect()
}

/// For each grid height under a box's horizontal extent, the point of the box's lower surface
/// right above it (where a vertical line through it enters the box), if any.
fn box_bottom_over_grid(
    half: &Vector3<f64>,
    pose: &Isometry3<f64>,
    grid: &HeightGrid,
    out: &mut Vec<Point3<f64>>,
) {
    let shape = Shape::Box {
        half_extents: *half,
    };
    let (lo, hi) = horizontal_extent(&shape, pose);
    let (columns, rows) = grid.cells_in([lo.x, hi.x], [lo.y, hi.y]);
    // Cap the work for a box far larger than the grid's cells.
    if columns.len() * rows.len() > 40_000 {
        return;
    }
    let inverse = pose.inverse();
    let up = inverse.rotation * Vector3::z();
    for k in rows.start..=rows.end {
        for c in columns.start..=columns.end {
            let ground = grid.point(c, k);
            // The vertical line through this grid point, in the box's frame: o + t·up.
            let o = inverse * Point3::new(ground.x, ground.y, 0.0);
            if let Some(t) = slab_entry(&o, &up, half) {
                out.push(Point3::new(ground.x, ground.y, t));
            }
        }
    }
}

/// Where the line o + t·d (box frame) first enters the box of half extents `half`: the
/// smallest t, or `None` if it misses.
fn slab_entry(o: &Point3<f64>, d: &Vector3<f64>, half: &Vector3<f64>) -> Option<f64> {
    let (mut enter, mut leave) = (f64::NEG_INFINITY, f64::INFINITY);
    for i in 0..3 {
        if d[i].abs() < 1e-12 {
            if o[i].abs() > half[i] {
                return None;
            }
            continue;
        }
        let a = (-half[i] - o[i]) / d[i];
        let b = (half[i] - o[i]) / d[i];
        enter = enter.max(a.min(b));
        leave = leave.min(a.max(b));
    }
    (enter <= leave).then_some(enter)
}

/// The point of triangle (a, b, c) closest to `p` (by the triangle's Voronoi regions: its
/// vertices, edges and face).
pub(crate) fn closest_on_triangle(
    p: &Point3<f64>,
    a: &Point3<f64>,
    b: &Point3<f64>,
    c: &Point3<f64>,
) -> Point3<f64> {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return *a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return *b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + ab * (d1 / (d1 - d3));
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return *c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + ac * (d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}
