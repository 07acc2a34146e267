//! What the velocity task reports in a step's info, as the fronts read it: [`VELOCITY_INFO_KEYS`]
//! (flat keys `velocity.<name>` in Python's info), declared as the info's
//! [`INFO_KEYS`](crate::INFO_KEYS) is.

use super::VelocityInfo;
use crate::info::{InfoKey, InfoValue, StepInfo, VectorLen};

/// The prefix of every key of [`VELOCITY_INFO_KEYS`].
pub const VELOCITY_PREFIX: &str = "velocity.";

/// `info`'s velocity-task report, when it has one.
fn report(info: &StepInfo) -> Option<&VelocityInfo> {
    info.velocity.as_ref()
}

/// The `k`-th term (hyq-tasks' `TERM_NAMES` order) of `info`'s report, 0 without one.
fn term(info: &StepInfo, k: usize) -> f64 {
    report(info).map_or(0.0, |v| v.terms.to_array()[k])
}

macro_rules! term_keys {
    ($($k:literal => $name:literal),* $(,)?) => {
        /// The info keys an environment under `task.kind = "velocity"` adds to
        /// [`INFO_KEYS`](crate::INFO_KEYS), on every step and reset, in the order a front writes
        /// them (the spec's task has none of them): the command, the trunk's velocities, the
        /// task's reward and each of its terms unscaled.
        pub const VELOCITY_INFO_KEYS: [InfoKey; 5 + hyq_tasks::TERM_NAMES.len()] = [
            InfoKey {
                name: "velocity.command",
                value: InfoValue::Vector(|i| report(i).map_or(&[], |v| &v.command), VectorLen::Three),
                meaning: "the command the step was judged by: v_x, v_y (m/s), yaw rate (rad/s)",
            },
            InfoKey {
                name: "velocity.next_command",
                value: InfoValue::Vector(
                    |i| report(i).map_or(&[], |v| &v.next_command),
                    VectorLen::Three,
                ),
                meaning: "the command the returned observation holds",
            },
            InfoKey {
                name: "velocity.lin_vel",
                value: InfoValue::Vector(|i| report(i).map_or(&[], |v| &v.lin_vel), VectorLen::Three),
                meaning: "the trunk's velocity in its frame (m/s)",
            },
            InfoKey {
                name: "velocity.ang_vel",
                value: InfoValue::Vector(|i| report(i).map_or(&[], |v| &v.ang_vel), VectorLen::Three),
                meaning: "the trunk's angular velocity in its frame (rad/s)",
            },
            InfoKey {
                name: "velocity.reward",
                value: InfoValue::Float(|i| report(i).map_or(0.0, |v| v.reward)),
                meaning: "the task's reward, the step's",
            },
            $(
                InfoKey {
                    name: concat!("velocity.", $name),
                    value: InfoValue::Float(|i| term(i, $k)),
                    meaning: "the term, unscaled (docs/velocity.md)",
                },
            )*
        ];
    };
}

term_keys! {
    0 => "tracking_lin_vel",
    1 => "tracking_ang_vel",
    2 => "lin_vel_z",
    3 => "ang_vel_xy",
    4 => "orientation",
    5 => "torques",
    6 => "torques_abs",
    7 => "joint_acc",
    8 => "action_rate",
    9 => "feet_air_time",
    10 => "foot_slip",
    11 => "stand_still",
    12 => "joint_limits",
    13 => "termination",
}
