//! The HyQ walk-to-goal environment: the spec's rules (`hyq-spec`) on a physics backend
//! (`hyq-physics`), with actions, goals, resets, policies and vector envs.

pub mod action;
pub mod config;
pub mod env;
pub mod goal;
pub mod info;

pub use action::{ActionError, ActionScalar, ActionSpace};
pub use config::{
    ActionConfig, ActionMode, ConfigError, ControlConfig, EnvConfig, Gains, GoalConfig, GoalMode,
    OutOfRange, PhysicsConfig, ResetConfig,
};
pub use env::{DEFAULT_SEED, Env, EnvError, Reset, ResetOptions, Step, StepTiming};
pub use info::{Reason, Reasons, StepInfo};
