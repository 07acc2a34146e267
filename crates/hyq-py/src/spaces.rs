//! The observation and action spaces as the Python side needs them: bounds as f32 arrays, and
//! observations clipped to their declared bounds when the env was built with
//! `clip_observations=True`.

use hyq_env::Env;
use hyq_physics::Backend;

/// The observation's declared bounds (low, high) as f32, one per row.
pub type Bounds = (Vec<f32>, Vec<f32>);

/// The observation's declared bounds as f32 (the §3 table's for HyQ).
pub fn observation_bounds<B: Backend>(env: &Env<B>) -> Bounds {
    let rows = env.observation_layout().rows();
    (
        rows.iter().map(|r| r.min as f32).collect(),
        rows.iter().map(|r| r.max as f32).collect(),
    )
}

/// `values` (action space bounds, f64) as the f32 a `gymnasium.spaces.Box` of float32 takes.
pub fn to_f32(values: &[f64]) -> Vec<f32> {
    values.iter().map(|v| *v as f32).collect()
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
