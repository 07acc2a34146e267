//! Spec §2 (User Variables): the task's user variables, with the spec's names.
//!
//! | field | symbol | default | valid | spec |
//! |---|---|---|---|---|
//! | `base_rew_scaling` | k_base | unset (r_b = 0) | finite, > 0 | §2, §4.1 |
//! | `exp_rew_scaling` | k_exp | 5.0 | finite, > 0, or unset (r_e = 0) | §2, §4.3 |
//! | `norm_rew_scaling` | k_norm | unset (r_n = 0) | finite, > 0 | §2, §4.2 |
//! | `reach_target_bonus_reward` | r_reach | 0.0 | finite, ≥ 0 | §2, §4.4 |
//! | `accepted_error` | ε_reach | 0.001 m | finite, > 0 | §2, §6.1 |
//! | `accepted_dist_to_bounds` | ε_joint | 0.01 rad | finite, ≥ 0 | §2, §6.2 |
//! | `reach_bounds_penalty` | | 0.0 | finite, ≥ 0 | §5.3 |
//! | `fall_penalty` | | 0.0 | finite, ≥ 0 | §5.4 |
//! | `max_time_steps` | t_max | 1000 | ≥ 1 | §6.4 |
//! | `yaw_limit_deg` | | 2.5° | finite, in [0, 180] | §5.1.1 |
//! | `pitch_limit_deg` | | 2.5° | finite, in [0, 180] | §5.1.2 |
//! | `height_penalty` | | unset (off) | see [`HeightPenalty`] | §5.2 (TBD in the spec) |
//!
//! In TOML every field is optional (a missing field takes its default), unknown fields are
//! rejected, and the three reward scalings take a number or the string `"off"`:
//! `exp_rew_scaling = "off"` is how to unset k_exp, whose default is set, since TOML has no null
//! (formats that have one, such as JSON, also accept `null`).
//! Deserialising validates every value; so does [`TaskConfig::validate`], which
//! [`crate::EpisodeRules::new`] runs on any configuration built in code. An invalid value is an
//! error naming the field and the value.
//!
//! The physics settings (`sim_steps_per_env_step`, the physics time step; spec §7.3) belong to
//! the environment, not to these rules: the rules see their effect only through
//! the fall fact and the step count they are given.

use serde::{Deserialize, Deserializer, Serialize, Serializer, de};
use std::fmt;
use thiserror::Error;

