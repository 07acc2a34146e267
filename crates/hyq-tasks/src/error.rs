//! Why a value of the task's configuration was refused.

use thiserror::Error;

/// A configuration value outside its range, named by its dotted key (`command.lin_vel_x`).
#[derive(Clone, Debug, PartialEq, Error)]
#[error("{key} = {value}: {expected}")]
pub struct ConfigError {
    /// The dotted key (`command.lin_vel_x`, `velocity.tracking_sigma`).
    pub key: String,
    /// The value as given.
    pub value: String,
    /// What the key accepts.
    pub expected: String,
}

impl ConfigError {
    /// The refusal of `value` at `key`, which must be `expected`.
    pub fn new(key: &str, value: impl std::fmt::Debug, expected: &str) -> Self {
        Self {
            key: key.to_owned(),
            value: format!("{value:?}"),
            expected: expected.to_owned(),
        }
    }
}

/// Checks that `v` is finite and within `[lo, hi]`, naming `key`.
pub(crate) fn check_in(key: &str, v: f64, lo: f64, hi: f64) -> Result<(), ConfigError> {
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(ConfigError::new(
            key,
            v,
            &format!("must be a finite number in [{lo}, {hi}]"),
        ))
    }
}

/// Checks that `[lo, hi]` is an ordered pair of finite numbers within `±bound`, naming `key`.
pub(crate) fn check_range(key: &str, r: [f64; 2], bound: f64) -> Result<(), ConfigError> {
    let ok = r.iter().all(|v| v.is_finite() && v.abs() <= bound) && r[0] <= r[1];
    if ok {
        Ok(())
    } else {
        Err(ConfigError::new(
            key,
            r,
            &format!("must be [lo, hi] with -{bound} <= lo <= hi <= {bound}"),
        ))
    }
}
