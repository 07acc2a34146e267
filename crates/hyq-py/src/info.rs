//! A step's [`StepInfo`] as the Python `info` dict, and N of them as a Gymnasium vector info.
//!
//! Single env keys (a fresh dict and fresh arrays every call):
//!
//! | key | type | meaning |
//! |---|---|---|
//! | `t` | int | env steps since reset (0 after reset) |
//! | `r_b`, `r_n`, `r_e`, `r_reach` | float | the reward terms (§4) |
//! | `m_yaw`, `m_pitch`, `m_height` | float | the multipliers (§5.1, §5.2) |
//! | `joint_penalty`, `fall_penalty` | float | the penalties subtracted (§5.3, §5.4) |
//! | `reward` | float | the step's reward, the same number `step` returns |
//! | `reasons` | tuple of str | every reason the episode ended, in the order `reached`, `joint_limit`, `fell`, `timeout`, `diverged` |
//! | `reached`, `joint_limit`, `fell`, `timeout`, `diverged` | bool | the same reasons as flags |
//! | `distance_to_goal` | float | D^t (m) |
//! | `d_n` | float | D_n^t = D^t / K |
//! | `roll`, `pitch`, `yaw` | float | the trunk's attitude (rad, intrinsic Z-Y-X) |
//! | `goal`, `initial_position` | float64 array (3,) | G and C^0 (m, world; C^t is the observation's rows 36–38) |
//! | `joint_targets` | float64 array (12,) | the joint targets the actuator tracked (rad) |
//! | `action_clipped` | bool | whether an action value was outside the space and clipped |
//! | `joint_at_limit` | None or dict | `{"joint": name, "angle": rad, "side": "lower"/"upper"}` on a joint-limit step |
//! | `divergence` | None or str | what diverged, on a `diverged` step |
//! | `observation_clipped` | bool | whether an observation value was outside the declared bounds and clipped to them (added by the caller, which does the clipping) |
//!
//! The vector info holds the numeric and flag keys as arrays over the envs, each with Gymnasium's `_key` mask (all true: every env reports every key every step).

use hyq_env::{Reason, StepInfo};
use hyq_physics::RobotModel;
use hyq_spec::LimitSide;
use numpy::IntoPyArray;
use numpy::ndarray::Array2;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};

/// A key of the info and how to read its value from a [`StepInfo`].
type Key<T> = (&'static str, fn(&StepInfo) -> T);

/// The scalar float keys, in the order written.
const FLOAT_KEYS: [Key<f64>; 15] = [
    ("r_b", |i| i.reward.r_b),
    ("r_n", |i| i.reward.r_n),
    ("r_e", |i| i.reward.r_e),
    ("r_reach", |i| i.reward.r_reach),
    ("m_yaw", |i| i.reward.m_yaw),
    ("m_pitch", |i| i.reward.m_pitch),
    ("m_height", |i| i.reward.m_height),
    ("joint_penalty", |i| i.reward.joint_penalty),
    ("fall_penalty", |i| i.reward.fall_penalty),
    ("reward", |i| i.reward.total),
    ("distance_to_goal", |i| i.distance_to_goal),
    ("d_n", |i| i.d_n),
    ("roll", |i| i.roll),
    ("pitch", |i| i.pitch),
    ("yaw", |i| i.yaw),
];

/// The 3-vector keys, with how to read each.
const VECTOR_KEYS: [Key<[f64; 3]>; 2] = [
    ("goal", |i| i.goal),
    ("initial_position", |i| i.initial_position),
];

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
    for (key, read) in FLOAT_KEYS {
        d.set_item(key, read(info))?;
    }
    let reasons: Vec<&str> = info.reasons.iter().map(Reason::as_str).collect();
    d.set_item("reasons", PyTuple::new(py, reasons)?)?;
    for reason in Reason::ALL {
        d.set_item(reason.as_str(), info.reasons.contains(reason))?;
    }
    for (key, read) in VECTOR_KEYS {
        d.set_item(key, read(info).to_vec().into_pyarray(py))?;
    }
    d.set_item("joint_targets", info.joint_targets.clone().into_pyarray(py))?;
    d.set_item("action_clipped", info.action_clipped)?;
    match &info.joint_at_limit {
        Some(hit) => {
            let j = PyDict::new(py);
            let name = model
                .joints()
                .get(hit.joint)
                .map_or("?", |joint| joint.name.as_str());
            j.set_item("joint", name)?;
            j.set_item("angle", hit.angle)?;
            j.set_item(
                "side",
                match hit.side {
                    LimitSide::Lower => "lower",
                    LimitSide::Upper => "upper",
                },
            )?;
            d.set_item("joint_at_limit", j)?;
        }
        None => d.set_item("joint_at_limit", py.None())?,
    }
    d.set_item("divergence", info.divergence.as_deref())?;
    Ok(d)
}

/// The vector info of `infos`, one per env (see the module docs).
pub fn vector_info_dict<'py>(py: Python<'py>, infos: &[&StepInfo]) -> PyResult<Bound<'py, PyDict>> {
    let n = infos.len();
    let d = PyDict::new(py);
    let mask = |d: &Bound<'py, PyDict>, key: &str| -> PyResult<()> {
        d.set_item(format!("_{key}"), vec![true; n].into_pyarray(py))
    };
    d.set_item(
        "t",
        infos
            .iter()
            .map(|i| i.t)
            .collect::<Vec<_>>()
            .into_pyarray(py),
    )?;
    mask(&d, "t")?;
    for (key, read) in FLOAT_KEYS {
        d.set_item(
            key,
            infos
                .iter()
                .map(|i| read(i))
                .collect::<Vec<_>>()
                .into_pyarray(py),
        )?;
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
