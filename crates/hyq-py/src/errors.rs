//! The core's errors as Python exceptions, with the core's messages unchanged.
//!
//! `ValueError` for what the caller gave (an action of the wrong length or with a NaN, a bad
//! configuration key or value, a goal the rules cannot use); `RuntimeError` for a call in the
//! wrong state (step before reset, step after the episode ended) or a physics failure.

use hyq_env::{EnvError, VecEnvError};
use hyq_render::RenderError;
use pyo3::PyErr;
use pyo3::exceptions::{PyRuntimeError, PyValueError};

/// Whether `e` is about what the caller gave rather than the state the env is in.
fn is_value_error(e: &EnvError) -> bool {
    match e {
        EnvError::Action(_) | EnvError::Config(_) | EnvError::Episode(_) => true,
        EnvError::NotReset | EnvError::EpisodeOver { .. } | EnvError::Physics(_) => false,
    }
}

/// `message` as a `ValueError` or a `RuntimeError`.
fn raise(value_error: bool, message: String) -> PyErr {
    if value_error {
        PyValueError::new_err(message)
    } else {
        PyRuntimeError::new_err(message)
    }
}

/// An environment error as the Python exception its kind calls for.
pub fn env_error(e: EnvError) -> PyErr {
    raise(is_value_error(&e), e.to_string())
}

/// A vector env error: the env's own error keeps its kind, its message prefixed with the env's
/// index (`env 3: ...`).
pub fn vec_env_error(e: VecEnvError) -> PyErr {
    let value_error = match &e {
        VecEnvError::Env { source, .. } => is_value_error(source),
        VecEnvError::Buffer { .. } | VecEnvError::Setup(_) => true,
    };
    raise(value_error, e.to_string())
}

/// A renderer error (a bad frame size is the caller's).
pub fn render_error(e: RenderError) -> PyErr {
    PyValueError::new_err(format!("render: {e}"))
}
