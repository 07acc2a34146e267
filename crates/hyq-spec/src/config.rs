//! Spec §2 (User Variables): the task's user variables, with the spec's names.
//!
//! [`TaskConfig`] states each variable once: its field (meaning, symbol, unit, default, valid
//! range and spec section in its doc), its value in `Default` (the §2 table) and its check in
//! [`TaskConfig::validate`], the one place its range is enforced.
//!
//! In TOML every field is optional (a missing field takes its default), unknown fields are
//! rejected, and the three reward scalings take a number or the string `"off"`:
//! `exp_rew_scaling = "off"` is how to unset k_exp, whose default is set, since TOML has no null
//! (formats that have one, such as JSON, also accept `null`). Reading a configuration checks
//! its keys and types only; its values are checked by [`TaskConfig::validate`], which the
//! environment runs when it reads a configuration, and [`crate::EpisodeRules::new`] on every
//! configuration it is given, so no rule ever runs on an invalid value. An invalid value is an
//! error naming the field and the value.
//!
//! The physics settings (`sim_steps_per_env_step`, the physics time step; spec §7.3) belong to
//! the environment, not to these rules: the rules see their effect only through
//! the fall fact and the step count they are given.

use serde::{Deserialize, Serialize};
use thiserror::Error;

/// The task's user variables (spec §2): reward scalings, bonus, penalties,
/// tolerances and limits.
///
/// Plain data with the spec's names. `Default` is the §2 table. [`TaskConfig::validate`] checks
/// every field, and [`crate::EpisodeRules::new`] runs it on every configuration, so no rule ever
/// runs on an invalid value.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TaskConfig {
    /// k_base, the base reward's scale: r_b = k_base · (D^{t−1} − D^t), D in metres, so r_b is
    /// k_base per metre of progress towards the goal. `None` turns r_b off (r_b = 0). In
    /// (0, [`REWARD_SCALE_MAX`]] when set. (default: `None`, the spec's "No impl") Spec §2, §4.1.
    #[serde(with = "scaling")]
    pub base_rew_scaling: Option<f64>,
    /// k_exp, the exponential reward's scale, dimensionless: R_e(D_n) = (e^{k_exp(1−D_n)} − 1) /
    /// k_exp on 0 ≤ D_n ≤ 1. `None` turns r_e off. In (0, [`EXP_REW_SCALING_MAX`]] when set.
    /// (default: `Some(5.0)`) Spec §2, §4.3.
    #[serde(with = "scaling")]
    pub exp_rew_scaling: Option<f64>,
    /// k_norm, the normalised reward's scale: r_n = k_norm · (D^{t−1} − D^t) / K, so a whole walk
    /// from start to goal earns k_norm. `None` turns r_n off. In (0, [`REWARD_SCALE_MAX`]] when
    /// set. (default: `None`, the spec's "No impl"; the spec's Figures 3–4 use 10) Spec §2, §4.2.
    #[serde(with = "scaling")]
    pub norm_rew_scaling: Option<f64>,
    /// r_reach, the reward added on the step the goal is reached (§6.1), before the orientation
    /// multipliers. Reward units. In [0, [`REWARD_SCALE_MAX`]]. (default: `0.0`) Spec §2, §4.4.
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
    /// reached (§6.2). Reward units. In [0, [`REWARD_SCALE_MAX`]]. (default: `0.0`) Spec §5.3.
    pub reach_bounds_penalty: f64,
    /// The fixed penalty subtracted, after the multipliers, on a step where the trunk touched the
    /// ground (§6.3). Reward units. In [0, [`REWARD_SCALE_MAX`]]. (default: `0.0`) Spec §5.4.
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
    #[serde(skip_serializing_if = "Option::is_none")]
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

/// The largest k_exp (`exp_rew_scaling`): R_e(0) = (e^k − 1)/k is then about 2.8e214, so a
/// step's r_e and any sum of them over the longest episode (2^63 steps) stay finite. (e^k
/// itself overflows f64 above k ≈ 709.78.)
pub const EXP_REW_SCALING_MAX: f64 = 500.0;

