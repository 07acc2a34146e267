//! `[velocity]`: every term's scale as a key, on top of a named preset of one anchor, and the
//! task's optional termination on trunk contact.
//!
//! The reward of a step is `Σ s_i · r_i · Δt_env` (both anchors scale by the policy period),
//! clipped below at 0 when `only_positive` (legged_gym's `only_positive_rewards`; Playground
//! clips its sum to [0, 10000]). A key left unset takes the preset's value:
//!
//! | key | `legged_gym` | `playground` |
//! |---|---|---|
//! | `tracking_lin_vel` | 1.0 | 1.0 |
//! | `tracking_ang_vel` | 0.5 | 0.5 |
//! | `lin_vel_z` | −2.0 | −0.5 |
//! | `ang_vel_xy` | −0.05 | −0.05 |
//! | `orientation` | 0 | −5.0 |
//! | `torques` | −1e-5 | 0 |
//! | `torques_abs` | 0 | −2e-4 |
//! | `joint_acc` | −2.5e-7 | 0 |
//! | `action_rate` | −0.01 | −0.01 |
//! | `feet_air_time` | 1.0 | 0.1 |
//! | `foot_slip` | 0 | −0.1 |
//! | `stand_still` | 0 | −1.0 |
//! | `joint_limits` | 0 | −1.0 |
//! | `termination` | 0 | −1.0 |
//! | `tracking_sigma` | 0.25 | 0.25 |
//! | `feet_air_time_threshold_s` | 0.5 | 0.1 |
//! | `soft_joint_limit_factor` | 1.0 | 0.95 |
//! | `command_gate` | 0.1 | 0.01 |
//! | `only_positive` | true | true |
//!
//! Sources: legged_gym `legged_robot_config.py` (`rewards.scales`, `tracking_sigma`,
//! `soft_dof_pos_limit`), its `_reward_feet_air_time` and `_reward_stand_still` gates; MuJoCo
//! Playground `go1/joystick.py` (`reward_config.scales`, `tracking_sigma`,
//! `soft_joint_pos_limit_factor`, its air-time threshold and command gate). Terms of the
//! anchors not listed (legged_gym's collision, Playground's pose, energy, foot clearance and
//! height) are not part of this task; docs/velocity.md says why.

use serde::{Deserialize, Serialize};

use crate::error::{ConfigError, check_in};

/// The largest magnitude of a term's scale.
pub const SCALE_MAX: f64 = 1.0e4;

