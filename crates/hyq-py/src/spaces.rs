//! The observation and action spaces as the Python side needs them: bounds as f32 arrays (the
//! action space's rounded inward, so that every float32 action in it is inside the env's), the
//! spec's §3 table as data, and observations clipped to the table when the env was built with
//! `clip_observations=True`.
//!
//! The declared observation space must contain every observation emitted (spec §3;
//! Gymnasium's and Stable-Baselines3's checkers hold an env to it). Clipped, it is the table.
//! Unclipped (the default), it carries the table's bounds only on the rows that are invariants,
//! the contact flags (0 or 1) and the quaternion (a unit quaternion's components lie in
//! [−1, 1]); the rows the physics can leave (joint angles past a limit by an overshoot, joint
//! speeds, the trunk's acceleration and position) are unbounded, declared as the whole finite
//! float32 range (±3.4028235e38) rather than ±inf, which Gymnasium's checker flags as "probably
//! too low/high". The environment never emits a value outside that range (it ends the episode as
//! `diverged` first).

use hyq_spec::ObservationLayout;
use pyo3::prelude::*;

use crate::engines::EnvView;

/// The observation's bounds (low, high) as f32, one per row.
pub type Bounds = (Vec<f32>, Vec<f32>);

/// Whether row `i` of `layout` is an invariant (a contact flag or a quaternion component), whose
/// table bounds hold for every value the physics can produce.
fn is_invariant(layout: &ObservationLayout, i: usize) -> bool {
    layout.foot_contacts().contains(&i)
        || i == layout.trunk_contact()
        || layout.trunk_rotation().contains(&i)
}

/// The unit of row `i` of `layout`.
fn unit_of(layout: &ObservationLayout, i: usize) -> &'static str {
    if layout.joint_angles().contains(&i) {
        "rad"
    } else if layout.joint_speeds().contains(&i) {
        "rad/s"
    } else if layout.foot_contacts().contains(&i) || i == layout.trunk_contact() {
        "0/1"
    } else if layout.trunk_rotation().contains(&i) {
        "1"
    } else if layout.trunk_acceleration().contains(&i) {
        "m/s^2"
    } else {
        "m"
    }
}

/// The §3 table's bounds as f32: what observations are clipped to, and the space when they are.
pub fn table_bounds(env: &dyn EnvView) -> Bounds {
    let rows = env.observation_layout().rows();
    (
        rows.iter().map(|r| r.min as f32).collect(),
        rows.iter().map(|r| r.max as f32).collect(),
    )
}

/// The declared observation space's bounds (see the module docs): the table when `clipped`,
/// else the table on the invariant rows and the finite float32 range elsewhere.
pub fn declared_bounds(env: &dyn EnvView, clipped: bool) -> Bounds {
    let (mut low, mut high) = table_bounds(env);
    if !clipped {
        let layout = env.observation_layout();
        for i in (0..low.len()).filter(|&i| !is_invariant(layout, i)) {
            low[i] = f32::MIN;
            high[i] = f32::MAX;
        }
    }
    (low, high)
}

/// One row of the table as Python receives it: (index, name, low, high, unit, estimated,
/// invariant).
type TableRow = (usize, String, f64, f64, &'static str, bool, bool);

/// The §3 observation table of `robot` (a bundled name or a profile path; default HyQ, the
/// spec's table), one tuple per row: (index, name, low,
/// high, unit, estimated, invariant). `estimated` marks the rows the spec gives only estimated
/// bounds for (33–38); `invariant` the rows whose bounds every value respects (24–32).
#[pyfunction]
#[pyo3(signature = (robot=None))]
pub fn observation_table(robot: Option<&str>) -> PyResult<Vec<TableRow>> {
    let layout = hyq_env::observation_layout_of(&*crate::engines::robot(robot)?)
        .map_err(|e| pyo3::exceptions::PyRuntimeError::new_err(e.to_string()))?;
    Ok(layout
        .rows()
        .iter()
        .map(|r| {
            (
                r.index,
                r.name.to_string(),
                r.min,
                r.max,
                unit_of(&layout, r.index),
                r.estimated,
                is_invariant(&layout, r.index),
            )
        })
        .collect())
}

/// Lower action-space bounds (f64) as the float32 a `gymnasium.spaces.Box` takes, rounded
/// inward: the smallest f32 at or above each bound. Rounded to nearest, a bound could land just
/// outside the environment's space (HyQ's -0.8726646259971648 rad becomes -0.87266463), and
/// `step(action_space.low)` would be clipped, or refused under `out_of_range = "error"`.
pub fn low_inward(values: &[f64]) -> Vec<f32> {
    values
        .iter()
        .map(|&v| {
            let f = v as f32;
            if f64::from(f) < v { f.next_up() } else { f }
        })
        .collect()
}

/// Upper action-space bounds as float32, rounded inward: the largest f32 at or below each
/// (see [`low_inward`]).
pub fn high_inward(values: &[f64]) -> Vec<f32> {
    values
        .iter()
        .map(|&v| {
            let f = v as f32;
            if f64::from(f) > v { f.next_down() } else { f }
        })
        .collect()
}

/// Clips `obs` in place to `clip`'s bounds when given; returns whether any value was outside
/// them (and so clipped). A NaN counts as outside (it stays NaN). Without bounds, nothing
/// changes and the answer is false.
pub fn clip_in_place(obs: &mut [f32], clip: Option<&Bounds>) -> bool {
    let Some((low, high)) = clip else {
        return false;
    };
    let mut clipped = false;
    for (v, (lo, hi)) in obs.iter_mut().zip(low.iter().zip(high)) {
        let c = v.clamp(*lo, *hi);
        // `!=` rather than a range test, so that a NaN (which clamp keeps) is reported.
        clipped |= c != *v;
        *v = c;
    }
    clipped
}

/// Whether clipping `obs` to `clip`'s bounds would change it: the `observation_clipped` flag
/// of an observation already handed out (false without bounds).
pub fn would_clip(obs: &[f32], clip: Option<&Bounds>) -> bool {
    clip.is_some_and(|(low, high)| {
        obs.iter()
            .zip(low.iter().zip(high))
            .any(|(v, (lo, hi))| v.clamp(*lo, *hi) != *v)
    })
}
