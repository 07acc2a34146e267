//! A step's [`StepInfo`] as the Python `info` dict, and N of them as a Gymnasium vector info.
//!
//! The schema is stated once, as hyq-env's [`INFO_KEYS`] (from which `hyq.INFO_SCHEMA` and the
//! README's info table are made): every key on every step and reset, each with one type, so that
//! Gymnasium's vector info aggregation (and `DictInfoToList`, which RLlib uses) works. What is absent on most steps is still there
//! with a neutral value: `joint_at_limit` (a joint's name) and `joint_at_limit_side` are `""`
//! and `joint_at_limit_angle` is 0.0 unless `joint_limit` holds, `divergence` is `""` unless
//! `diverged` holds, `reasons` is `""` while the episode goes on. The caller gives
//! `observation_clipped` (it does the clipping). A fresh dict and fresh arrays every call.
//!
//! When `[randomize]` is on, the info also holds hyq-env's [`RANDOMIZE_INFO_KEYS`] (the
//! episode's draws and the step's push, `randomize.<name>`), read the same way, after the
//! others; an env whose `[randomize]` is off has none of them. Under `task.kind = "velocity"`
//! the info holds hyq-env's [`VELOCITY_INFO_KEYS`] last (`velocity.<name>`: the command, the
//! trunk's velocities, the task's reward and terms); the spec's task has none of them. With
//! `[regularizers]` on, the info ends with hyq-env's regularizer keys (`regularizers.reward`
//! and `regularizers.<term>` for each term that is on; [`regularizer_info_keys`]); an env with
//! them off has none of them.
//!
//! The vector info holds the same keys as arrays over the envs, exactly as Gymnasium's
//! `SyncVectorEnv` builds them from N single infos: int64, float64 and bool arrays, object
//! arrays of str, and float64 (N, k) arrays, each with its `_key` mask (all true: every env
//! reports every key every step).

use hyq_env::{
    INFO_KEYS, InfoKey, InfoValue, RANDOMIZE_INFO_KEYS, Reason, StepInfo, VELOCITY_INFO_KEYS,
    regularizer_info_keys,
};
use hyq_physics::RobotModel;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

/// The schema of `keys` as `(key, type)` pairs in their order, every family expanded
/// (`hyq.INFO_SCHEMA` of [`INFO_KEYS`], `hyq.randomize_info_schema` of
/// [`RANDOMIZE_INFO_KEYS`]); `joints` and `links` are the robot's joint and body counts.
pub fn info_schema(keys: &[InfoKey], joints: usize, links: usize) -> Vec<(&'static str, String)> {
    keys.iter()
        .flat_map(|k| {
            k.names()
                .into_iter()
                .map(move |n| (n, k.kind(joints, links)))
        })
        .collect()
}

/// The keys an info of `info` holds, in order: [`INFO_KEYS`], then [`RANDOMIZE_INFO_KEYS`] when
/// the env's `[randomize]` is on, then [`VELOCITY_INFO_KEYS`] under `task.kind = "velocity"`,
/// then the regularisers' keys that are on ([`regularizer_info_keys`]).
fn keys_of(info: &StepInfo) -> impl Iterator<Item = &'static InfoKey> {
    let randomized: &'static [InfoKey] = if info.randomize.is_some() {
        &RANDOMIZE_INFO_KEYS
    } else {
        &[]
    };
    let velocity: &'static [InfoKey] = if info.velocity.is_some() {
        &VELOCITY_INFO_KEYS
    } else {
        &[]
    };
    INFO_KEYS
        .iter()
        .chain(randomized)
        .chain(velocity)
        .chain(regularizer_info_keys(info))
}

/// The single env's info dict (see the module docs): every key of [`INFO_KEYS`] in its order,
/// `observation_clipped` the front's flag and `engine` the name of the env's engine.
pub fn info_dict<'py>(
    py: Python<'py>,
    info: &StepInfo,
    model: &RobotModel,
    observation_clipped: bool,
    engine: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    // The core's episode counter (episodes since the env was built) is not a key: an info must
    // be a function of the seed and the actions (Gymnasium's step-determinism check), and
    // that count is not.
    for key in keys_of(info) {
        match key.value {
            InfoValue::Int(read) => d.set_item(key.name, read(info))?,
            InfoValue::Float(read) => d.set_item(key.name, read(info))?,
            InfoValue::Bool(read) => d.set_item(key.name, read(info))?,
            InfoValue::Text(read) => d.set_item(key.name, read(info, model))?,
            InfoValue::Vector(read, _) => {
                d.set_item(key.name, read(info).to_vec().into_pyarray(py))?;
            }
            InfoValue::Terms => {
                for (term, value) in info.reward.terms() {
                    d.set_item(term.name, value)?;
                }
            }
            InfoValue::ReasonFlags => {
                for reason in Reason::ALL {
                    d.set_item(reason.as_str(), info.reasons.contains(reason))?;
                }
            }
            InfoValue::FrontFlag => d.set_item(key.name, observation_clipped)?,
            InfoValue::Engine => d.set_item(key.name, engine)?,
        }
    }
    Ok(d)
}

