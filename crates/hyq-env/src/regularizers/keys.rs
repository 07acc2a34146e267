//! What the regularisers report in a step's info, as the fronts read it:
//! [`REGULARIZER_INFO_KEYS`] (flat keys `regularizers.<name>` in Python's info), declared as the
//! info's [`INFO_KEYS`](crate::INFO_KEYS) is.

use hyq_tasks::REGULARIZER_NAMES;

use crate::info::{InfoKey, InfoValue, StepInfo};

/// The prefix of every key of [`REGULARIZER_INFO_KEYS`].
pub const REGULARIZER_PREFIX: &str = "regularizers.";

/// The `k`-th term's value of `info`'s report (0 without one).
fn term(info: &StepInfo, k: usize) -> f64 {
    info.regularizers
        .map_or(0.0, |r| r.terms.values.to_array()[k])
}

macro_rules! regularizer_keys {
    ($($k:literal => $name:literal),* $(,)?) => {
        /// The info keys an environment with `[regularizers]` on adds after every other, on
        /// every step and reset: the regularisers' reward, then each term's value unscaled.
        /// A term that is off has no key ([`regularizer_info_keys`] picks the keys of an
        /// info); an environment with every term off has none.
        pub const REGULARIZER_INFO_KEYS: [InfoKey; 1 + REGULARIZER_NAMES.len()] = [
            InfoKey {
                name: "regularizers.reward",
                value: InfoValue::Float(|i| i.regularizers.map_or(0.0, |r| r.reward)),
                meaning: "Σ s·r·Δt over the regularisers that are on: what the step's reward \
                          adds to the spec's",
            },
            $(
                InfoKey {
                    name: concat!("regularizers.", $name),
                    value: InfoValue::Float(|i| term(i, $k)),
                    meaning: "the regulariser, unscaled (docs/regularizers.md); only when on",
                },
            )*
        ];
    };
}

regularizer_keys! {
    0 => "action_rate",
    1 => "torques",
    2 => "joint_acc",
    3 => "feet_air_time",
    4 => "foot_slip",
    5 => "base_height",
    6 => "collision",
    7 => "goal_heading",
    8 => "goal_line",
    9 => "goal_line_approach",
    10 => "orientation",
}

/// The keys of [`REGULARIZER_INFO_KEYS`] `info` holds: none with the regularisers off, else
/// the reward and the terms that are on.
pub fn regularizer_info_keys(info: &StepInfo) -> impl Iterator<Item = &'static InfoKey> {
    let on = info.regularizers.map(|r| r.terms.on);
    REGULARIZER_INFO_KEYS
        .iter()
        .enumerate()
        .filter(move |(k, _)| on.is_some_and(|on| *k == 0 || on[k - 1]))
        .map(|(_, key)| key)
}
