//! [`HeightGrid`]: heights on a regular grid over a rectangle of the world's xy plane, and the
//! triangulated surface every engine builds from them.

use nalgebra::Point3;

use super::TerrainError;

/// The most heights a grid may hold: 1,048,576 (1024 × 1024). A grid this large is a 4 MB
/// single-precision array in each engine and about 10 MB of MJCF text.
pub const MAX_GRID_POINTS: usize = 1 << 20;

/// The largest height magnitude (m) a grid may hold: the environment's world ends 100 m from
/// the origin in every direction.
pub const MAX_HEIGHT_M: f64 = 100.0;

/// The grid's rectangle must lie within ±`MAX_SIDE_M / 2` of the origin in x and y (the
/// environment's world).
pub const MAX_SIDE_M: f64 = 200.0;

/// The smallest spacing (m) between neighbouring heights, in x and in y.
pub const MIN_SPACING_M: f64 = 0.001;

/// Heights (m) sampled on a regular grid over a rectangle of the world's xy plane.
///
/// Column `c` lies at x = x₀ + c·dx and row `k` at y = y₀ + k·dy, where (x₀, y₀) is the
/// rectangle's corner of lowest x and y and dx, dy the spacings ([`HeightGrid::spacing`]); the
/// heights are stored row after row ([`HeightGrid::heights`]). The surface is the grid's cells,
/// each split along its diagonal from (x₀ + c·dx, y₀ + k·dy) to (x₀ + (c+1)·dx, y₀ + (k+1)·dy)
/// into two flat triangles: what every engine builds and [`HeightGrid::height_at`]
/// interpolates.
///
/// Built only through [`HeightGrid::new`] (or the generators and file readers that call it), so
/// every grid holds finite heights within the limits above.
#[derive(Debug, Clone, PartialEq)]
pub struct HeightGrid {
    center: [f64; 2],
    size: [f64; 2],
    columns: usize,
    rows: usize,
    heights: Vec<f64>,
    min: f64,
    max: f64,
}

impl HeightGrid {
    /// A grid of `columns` heights along x by `rows` along y over the rectangle of side lengths
    /// `size` (m, x then y) centred on `center` (m, world x and y), `heights` row after row
    /// (`heights[k * columns + c]` at column `c`, row `k`).
    ///
    /// Errors name what is out of range: fewer than 2 heights along a side, more than
    /// [`MAX_GRID_POINTS`] in all, a spacing below [`MIN_SPACING_M`], a rectangle outside the
    /// world, a height that is not finite or beyond ±[`MAX_HEIGHT_M`], or a `heights` length
    /// other than `columns × rows`.
    pub fn new(
        center: [f64; 2],
        size: [f64; 2],
        columns: usize,
        rows: usize,
        heights: Vec<f64>,
    ) -> Result<Self, TerrainError> {
        check_layout(center, size, columns, rows)?;
        if heights.len() != columns * rows {
            return Err(TerrainError::invalid(
                "heights",
                format!(
                    "{} values for a grid of {columns} × {rows} = {} points",
                    heights.len(),
                    columns * rows
                ),
            ));
        }
        let (mut min, mut max) = (f64::INFINITY, f64::NEG_INFINITY);
        for (i, &h) in heights.iter().enumerate() {
            if !(h.is_finite() && h.abs() <= MAX_HEIGHT_M) {
                return Err(TerrainError::invalid(
                    "heights",
                    format!(
                        "height {} at column {}, row {} is not finite or beyond ±{MAX_HEIGHT_M} m",
                        crate::bounds::short(h),
                        i % columns,
                        i / columns
                    ),
                ));
            }
            min = min.min(h);
            max = max.max(h);
        }
        Ok(Self {
            center,
            size,
            columns,
            rows,
            heights,
            min,
            max,
        })
    }

    /// The rectangle's centre (m, world x and y).
    pub fn center(&self) -> [f64; 2] {
        self.center
    }

    /// The rectangle's side lengths (m, along x and y).
    pub fn size(&self) -> [f64; 2] {
        self.size
    }

    /// Heights along x (one per column).
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// Heights along y (one per row).
    pub fn rows(&self) -> usize {
        self.rows
    }

    /// The spacing between neighbouring heights (m): [dx, dy].
    pub fn spacing(&self) -> [f64; 2] {
        [
            self.size[0] / (self.columns - 1) as f64,
            self.size[1] / (self.rows - 1) as f64,
        ]
    }

    /// The rectangle's corner of lowest x and y (m): where column 0 and row 0 meet.
    pub fn origin(&self) -> [f64; 2] {
        [
            self.center[0] - 0.5 * self.size[0],
            self.center[1] - 0.5 * self.size[1],
        ]
    }

    /// Every height, row after row (`[k * columns + c]` at column `c`, row `k`).
    pub fn heights(&self) -> &[f64] {
        &self.heights
    }

    /// The height at column `c`, row `k`.
    ///
    /// # Panics
    /// If `c` or `k` is outside the grid.
    pub fn height(&self, c: usize, k: usize) -> f64 {
        assert!(c < self.columns && k < self.rows, "grid index out of range");
        self.heights[k * self.columns + c]
    }

    /// The lowest height (m).
    pub fn min_height(&self) -> f64 {
        self.min
    }

    /// The highest height (m).
    pub fn max_height(&self) -> f64 {
        self.max
    }

    /// The world point of column `c`, row `k`, at its height.
    pub fn point(&self, c: usize, k: usize) -> Point3<f64> {
        let [x0, y0] = self.origin();
        let [dx, dy] = self.spacing();
        Point3::new(x0 + c as f64 * dx, y0 + k as f64 * dy, self.height(c, k))
    }

