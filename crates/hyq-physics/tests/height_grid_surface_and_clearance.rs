//! A height grid's surface is its cells split along the (x₀, y₀)–(x₁, y₁) diagonal into flat
//! triangles: `height_at` interpolates on exactly those triangles (exact at the samples,
//! continuous across every edge, clamped to the nearest edge outside), `point_distance` is the
//! exact distance to them (checked against every triangle), and the clearance bounds of a
//! shape bracket its distance (equal for a sphere, meeting on a flat patch for a box).

use hyq_physics::na::{Isometry3, Point3, UnitQuaternion, Vector3};
use hyq_physics::terrain::HeightGrid;
use hyq_physics::{Shape, Terrain};
use proptest::prelude::*;

/// A 4 × 3 grid of distinct heights over [−1.5, 1.5] × [−1, 1] (spacing 1 m).
fn small() -> HeightGrid {
    let heights = vec![
        0.0, 0.1, 0.3, 0.2, // row 0, y = −1
        0.4, 0.0, 0.5, 0.1, // row 1, y = 0
        0.2, 0.6, 0.1, 0.3, // row 2, y = 1
    ];
    HeightGrid::new([0.0, 0.0], [3.0, 2.0], 4, 3, heights).expect("a valid grid")
}

#[test]
fn samples_sit_where_the_layout_says() {
    let g = small();
    assert_eq!(g.spacing(), [1.0, 1.0]);
    assert_eq!(g.origin(), [-1.5, -1.0]);
    for k in 0..3 {
        for c in 0..4 {
            let p = g.point(c, k);
            assert_eq!((p.x, p.y), (-1.5 + c as f64, -1.0 + k as f64));
            assert_eq!(g.height_at(p.x, p.y), g.height(c, k), "sample ({c}, {k})");
        }
    }
    assert_eq!((g.min_height(), g.max_height()), (0.0, 0.6));
}

#[test]
fn each_cell_splits_along_its_rising_diagonal() {
    let g = small();
    // Cell (0, 0): corners h00 = 0, h10 = 0.1, h01 = 0.4, h11 = 0.0. Below the diagonal
    // (u > v) the plane through h00, h10, h11; above it the plane through h00, h01, h11.
    let (x0, y0) = (-1.5, -1.0);
    let below = g.height_at(x0 + 0.75, y0 + 0.25);
    assert!(
        (below - (0.0 + 0.75 * 0.1 + 0.25 * (0.0 - 0.1))).abs() < 1e-12,
        "{below}"
    );
    let above = g.height_at(x0 + 0.25, y0 + 0.75);
    assert!(
        (above - (0.0 + 0.75 * 0.4 + 0.25 * (0.0 - 0.4))).abs() < 1e-12,
        "{above}"
    );
    // On the diagonal both planes agree: the average of its ends at its middle.
    assert!((g.height_at(x0 + 0.5, y0 + 0.5) - 0.0).abs() < 1e-12);
    // The other diagonal would put the cell's middle at (0.1 + 0.4) / 2.
    assert!((g.height_at(x0 + 0.5, y0 + 0.5) - 0.25).abs() > 0.2);
}

#[test]
fn outside_the_rectangle_the_nearest_edge_answers() {
    let g = small();
    assert!(!g.contains(-1.6, 0.0) && g.contains(-1.5, 0.0) && g.contains(1.5, 1.0));
    assert_eq!(g.height_at(-7.0, -9.0), g.height(0, 0));
    assert_eq!(g.height_at(9.0, 0.0), g.height(3, 1));
    assert_eq!(g.height_at(0.5, 5.0), g.height_at(0.5, 1.0));
    assert!(g.height_at(f64::NAN, 0.0).is_finite());
}

/// The distance from `p` to the surface by brute force over every triangle.
fn brute_distance(g: &HeightGrid, p: &Point3<f64>) -> f64 {
    let mut best = f64::INFINITY;
    for k in 0..g.rows() - 1 {
        for c in 0..g.columns() - 1 {
            for [a, b, t] in g.cell_triangles(c, k) {
                // Dense barycentric sampling: good to well under a millimetre here.
                let n = 200;
                for i in 0..=n {
                    for j in 0..=(n - i) {
                        let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                        let q = a + (b - a) * u + (t - a) * v;
                        best = best.min((p - q).norm());
                    }
                }
            }
        }
    }
    best
}

#[test]
fn point_distance_is_the_distance_to_the_triangles() {
    let g = small();
    for p in [
        Point3::new(0.2, 0.3, 0.9),
        Point3::new(-1.2, -0.7, 0.35),
        Point3::new(1.4, 0.9, 0.31),
        Point3::new(-0.5, 0.5, 0.05),
    ] {
        let d = g.point_distance(&p);
        let brute = brute_distance(&g, &p);
        assert!(
            (d.abs() - brute).abs() < 5e-3,
            "{p}: {d} vs brute force {brute}"
        );
        assert_eq!(d >= 0.0, p.z >= g.height_at(p.x, p.y), "{p}: sign of {d}");
        assert!(
            d.abs() <= brute + 1e-12,
            "{p}: exact {d} above the sampled {brute}"
        );
    }
}