/// The task's user variables (spec §2): reward scalings, bonus, penalties,
/// tolerances and limits.
///
/// Plain data with the spec's names. `Default` is the §2 table. Deserialising validates every
/// field; a value built in code is validated by [`TaskConfig::validate`] and, again, by
/// [`crate::EpisodeRules::new`], so no rule ever runs on an invalid value.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawTaskConfig", into = "RawTaskConfig")]
pub struct TaskConfig {
    /// k_base, the base reward's scale: r_b = k_base · (D^{t−1} − D^t), D in metres, so r_b is
    /// k_base per metre of progress towards the goal. `None` turns r_b off (r_b = 0). Finite and
    /// > 0 when set. (default: `None`, the spec's "No impl") Spec §2, §4.1.
    pub base_rew_scaling: Option<f64>,
    /// k_exp, the exponential reward's scale, dimensionless: R_e(D_n) = (e^{k_exp(1−D_n)} − 1) /
    /// k_exp on 0 ≤ D_n ≤ 1. `None` turns r_e off. Finite and > 0 when set. (default:
    /// `Some(5.0)`) Spec §2, §4.3.
    pub exp_rew_scaling: Option<f64>,
    /// k_norm, the normalised reward's scale: r_n = k_norm · (D^{t−1} − D^t) / K, so a whole walk
    /// from start to goal earns k_norm. `None` turns r_n off. Finite and > 0 when set. (default:
    /// `None`, the spec's "No impl"; the spec's Figures 3–4 use 10) Spec §2, §4.2.
    pub norm_rew_scaling: Option<f64>,
    /// r_reach, the reward added on the step the goal is reached (§6.1), before the orientation
    /// multipliers. Reward units. Finite, ≥ 0. (default: `0.0`) Spec §2, §4.4.
    pub reach_target_bonus_reward: f64,
    /// ε_reach, the side of the cube centred on the goal inside which the goal counts as
    /// reached, in metres: reached when |C_i − G_i| ≤ ε_reach / 2 on each axis. Finite, > 0.
    /// (default: `0.001` m) Spec §2, §6.1.
    pub accepted_error: f64,
    /// ε_joint, how close to a joint limit counts as reaching it, in radians: reached when
    /// θ ≤ θ_min + ε_joint or θ ≥ θ_max − ε_joint. Finite, ≥ 0. (default: `0.01` rad) Spec §2,
    /// §6.2.
    pub accepted_dist_to_bounds: f64,
    /// The fixed penalty subtracted, after the multipliers, on a step where a joint limit is
    /// reached (§6.2). Reward units. Finite, ≥ 0. (default: `0.0`) Spec §5.3.
    pub reach_bounds_penalty: f64,
    /// The fixed penalty subtracted, after the multipliers, on a step where the trunk touched the
    /// ground (§6.3). Reward units. Finite, ≥ 0. (default: `0.0`) Spec §5.4.
    pub fall_penalty: f64,
    /// t_max, the number of env steps after which the episode times out: timeout when t ≥ t_max,
    /// so 1 ends the episode after its first step. Env steps, ≥ 1. (default: `1000`) Spec §6.4.
    pub max_time_steps: u64,
    /// The yaw angle up to which the yaw multiplier is 1, in degrees: m_yaw = 1 if |yaw| ≤ limit,
    /// else max(0, cos yaw). Finite, in [0, 180]; 180 turns the yaw penalty off. (default: `2.5`°)
    /// Spec §5.1.1.
    pub yaw_limit_deg: f64,
    /// The pitch angle up to which the pitch multiplier is 1, in degrees: m_pitch = 1 if
    /// |pitch| ≤ limit, else max(0, cos pitch). Finite, in [0, 180]; 90 or more turns the pitch
    /// penalty off, as |pitch| ≤ 90°. (default: `2.5`°) Spec §5.1.2.
    pub pitch_limit_deg: f64,
    /// The opt-in height multiplier (the original's §5.2 is "TBD"; off by default).
    /// `None` turns it off (m_height = 1). In TOML, a `[height_penalty]` table with all three
    /// fields. (default: `None`) Spec §5.2.
    pub height_penalty: Option<HeightPenalty>,
}

/// Parameters of the opt-in height multiplier (spec §5.2, "TBD"; see
/// [`crate::penalty::height`] for the formula, which follows the system the spec describes).
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct HeightPenalty {
    /// z_0, the trunk height at which no penalty applies, in metres (world z). Finite. The
    /// system the spec describes used 0.62 m for HyQ.
    pub nominal_height_m: f64,
    /// How far from z_0 the trunk may be without penalty, in metres: m_height = 1 when
    /// |z − z_0| ≤ tolerance. Finite, ≥ 0. The system the spec describes used 0.1 m.
    pub tolerance_m: f64,
    /// λ, the decay rate beyond the tolerance, per metre: m_height = e^{−λ|z − z_0|}. Finite,
    /// > 0. The system the spec describes used 2.0.
    pub rate_per_m: f64,
}

impl Default for TaskConfig {
    /// The spec's §2 table, including the defaults it sets for the variables the original names
    /// without one.
    fn default() -> Self {
        TaskConfig {
            base_rew_scaling: None,
            exp_rew_scaling: Some(5.0),
            norm_rew_scaling: None,
            reach_target_bonus_reward: 0.0,
            accepted_error: 0.001,
            accepted_dist_to_bounds: 0.01,
            reach_bounds_penalty: 0.0,
            fall_penalty: 0.0,
            max_time_steps: 1000,
            yaw_limit_deg: 2.5,
            pitch_limit_deg: 2.5,
            height_penalty: None,
        }
    }
}