macro_rules! velocity_terms {
    ($( $(#[$doc:meta])* $name:ident = $lg:expr, $pg:expr; )*) => {
        /// The unscaled value of every term on one step (see [`crate::terms`]).
        #[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
        pub struct TermValues {
            $( $(#[$doc])* pub $name: f64, )*
        }

        /// The terms' names, in [`TermValues::to_array`]'s order.
        pub const TERM_NAMES: &[&str] = &[$(stringify!($name)),*];

        impl TermValues {
            /// The values in [`TERM_NAMES`]' order.
            pub fn to_array(&self) -> [f64; TERM_NAMES.len()] {
                [$(self.$name),*]
            }
        }

        /// Each term's scale, resolved from a preset and the overrides.
        #[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
        pub struct TermScales {
            $( $(#[$doc])* pub $name: f64, )*
        }

        impl TermScales {
            /// The scales in [`TERM_NAMES`]' order.
            pub fn to_array(&self) -> [f64; TERM_NAMES.len()] {
                [$(self.$name),*]
            }

            /// legged_gym's base scales.
            pub const LEGGED_GYM: TermScales = TermScales { $($name: $lg),* };
            /// MuJoCo Playground's Go1 joystick scales.
            pub const PLAYGROUND: TermScales = TermScales { $($name: $pg),* };
        }

        /// `[velocity]`: a preset and any scale or setting set on top of it.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
        #[serde(deny_unknown_fields, default)]
        pub struct VelocityConfig {
            /// The anchor whose values the unset keys take. (default: `"legged_gym"`)
            pub preset: Preset,
            $(
                /// This term's scale, instead of the preset's; finite, |s| ≤ 1e4.
                #[serde(skip_serializing_if = "Option::is_none")]
                pub $name: Option<f64>,
            )*
            /// σ of the tracking terms (m²/s², rad²/s²), in (0, 100].
            #[serde(skip_serializing_if = "Option::is_none")]
            pub tracking_sigma: Option<f64>,
            /// The air time (s) a touchdown must beat to earn `feet_air_time`, in [0, 10].
            #[serde(skip_serializing_if = "Option::is_none")]
            pub feet_air_time_threshold_s: Option<f64>,
            /// The share of each joint's range, about its middle, within which `joint_limits`
            /// is 0, in (0, 1].
            #[serde(skip_serializing_if = "Option::is_none")]
            pub soft_joint_limit_factor: Option<f64>,
            /// The command norm above which the robot is asked to move (gait terms on) and
            /// below which to stand (`stand_still` on), in [0, 10].
            #[serde(skip_serializing_if = "Option::is_none")]
            pub command_gate: Option<f64>,
            /// Whether a step's total below 0 is clipped to 0.
            #[serde(skip_serializing_if = "Option::is_none")]
            pub only_positive: Option<bool>,
            /// Whether the trunk touching the ground ends the episode (legged_gym's base
            /// contact rule), besides being upside down (Playground's). (default: `false`)
            pub terminate_on_trunk_contact: bool,
        }

        impl VelocityConfig {
            /// The scales and settings: the preset's, with the keys set here on top.
            pub fn resolve(&self) -> RewardScales {
                let base = self.preset.scales();
                RewardScales {
                    terms: TermScales { $($name: self.$name.unwrap_or(base.terms.$name)),* },
                    tracking_sigma: self.tracking_sigma.unwrap_or(base.tracking_sigma),
                    feet_air_time_threshold_s: self
                        .feet_air_time_threshold_s
                        .unwrap_or(base.feet_air_time_threshold_s),
                    soft_joint_limit_factor: self
                        .soft_joint_limit_factor
                        .unwrap_or(base.soft_joint_limit_factor),
                    command_gate: self.command_gate.unwrap_or(base.command_gate),
                    only_positive: self.only_positive.unwrap_or(base.only_positive),
                }
            }

            /// Checks every key set against its range; the error names the first bad one.
            pub fn validate(&self) -> Result<(), ConfigError> {
                $(
                    if let Some(s) = self.$name {
                        check_in(
                            concat!("velocity.", stringify!($name)),
                            s, -SCALE_MAX, SCALE_MAX,
                        )?;
                    }
                )*
                self.validate_settings()
            }
        }
    };
}

velocity_terms! {
    /// exp(−‖c_xy − v_xy‖²/σ).
    tracking_lin_vel = 1.0, 1.0;
    /// exp(−(c_yaw − ω_z)²/σ).
    tracking_ang_vel = 0.5, 0.5;
    /// v_z².
    lin_vel_z = -2.0, -0.5;
    /// ω_x² + ω_y².
    ang_vel_xy = -0.05, -0.05;
    /// g_x² + g_y².
    orientation = 0.0, -5.0;
    /// Σ τ².
    torques = -1.0e-5, 0.0;
    /// ‖τ‖ + Σ|τ|.
    torques_abs = 0.0, -2.0e-4;
    /// Σ q̈².
    joint_acc = -2.5e-7, 0.0;
    /// Σ (a − a_prev)².
    action_rate = -0.01, -0.01;
    /// Σ (t_air − t_min) at touchdown, if moving.
    feet_air_time = 1.0, 0.1;
    /// Σ ‖v_foot,xy‖² in contact, if moving.
    foot_slip = 0.0, -0.1;
    /// Σ |q − q₀|, if standing.
    stand_still = 0.0, -1.0;
    /// Σ distance past the soft joint limits.
    joint_limits = 0.0, -1.0;
    /// 1 on a terminating step.
    termination = 0.0, -1.0;
}

/// The anchors whose values a `[velocity]` starts from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Preset {
    /// legged_gym's `LeggedRobotCfg.rewards` (base configuration).
    #[default]
    LeggedGym,
    /// MuJoCo Playground's `Go1JoystickFlatTerrain`.
    Playground,
}

impl Preset {
    /// Every preset, in documentation order.
    pub const ALL: [Preset; 2] = [Preset::LeggedGym, Preset::Playground];

    /// The preset's name as a configuration writes it.
    pub fn as_str(self) -> &'static str {
        match self {
            Preset::LeggedGym => "legged_gym",
            Preset::Playground => "playground",
        }
    }

    /// The preset's scales and settings.
    pub fn scales(self) -> RewardScales {
        match self {
            Preset::LeggedGym => RewardScales {
                terms: TermScales::LEGGED_GYM,
                tracking_sigma: 0.25,
                feet_air_time_threshold_s: 0.5,
                soft_joint_limit_factor: 1.0,
                command_gate: 0.1,
                only_positive: true,
            },
            Preset::Playground => RewardScales {
                terms: TermScales::PLAYGROUND,
                tracking_sigma: 0.25,
                feet_air_time_threshold_s: 0.1,
                soft_joint_limit_factor: 0.95,
                command_gate: 0.01,
                only_positive: true,
            },
        }
    }
}

/// The resolved scales and settings a step is judged with.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RewardScales {
    /// Each term's scale.
    pub terms: TermScales,
    /// σ of the tracking terms.
    pub tracking_sigma: f64,
    /// The air time a touchdown must beat (s).
    pub feet_air_time_threshold_s: f64,
    /// The soft limits' share of each joint range.
    pub soft_joint_limit_factor: f64,
    /// The command norm that separates moving from standing.
    pub command_gate: f64,
    /// Whether a negative total is clipped to 0.
    pub only_positive: bool,
}

impl VelocityConfig {
    /// The settings' checks (the scales' are in `validate`).
    fn validate_settings(&self) -> Result<(), ConfigError> {
        if let Some(s) = self.tracking_sigma {
            check_in("velocity.tracking_sigma", s, f64::MIN_POSITIVE, 100.0)?;
        }
        if let Some(t) = self.feet_air_time_threshold_s {
            check_in("velocity.feet_air_time_threshold_s", t, 0.0, 10.0)?;
        }
        if let Some(f) = self.soft_joint_limit_factor {
            check_in(
                "velocity.soft_joint_limit_factor",
                f,
                f64::MIN_POSITIVE,
                1.0,
            )?;
        }
        if let Some(g) = self.command_gate {
            check_in("velocity.command_gate", g, 0.0, 10.0)?;
        }
        Ok(())
    }
}
