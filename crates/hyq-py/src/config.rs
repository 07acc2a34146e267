//! Building an [`EnvConfig`] from what Python gives: an optional TOML file, then dotted
//! `(key, TOML value)` pairs (the Python package turns keyword arguments into these), applied
//! together by [`EnvConfig::set_all`], the same code path as `hyq run --set`.

use hyq_env::{ActionMode, EnvConfig};
use pyo3::PyResult;

use crate::errors::env_error;

/// The configuration: the file's (or the defaults), with `pairs` set on top and validated.
pub fn build(config_file: Option<&str>, pairs: &[(String, String)]) -> PyResult<EnvConfig> {
    let mut config = match config_file {
        Some(path) => EnvConfig::from_file(path).map_err(|e| env_error(e.into()))?,
        None => EnvConfig::default(),
    };
    let pairs: Vec<(&str, &str)> = pairs
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_str()))
        .collect();
    config.set_all(&pairs).map_err(|e| env_error(e.into()))?;
    Ok(config)
}

/// The configuration's action mode as written in TOML.
pub fn action_mode_name(mode: ActionMode) -> &'static str {
    match mode {
        ActionMode::Normalized => "normalized",
        ActionMode::Absolute => "absolute",
        ActionMode::Delta => "delta",
        ActionMode::Offset => "offset",
    }
}
