//! Tasks beside the spec's. The spec's task (walk the trunk to a goal) is `hyq-spec`'s and stays
//! the environment's default; this crate holds the other task legged-RL users train, the
//! velocity-command ("joystick") task: follow a commanded forward, sideways and turning speed.
//!
//! Its rules are pure functions of explicit numbers, as hyq-spec's are, with the definitions of
//! its two anchors (legged_gym's `LeggedRobot` and MuJoCo Playground's Go1 joystick), and the
//! rulings where this crate departs from either in docs/velocity.md:
//!
//! | module | what |
//! |---|---|
//! | [`command`] | `[command]`: the ranges, the resampling rules (uniform, keep/zero), standing commands, the seeded draws |
//! | [`terms`] | each reward term as a function of numbers (tracking `exp(−err²/σ)`, the regularisers) |
//! | [`scales`] | `[velocity]`: every term's scale as a key, and the anchors' presets |
//! | [`step`] | one step of the task: the terms, their scaled sum and the terminations from a [`step::VelocitySnapshot`] |
//! | [`regularizers`] | `[regularizers]`: gait regularisers for the spec's goal task, each a [`terms`] function, off unless scaled |
//! | [`termination`] | Playground's upside-down rule, trunk contact as an option |
//! | [`error`] | [`ConfigError`]: a key's value refused, named by its dotted key |
//! | [`observation`] | the task's observation rows (body-frame velocities, projected gravity, command, joints, last action) |
//!
//! No I/O, no simulator, no environment: the environment (`hyq-env`) reads the robot and the
//! state, builds the snapshot, and reports what comes back.

pub mod command;
pub mod error;
pub mod observation;
pub mod regularizers;
pub mod scales;
pub mod step;
pub mod termination;
pub mod terms;

pub use command::{Command, CommandConfig, CommandSampler, ResamplingRule, ResamplingTiming};
pub use error::ConfigError;
pub use regularizers::{
    GoalGeometry, REGULARIZER_NAMES, RegularizerConfig, RegularizerPreset, RegularizerScales,
    RegularizerTerms, ReportedRegularizers,
};
pub use scales::{Preset, RewardScales, TERM_NAMES, TermScales, TermValues, VelocityConfig};
pub use step::{AirTime, FootVelocity, VelocityOutcome, VelocitySnapshot, evaluate};
