//! `[regularizers]`: the legged-RL field's gait regularisers, and three goal terms for the
//! reach, as optional reward terms of the spec's goal task, every one off unless given a scale
//! (docs/regularizers.md).
//!
//! Each term is one of [`crate::terms`]' functions (a gait term the velocity task's own, a goal
//! term the heading or the start–goal line's geometry); this module only names them, holds their scales and adds them up. A step's regulariser reward is
//! `Σ s_i · r_i · Δt_env` over the terms whose scale is not 0 (legged_gym multiplies every
//! scale by the policy period), never clipped; docs/spec.md §7.12 rules how it joins the spec's
//! reward.
//!
//! | key | term | `legged_gym` preset | legged_gym's name |
//! |---|---|---|---|
//! | `action_rate` | Σ (a − a_prev)² | −0.01 | `action_rate` |
//! | `torques` | Σ τ² | −1e-5 | `torques` |
//! | `joint_acc` | Σ ((q̇ − q̇_prev) / Δt)² | −2.5e-7 | `dof_acc` |
//! | `feet_air_time` | Σ (t_air − t_min) over feet touching down | 1.0 | `feet_air_time` |
//! | `foot_slip` | Σ ‖v_foot,xy‖² over feet in contact | 0 (Playground's −0.1) | (none) |
//! | `base_height` | (h − h_target)² | 0 | `base_height` |
//! | `collision` | penalised bodies touching the ground | −1.0 | `collision` |
//! | `goal_heading` | \|∠(heading, bearing to the goal)\| | 0 | (none: the reach's shaping) |
//! | `goal_line` | distance off the start–goal line | 0 | (none: the reach's shaping) |
//! | `goal_line_approach` | (d_prev − d) / Δt, d the distance off that line | 0 | (none: the reach's shaping) |
//! | `orientation` | g_x² + g_y², g gravity in the trunk's frame | 0 | `orientation` |
//! | `feet_air_time_threshold_s` | t_min | 0.5 | `feet_air_time`'s 0.5 |
//! | `base_height_target_m` | h_target | the robot's standing height | `base_height_target` |
//!
//! Sources: legged_gym `legged_robot_config.py` (`rewards.scales`, `base_height_target`) and
//! `legged_robot.py` (`_reward_*`, `_prepare_reward_function`'s `*= self.dt`); Playground
//! `go1/joystick.py` (`feet_slip`).

use serde::de::{Error as _, MapAccess, Visitor};
use serde::ser::SerializeMap;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::error::{ConfigError, check_in};
use crate::scales::SCALE_MAX;
use crate::terms;

/// The largest base-height target (m).
pub const BASE_HEIGHT_TARGET_MAX_M: f64 = 10.0;
/// The largest air-time threshold (s).
pub const AIR_TIME_THRESHOLD_MAX_S: f64 = 10.0;