#[test]
fn on_a_plane_slope_the_distance_is_the_normal_distance() {
    // z = 0.2 x: every cell is the same plane.
    let n = 11;
    let heights = (0..n * n)
        .map(|i| 0.2 * (-1.0 + 0.2 * (i % n) as f64))
        .collect();
    let g = HeightGrid::new([0.0, 0.0], [2.0, 2.0], n, n, heights).expect("valid");
    let cos = 1.0 / (1.0f64 + 0.04).sqrt();
    for (x, y, gap) in [(0.1, 0.2, 0.3), (-0.33, 0.5, 0.05), (0.4, -0.45, -0.02)] {
        let p = Point3::new(x, y, 0.2 * x + gap);
        let d = g.point_distance(&p);
        assert!(
            (d - gap * cos).abs() < 1e-12,
            "({x}, {y}): {d} vs {}",
            gap * cos
        );
    }
}

#[test]
fn a_sphere_is_exact_and_a_box_is_bracketed() {
    let g = small();
    let terrain = Terrain::field(g.clone());
    let sphere = Shape::Sphere { radius: 0.1 };
    let at = Isometry3::translation(0.2, 0.3, 0.9);
    let c = terrain.clearance(&sphere, &at);
    assert_eq!(c.lower, c.upper);
    assert!((c.lower - (g.point_distance(&Point3::new(0.2, 0.3, 0.9)) - 0.1)).abs() < 1e-15);
    let block = Shape::Box {
        half_extents: Vector3::new(0.3, 0.2, 0.1),
    };
    for (x, y, z, yaw) in [
        (0.2, 0.3, 1.2, 0.3),
        (-1.0, -0.5, 0.6, 1.0),
        (1.0, 0.4, 0.8, 0.0),
    ] {
        let pose = Isometry3::from_parts(
            Vector3::new(x, y, z).into(),
            UnitQuaternion::from_euler_angles(0.1, -0.2, yaw),
        );
        let c = terrain.clearance(&block, &pose);
        // The true distance, by sampling the box's surface densely.
        let mut truth = f64::INFINITY;
        let n = 24;
        for i in 0..=n {
            for j in 0..=n {
                let (a, b) = (
                    -1.0 + 2.0 * i as f64 / n as f64,
                    -1.0 + 2.0 * j as f64 / n as f64,
                );
                for face in [
                    Vector3::new(a, b, 1.0),
                    Vector3::new(a, b, -1.0),
                    Vector3::new(a, 1.0, b),
                    Vector3::new(a, -1.0, b),
                    Vector3::new(1.0, a, b),
                    Vector3::new(-1.0, a, b),
                ] {
                    let q = pose * Point3::from(face.component_mul(&Vector3::new(0.3, 0.2, 0.1)));
                    truth = truth.min(g.point_distance(&q));
                }
            }
        }
        assert!(
            c.lower <= truth + 1e-9,
            "({x}, {y}): lower {} above {truth}",
            c.lower
        );
        assert!(
            c.upper >= truth - 1e-9,
            "({x}, {y}): upper {} below {truth}",
            c.upper
        );
    }
    // Level over a level patch, the bounds meet at the gap.
    let level = HeightGrid::new([0.0, 0.0], [2.0, 2.0], 3, 3, vec![0.1; 9]).expect("valid");
    let c = Terrain::field(level).clearance(&block, &Isometry3::translation(0.1, 0.0, 0.25));
    assert!(
        (c.lower - 0.05).abs() < 1e-12 && (c.upper - 0.05).abs() < 1e-12,
        "{c:?}"
    );
}

#[test]
fn flat_ground_is_the_lowest_point() {
    let block = Shape::Box {
        half_extents: Vector3::new(0.3, 0.2, 0.1),
    };
    let pose = Isometry3::from_parts(
        Vector3::new(0.0, 0.0, 0.5).into(),
        UnitQuaternion::from_euler_angles(0.3, 0.1, 0.0),
    );
    let c = Terrain::Flat.clearance(&block, &pose);
    assert_eq!(
        (c.lower, c.upper),
        (block.lowest_z(&pose), block.lowest_z(&pose))
    );
    assert_eq!(Terrain::Flat.height_at(3.0, -2.0), 0.0);
    assert!(Terrain::Flat.contains(1e6, -1e6));
}

proptest! {
    /// The surface is continuous: two points a micrometre apart anywhere (across cell edges
    /// and diagonals included) differ in height by at most the steepest gradient times that.
    #[test]
    fn the_surface_is_continuous(x in -1.6f64..1.6, y in -1.1f64..1.1, a in 0.0f64..6.3) {
        let g = small();
        let e = 1e-6;
        let (x2, y2) = (x + e * a.cos(), y + e * a.sin());
        let jump = (g.height_at(x, y) - g.height_at(x2, y2)).abs();
        prop_assert!(jump <= g.steepest_gradient() * e * 1.0001 + 1e-15, "jump {jump}");
    }

    /// The exact distance is never above the vertical gap, and has its sign.
    #[test]
    fn distance_is_at_most_the_vertical_gap(x in -1.5f64..1.5, y in -1.0f64..1.0, gap in -0.3f64..0.5) {
        let g = small();
        let p = Point3::new(x, y, g.height_at(x, y) + gap);
        let d = g.point_distance(&p);
        prop_assert!(d.abs() <= gap.abs() + 1e-12);
        prop_assert!(gap == 0.0 || (d >= 0.0) == (gap > 0.0));
    }
}