/// The largest `base_rew_scaling`, `norm_rew_scaling`, `reach_target_bonus_reward`,
/// `reach_bounds_penalty` and `fall_penalty`. With every distance bounded (the environment keeps
/// every position within ±100 m of the origin) and K ≥ [`crate::MIN_START_GOAL_DISTANCE`], r_b,
/// r_n, the bonus and the penalties then stay below 4·10²⁰ per step, and every sum over an
/// episode finite.
pub const REWARD_SCALE_MAX: f64 = 1e12;

/// What a real-valued field accepts. Every range refuses NaN (NaN fails every comparison and
/// `is_finite`).
#[derive(Clone, Copy, Debug)]
enum Range {
    /// A reward scaling, bonus or penalty: finite, ≥ 0 (> 0 when `positive`), at most `max`
    /// (with the reason for that bound).
    Scale {
        positive: bool,
        max: f64,
        why_max: &'static str,
    },
    /// Finite and > 0.
    Positive,
    /// Finite and ≥ 0.
    NonNegative,
    /// An angle limit in degrees, in [0, 180].
    AngleLimit,
    /// Any finite number.
    Finite,
}

/// k_exp's range.
const EXP_SCALING: Range = Range::Scale {
    positive: true,
    max: EXP_REW_SCALING_MAX,
    why_max: "at most 500, so that R_e(0) = (e^k - 1)/k and every sum of rewards over an episode \
              stay finite",
};
/// The range of r_b's and r_n's scalings.
const SCALING: Range = Range::Scale {
    positive: true,
    max: REWARD_SCALE_MAX,
    why_max: WHY_SCALE_MAX,
};
/// The range of the bonus and the fixed penalties.
const AMOUNT: Range = Range::Scale {
    positive: false,
    max: REWARD_SCALE_MAX,
    why_max: WHY_SCALE_MAX,
};
/// The words of [`SCALING`]'s and [`AMOUNT`]'s upper bound.
const WHY_SCALE_MAX: &str =
    "at most 1e12, so that every reward term and every sum of rewards over an episode stay finite";

impl Range {
    /// `Ok` when `value` is in the range; else the error naming `field`, `value` and the bound.
    fn check(self, field: &'static str, value: f64) -> Result<(), ConfigError> {
        let (ok, expected) = match self {
            Range::Scale {
                positive,
                max,
                why_max,
            } => {
                let sign_ok = if positive { value > 0.0 } else { value >= 0.0 };
                match (value.is_finite() && sign_ok, value <= max) {
                    (true, true) => (true, ""),
                    (true, false) => (false, why_max),
                    (false, _) if positive => (false, "finite and > 0"),
                    (false, _) => (false, "finite and >= 0"),
                }
            }
            Range::Positive => (value.is_finite() && value > 0.0, "finite and > 0"),
            Range::NonNegative => (value.is_finite() && value >= 0.0, "finite and >= 0"),
            Range::AngleLimit => (
                (0.0..=180.0).contains(&value),
                "finite and in [0, 180] degrees",
            ),
            Range::Finite => (value.is_finite(), "finite"),
        };
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
}

impl TaskConfig {
    /// Checks every field against its range, the one statement of it; the first invalid field
    /// is the error.
    ///
    /// The environment runs this when it reads a configuration; [`crate::EpisodeRules::new`]
    /// runs it on every configuration it is given, so one edited in code cannot reach the rules
    /// unchecked.
    pub fn validate(&self) -> Result<(), ConfigError> {
        let t = self;
        for (field, value, range) in [
            ("base_rew_scaling", t.base_rew_scaling, SCALING),
            ("exp_rew_scaling", t.exp_rew_scaling, EXP_SCALING),
            ("norm_rew_scaling", t.norm_rew_scaling, SCALING),
            (
                "reach_target_bonus_reward",
                Some(t.reach_target_bonus_reward),
                AMOUNT,
            ),
            ("accepted_error", Some(t.accepted_error), Range::Positive),
            (
                "accepted_dist_to_bounds",
                Some(t.accepted_dist_to_bounds),
                Range::NonNegative,
            ),
            ("reach_bounds_penalty", Some(t.reach_bounds_penalty), AMOUNT),
            ("fall_penalty", Some(t.fall_penalty), AMOUNT),
            ("yaw_limit_deg", Some(t.yaw_limit_deg), Range::AngleLimit),
            (
                "pitch_limit_deg",
                Some(t.pitch_limit_deg),
                Range::AngleLimit,
            ),
        ] {
            value.map_or(Ok(()), |v| range.check(field, v))?;
        }
        if t.max_time_steps < 1 {
            return Err(ConfigError::Integer {
                field: "max_time_steps",
                value: t.max_time_steps,
                expected: "at least 1",
            });
        }
        if let Some(h) = &t.height_penalty {
            for (field, value, range) in [
                (
                    "height_penalty.nominal_height_m",
                    h.nominal_height_m,
                    Range::Finite,
                ),
                (
                    "height_penalty.tolerance_m",
                    h.tolerance_m,
                    Range::NonNegative,
                ),
                ("height_penalty.rate_per_m", h.rate_per_m, Range::Positive),
            ] {
                range.check(field, value)?;
            }
        }
        Ok(())
    }