/// The vector info of `infos`, one per env, of envs of `model`, with each env's
/// `observation_clipped` flag and engine's name (see the module docs): every key of
/// [`INFO_KEYS`] as an array over the envs, with its `_key` mask.
pub fn vector_info_dict<'py>(
    py: Python<'py>,
    infos: &[&StepInfo],
    model: &RobotModel,
    observation_clipped: &[bool],
    engines: &[&str],
) -> PyResult<Bound<'py, PyDict>> {
    let n = infos.len();
    let d = PyDict::new(py);
    let set = |key: &str, array: Bound<'py, PyAny>| -> PyResult<()> {
        d.set_item(key, array)?;
        d.set_item(format!("_{key}"), vec![true; n].into_pyarray(py))
    };
    let floats = |read: &dyn Fn(&StepInfo) -> f64| -> Bound<'py, PyAny> {
        let column: Vec<f64> = infos.iter().map(|i| read(i)).collect();
        column.into_pyarray(py).into_any()
    };
    let flags = |read: &dyn Fn(&StepInfo) -> bool| -> Bound<'py, PyAny> {
        let column: Vec<bool> = infos.iter().map(|i| read(i)).collect();
        column.into_pyarray(py).into_any()
    };
    // The envs share one configuration, so the first says whether `[randomize]` keys are there.
    let keys: Vec<&InfoKey> = infos.first().map_or_else(
        || INFO_KEYS.iter().collect(),
        |first| keys_of(first).collect(),
    );
    for key in keys {
        match key.value {
            // int64, as Gymnasium builds an array of Python ints. Invariant: the integer keys
            // count env steps, pushes or sub-steps, far below 2^63.
            InfoValue::Int(read) => {
                let column: Vec<i64> = infos
                    .iter()
                    .map(|i| i64::try_from(read(i)).unwrap_or(i64::MAX))
                    .collect();
                set(key.name, column.into_pyarray(py).into_any())?;
            }
            InfoValue::Float(read) => set(key.name, floats(&read))?,
            InfoValue::Bool(read) => set(key.name, flags(&read))?,
            // An object array of str.
            InfoValue::Text(read) => {
                let values: Vec<Py<PyAny>> = infos
                    .iter()
                    .map(|i| PyString::new(py, &read(i, model)).into_any().unbind())
                    .collect();
                set(key.name, PyArray1::from_vec(py, values).into_any())?;
            }
            // One row per env.
            InfoValue::Vector(read, _) => {
                let width = infos.first().map_or(0, |i| read(i).len());
                let values: Vec<f64> = infos.iter().flat_map(|i| read(i).iter().copied()).collect();
                // Invariant: every env of a vector env has the same robot, so the same width.
                let array = Array2::from_shape_vec((n, width), values).map_err(|e| {
                    pyo3::exceptions::PyRuntimeError::new_err(format!("{}: {e}", key.name))
                })?;
                set(key.name, array.into_pyarray(py).into_any())?;
            }
            InfoValue::Terms => {
                for term in &hyq_spec::REWARD_TERMS {
                    set(term.name, floats(&|i| (term.get)(&i.reward)))?;
                }
            }
            InfoValue::ReasonFlags => {
                for reason in Reason::ALL {
                    set(reason.as_str(), flags(&|i| i.reasons.contains(reason)))?;
                }
            }
            InfoValue::FrontFlag => {
                set(
                    key.name,
                    observation_clipped.to_vec().into_pyarray(py).into_any(),
                )?;
            }
            // An object array of str, as `Text`.
            InfoValue::Engine => {
                let values: Vec<Py<PyAny>> = engines
                    .iter()
                    .map(|e| PyString::new(py, e).into_any().unbind())
                    .collect();
                set(key.name, PyArray1::from_vec(py, values).into_any())?;
            }
        }
    }
    Ok(d)
}
