//! What `[randomize]` did in an episode, as the fronts report it: the step's info (flat keys
//! `randomize.<name>` in Python's), the `--record` lines and `hyq run --json` (an object under
//! `randomize`). [`RANDOMIZE_INFO_KEYS`] is its one schema, declared as the info's
//! [`INFO_KEYS`](crate::INFO_KEYS) is: the Python info dicts, `hyq.randomize_info_schema` and
//! the documents' table are made from it, and a test holds the serialised names to it.

use serde::{Deserialize, Serialize};

use super::EpisodeDraw;
use crate::info::{InfoKey, InfoValue, StepInfo, VectorLen};

/// The episode's draws and the pushes so far, present on every step and reset of an
/// environment whose `[randomize]` is on (absent otherwise, so the spec's environment reports
/// what it always did).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RandomizeInfo {
    /// The episode's drawn values (nominal for the options that are off).
    #[serde(flatten)]
    pub draw: EpisodeDraw,
    /// The velocity the step's push added to the trunk (m/s, world; zeros when none, and
    /// after reset).
    pub push_velocity_mps: [f64; 3],
    /// Pushes so far this episode.
    pub pushes: u64,
}

impl RandomizeInfo {
    /// The info of an episode that drew `draw`, before its first step.
    pub fn at_reset(draw: &EpisodeDraw) -> Self {
        Self {
            draw: draw.clone(),
            push_velocity_mps: [0.0; 3],
            pushes: 0,
        }
    }
}

/// What `[randomize]` did in a whole episode, as `hyq run --json` and `hyq compare` report it:
/// the drawn values (under the record's names) and how many pushes the episode had.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeRandomization {
    /// The drawn values.
    #[serde(flatten)]
    pub draw: EpisodeDraw,
    /// Pushes in the episode.
    pub pushes: u64,
}

impl EpisodeRandomization {
    /// The randomisation of an episode that drew `draw`, before its first push.
    pub fn starting(draw: &EpisodeDraw) -> Self {
        Self {
            draw: draw.clone(),
            pushes: 0,
        }
    }
}

/// The prefix of every key of [`RANDOMIZE_INFO_KEYS`]; without it, a key is the name the
/// record, `hyq run --json` and `hyq compare` write under `randomize`.
pub const RANDOMIZE_PREFIX: &str = "randomize.";

/// The draw of `info`'s episode. Only read for an info that has one (a front writes these keys
/// only then); the empty fallbacks keep the readers total.
fn draw(info: &StepInfo) -> Option<&EpisodeDraw> {
    info.randomize.as_ref().map(|r| &r.draw)
}

/// A per-joint or per-body factor of `info`'s draw.
fn factors(info: &StepInfo, read: fn(&EpisodeDraw) -> &[f64]) -> &[f64] {
    draw(info).map_or(&[], read)
}

/// The info keys an environment whose `[randomize]` is on adds to [`INFO_KEYS`](crate::INFO_KEYS),
/// on every step and reset, in the order a front writes them (an environment with it off has
/// none of them). The names after [`RANDOMIZE_PREFIX`] are the configuration keys that drew
/// each value.
pub const RANDOMIZE_INFO_KEYS: [InfoKey; 12] = [
    InfoKey {
        name: "randomize.ground_friction",
        value: InfoValue::Float(|i| draw(i).map_or(0.0, |d| d.ground_friction)),
        meaning: "the episode's ground friction coefficient",
    },
    InfoKey {
        name: "randomize.trunk_added_mass_kg",
        value: InfoValue::Float(|i| draw(i).map_or(0.0, |d| d.trunk_added_mass_kg)),
        meaning: "mass added to the trunk (kg)",
    },
    InfoKey {
        name: "randomize.trunk_com_offset_m",
        value: InfoValue::Vector(
            |i| draw(i).map_or(&[], |d| &d.trunk_com_offset_m),
            VectorLen::Three,
        ),
        meaning: "offset of the trunk's centre of mass (m, trunk frame)",
    },
    InfoKey {
        name: "randomize.link_mass_scale",
        value: InfoValue::Vector(|i| factors(i, |d| &d.link_mass_scale), VectorLen::Links),
        meaning: "factor of each body's mass and inertia (model order)",
    },
    InfoKey {
        name: "randomize.kp_scale",
        value: InfoValue::Vector(|i| factors(i, |d| &d.kp_scale), VectorLen::Joints),
        meaning: "factor of each joint's kp (action order)",
    },
    InfoKey {
        name: "randomize.kd_scale",
        value: InfoValue::Vector(|i| factors(i, |d| &d.kd_scale), VectorLen::Joints),
        meaning: "factor of each joint's kd",
    },
    InfoKey {
        name: "randomize.effort_scale",
        value: InfoValue::Vector(|i| factors(i, |d| &d.effort_scale), VectorLen::Joints),
        meaning: "factor of each joint's effort limit",
    },
    InfoKey {
        name: "randomize.joint_damping_scale",
        value: InfoValue::Vector(
            |i| factors(i, |d| &d.joint_damping_scale),
            VectorLen::Joints,
        ),
        meaning: "factor of each joint's damping",
    },
    InfoKey {
        name: "randomize.joint_friction_scale",
        value: InfoValue::Vector(
            |i| factors(i, |d| &d.joint_friction_scale),
            VectorLen::Joints,
        ),
        meaning: "factor of each joint's Coulomb friction",
    },
    InfoKey {
        name: "randomize.actuator_delay_substeps",
        value: InfoValue::Int(|i| draw(i).map_or(0, |d| u64::from(d.actuator_delay_substeps))),
        meaning: "the actuator's delay (physics sub-steps)",
    },
    InfoKey {
        name: "randomize.push_velocity_mps",
        value: InfoValue::Vector(
            |i| i.randomize.as_ref().map_or(&[], |r| &r.push_velocity_mps),
            VectorLen::Three,
        ),
        meaning: "the velocity the step's push added to the trunk (m/s, world; zeros when none)",
    },
    InfoKey {
        name: "randomize.pushes",
        value: InfoValue::Int(|i| i.randomize.as_ref().map_or(0, |r| r.pushes)),
        meaning: "pushes so far this episode",
    },
];

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used)]

    use super::*;
    use hyq_physics::{PhysicsParams, bundled};

    /// The serialised names are the key list's without its prefix, in its order, so the record
    /// and the Python info cannot name a value differently (the record's test checks each key
    /// reads what the record holds).
    #[test]
    fn serialised_names_follow_the_key_list() {
        let model = bundled::hyq();
        let randomize =
            RandomizeInfo::at_reset(&EpisodeDraw::nominal(&model, &PhysicsParams::default()));
        let json = serde_json::to_value(&randomize).unwrap();
        // serde_json's map is sorted by key, so the order is the record test's to check.
        let serialised: Vec<&str> = json
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        let mut names: Vec<&str> = RANDOMIZE_INFO_KEYS
            .iter()
            .map(|k| k.name.strip_prefix(RANDOMIZE_PREFIX).unwrap())
            .collect();
        names.sort_unstable();
        assert_eq!(serialised, names);
        let back: RandomizeInfo = serde_json::from_value(json).unwrap();
        assert_eq!(back, randomize);
    }
}
