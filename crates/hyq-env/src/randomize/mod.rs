//! Robustness options (`[randomize]`): varied dynamics, the actuator's variations and delay drawn
//! per episode, observation noise drawn per step, and pushes. All off by default: an absent or
//! empty table is the spec's environment bit for bit.
//!
//! The draws live here, in the environment, and the physics they change lives in hyq-physics
//! (`randomize`: the values' rules; the `Backend` trait's `set_dynamics` and `push_trunk`,
//! implemented by every engine), so that every engine receives the same numbers from the same
//! seed. Each option draws from a ChaCha8 stream of its own (turning one on changes no other
//! draw); the streams restart at every seeded reset, like the goal and reset-noise streams.
//!
//! What the policy sees is noisy; what the rules see is not (spec §7.9): rewards, terminations,
//! the info's distances and attitude, and the state the environment reports come from the
//! simulated state, never from the noisy observation.
//!
//! The table and its checks are `config/randomize.rs` (one file per table, like every other);
//! here, `presets.rs` holds the anchors' ranges, `draw.rs` the streams and the draws, and
//! `info.rs` what the fronts report of them.

mod draw;
mod info;
mod presets;

pub use draw::{EpisodeDraw, FIRST_OPTION_STREAM, OBS_NOISE_STREAM, PUSH_STREAM, Randomizer};
pub use info::{EpisodeRandomization, RANDOMIZE_INFO_KEYS, RANDOMIZE_PREFIX, RandomizeInfo};
pub use presets::{PRESET_RANGES, Preset, PresetRange, preset_table};

use hyq_physics::RobotModel;

use crate::config::{ConfigError, RandomizeConfig};

/// Checks what `[randomize]` needs of `model`: the trunk's lightest drawn mass (its smallest
/// scale times its mass, plus the smallest added mass) stays positive. The error names
/// `randomize.trunk_added_mass_kg` and the bound.
pub fn check_for_robot(model: &RobotModel, config: &RandomizeConfig) -> Result<(), ConfigError> {
    let e = config.effective();
    let Some([lo, hi]) = e.trunk_added_mass_kg else {
        return Ok(());
    };
    let trunk = &model.links()[0];
    let scale = e.link_mass_scale.map_or(1.0, |[s, _]| s);
    let lightest = scale * trunk.mass + lo;
    if lightest > 0.0 {
        return Ok(());
    }
    Err(ConfigError::Invalid {
        key: "randomize.trunk_added_mass_kg".into(),
        value: format!("{:?}", [lo, hi]),
        expected: format!(
            "must keep the trunk's mass positive: {}'s trunk ({}) is {} kg{}, so lo must be \
             above {}",
            model.name(),
            trunk.name,
            trunk.mass,
            if scale == 1.0 {
                String::new()
            } else {
                format!(" (× {scale}, the smallest randomize.link_mass_scale)")
            },
            -scale * trunk.mass
        ),
    })
}