/// An invalid configuration value: names the field, the value and what was expected.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum ConfigError {
    /// A real-valued field out of its range (or NaN or infinite).
    #[error("invalid {field} = {value}: must be {expected}")]
    Real {
        /// The field's name as written in the configuration (e.g. `"accepted_error"`).
        field: &'static str,
        /// The rejected value.
        value: f64,
        /// What the field accepts (e.g. `"finite and > 0"`).
        expected: &'static str,
    },
    /// An integer field out of its range.
    #[error("invalid {field} = {value}: must be {expected}")]
    Integer {
        /// The field's name as written in the configuration (e.g. `"max_time_steps"`).
        field: &'static str,
        /// The rejected value.
        value: u64,
        /// What the field accepts (e.g. `"at least 1"`).
        expected: &'static str,
    },
}

const POSITIVE: &str = "finite and > 0";
const NON_NEGATIVE: &str = "finite and >= 0";
const ANGLE_LIMIT: &str = "finite and in [0, 180] degrees";

fn check(
    field: &'static str,
    value: f64,
    ok: bool,
    expected: &'static str,
) -> Result<(), ConfigError> {
    // Every caller's `ok` is false for NaN as well (NaN fails every comparison and `is_finite`);
    // testing it here too means a future range written carelessly cannot let NaN through.
    if ok && !value.is_nan() {
        Ok(())
    } else {
        Err(ConfigError::Real {
            field,
            value,
            expected,
        })
    }
}

fn positive(field: &'static str, value: f64) -> Result<(), ConfigError> {
    check(field, value, value.is_finite() && value > 0.0, POSITIVE)
}

fn non_negative(field: &'static str, value: f64) -> Result<(), ConfigError> {
    check(
        field,
        value,
        value.is_finite() && value >= 0.0,
        NON_NEGATIVE,
    )
}

fn angle_limit(field: &'static str, value: f64) -> Result<(), ConfigError> {
    check(field, value, (0.0..=180.0).contains(&value), ANGLE_LIMIT)
}

impl TaskConfig {
    /// Checks every field against its documented range; the first invalid field is the error.
    ///
    /// Deserialisation runs this; [`crate::EpisodeRules::new`] runs it again, so a configuration
    /// edited in code after it was built cannot reach the rules unchecked.
    pub fn validate(&self) -> Result<(), ConfigError> {
        for (field, value) in [
            ("base_rew_scaling", self.base_rew_scaling),
            ("exp_rew_scaling", self.exp_rew_scaling),
            ("norm_rew_scaling", self.norm_rew_scaling),
        ] {
            if let Some(value) = value {
                positive(field, value)?;
            }
        }
        non_negative("reach_target_bonus_reward", self.reach_target_bonus_reward)?;
        positive("accepted_error", self.accepted_error)?;
        non_negative("accepted_dist_to_bounds", self.accepted_dist_to_bounds)?;
        non_negative("reach_bounds_penalty", self.reach_bounds_penalty)?;
        non_negative("fall_penalty", self.fall_penalty)?;
        if self.max_time_steps < 1 {
            return Err(ConfigError::Integer {
                field: "max_time_steps",
                value: self.max_time_steps,
                expected: "at least 1",
            });
        }
        angle_limit("yaw_limit_deg", self.yaw_limit_deg)?;
        angle_limit("pitch_limit_deg", self.pitch_limit_deg)?;
        if let Some(h) = &self.height_penalty {
            check(
                "height_penalty.nominal_height_m",
                h.nominal_height_m,
                h.nominal_height_m.is_finite(),
                "finite",
            )?;
            non_negative("height_penalty.tolerance_m", h.tolerance_m)?;
            positive("height_penalty.rate_per_m", h.rate_per_m)?;
        }
        Ok(())
    }

    /// Whether r_n or r_e is on: both divide by K = ‖G − C^0‖, so the episode's goal must then
    /// be away from its start (see [`crate::EpisodeRules::new`]).
    pub fn needs_start_goal_distance(&self) -> bool {
        self.norm_rew_scaling.is_some() || self.exp_rew_scaling.is_some()
    }
}

