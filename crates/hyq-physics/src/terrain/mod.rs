//! The ground the robot walks on: flat (the plane z = 0 every backend builds by default) or a
//! height field built from one regular grid of heights ([`HeightGrid`]).
//!
//! One grid, one surface. Every engine builds a single height field from the same grid (rapier's
//! `HeightField`, DART's `HeightmapShapef` under its Bullet detector, MuJoCo's `hfield`), never
//! tiles of several fields: rapier lets a capsule sink at the seam between two fields. Each cell
//! of the grid is split into two triangles along the same diagonal in every engine, from its
//! corner of lowest x and y to its corner of highest x and y (MuJoCo's only split; the rapier and
//! DART backends lay their fields out so that theirs is the same), and [`HeightGrid::height_at`]
//! interpolates on exactly those triangles. Each engine stores heights in single precision, so
//! its surface is the grid's to within a float's rounding (micrometres).
//!
//! Where the grids come from:
//! - [`generate`]: rough ground (random heights on a lattice of a given feature size,
//!   interpolated), a plane sloping at an angle in a direction, and stairs (steps of a height and
//!   depth, climbing or descending in a direction), each from a seed, deterministically: the same
//!   seed gives the same grid bit for bit on every machine;
//! - [`file`]: a user's file of heights, NumPy `.npy` or PNG, with its size on the ground and its
//!   vertical scale.
//!
//! [`geometry`] measures how far a shape is above the surface, for contact tests and the
//! backends that need a geometric contact test of their own (DART); [`placement`] puts a robot
//! down on the ground.
//!
//! Outside the grid's rectangle the engines have no ground at all; [`HeightGrid::height_at`]
//! answers there with the nearest edge's height, and [`HeightGrid::contains`] says whether a
//! point is over the field.

pub mod file;
pub mod generate;
pub mod geometry;
mod grid;
pub mod placement;

use std::sync::Arc;

pub use grid::{HeightGrid, MAX_GRID_POINTS, MAX_HEIGHT_M, MAX_SIDE_M, MIN_SPACING_M};

/// Why a terrain could not be made. Every message is one line naming the file or the parameter.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum TerrainError {
    /// A height file could not be used: missing, unreadable, not numeric, non-finite, of the
    /// wrong shape or too large.
    #[error("height file {}: {reason}", path.display())]
    File {
        /// The file, as given.
        path: std::path::PathBuf,
        /// What is wrong with it.
        reason: String,
    },
    /// A terrain parameter or a grid is out of its valid range.
    #[error("terrain {what}: {reason}")]
    Invalid {
        /// The parameter, e.g. `amplitude_m`, or the grid's part, e.g. `heights`.
        what: String,
        /// What is wrong, with the value and the valid range.
        reason: String,
    },
}

impl TerrainError {
    /// An [`TerrainError::Invalid`] for `what`.
    pub(crate) fn invalid(what: impl Into<String>, reason: impl Into<String>) -> Self {
        Self::Invalid {
            what: what.into(),
            reason: reason.into(),
        }
    }
}

/// The ground of a world: the flat plane z = 0, or a height field.
///
/// Cheap to clone (the grid is shared). The default is [`Terrain::Flat`], the ground every
/// backend builds.
#[derive(Debug, Clone, Default, PartialEq)]
pub enum Terrain {
    /// The plane z = 0, unbounded (DART's ground box ends 100 m out).
    #[default]
    Flat,
    /// A height field over the grid's rectangle, and nothing outside it.
    Field(Arc<HeightGrid>),
}

impl Terrain {
    /// A height field of `grid`.
    pub fn field(grid: HeightGrid) -> Self {
        Self::Field(Arc::new(grid))
    }

    /// Whether `other` is the same ground: both flat, or fields of equal grids (the same grid
    /// is recognised without comparing its heights).
    pub fn same_as(&self, other: &Terrain) -> bool {
        match (self, other) {
            (Terrain::Flat, Terrain::Flat) => true,
            (Terrain::Field(a), Terrain::Field(b)) => Arc::ptr_eq(a, b) || a == b,
            _ => false,
        }
    }

    /// Whether this is the flat plane.
    pub fn is_flat(&self) -> bool {
        matches!(self, Terrain::Flat)
    }

    /// The grid of a height field.
    pub fn grid(&self) -> Option<&HeightGrid> {
        match self {
            Terrain::Flat => None,
            Terrain::Field(grid) => Some(grid),
        }
    }

    /// The ground's height (m) under the point (x, y) of the world: 0 on flat ground, the
    /// field's surface over a field (its nearest edge's height outside its rectangle).
    pub fn height_at(&self, x: f64, y: f64) -> f64 {
        match self {
            Terrain::Flat => 0.0,
            Terrain::Field(grid) => grid.height_at(x, y),
        }
    }

    /// Whether the point (x, y) has ground under it: always on flat ground, inside the grid's
    /// rectangle for a field.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        match self {
            Terrain::Flat => true,
            Terrain::Field(grid) => grid.contains(x, y),
        }
    }
}
