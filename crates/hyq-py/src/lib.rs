//! The extension module `hyq._core`: the Rust side of the Python package `hyq`.
//!
//! It holds the environment ([`hyq_env::Env`] of the chosen robot on the chosen backend, rapier
//! by default; see [`engines`]) and the vector env ([`hyq_env::VecEnv`]) and hands their results to Python as fresh NumPy arrays and dicts. The
//! Gymnasium classes users see (`hyq.HyQEnv`, `hyq.HyQVectorEnv`) are thin Python subclasses of
//! `gymnasium.Env` and `gymnasium.vector.VectorEnv` in `python/hyq/`, because a `#[pyclass]`
//! cannot pass the `isinstance(env, gymnasium.Env)` checks of Gymnasium's and
//! Stable-Baselines3's checkers.
//!
//! Contract with the Python side:
//! - configuration crosses as dotted `(key, TOML value)` pairs applied with
//!   [`hyq_env::EnvConfig::set_all`] on top of an optional TOML file, so Python keyword
//!   arguments, `hyq run --set` and TOML files share one parser and one set of error messages;
//! - every array returned is newly allocated (Gymnasium's data-reuse check);
//! - errors keep the core's messages: a refused action, a bad configuration or an unusable goal
//!   is a `ValueError`; a step before reset or after the episode ended, or a physics failure
//!   while building or resetting, is a `RuntimeError`;
//! - the physics runs with the GIL released (`Python::detach`), the vector env on rayon;
//! - every call goes through [`guard`]: a second thread inside the same env gets a message
//!   saying so, and a Rust panic becomes a `RuntimeError` (never PyO3's `PanicException`) and
//!   retires the env.

mod config;
mod engines;
mod errors;
mod frames;
mod guard;
mod info;
mod single;
mod spaces;
mod stats;
mod vector;

use pyo3::prelude::*;

/// Whether observations are clipped to the spec's table unless `clip_observations=` says
/// otherwise (they are not: see the README's env card).
pub const CLIP_OBSERVATIONS_DEFAULT: bool = false;

/// The default t_max (`task.max_time_steps`): the `max_episode_steps` `HyQ-v0` is registered
/// with.
#[pyfunction]
fn default_max_time_steps() -> u64 {
    hyq_env::EnvConfig::default().task.max_time_steps
}

/// The default configuration as TOML text, every key written.
#[pyfunction]
fn default_config_toml() -> String {
    hyq_env::EnvConfig::default().to_toml_string()
}

/// The backends this build has, `rapier` (the default) first.
#[pyfunction]
fn backends() -> Vec<&'static str> {
    engines::built_backends()
}

/// The keys and types an env whose `[randomize]` is on adds to its info
/// (`hyq.randomize_info_schema`), for a robot of `num_links` bodies and `num_joints` joints.
#[pyfunction]
fn randomize_info_schema(num_links: usize, num_joints: usize) -> Vec<(&'static str, String)> {
    info::info_schema(&hyq_env::RANDOMIZE_INFO_KEYS, num_joints, num_links)
}

/// The `hyq._core` module.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<single::Core>()?;
    m.add_class::<vector::VecCore>()?;
    m.add_function(wrap_pyfunction!(default_max_time_steps, m)?)?;
    m.add_function(wrap_pyfunction!(default_config_toml, m)?)?;
    m.add_function(wrap_pyfunction!(spaces::observation_table, m)?)?;
    m.add_function(wrap_pyfunction!(backends, m)?)?;
    m.add_function(wrap_pyfunction!(randomize_info_schema, m)?)?;
    stats::register(m)?;
    m.add("ROBOTS", hyq_formats::robots::NAMES.to_vec())?;
    m.add("DEFAULT_ROBOT", hyq_physics::bundled::DEFAULT)?;
    m.add("DEFAULT_BACKEND", hyq_engines::DEFAULT.name)?;
    // The configuration's tables, which keyword arguments may give as dicts.
    m.add("CONFIG_TABLES", hyq_env::EnvConfig::TABLES.to_vec())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    // The ranges the Python side checks arguments against, from the crates that enforce them.
    m.add("MAX_ENVS", hyq_env::MAX_ENVS)?;
    m.add("MAX_THREADS", hyq_env::MAX_THREADS)?;
    m.add("RENDER_SIDE_MIN", hyq_render::MIN_SIDE_PX)?;
    m.add("RENDER_SIDE_MAX", hyq_render::MAX_SIDE_PX)?;
    // The defaults of the options that are not configuration keys, defined once.
    m.add("CLIP_OBSERVATIONS_DEFAULT", CLIP_OBSERVATIONS_DEFAULT)?;
    m.add("RENDER_WIDTH_DEFAULT", hyq_render::DEFAULT_WIDTH_PX)?;
    m.add("RENDER_HEIGHT_DEFAULT", hyq_render::DEFAULT_HEIGHT_PX)?;
    // The info's keys and their types (`hyq.INFO_SCHEMA`), for the default robot.
    let default_robot = hyq_physics::resolve_robot(hyq_physics::bundled::DEFAULT)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    m.add(
        "INFO_SCHEMA",
        info::info_schema(
            &hyq_env::INFO_KEYS,
            default_robot.joints().len(),
            default_robot.num_links(),
        ),
    )?;
    // The reward terms' names in hyq-spec's table order: the info's term keys.
    m.add(
        "REWARD_TERMS",
        pyo3::types::PyTuple::new(m.py(), hyq_spec::TERM_NAMES)?,
    )?;
    // The gait regularisers' names (`[regularizers]`, docs/regularizers.md): the info's
    // `regularizers.<name>` keys of the terms that are on.
    let regularizers: Vec<&str> = hyq_env::REGULARIZER_INFO_KEYS[1..]
        .iter()
        .map(|k| {
            k.name
                .strip_prefix(hyq_env::regularizers::REGULARIZER_PREFIX)
                .unwrap_or(k.name)
        })
        .collect();
    m.add(
        "REGULARIZER_TERMS",
        pyo3::types::PyTuple::new(m.py(), regularizers)?,
    )?;
    Ok(())
}
