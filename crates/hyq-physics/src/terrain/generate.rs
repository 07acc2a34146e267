//! Height grids generated from a few numbers and a seed: rough ground, a slope, stairs.
//!
//! Deterministic: the same parameters and seed give the same grid bit for bit on every machine
//! (the random heights come from ChaCha8, a portable stream, and the rest is plain `f64`
//! arithmetic). Each relief is anchored at a point of the world (the robot's spawn point): the
//! slope passes through height 0 there and the stairs start a given distance ahead of it, so
//! the robot spawns on the same ground whatever the grid's rectangle.

use crate::bounds::short;
use rand::{RngExt, SeedableRng};
use rand_chacha::ChaCha8Rng;

use super::{HeightGrid, MAX_HEIGHT_M, TerrainError};

/// The rectangle a generator covers and its resolution.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extent {
    /// The rectangle's centre (m, world x and y).
    pub center: [f64; 2],
    /// The rectangle's side lengths (m, along x and y).
    pub size: [f64; 2],
    /// The target spacing between heights (m); each side gets a whole number of cells, so the
    /// spacing used is the nearest that divides it.
    pub resolution: f64,
}

/// Random bumps: heights drawn uniformly in [−amplitude, amplitude] on a lattice of spacing
/// `feature`, linearly interpolated between (legged_gym's `random_uniform_terrain`, with its
/// `downsampled_scale` as the feature size).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rough {
    /// Half the range of the heights (m), in [0, 1].
    pub amplitude: f64,
    /// The lattice spacing (m): the size of a bump. At least the grid's resolution.
    pub feature: f64,
}

/// A plane through the anchor, rising at `angle_deg` towards `direction_deg`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Slope {
    /// The slope's angle (degrees), in [−45, 45]; negative descends towards `direction_deg`.
    pub angle_deg: f64,
    /// The uphill direction (degrees about +z from +x).
    pub direction_deg: f64,
}

/// Whether stairs climb or descend along their direction.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Climb {
    /// Each step is `step_height` above the previous.
    Up,
    /// Each step is `step_height` below the previous.
    Down,
}

/// Straight stairs: flat up to `start` ahead of the anchor along `direction_deg`, then a step
/// of `step_height` every `step_depth`, up or down. Each riser rises across the one grid cell
/// that holds its edge.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Stairs {
    /// The height of one step (m), in (0, 1].
    pub step_height: f64,
    /// The depth of one step (m), at least twice the grid's resolution.
    pub step_depth: f64,
    /// The direction the stairs run (degrees about +z from +x).
    pub direction_deg: f64,
    /// Up or down.
    pub climb: Climb,
    /// Where the first riser is (m ahead of the anchor along the direction; may be negative).
    pub start: f64,
}

/// What to generate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Relief {
    /// Rough ground.
    Rough(Rough),
    /// A plane slope.
    Slope(Slope),
    /// Stairs.
    Stairs(Stairs),
}

/// The grid of `relief` over `extent`, anchored at `anchor` (m, world x and y), from `seed`
/// (only rough ground draws from it). Errors name the parameter out of range.
pub fn generate(
    extent: &Extent,
    relief: &Relief,
    anchor: [f64; 2],
    seed: u64,
) -> Result<HeightGrid, TerrainError> {
    let (columns, rows) = check(extent, relief)?;
    if !anchor.iter().all(|a| a.is_finite()) {
        return Err(TerrainError::invalid(
            "anchor",
            format!("{anchor:?} is not finite"),
        ));
    }
    let origin = [
        extent.center[0] - 0.5 * extent.size[0],
        extent.center[1] - 0.5 * extent.size[1],
    ];
    let spacing = [
        extent.size[0] / (columns - 1) as f64,
        extent.size[1] / (rows - 1) as f64,
    ];
    let height: Box<dyn Fn(f64, f64) -> f64> = match *relief {
        Relief::Rough(r) => Box::new(rough(&r, origin, extent, seed)),
        Relief::Slope(s) => Box::new(slope(&s, anchor)),
        Relief::Stairs(s) => Box::new(stairs(&s, anchor)),
    };
    let mut heights = Vec::with_capacity(columns * rows);
    for k in 0..rows {
        let y = origin[1] + k as f64 * spacing[1];
        for c in 0..columns {
            heights.push(height(origin[0] + c as f64 * spacing[0], y));
        }
    }
    HeightGrid::new(extent.center, extent.size, columns, rows, heights)
}

/// Checks `extent` and `relief`'s parameters without generating anything (what
/// [`generate`] checks first); returns the number of heights along x and y. Errors name the
/// parameter out of range.
pub fn check(extent: &Extent, relief: &Relief) -> Result<(usize, usize), TerrainError> {
    let (columns, rows) = counts(extent)?;
    let spacing = [
        extent.size[0] / (columns - 1) as f64,
        extent.size[1] / (rows - 1) as f64,
    ];
    match relief {
        Relief::Rough(r) => check_rough(r, spacing)?,
        Relief::Slope(s) => check_slope(s)?,
        Relief::Stairs(s) => check_stairs(s, spacing)?,
    }
    Ok((columns, rows))
}