    /// Whether (x, y) lies over the grid's rectangle (edges included).
    pub fn contains(&self, x: f64, y: f64) -> bool {
        let [x0, y0] = self.origin();
        (x0..=x0 + self.size[0]).contains(&x) && (y0..=y0 + self.size[1]).contains(&y)
    }

    /// The cell holding (x, y) (clamped to the grid) and the point's place in it, each in
    /// [0, 1]: `(c, k, u, v)` with u along x from column `c`, v along y from row `k`.
    fn locate(&self, x: f64, y: f64) -> (usize, usize, f64, f64) {
        let [x0, y0] = self.origin();
        let [dx, dy] = self.spacing();
        let along = |p: f64, n: usize| -> (usize, f64) {
            let f = if p.is_nan() {
                0.0
            } else {
                p.clamp(0.0, (n - 1) as f64)
            };
            // f is within [0, n - 1], so the cast is exact and the index in range.
            let i = (f.floor() as usize).min(n - 2);
            (i, f - i as f64)
        };
        let (c, u) = along((x - x0) / dx, self.columns);
        let (k, v) = along((y - y0) / dy, self.rows);
        (c, k, u, v)
    }

    /// The surface's height (m) at (x, y): linear on the triangle of the cell that holds the
    /// point, as every engine builds it (see the type's documentation). Outside the rectangle,
    /// the height at the nearest point of its edge.
    pub fn height_at(&self, x: f64, y: f64) -> f64 {
        let (c, k, u, v) = self.locate(x, y);
        let h00 = self.height(c, k);
        let h10 = self.height(c + 1, k);
        let h01 = self.height(c, k + 1);
        let h11 = self.height(c + 1, k + 1);
        // Barycentric weights, which give each sample's height exactly at the sample.
        if u >= v {
            // The triangle (c, k), (c + 1, k), (c + 1, k + 1).
            (1.0 - u) * h00 + (u - v) * h10 + v * h11
        } else {
            // The triangle (c, k), (c, k + 1), (c + 1, k + 1).
            (1.0 - v) * h00 + (v - u) * h01 + u * h11
        }
    }

    /// The two triangles of cell (c, k) (c < columns − 1, k < rows − 1), world coordinates,
    /// each counter-clockwise seen from above.
    pub fn cell_triangles(&self, c: usize, k: usize) -> [[Point3<f64>; 3]; 2] {
        let p00 = self.point(c, k);
        let p10 = self.point(c + 1, k);
        let p01 = self.point(c, k + 1);
        let p11 = self.point(c + 1, k + 1);
        [[p00, p10, p11], [p00, p11, p01]]
    }

    /// The cells whose rectangles meet [x_min, x_max] × [y_min, y_max] (clamped to the grid):
    /// column and row ranges, each end exclusive.
    pub fn cells_in(
        &self,
        x: [f64; 2],
        y: [f64; 2],
    ) -> (std::ops::Range<usize>, std::ops::Range<usize>) {
        let (c0, k0, _, _) = self.locate(x[0], y[0]);
        let (c1, k1, _, _) = self.locate(x[1], y[1]);
        (c0..c1 + 1, k0..k1 + 1)
    }

    /// The steepest slope of any triangle of the surface, as a gradient magnitude (rise over
    /// run): tan of the steepest angle.
    pub fn steepest_gradient(&self) -> f64 {
        let [dx, dy] = self.spacing();
        let mut steepest: f64 = 0.0;
        for k in 0..self.rows - 1 {
            for c in 0..self.columns - 1 {
                let h00 = self.height(c, k);
                let h10 = self.height(c + 1, k);
                let h01 = self.height(c, k + 1);
                let h11 = self.height(c + 1, k + 1);
                let lower = ((h10 - h00) / dx).hypot((h11 - h10) / dy);
                let upper = ((h11 - h01) / dx).hypot((h01 - h00) / dy);
                steepest = steepest.max(lower).max(upper);
            }
        }
        steepest
    }
}

/// Checks a grid's rectangle and counts (see [`HeightGrid::new`]).
fn check_layout(
    center: [f64; 2],
    size: [f64; 2],
    columns: usize,
    rows: usize,
) -> Result<(), TerrainError> {
    if columns < 2 || rows < 2 {
        return Err(TerrainError::invalid(
            "grid",
            format!("{columns} × {rows} heights: at least 2 are needed along each side"),
        ));
    }
    if columns
        .checked_mul(rows)
        .is_none_or(|n| n > MAX_GRID_POINTS)
    {
        return Err(TerrainError::invalid(
            "grid",
            format!(
                "{columns} × {rows} heights is more than the cap of {MAX_GRID_POINTS} \
                 (1024 × 1024)"
            ),
        ));
    }
    for (axis, (&s, n)) in ["x", "y"].iter().zip(size.iter().zip([columns, rows])) {
        if !(s.is_finite() && s / (n - 1) as f64 >= MIN_SPACING_M) {
            return Err(TerrainError::invalid(
                "size",
                format!(
                    "{s} m along {axis} over {n} heights: the spacing must be at least \
                     {MIN_SPACING_M} m"
                ),
            ));
        }
    }
    let half = 0.5 * MAX_SIDE_M;
    for (axis, (&c, &s)) in ["x", "y"].iter().zip(center.iter().zip(&size)) {
        if !(c.is_finite() && c - 0.5 * s >= -half && c + 0.5 * s <= half) {
            return Err(TerrainError::invalid(
                "size",
                format!(
                    "the grid spans {} .. {} m along {axis}: it must lie within ±{half} m of \
                     the origin",
                    c - 0.5 * s,
                    c + 0.5 * s
                ),
            ));
        }
    }
    Ok(())
}
