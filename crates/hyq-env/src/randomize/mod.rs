//! Robustness options (`[randomize]`): varied dynamics, the actuator's variations and delay drawn
//! per episode, observation noise drawn per step, and pushes. All off by default: an absent or
//! empty table is the spec's environment bit for bit.
//!
//! The draws live here, in the environment, and the physics they change lives in hyq-physics
//! (`dynamics`: the values' rules; the `Backend` trait's `set_dynamics` and `push_trunk`,
//! implemented by every engine), so that every engine receives the same numbers from the same
//! seed. Each option draws from a ChaCha8 stream of its own (turning one on changes no other
//! draw); the streams restart at every seeded reset, like the goal and reset-noise streams.
//!
//! What the policy sees is noisy; what the rules see is not (spec §7.9): rewards, terminations,
//! the info's distances and attitude, and the state the environment reports come from the
//! simulated state, never from the noisy observation.
//!
//! The table and its checks are `config/randomize.rs` (one file per table, like every other),
//! the anchors' ranges `config/presets.rs`; here, `draw.rs` holds the streams and the draws,
//! and `info.rs` what the fronts report of them (their info keys are `crate::info`'s). Imports
//! run one way, from here to the configuration and from the info to here, never back.

mod draw;
mod info;

pub use crate::config::{PRESET_RANGES, Preset, PresetRange, preset_table};
pub use draw::{EpisodeDraw, FIRST_OPTION_STREAM, OBS_NOISE_STREAM, PUSH_STREAM, Randomizer};
pub use info::{EpisodeRandomization, RANDOMIZE_PREFIX, RandomizeInfo};

use hyq_physics::{DrawRanges, DrawnQuantity, RobotModel, check_draw_ranges};

use crate::config::{ConfigError, RandomizeConfig};

/// Checks what `[randomize]` needs of `model`: every draw of its ranges gives bodies and
/// joints inside the robot bounds table that the robot's own are held to (what rapier, DART and
/// MuJoCo all hold: a drawn mass in [1e-4, 1e6] kg, principal moments in [1e-8, 1e6] kg·m²,
/// damping in [0, 1e6] N·m·s/rad), checked once here on the ranges' corners
/// ([`hyq_physics::check_draw_ranges`]). The error names the key, its value, the body or joint
/// and the bound.
pub fn check_for_robot(model: &RobotModel, config: &RandomizeConfig) -> Result<(), ConfigError> {
    let e = config.effective();
    let ranges = DrawRanges {
        link_mass_scale: e
            .link_mass_scale
            .unwrap_or(DrawRanges::NOMINAL.link_mass_scale),
        trunk_added_mass_kg: e
            .trunk_added_mass_kg
            .unwrap_or(DrawRanges::NOMINAL.trunk_added_mass_kg),
        joint_damping_scale: e
            .joint_damping_scale
            .unwrap_or(DrawRanges::NOMINAL.joint_damping_scale),
    };
    let Err(fault) = check_draw_ranges(model, &ranges) else {
        return Ok(());
    };
    let (key, value) = match fault.quantity {
        DrawnQuantity::LinkMassScale => ("link_mass_scale", ranges.link_mass_scale),
        DrawnQuantity::TrunkAddedMass => ("trunk_added_mass_kg", ranges.trunk_added_mass_kg),
        DrawnQuantity::JointDampingScale => ("joint_damping_scale", ranges.joint_damping_scale),
    };
    Err(ConfigError::Invalid {
        key: format!("randomize.{key}"),
        value: format!("{value:?}"),
        expected: format!(
            "a draw from this range takes {} outside the robot bounds table, which every \
             engine holds: {}",
            model.name(),
            fault.reason
        ),
    })
}
