//! The HyQ walk-to-goal environment: the spec's rules (`hyq-spec`) on a physics backend
//! (`hyq-physics`), with actions, goals, resets, policies and vector envs.

pub mod action;
pub mod config;
pub mod env;
pub mod goal;
pub mod info;
pub mod policy;
pub mod record;
pub mod testing;
pub mod vec_env;

pub use action::{ActionError, ActionScalar, ActionSpace};
pub use config::{
    ActionConfig, ActionMode, ConfigError, ControlConfig, EnvConfig, Gains, GoalConfig, GoalMode,
    OutOfRange, PhysicsConfig, ResetConfig,
};
pub use env::{DEFAULT_SEED, Env, EnvError, Reset, ResetOptions, Step, StepTiming};
pub use info::{Reason, Reasons, StepInfo};
pub use policy::{Policy, PolicyInput, RandomPolicy, Stand, Trot, TrotParams};
pub use record::{RecordTerms, StepRecord};
pub use vec_env::{AutoReset, VecEnv, VecEnvError, VecStepOut};
