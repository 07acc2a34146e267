//! Building an [`EnvConfig`] from what Python gives: an optional TOML file, then dotted
//! `(key, TOML value)` pairs (the Python package turns keyword arguments into these), applied
//! together by [`EnvConfig::load`], the loader of `hyq run --config --set`.

use std::path::Path;

use hyq_env::{ActionMode, ConfigError, EnvConfig};
use pyo3::PyResult;

use crate::errors::env_error;

/// The configuration: the file's (or the defaults), with `pairs` set on top and validated, by
/// the loader `hyq --config --set` uses.
pub fn build(config_file: Option<&str>, pairs: &[(String, String)]) -> PyResult<EnvConfig> {
    EnvConfig::load(config_file.map(Path::new), pairs)
        .map_err(|e| env_error(ConfigError::from(e).into()))
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