/// The number of heights along x and y for `extent`, checked against the grid's cap.
fn counts(extent: &Extent) -> Result<(usize, usize), TerrainError> {
    let r = extent.resolution;
    if !(r.is_finite() && r > 0.0) {
        return Err(TerrainError::invalid(
            "resolution_m",
            format!("{} must be finite and > 0", short(r)),
        ));
    }
    let mut n = [0usize; 2];
    for (axis, (out, &s)) in ["x", "y"].iter().zip(n.iter_mut().zip(&extent.size)) {
        if !(s.is_finite() && s > 0.0) {
            return Err(TerrainError::invalid(
                "size_m",
                format!("{} along {axis} must be finite and > 0", short(s)),
            ));
        }
        let cells = (s / r).round();
        if cells > super::MAX_GRID_POINTS as f64 {
            return Err(TerrainError::invalid(
                "resolution_m",
                format!(
                    "{r} m over {s} m along {axis} is more than {} heights",
                    super::MAX_GRID_POINTS
                ),
            ));
        }
        // `cells` is a whole number below the cap, so the cast is exact.
        *out = (cells as usize).max(1) + 1;
    }
    if n[0] * n[1] > super::MAX_GRID_POINTS {
        return Err(TerrainError::invalid(
            "resolution_m",
            format!(
                "{r} m over {} × {} m makes {} × {} heights, more than the cap of {} \
                 (1024 × 1024)",
                extent.size[0],
                extent.size[1],
                n[0],
                n[1],
                super::MAX_GRID_POINTS
            ),
        ));
    }
    Ok((n[0], n[1]))
}

/// Checks that `value` (named `what`) is finite and within [lo, hi].
fn within(what: &str, value: f64, lo: f64, hi: f64, unit: &str) -> Result<(), TerrainError> {
    if value.is_finite() && (lo..=hi).contains(&value) {
        Ok(())
    } else {
        Err(TerrainError::invalid(
            what,
            format!("{} must be within [{lo}, {hi}] {unit}", short(value)),
        ))
    }
}

/// Checks rough ground's parameters (`spacing`: the grid's).
fn check_rough(r: &Rough, spacing: [f64; 2]) -> Result<(), TerrainError> {
    within("amplitude_m", r.amplitude, 0.0, 1.0, "m")?;
    let finest = spacing[0].min(spacing[1]);
    within(
        "feature_m",
        r.feature,
        finest,
        0.5 * MAX_HEIGHT_M,
        "m (the resolution up to 50 m)",
    )
}

/// The height function of rough ground over `extent` (lattice from `origin`).
fn rough(
    r: &Rough,
    origin: [f64; 2],
    extent: &Extent,
    seed: u64,
) -> impl Fn(f64, f64) -> f64 + use<> {
    // Lattice nodes cover the rectangle, the last one at or beyond its far edge.
    let nodes = |s: f64| (s / r.feature).ceil() as usize + 1;
    let (nx, ny) = (nodes(extent.size[0]), nodes(extent.size[1]));
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let lattice: Vec<f64> = (0..nx * ny)
        .map(|_| r.amplitude * (2.0 * rng.random::<f64>() - 1.0))
        .collect();
    let feature = r.feature;
    move |x: f64, y: f64| {
        let locate = |p: f64, n: usize| {
            let f = p.clamp(0.0, (n - 1) as f64);
            let i = (f.floor() as usize).min(n - 2);
            (i, f - i as f64)
        };
        let (i, u) = locate((x - origin[0]) / feature, nx);
        let (j, v) = locate((y - origin[1]) / feature, ny);
        let at = |a: usize, b: usize| lattice[b * nx + a];
        let low = at(i, j) + u * (at(i + 1, j) - at(i, j));
        let high = at(i, j + 1) + u * (at(i + 1, j + 1) - at(i, j + 1));
        low + v * (high - low)
    }
}

/// Checks a slope's parameters.
fn check_slope(s: &Slope) -> Result<(), TerrainError> {
    within("slope_deg", s.angle_deg, -45.0, 45.0, "degrees")?;
    within("direction_deg", s.direction_deg, -360.0, 360.0, "degrees")
}

/// The height function of a slope through `anchor`.
fn slope(s: &Slope, anchor: [f64; 2]) -> impl Fn(f64, f64) -> f64 + use<> {
    let gradient = s.angle_deg.to_radians().tan();
    let (sin, cos) = s.direction_deg.to_radians().sin_cos();
    move |x: f64, y: f64| gradient * ((x - anchor[0]) * cos + (y - anchor[1]) * sin)
}

/// Checks stairs' parameters (`spacing`: the grid's).
fn check_stairs(s: &Stairs, spacing: [f64; 2]) -> Result<(), TerrainError> {
    within("step_height_m", s.step_height, 0.0, 1.0, "m")?;
    if s.step_height <= 0.0 {
        return Err(TerrainError::invalid(
            "step_height_m",
            format!(
                "{} must be > 0 (stairs that go down: stairs = \"down\")",
                s.step_height
            ),
        ));
    }
    let coarsest = spacing[0].max(spacing[1]);
    within(
        "step_depth_m",
        s.step_depth,
        2.0 * coarsest,
        0.5 * MAX_HEIGHT_M,
        "m (twice the resolution up to 50 m)",
    )?;
    within("direction_deg", s.direction_deg, -360.0, 360.0, "degrees")?;
    within("start_m", s.start, -MAX_HEIGHT_M, MAX_HEIGHT_M, "m")
}

/// The height function of stairs from `anchor`.
fn stairs(s: &Stairs, anchor: [f64; 2]) -> impl Fn(f64, f64) -> f64 + use<> {
    let rise = match s.climb {
        Climb::Up => s.step_height,
        Climb::Down => -s.step_height,
    };
    let (sin, cos) = s.direction_deg.to_radians().sin_cos();
    let (start, depth) = (s.start, s.step_depth);
    move |x: f64, y: f64| {
        let along = (x - anchor[0]) * cos + (y - anchor[1]) * sin;
        if along < start {
            0.0
        } else {
            rise * (((along - start) / depth).floor() + 1.0)
        }
    }
}