macro_rules! regularizers {
    ($( $(#[$doc:meta])* $name:ident = $lg:expr; )*) => {
        /// One number per regulariser: a step's values, or the scales.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
        pub struct RegularizerTerms {
            $( $(#[$doc])* pub $name: f64, )*
        }

        /// The regularisers' names, in [`RegularizerTerms::to_array`]'s order.
        pub const REGULARIZER_NAMES: &[&str] = &[$(stringify!($name)),*];

        /// How many regularisers there are.
        pub const REGULARIZER_COUNT: usize = REGULARIZER_NAMES.len();

        impl RegularizerTerms {
            /// The numbers in [`REGULARIZER_NAMES`]' order.
            pub fn to_array(&self) -> [f64; REGULARIZER_COUNT] {
                [$(self.$name),*]
            }

            /// The numbers of `a`, in [`REGULARIZER_NAMES`]' order.
            pub fn from_array(a: [f64; REGULARIZER_COUNT]) -> Self {
                let [$($name),*] = a;
                Self { $($name),* }
            }

            /// legged_gym's base scales (`LeggedRobotCfg.rewards.scales`).
            pub const LEGGED_GYM: RegularizerTerms = RegularizerTerms { $($name: $lg),* };
        }

        /// `[regularizers]`: a preset and any scale or setting set on top of it.
        #[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
        #[serde(deny_unknown_fields, default)]
        pub struct RegularizerConfig {
            /// The scales the unset keys take: `"off"` (every scale 0) or `"legged_gym"`.
            /// (default: `"off"`)
            pub preset: RegularizerPreset,
            $(
                /// This term's scale, instead of the preset's; finite, |s| ≤ 1e4; 0 is off.
                #[serde(skip_serializing_if = "Option::is_none")]
                pub $name: Option<f64>,
            )*
            /// The air time (s) a touchdown must beat to earn `feet_air_time`, in [0, 10].
            /// (default: 0.5, legged_gym's)
            #[serde(skip_serializing_if = "Option::is_none")]
            pub feet_air_time_threshold_s: Option<f64>,
            /// The trunk height above the ground (m) `base_height` measures from, in (0, 10].
            /// (default: the robot's standing height)
            #[serde(skip_serializing_if = "Option::is_none")]
            pub base_height_target_m: Option<f64>,
        }

        impl RegularizerConfig {
            /// The scales: the preset's, with the keys set here on top.
            pub fn scales(&self) -> RegularizerTerms {
                let base = self.preset.scales();
                RegularizerTerms { $($name: self.$name.unwrap_or(base.$name)),* }
            }

            /// Checks every key set against its range; the error names the first bad one.
            pub fn validate(&self) -> Result<(), ConfigError> {
                $(
                    if let Some(s) = self.$name {
                        check_in(
                            concat!("regularizers.", stringify!($name)),
                            s, -SCALE_MAX, SCALE_MAX,
                        )?;
                    }
                )*
                self.validate_settings()
            }
        }
    };
}

regularizers! {
    /// Σ (a − a_prev)².
    action_rate = -0.01;
    /// Σ τ².
    torques = -1.0e-5;
    /// Σ q̈².
    joint_acc = -2.5e-7;
    /// Σ (t_air − t_min) at touchdown.
    feet_air_time = 1.0;
    /// Σ ‖v_foot,xy‖² in contact.
    foot_slip = 0.0;
    /// (h − h_target)².
    base_height = 0.0;
    /// Penalised bodies touching the ground.
    collision = -1.0;
    /// |∠(trunk heading, bearing to the goal)| (rad).
    goal_heading = 0.0;
    /// The trunk's horizontal distance from the start–goal line (m).
    goal_line = 0.0;
    /// How fast that distance falls (m/s).
    goal_line_approach = 0.0;
    /// g_x² + g_y², gravity's direction in the trunk's frame: how far the trunk is from level.
    orientation = 0.0;
}

/// The scales a `[regularizers]` starts from.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum RegularizerPreset {
    /// Every scale 0: nothing on unless a key sets it.
    #[default]
    Off,
    /// legged_gym's base scales.
    LeggedGym,
}

impl RegularizerPreset {
    /// The preset's scales.
    pub fn scales(self) -> RegularizerTerms {
        match self {
            RegularizerPreset::Off => RegularizerTerms::default(),
            RegularizerPreset::LeggedGym => RegularizerTerms::LEGGED_GYM,
        }
    }
}

impl RegularizerConfig {
    /// Whether every scale is 0 (the environment is then the spec's, bit for bit).
    pub fn is_off(&self) -> bool {
        self.scales().to_array().iter().all(|s| *s == 0.0)
    }

    /// Whether the table holds its defaults (it is then not written).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// The scales and settings, `standing_height` (m) standing in for an unset base-height
    /// target.
    pub fn resolve(&self, standing_height: f64) -> RegularizerScales {
        RegularizerScales {
            terms: self.scales(),
            feet_air_time_threshold_s: self.feet_air_time_threshold_s.unwrap_or(0.5),
            base_height_target_m: self.base_height_target_m.unwrap_or(standing_height),
        }
    }

    /// The settings' checks (the scales' are in `validate`).
    fn validate_settings(&self) -> Result<(), ConfigError> {
        if let Some(t) = self.feet_air_time_threshold_s {
            check_in(
                "regularizers.feet_air_time_threshold_s",
                t,
                0.0,
                AIR_TIME_THRESHOLD_MAX_S,
            )?;
        }
        if let Some(h) = self.base_height_target_m {
            check_in(
                "regularizers.base_height_target_m",
                h,
                f64::MIN_POSITIVE,
                BASE_HEIGHT_TARGET_MAX_M,
            )?;
        }
        Ok(())
    }
}

/// The resolved scales and settings a step is judged with.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegularizerScales {
    /// Each term's scale (0: off).
    pub terms: RegularizerTerms,
    /// The air time a touchdown must beat (s).
    pub feet_air_time_threshold_s: f64,
    /// The trunk height `base_height` measures from (m).
    pub base_height_target_m: f64,
}

impl RegularizerScales {
    /// Which terms are on (scale not 0), in [`REGULARIZER_NAMES`]' order.
    pub fn on(&self) -> [bool; REGULARIZER_COUNT] {
        self.terms.to_array().map(|s| s != 0.0)
    }
}

/// Everything the regularisers judge a step on, as plain numbers (joints in action order, feet
/// in the robot's order).
#[derive(Clone, Copy, Debug)]
pub struct RegularizerSnapshot<'a> {
    /// The step's action, as given.
    pub action: &'a [f64],
    /// The previous step's action (zeros on an episode's first step).
    pub previous_action: &'a [f64],
    /// The joint torques of the step's last sub-step (N·m).
    pub torques: &'a [f64],
    /// q̇ at the end of the step (rad/s).
    pub joint_speeds: &'a [f64],
    /// q̇ at the end of the previous step (rad/s; zeros after reset, at rest).
    pub previous_joint_speeds: &'a [f64],
    /// Each foot's air time at touchdown this step (s), 0 for a foot not touching down
    /// ([`crate::step::AirTime::update`]).
    pub air_at_touchdown: &'a [f64],
    /// Each foot's horizontal velocity (m/s, world frame).
    pub foot_velocity_xy: &'a [[f64; 2]],
    /// Which feet touched the ground during the step.
    pub foot_contacts: &'a [bool],
    /// The trunk's height above the ground under it (m).
    pub base_height: f64,
    /// Gravity's direction in the trunk's frame, Rᵀ (0, 0, −1).
    pub projected_gravity: [f64; 3],
    /// Which penalised bodies touched the ground during the step.
    pub penalised_contacts: &'a [bool],
    /// The goal task's geometry at the end of the step.
    pub goal: GoalGeometry,
    /// The trunk's distance off the start–goal line at the end of the previous step (m; 0
    /// after reset).
    pub previous_goal_line: f64,
    /// Δt_env (s).
    pub env_dt: f64,
}

/// Where the trunk is and faces, and where its episode started and its goal is: the goal terms'
/// inputs, horizontal (world x and y, m).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct GoalGeometry {
    /// The trunk frame origin (C^t).
    pub trunk: [f64; 2],
    /// The trunk's x axis, horizontal part (not normalised; zero when it points straight up or
    /// down).
    pub heading: [f64; 2],
    /// The episode's start (C^0).
    pub start: [f64; 2],
    /// The goal (G).
    pub goal: [f64; 2],
}

