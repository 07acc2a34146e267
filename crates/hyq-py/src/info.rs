//! A step's [`StepInfo`] as the Python `info` dict, and N of them as a Gymnasium vector info.
//!
//! The schema is stated once, in the README's env card (and as data in `hyq.INFO_SCHEMA`): every
//! key on every step and reset, each with one type, so that Gymnasium's vector info aggregation
//! (and `DictInfoToList`, which RLlib uses) works. What is absent on most steps is still there
//! with a neutral value: `joint_at_limit` (a joint's name) and `joint_at_limit_side` are `""`
//! and `joint_at_limit_angle` is 0.0 unless `joint_limit` holds, `divergence` is `""` unless
//! `diverged` holds, `reasons` is `""` while the episode goes on. The caller adds
//! `observation_clipped` (it does the clipping). A fresh dict and fresh arrays every call.
//!
//! The vector info holds the same keys as arrays over the envs, exactly as Gymnasium's
//! `SyncVectorEnv` builds them from N single infos: int64, float64 and bool arrays, object
//! arrays of str, and float64 (N, k) arrays, each with its `_key` mask (all true: every env
//! reports every key every step).

use hyq_env::{Reason, Reasons, StepInfo};
use hyq_physics::RobotModel;
use hyq_spec::{LimitSide, TERM_NAMES};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

/// A key of the info and how to read its value from a [`StepInfo`].
type Key<T> = (&'static str, fn(&StepInfo) -> T);

/// The scalar float keys besides the reward terms, in the order written.
const FLOAT_KEYS: [Key<f64>; 6] = [
    ("reward", |i| i.reward.total),
    ("distance_to_goal", |i| i.distance_to_goal),
    ("d_n", |i| i.d_n),
    ("roll", |i| i.roll),
    ("pitch", |i| i.pitch),
    ("yaw", |i| i.yaw),
];

/// Every scalar float key with its value: each reward term of hyq-spec's table
/// ([`hyq_spec::REWARD_TERMS`]) by its name, then [`FLOAT_KEYS`].
fn float_values(info: &StepInfo) -> impl Iterator<Item = (&'static str, f64)> + '_ {
    let terms = info.reward.terms().map(|(t, v)| (t.name, v));
    terms.chain(FLOAT_KEYS.iter().map(move |(key, read)| (*key, read(info))))
}

/// The scalar float keys, in [`float_values`]' order.
fn float_keys() -> impl Iterator<Item = &'static str> {
    TERM_NAMES
        .into_iter()
        .chain(FLOAT_KEYS.iter().map(|(key, _)| *key))
}

/// The 3-vector keys, with how to read each.
const VECTOR_KEYS: [Key<[f64; 3]>; 2] = [
    ("goal", |i| i.goal),
    ("initial_position", |i| i.initial_position),
];

/// `reasons` as one string: the names of the reasons that hold joined by `+`, in
/// [`Reason::ALL`]'s order (`""` while the episode goes on).
fn reasons_text(reasons: Reasons) -> String {
    reasons
        .iter()
        .map(Reason::as_str)
        .collect::<Vec<_>>()
        .join("+")
}

/// The string keys, in the order [`string_values`] gives them.
const STRING_KEYS: [&str; 4] = [
    "reasons",
    "joint_at_limit",
    "joint_at_limit_side",
    "divergence",
];

/// The values of [`STRING_KEYS`] (`model` names the joint).
fn string_values(info: &StepInfo, model: &RobotModel) -> [String; 4] {
    let (joint, side) = match &info.joint_at_limit {
        Some(hit) => (
            model
                .joints()
                .get(hit.joint)
                .map_or_else(String::new, |j| j.name.clone()),
            match hit.side {
                LimitSide::Lower => "lower",
                LimitSide::Upper => "upper",
            },
        ),
        None => (String::new(), ""),
    };
    [
        reasons_text(info.reasons),
        joint,
        side.to_owned(),
        info.divergence
            .as_ref()
            .map(ToString::to_string)
            .unwrap_or_default(),
    ]
}

/// The angle of the joint at its limit (rad), 0.0 when none is.
fn joint_at_limit_angle(info: &StepInfo) -> f64 {
    info.joint_at_limit.as_ref().map_or(0.0, |hit| hit.angle)
}

/// The single env's info dict (see the module docs).
pub fn info_dict<'py>(
    py: Python<'py>,
    info: &StepInfo,
    model: &RobotModel,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    // The core's episode counter (episodes since the env was built) is left out: an info must
    // be a function of the seed and the actions (Gymnasium's step-determinism check), and
    // that count is not.
    d.set_item("t", info.t)?;
    for (key, value) in float_values(info) {
        d.set_item(key, value)?;
    }
    for reason in Reason::ALL {
        d.set_item(reason.as_str(), info.reasons.contains(reason))?;
    }
    for (key, read) in VECTOR_KEYS {
        d.set_item(key, read(info).to_vec().into_pyarray(py))?;
    }
    d.set_item("joint_targets", info.joint_targets.clone().into_pyarray(py))?;
    d.set_item("action_clipped", info.action_clipped)?;
    d.set_item("joint_at_limit_angle", joint_at_limit_angle(info))?;
    for (key, value) in STRING_KEYS.into_iter().zip(string_values(info, model)) {
        d.set_item(key, value)?;
    }
    Ok(d)
}

