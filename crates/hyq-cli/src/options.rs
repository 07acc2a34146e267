//! The options subcommands share: the physics backend, the robot, a configuration file and `--set`
//! overrides of single configuration values ([`EnvArgs`], with the configuration part alone in
//! [`ConfigArgs`] for commands that build no environment), the policy and seed of the commands
//! that run an episode ([`PolicyArgs`]); and building the environment and the policy from them.

use std::path::PathBuf;
use std::sync::Arc;

use clap::Args;
use hyq_env::{Env, EnvConfig, LoadError, Policy, RandomPolicy, Stand, Trot};
use hyq_physics::{Backend, RobotModel};

use crate::Failure;
use crate::backend::BackendChoice;
use crate::run::PolicyChoice;

/// The environment's options (shared by `run`, `bench`, `soak` and `render`).
#[derive(Debug, Clone, Args)]
pub struct EnvArgs {
    /// The physics backend.
    #[arg(long, value_enum, default_value_t = BackendChoice::Rapier)]
    pub backend: BackendChoice,
    /// The robot.
    #[command(flatten)]
    pub robot: RobotArgs,
    /// The configuration file and overrides.
    #[command(flatten)]
    pub configuration: ConfigArgs,
}

/// The robot option (shared by every command that builds an environment, and `hyq model`).
#[derive(Debug, Clone, Args)]
pub struct RobotArgs {
    /// The robot: a bundled robot's name (hyq, anymal_c) or the path to a robot profile (a
    /// .toml file next to its URDF; see docs/adding-a-robot.md).
    #[arg(long = "robot", value_name = "NAME|PROFILE.toml", default_value = hyq_physics::bundled::DEFAULT)]
    pub choice: String,
}

impl RobotArgs {
    /// The chosen robot's model: a bundled one is shared, a profile is loaded. A choice that is
    /// neither, or a profile that cannot be used, is a usage error naming it.
    pub fn model(&self) -> Result<Arc<RobotModel>, Failure> {
        hyq_physics::resolve_robot(&self.choice).map_err(|e| {
            usage(format!(
                "--robot {}: {}",
                self.choice,
                one_line(&e.to_string())
            ))
        })
    }
}

/// `text` on one line: line breaks (from a parser's multi-line message) become spaces.
fn one_line(text: &str) -> String {
    text.split_whitespace().collect::<Vec<_>>().join(" ")
}

/// The configuration options alone: a file and `--set` overrides (`hyq plot` reads k_exp and
/// the env step from them without building an environment).
#[derive(Debug, Clone, Args)]
pub struct ConfigArgs {
    /// A TOML configuration file (tables [task], [goal], [action], [control], [physics],
    /// [reset]; every key optional). Unknown keys are errors.
    #[arg(long, value_name = "FILE")]
    pub config: Option<PathBuf>,
    /// Override one configuration value, after the file: `table.key=value`, e.g.
    /// `--set task.fall_penalty=1` or `--set goal.distance_m=3`. Repeatable; all overrides are
    /// applied together, then the whole configuration is validated.
    #[arg(long = "set", value_name = "TABLE.KEY=VALUE")]
    pub set: Vec<String>,
}

/// A usage error (status 2) with `message`.
pub fn usage(message: impl Into<String>) -> Failure {
    Failure {
        status: 2,
        message: message.into(),
    }
}

impl EnvArgs {
    /// The configuration: the defaults, then the file, then the overrides, validated.
    pub fn config(&self) -> Result<EnvConfig, Failure> {
        self.configuration.config()
    }

    /// The chosen robot's model (see [`RobotArgs::model`]).
    pub fn model(&self) -> Result<Arc<RobotModel>, Failure> {
        self.robot.model()
    }
}

impl ConfigArgs {
    /// The configuration: the defaults, then the file, then the overrides, validated.
    pub fn config(&self) -> Result<EnvConfig, Failure> {
        let mut pairs = Vec::with_capacity(self.set.len());
        for item in &self.set {
            let (key, value) = item.split_once('=').ok_or_else(|| {
                usage(format!(
                    "--set {item:?}: expected TABLE.KEY=VALUE, e.g. --set task.fall_penalty=1"
                ))
            })?;
            let key = key.trim();
            if key.is_empty() {
                return Err(usage(format!(
                    "--set {item:?}: the key before `=` is empty (expected TABLE.KEY=VALUE)"
                )));
            }
            pairs.push((key, value.trim()));
        }
        EnvConfig::load(self.config.as_deref(), &pairs).map_err(|e| match e {
            LoadError::File(e) => usage(e.to_string()),
            LoadError::Overrides(e) => usage(format!("--set: {e}")),
        })
    }
}

/// An environment on backend `B` with `config`.
pub fn make_env<B: Backend>(model: Arc<RobotModel>, config: EnvConfig) -> Result<Env<B>, Failure> {
    Env::new(model, config)
        .map_err(|e| usage(format!("cannot build the {} environment: {e}", B::NAME)))
}

/// The policy and seed of a command that runs episodes (`run`, `render`).
#[derive(Debug, Clone, Args)]
pub struct PolicyArgs {
    /// The policy.
    #[arg(long, value_enum, default_value_t = PolicyChoice::Trot)]
    pub policy: PolicyChoice,
    /// Seed of the first reset (goal and reset-noise streams) and of the random policy.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

impl PolicyArgs {
    /// The chosen policy for `env`'s robot (the random one seeded with `--seed`).
    pub fn make<B: Backend>(&self, env: &Env<B>) -> Result<Box<dyn Policy>, Failure> {
        Ok(match self.policy {
            PolicyChoice::Stand => Box::new(Stand),
            PolicyChoice::Random => Box::new(RandomPolicy::new(self.seed)),
            PolicyChoice::Trot => Box::new(
                Trot::from_profile(env.model())
                    .map_err(|e| usage(format!("--policy trot: {e}")))?,
            ),
        })
    }
}
