//! `[action]`: how an action becomes the joint targets of the PD actuator.

use serde::{Deserialize, Serialize};

use super::validate::finite_positive;
use super::{ConfigError, EnvConfig, Table};

/// How an action becomes the 12 joint targets of the PD actuator (`[action]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ActionConfig {
    /// `"normalized"`: a ∈ [−1, 1] maps linearly onto each joint's range (−1 the lower limit,
    /// +1 the upper); `"absolute"`: targets in radians; `"delta"`: target = the joint's angle at
    /// the start of the step + a · `max_delta_rad`, a ∈ [−1, 1]; `"offset"`: target = the
    /// robot's standing angle + a · `max_offset_rad`, a ∈ [−1, 1] (a project-defined mode, spec
    /// §7.1). Targets are always clipped to the joint limits. (default: `"normalized"`)
    pub mode: ActionMode,
    /// What a finite value outside the action space does: `"clip"` clips it to the space (and
    /// the step's info says so), `"error"` refuses the step. Non-finite values are always
    /// errors. (default: `"clip"`)
    pub out_of_range: OutOfRange,
    /// The largest change of a joint target per env step in `"delta"` mode (rad). Finite, > 0.
    /// (default: 0.1, i.e. up to 10 rad/s at 100 env steps per second, within HyQ's 12 rad/s)
    pub max_delta_rad: f64,
    /// The largest distance of a joint target from the standing pose in `"offset"` mode (rad).
    /// Finite, > 0. (default: 0.5, within every HyQ joint's room on both sides of standing
    /// but the hip flexions' 0.47 rad to one limit)
    pub max_offset_rad: f64,
}

impl Default for ActionConfig {
    fn default() -> Self {
        Self {
            mode: ActionMode::Normalized,
            out_of_range: OutOfRange::Clip,
            max_delta_rad: 0.1,
            max_offset_rad: 0.5,
        }
    }
}

/// The action modes; see [`ActionConfig::mode`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ActionMode {
    /// [−1, 1] onto each joint's range.
    Normalized,
    /// Radians, within the joint limits.
    Absolute,
    /// [−1, 1] times `max_delta_rad` from the current angle.
    Delta,
    /// [−1, 1] times `max_offset_rad` from the standing pose.
    Offset,
}

/// What happens to a finite action value outside the action space; see
/// [`ActionConfig::out_of_range`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OutOfRange {
    /// Clip to the action space.
    Clip,
    /// Refuse the step with an error naming the index and value.
    Error,
}

/// `[action]`: the two step sizes.
impl Table for ActionConfig {
    fn validate(&self, _: &EnvConfig) -> Result<(), ConfigError> {
        finite_positive("action.max_delta_rad", self.max_delta_rad)?;
        finite_positive("action.max_offset_rad", self.max_offset_rad)
    }
}
