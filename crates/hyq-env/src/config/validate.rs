//! What every table's validation shares: the [`Table`] trait each table implements, the world's
//! bound on every position, and the checks several tables make.

use std::fmt;

use super::{ConfigError, EnvConfig};

/// One table of the configuration (`[name]`), registered by its row in [`EnvConfig`].
pub trait Table {
    /// Checks the table's values against their documented ranges. `config` is the whole
    /// configuration, for a table whose values are read against another's (the goal is placed
    /// from the spawn point). The first invalid value is the error, named by its dotted key.
    fn validate(&self, config: &EnvConfig) -> Result<(), ConfigError>;
}

/// Half the side (m) of the cube, centred on the world origin, in which every position must lie
/// on each axis: the spawn point, the goal, and the trunk during an episode (a trunk that leaves
/// it ends the episode as `diverged`). The reason is rapier's f32 positions: at 100 m they step
/// by 7.6 µm, under 1 % of the trunk's motion in a 1 ms sub-step at 1 m/s, and a 3 s trot from
/// x = 100 m moves 1.0061 m against 1.0086 m from the origin (the spread seen between origins 0
/// and 10 m too); from 1 km it moves 1.9 % less, from 10 km it cannot move at all. One bound
/// for every engine keeps runs on different engines comparable. It also bounds every distance,
/// which with hyq-spec's bounds on the scalings keeps every reward term and every sum over an
/// episode finite.
pub const WORLD_HALF_EXTENT_M: f64 = 100.0;

/// The reason given when a position is outside the world (see [`WORLD_HALF_EXTENT_M`]).
pub(crate) fn outside_world_reason() -> String {
    format!(
        "must lie within ±{WORLD_HALF_EXTENT_M} m of the origin on each axis (m), the world of \
         every engine: beyond it rapier's f32 positions are too coarse for faithful physics"
    )
}

/// Whether `v` is a coordinate inside the world (finite, |v| ≤ [`WORLD_HALF_EXTENT_M`]).
pub(crate) fn in_world(v: f64) -> bool {
    v.is_finite() && v.abs() <= WORLD_HALF_EXTENT_M
}

/// The error for `key` holding `value`, which must be as `expected` says.
pub(super) fn invalid(key: &str, value: impl fmt::Debug, expected: &str) -> ConfigError {
    ConfigError::Invalid {
        key: key.to_owned(),
        value: format!("{value:?}"),
        expected: expected.to_owned(),
    }
}

/// `Ok` when `v` is finite and > 0.
pub(super) fn finite_positive(key: &str, v: f64) -> Result<(), ConfigError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(key, v, "must be finite and > 0"))
    }
}

/// `Ok` when `v` is in the closed range `[lo, hi]`; else the error saying `expected`.
pub(super) fn in_range(
    key: &str,
    v: f64,
    lo: f64,
    hi: f64,
    expected: &str,
) -> Result<(), ConfigError> {
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(invalid(key, v, expected))
    }
}