    /// Whether r_n or r_e is on: both divide by K = ‖G − C^0‖, so the episode's goal must then
    /// be away from its start (see [`crate::EpisodeRules::new`]).
    pub fn needs_start_goal_distance(&self) -> bool {
        self.norm_rew_scaling.is_some() || self.exp_rew_scaling.is_some()
    }
}

/// A reward scaling as written in a file: a number, or the string `"off"` (or a null, in the
/// formats that have one) for unset.
mod scaling {
    use serde::{Deserializer, Serializer, de};
    use std::fmt;

    /// The string that unsets an optional scaling in a configuration file.
    const OFF: &str = "off";

    pub fn serialize<S: Serializer>(value: &Option<f64>, serializer: S) -> Result<S::Ok, S::Error> {
        match value {
            Some(value) => serializer.serialize_f64(*value),
            None => serializer.serialize_str(OFF),
        }
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(
        deserializer: D,
    ) -> Result<Option<f64>, D::Error> {
        struct ScalingVisitor;
        impl de::Visitor<'_> for ScalingVisitor {
            type Value = Option<f64>;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                write!(f, "a number or the string \"{OFF}\"")
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Option<f64>, E> {
                Ok(Some(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Option<f64>, E> {
                Ok(Some(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Option<f64>, E> {
                Ok(Some(v as f64))
            }
            // Formats with a null (JSON, Python's None through a binding) may unset with it too.
            fn visit_unit<E: de::Error>(self) -> Result<Option<f64>, E> {
                Ok(None)
            }
            fn visit_none<E: de::Error>(self) -> Result<Option<f64>, E> {
                Ok(None)
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Option<f64>, E> {
                if v == OFF {
                    Ok(None)
                } else {
                    Err(E::invalid_value(de::Unexpected::Str(v), &self))
                }
            }
        }
        deserializer.deserialize_any(ScalingVisitor)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The bounds' words name the constants' values.
    #[test]
    fn the_upper_bounds_words_state_the_constants() {
        let words = |range: Range| match range {
            Range::Scale { why_max, .. } => why_max,
            _ => "",
        };
        assert!(words(EXP_SCALING).starts_with(&format!("at most {EXP_REW_SCALING_MAX},")));
        for range in [SCALING, AMOUNT] {
            assert!(words(range).starts_with(&format!("at most {REWARD_SCALE_MAX:e},")));
        }
    }
}