/// A reward scaling as written in a file: a number, or the string `"off"` for unset.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Scaling(Option<f64>);

/// The string that unsets an optional scaling in a configuration file.
const OFF: &str = "off";

impl Serialize for Scaling {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        match self.0 {
            Some(value) => serializer.serialize_f64(value),
            None => serializer.serialize_str(OFF),
        }
    }
}

impl<'de> Deserialize<'de> for Scaling {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct ScalingVisitor;
        impl de::Visitor<'_> for ScalingVisitor {
            type Value = Scaling;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "a number or the string \"{OFF}\"")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Scaling, E> {
                Ok(Scaling(Some(v)))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Scaling, E> {
                Ok(Scaling(Some(v as f64)))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Scaling, E> {
                Ok(Scaling(Some(v as f64)))
            }
            // Formats with a null (JSON, Python's None through a binding) may unset with it too.
            fn visit_unit<E: de::Error>(self) -> Result<Scaling, E> {
                Ok(Scaling(None))
            }
            fn visit_none<E: de::Error>(self) -> Result<Scaling, E> {
                Ok(Scaling(None))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Scaling, E> {
                if v == OFF {
                    Ok(Scaling(None))
                } else {
                    Err(E::invalid_value(de::Unexpected::Str(v), &self))
                }
            }
        }
        deserializer.deserialize_any(ScalingVisitor)
    }
}

/// The file form of [`TaskConfig`]: every field optional, unknown fields rejected. Converting it
/// into a `TaskConfig` validates it.
#[derive(Clone, Debug, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct RawTaskConfig {
    base_rew_scaling: Scaling,
    exp_rew_scaling: Scaling,
    norm_rew_scaling: Scaling,
    reach_target_bonus_reward: f64,
    accepted_error: f64,
    accepted_dist_to_bounds: f64,
    reach_bounds_penalty: f64,
    fall_penalty: f64,
    max_time_steps: u64,
    yaw_limit_deg: f64,
    pitch_limit_deg: f64,
    #[serde(skip_serializing_if = "Option::is_none")]
    height_penalty: Option<HeightPenalty>,
}

impl Default for RawTaskConfig {
    fn default() -> Self {
        TaskConfig::default().into()
    }
}

impl From<TaskConfig> for RawTaskConfig {
    fn from(c: TaskConfig) -> Self {
        RawTaskConfig {
            base_rew_scaling: Scaling(c.base_rew_scaling),
            exp_rew_scaling: Scaling(c.exp_rew_scaling),
            norm_rew_scaling: Scaling(c.norm_rew_scaling),
            reach_target_bonus_reward: c.reach_target_bonus_reward,
            accepted_error: c.accepted_error,
            accepted_dist_to_bounds: c.accepted_dist_to_bounds,
            reach_bounds_penalty: c.reach_bounds_penalty,
            fall_penalty: c.fall_penalty,
            max_time_steps: c.max_time_steps,
            yaw_limit_deg: c.yaw_limit_deg,
            pitch_limit_deg: c.pitch_limit_deg,
            height_penalty: c.height_penalty,
        }
    }
}

impl TryFrom<RawTaskConfig> for TaskConfig {
    type Error = ConfigError;
    fn try_from(r: RawTaskConfig) -> Result<Self, ConfigError> {
        let config = TaskConfig {
            base_rew_scaling: r.base_rew_scaling.0,
            exp_rew_scaling: r.exp_rew_scaling.0,
            norm_rew_scaling: r.norm_rew_scaling.0,
            reach_target_bonus_reward: r.reach_target_bonus_reward,
            accepted_error: r.accepted_error,
            accepted_dist_to_bounds: r.accepted_dist_to_bounds,
            reach_bounds_penalty: r.reach_bounds_penalty,
            fall_penalty: r.fall_penalty,
            max_time_steps: r.max_time_steps,
            yaw_limit_deg: r.yaw_limit_deg,
            pitch_limit_deg: r.pitch_limit_deg,
            height_penalty: r.height_penalty,
        };
        config.validate()?;
        Ok(config)
    }
}
