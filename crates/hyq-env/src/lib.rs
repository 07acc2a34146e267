//! The HyQ walk-to-goal environment: IIT's HyQ quadruped (87 kg, 12 joints) must walk its trunk
//! to a goal. The spec's rules (`hyq-spec`: rewards, penalties, terminations, the observation
//! layout) run on a physics backend (`hyq-physics`' `Backend`: rapier by default, DART and
//! MuJoCo beside it), with actions, goals, resets, scripted and trained policies, a vector env
//! and one record schema around them.
//!
//! # Quickstart
//!
//! ```
//! use hyq_env::policy::{Policy, Stand};
//! use hyq_env::{Env, EnvConfig, ResetOptions};
//! use hyq_rapier::RapierBackend;
//!
//! let mut env = Env::<RapierBackend>::new(hyq_physics::bundled::hyq(), EnvConfig::default())?;
//! env.reset(Some(42), &ResetOptions::default())?;
//! let (mut policy, mut action) = (Stand, vec![0.0; 12]);
//! for _ in 0..50 {
//!     policy.act(&env.policy_input(), &mut action);
//!     let step = env.step(&action)?;
//!     assert!(!step.terminated && step.observation_f32.len() == 39);
//! }
//! assert!(env.info().distance_to_goal > 4.9); // standing still, 5 m from the goal
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
//!
//! The env card below is the README's (one text, kept true against the code by xtask's tests).
//!
#![doc = include_str!(env!("HYQ_ENV_CARD"))]
//!
//! # Configuration
//!
//! One TOML file ([`EnvConfig`]), a table per concern ([`EnvConfig::TABLES`]): `[task]` (the
//! spec's user variables, `hyq_spec::TaskConfig`), where the goal is, how actions map to joint
//! targets, the actuator, the physics (with one table per engine) and the reset. Every key has
//! a documented default, unknown keys are errors naming the key, and [`EnvConfig::set_all`]
//! overrides by dotted key (`"task.fall_penalty"`, `"1.5"`).
//!
//! # Modules
//!
//! | module | what |
//! |---|---|
//! | [`env`](mod@env) | [`Env`]: reset, step, the sub-step loop, divergence, timing |
//! | [`config`] | [`EnvConfig`] and its tables, one file each; reading, validation, messages |
//! | [`action`] | [`ActionSpace`]: checking actions and mapping them to joint targets |
//! | [`error`] | [`EnvError`]: why the environment refused a call |
//! | [`goal`] | goal sampling, the reset state and the rules of an episode from its start to its goal |
//! | [`info`] | [`StepInfo`], [`Reason`], [`Reasons`]; [`INFO_KEYS`], the info's schema |
//! | [`divergence`] | [`Divergence`]: why a step diverged, the text of the info's `divergence` |
//! | [`policy`] | [`Stand`], [`RandomPolicy`], [`Trot`] |
//! | [`mlp`] | [`MlpPolicy`]: a trained policy read from a safetensors file, run in plain Rust |
//! | [`observation`] | the observation's rows beyond the spec's (`observation.extra`): height scan, goal vector, trunk velocity |
//! | [`randomize`] | `[randomize]`: varied dynamics, actuator and delay, observation noise, pushes |
//! | [`vec_env`] | [`VecEnv`]: N envs on rayon into flat buffers, autoreset modes |
//! | [`velocity`] | `task.kind = "velocity"`: the velocity-command task's state, observation group and info (rules in `hyq-tasks`) |
//! | [`regularizers`] | `[regularizers]`: the gait regularisers' state and info added to the goal task's reward (rules in `hyq-tasks`) |
//! | `gait` (private) | the state both of them keep between steps: the previous action and joint speeds, the feet's air times and velocities |
//! | [`settle`] | a robot's standing height as `hyq robot init` measures it: the standing pose held for 1 s, seed 0 |
//! | [`record`] | [`StepRecord`]: the per-step JSONL schema |
//! | [`terrain`] | [`terrain::Ground`]: the ground of each episode, the robot put down on it, the goal over it, the curriculum |
//! | [`testing`] | [`testing::ScriptedBackend`]: a scripted backend for contract tests |
//!
//! # Measured
//!
//! What the scripted trot does on each engine, and what a step costs and where the time goes:
//! `docs/benchmarks.md`, with the commands that measure them.

pub mod action;
pub mod config;
pub mod divergence;
pub mod env;
pub mod error;
mod gait;
pub mod goal;
pub mod info;
pub mod mlp;
pub mod observation;
pub mod policy;
pub mod randomize;
pub mod record;
pub mod regularizers;
pub mod settle;
pub mod terrain;
pub mod testing;
pub mod vec_env;
pub mod velocity;

pub use action::{ActionError, ActionScalar, ActionSpace};
pub use config::RandomizeConfig;
pub use config::{
    ActionConfig, ActionMode, ConfigError, ControlConfig, EXP_REW_SCALING_MAX, EnvConfig, Gains,
    GoalConfig, GoalMode, JOINT_NOISE_MAX_RAD, LoadError, ObservationConfig, ObservationExtra,
    OutOfRange, PhysicsConfig, REWARD_SCALE_MAX, ResetConfig, StairsClimb, TaskKind, TaskTable,
    TerrainConfig, TerrainKind, TerrainSeed, WORLD_HALF_EXTENT_M,
};
pub use config::{CommandConfig, VelocityConfig};
pub use divergence::Divergence;
pub use env::{
    DEFAULT_SEED, Env, Reset, ResetOptions, Step, StepTiming, observation_layout_for,
    observation_layout_of,
};
pub use error::EnvError;
pub use hyq_spec::TermSums;
pub use info::{
    INFO_KEYS, InfoKey, InfoValue, RANDOMIZE_INFO_KEYS, Reason, Reasons, StepInfo, VectorLen,
};
pub use mlp::{MlpError, MlpMetadata, MlpPolicy};
pub use policy::{Policy, PolicyInput, RandomPolicy, Stand, Trot, TrotParams};
pub use randomize::{EpisodeDraw, EpisodeRandomization, Preset, RandomizeInfo};
pub use record::{RECORD_KEYS, RecordKey, StepRecord, VelocityRecord};
pub use regularizers::{REGULARIZER_INFO_KEYS, RegularizerInfo, regularizer_info_keys};
pub use vec_env::{AutoReset, MAX_ENVS, MAX_THREADS, VecEnv, VecEnvError, VecStepOut};
pub use velocity::{VELOCITY_INFO_KEYS, VelocityInfo};

/// The repository README, whose Rust quickstart runs as a doctest of this crate so that it stays
/// true (only with `cargo test --doc`; nothing of it is compiled into the library).
#[cfg(doctest)]
#[doc = include_str!("../../../README.md")]
pub struct ReadmeQuickstart;