/// Every regulariser's value on the step `s` (off terms too; the sum leaves them out).
pub fn values(scales: &RegularizerScales, s: &RegularizerSnapshot<'_>) -> RegularizerTerms {
    let goal_line = terms::goal_line(s.goal.start, s.goal.goal, s.goal.trunk);
    RegularizerTerms {
        action_rate: terms::action_rate(s.action, s.previous_action),
        torques: terms::torques(s.torques),
        joint_acc: terms::joint_acc(s.joint_speeds, s.previous_joint_speeds, s.env_dt),
        feet_air_time: terms::feet_air_time(
            s.air_at_touchdown,
            scales.feet_air_time_threshold_s,
            true,
        ),
        foot_slip: terms::foot_slip(s.foot_velocity_xy, s.foot_contacts, true),
        base_height: terms::base_height(s.base_height, scales.base_height_target_m),
        collision: terms::collision(s.penalised_contacts),
        goal_heading: terms::goal_heading(s.goal.trunk, s.goal.heading, s.goal.goal),
        goal_line,
        goal_line_approach: terms::goal_line_approach(s.previous_goal_line, goal_line, s.env_dt),
        orientation: terms::orientation(s.projected_gravity),
    }
}

/// Σ s_i · r_i · Δt over the terms whose scale is not 0, in [`REGULARIZER_NAMES`]' order,
/// unclipped. A term whose scale is 0 adds nothing, even when its value is not finite.
pub fn reward(scales: &RegularizerTerms, values: &RegularizerTerms, dt: f64) -> f64 {
    scales
        .to_array()
        .iter()
        .zip(values.to_array())
        .filter(|(s, _)| **s != 0.0)
        .map(|(s, v)| s * v * dt)
        .sum()
}

/// A step's regulariser values as reported: the terms that are on, by name, in
/// [`REGULARIZER_NAMES`]' order (a term that is off is not written and reads back as off).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct ReportedRegularizers {
    /// Each term's value (0 for one that is off).
    pub values: RegularizerTerms,
    /// Which terms are on.
    pub on: [bool; REGULARIZER_COUNT],
}

impl ReportedRegularizers {
    /// The terms that are on, with their values, in order.
    pub fn iter(&self) -> impl Iterator<Item = (&'static str, f64)> + '_ {
        REGULARIZER_NAMES
            .iter()
            .zip(self.values.to_array())
            .zip(self.on)
            .filter(|(_, on)| *on)
            .map(|((name, v), _)| (*name, v))
    }

    /// The value of the term named `name`, if it is on.
    pub fn get(&self, name: &str) -> Option<f64> {
        self.iter().find(|(n, _)| *n == name).map(|(_, v)| v)
    }
}

impl Serialize for ReportedRegularizers {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(None)?;
        for (name, v) in self.iter() {
            map.serialize_entry(name, &v)?;
        }
        map.end()
    }
}

impl<'de> Deserialize<'de> for ReportedRegularizers {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct Terms;
        impl<'de> Visitor<'de> for Terms {
            type Value = ReportedRegularizers;
            fn expecting(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                write!(
                    f,
                    "a map of regulariser names ({REGULARIZER_NAMES:?}) to numbers"
                )
            }
            fn visit_map<A: MapAccess<'de>>(self, mut m: A) -> Result<Self::Value, A::Error> {
                let mut values = [0.0; REGULARIZER_COUNT];
                let mut on = [false; REGULARIZER_COUNT];
                while let Some((name, v)) = m.next_entry::<String, f64>()? {
                    let k = REGULARIZER_NAMES
                        .iter()
                        .position(|n| *n == name)
                        .ok_or_else(|| A::Error::unknown_field(&name, REGULARIZER_NAMES))?;
                    if on[k] {
                        return Err(A::Error::custom(format!("duplicate regulariser `{name}`")));
                    }
                    values[k] = v;
                    on[k] = true;
                }
                Ok(ReportedRegularizers {
                    values: RegularizerTerms::from_array(values),
                    on,
                })
            }
        }
        d.deserialize_map(Terms)
    }
}