/// The vector info of `infos`, one per env, of envs of `model` (see the module docs).
pub fn vector_info_dict<'py>(
    py: Python<'py>,
    infos: &[&StepInfo],
    model: &RobotModel,
) -> PyResult<Bound<'py, PyDict>> {
    let n = infos.len();
    let d = PyDict::new(py);
    let mask = |d: &Bound<'py, PyDict>, key: &str| -> PyResult<()> {
        d.set_item(format!("_{key}"), vec![true; n].into_pyarray(py))
    };
    // int64, as Gymnasium builds an array of Python ints. Invariant: t counts env steps, far
    // below 2^63.
    d.set_item(
        "t",
        infos
            .iter()
            .map(|i| i64::try_from(i.t).unwrap_or(i64::MAX))
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    mask(&d, "t")?;
    d.set_item(
        "joint_at_limit_angle",
        infos
            .iter()
            .map(|i| joint_at_limit_angle(i))
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    mask(&d, "joint_at_limit_angle")?;
    // Object arrays of str, one per string key.
    let strings: Vec<[String; 4]> = infos.iter().map(|i| string_values(i, model)).collect();
    for (k, key) in STRING_KEYS.into_iter().enumerate() {
        let values: Vec<Py<PyAny>> = strings
            .iter()
            .map(|s| PyString::new(py, &s[k]).into_any().unbind())
            .collect();
        d.set_item(key, PyArray1::from_vec(py, values))?;
        mask(&d, key)?;
    }
    // One row of float values per env, its columns in the keys' order.
    let floats: Vec<Vec<f64>> = infos
        .iter()
        .map(|i| float_values(i).map(|(_, v)| v).collect())
        .collect();
    for (k, key) in float_keys().enumerate() {
        let column: Vec<f64> = floats.iter().map(|row| row[k]).collect();
        d.set_item(key, column.into_pyarray(py))?;
        mask(&d, key)?;
    }
    for reason in Reason::ALL {
        let flags: Vec<bool> = infos.iter().map(|i| i.reasons.contains(reason)).collect();
        d.set_item(reason.as_str(), flags.into_pyarray(py))?;
        mask(&d, reason.as_str())?;
    }
    let flags: Vec<bool> = infos.iter().map(|i| i.action_clipped).collect();
    d.set_item("action_clipped", flags.into_pyarray(py))?;
    mask(&d, "action_clipped")?;
    let rows = |key: &str, values: Vec<f64>, width: usize| -> PyResult<()> {
        // Invariant: `values` holds exactly n rows of `width` values, built just below.
        let array = Array2::from_shape_vec((n, width), values)
            .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(format!("{key}: {e}")))?;
        d.set_item(key, array.into_pyarray(py))?;
        mask(&d, key)
    };
    for (key, read) in VECTOR_KEYS {
        rows(key, infos.iter().flat_map(|i| read(i)).collect(), 3)?;
    }
    let width = infos.first().map_or(0, |i| i.joint_targets.len());
    rows(
        "joint_targets",
        infos
            .iter()
            .flat_map(|i| i.joint_targets.iter().copied())
            .collect(),
        width,
    )?;
    Ok(d)
}
