//! The options subcommands share: the physics backend, the robot, a configuration file and `--set`
//! overrides of single configuration values ([`EnvArgs`], with the configuration part alone in
//! [`ConfigArgs`] for commands that build no environment), the policy and seed of the commands
//! that run an episode ([`PolicyArgs`]); and building the environment and the policy from them.

use std::path::PathBuf;
use std::sync::Arc;

use clap::Args;
use hyq_env::{
    ConfigError, Env, EnvConfig, LoadError, MlpPolicy, Policy, RandomPolicy, Stand, Trot,
};
use hyq_physics::{Backend, RobotModel};

use crate::Failure;
use crate::backend::BackendChoice;

/// The policies `hyq run` can drive the robot with (`--policy stand|random|trot|mlp:FILE`).
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PolicyChoice {
    /// Hold the standing pose.
    Stand,
    /// Uniform random actions in the action space (seeded by --seed).
    Random,
    /// hyq-env's scripted open-loop trot along +x.
    Trot,
    /// A trained MLP read from a `hyq-mlp-policy` safetensors file (hyq-env's `mlp` module),
    /// run in the environment it was trained in unless a key is set by the user.
    Mlp(PathBuf),
}

impl std::str::FromStr for PolicyChoice {
    type Err = String;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s {
            "stand" => Ok(Self::Stand),
            "random" => Ok(Self::Random),
            "trot" => Ok(Self::Trot),
            _ => match s.strip_prefix("mlp:") {
                Some("") => {
                    Err("mlp: needs a file, e.g. mlp:assets/policies/hyq_walk.safetensors".into())
                }
                Some(file) => Ok(Self::Mlp(PathBuf::from(file))),
                None => Err(format!(
                    "{s:?} is not a policy: expected stand, random, trot or mlp:FILE"
                )),
            },
        }
    }
}

impl std::fmt::Display for PolicyChoice {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Self::Stand => f.write_str("stand"),
            Self::Random => f.write_str("random"),
            Self::Trot => f.write_str("trot"),
            Self::Mlp(file) => write!(f, "mlp:{}", file.display()),
        }
    }
}

/// The environment's options (shared by `run`, `bench`, `soak` and `render`).
#[derive(Debug, Clone, Args)]
pub struct EnvArgs {
    /// The physics backend.
    #[arg(long, value_enum, default_value_t = BackendChoice::DEFAULT)]
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
    /// The robot: a bundled robot's name (hyq, anymal_c, go1, a1, go1_urdf, anymal_b, laikago),
    /// the path to a robot profile (a .toml file next to its URDF or MJCF file; see
    /// docs/adding-a-robot.md), or an MJCF file with a keyframe and a <position> actuator on
    /// every joint (its profile drafted in memory, as `hyq robot init` drafts it).
    #[arg(long = "robot", value_name = "NAME|PROFILE.toml|ROBOT.xml", default_value = hyq_physics::bundled::DEFAULT)]
    pub choice: String,
}

impl RobotArgs {
    /// The chosen robot's model: a bundled one is shared, a profile is loaded. A choice that is
    /// neither, or a profile that cannot be used, is a usage error naming it.
    pub fn model(&self) -> Result<Arc<RobotModel>, Failure> {
        hyq_formats::robots::resolve_with(&self.choice, Some(&settle_height)).map_err(|e| {
            usage(format!(
                "--robot {}: {}",
                self.choice,
                hyq_physics::one_line(&e.to_string())
            ))
        })
    }
}

/// The configuration options alone: a file and `--set` overrides (`hyq plot` reads k_exp and
/// the env step from them without building an environment).
#[derive(Debug, Clone, Args)]
pub struct ConfigArgs {
    /// A TOML configuration file: a table per concern ([task] the spec's user variables, [goal],
    /// [action], [physics], ...: the crate README lists them), every key optional. Unknown keys
    /// are errors.
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
        self.config_over(&[], "")
    }

    /// The configuration with `base` (dotted keys and TOML values, e.g. a trained policy's
    /// environment) applied too: the defaults, then the file, then `base` except the keys the
    /// file or an override sets, then the overrides, validated once. An error about a key of
    /// `base` is told as `base_origin`'s (e.g. `--policy mlp:FILE: its env_config`), not as
    /// `--set`'s.
    pub fn config_over(
        &self,
        base: &[(String, String)],
        base_origin: &str,
    ) -> Result<EnvConfig, Failure> {
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
        let inherited = self.inherited(base)?;
        let base_keys: Vec<&str> = inherited.iter().map(|(k, _)| k.as_str()).collect();
        let inherited = inherited.iter().map(|(k, v)| (k.as_str(), v.as_str()));
        pairs.splice(0..0, inherited);
        EnvConfig::load(self.config.as_deref(), &pairs).map_err(|e| match e {
            LoadError::Overrides(e) if key_of(&e).is_some_and(|k| base_keys.contains(&k)) => {
                usage(format!("{base_origin}: {e}"))
            }
            other => load_error(other),
        })
    }
}

impl ConfigArgs {
    /// The entries of `base` that apply: those whose key neither the file nor an override
    /// sets. A bad file gets the loader's own error.
    pub fn inherited<'a>(
        &self,
        base: &'a [(String, String)],
    ) -> Result<Vec<&'a (String, String)>, Failure> {
        if base.is_empty() {
            return Ok(Vec::new());
        }
        let mut user_keys: Vec<String> = self
            .set
            .iter()
            .filter_map(|item| item.split_once('=').map(|(k, _)| k.trim().to_owned()))
            .collect();
        if let Some(path) = &self.config {
            // The file alone first, so that a bad file gets the loader's own error.
            EnvConfig::load::<&str, &str>(Some(path), &[]).map_err(load_error)?;
            user_keys.extend(file_keys(path)?);
        }
        Ok(base
            .iter()
            .filter(|(k, _)| !user_keys.contains(k))
            .collect())
    }
}

/// The key a configuration error names, if it names one.
fn key_of(e: &ConfigError) -> Option<&str> {
    match e {
        ConfigError::Set { key, .. } | ConfigError::Invalid { key, .. } => Some(key),
        _ => None,
    }
}

fn load_error(e: LoadError) -> Failure {
    match e {
        LoadError::File(e) => usage(e.to_string()),
        LoadError::Overrides(e) => usage(format!("--set: {e}")),
    }
}

/// The dotted keys a TOML configuration file sets (`task.fall_penalty`, `physics.rapier.x`).
fn file_keys(path: &std::path::Path) -> Result<Vec<String>, Failure> {
    fn walk(prefix: &str, table: &toml::Table, out: &mut Vec<String>) {
        for (key, value) in table {
            let dotted = if prefix.is_empty() {
                key.clone()
            } else {
                format!("{prefix}.{key}")
            };
            match value {
                toml::Value::Table(inner) => walk(&dotted, inner, out),
                _ => out.push(dotted),
            }
        }
    }
    // The loader has read and validated the file already; these errors are for a file changed
    // in between.
    let text = hyq_physics::input::read_text(path, &hyq_physics::input::CONFIG)
        .map_err(|e| usage(format!("--config {}: {e}", path.display())))?;
    let table: toml::Table = text.parse().map_err(|e: toml::de::Error| {
        usage(format!("--config {}: {}", path.display(), e.message()))
    })?;
    let mut keys = Vec::new();
    walk("", &table, &mut keys);
    Ok(keys)
}

/// The trunk frame's height (m) after holding the standing pose on the default engine
/// (rapier): what `hyq robot init` writes and an MJCF file given alone takes as its standing
/// height ([`hyq_env::settle`]).
pub fn settle_height(model: Arc<RobotModel>) -> Result<f64, String> {
    let engine = hyq_engines::DEFAULT.name;
    hyq_engines::with_engine!(engine, B => hyq_env::settle::settle_height::<B>(model))
        .unwrap_or_else(|| Err(format!("this hyq was built without the {engine} engine")))
}

/// An environment on backend `B` with `config`.
pub fn make_env<B: Backend>(model: Arc<RobotModel>, config: EnvConfig) -> Result<Env<B>, Failure> {
    Env::new(model, config)
        .map_err(|e| usage(format!("cannot build the {} environment: {e}", B::NAME)))
}

/// The policy and seed of a command that runs episodes (`run`, `render`).
#[derive(Debug, Clone, Args)]
pub struct PolicyArgs {
    /// The policy: stand, random, trot, or mlp:FILE (a trained policy file, e.g.
    /// mlp:assets/policies/hyq_walk.safetensors, run in the environment it was trained in:
    /// its action mode and reward settings apply unless --config or --set sets the key).
    #[arg(long, default_value = "trot", value_parser = parse_policy, value_name = "POLICY")]
    pub policy: PolicyChoice,
    /// Seed of the first reset (goal and reset-noise streams) and of the random policy.
    #[arg(long, default_value_t = 0)]
    pub seed: u64,
}

fn parse_policy(text: &str) -> Result<PolicyChoice, String> {
    text.parse()
}

/// Reads a trained policy file: a one-line usage error naming the file and the problem.
pub fn read_mlp(file: &std::path::Path) -> Result<MlpPolicy, Failure> {
    MlpPolicy::from_file(file).map_err(|e| usage(format!("--policy mlp:{e}")))
}

/// Checks that a trained policy fits an environment of `model` under `config` (robot,
/// observation and action layout, action mode and scale): a one-line usage error naming the
/// file and the mismatch.
pub fn check_mlp(
    policy: &MlpPolicy,
    file: &std::path::Path,
    model: &RobotModel,
    config: &EnvConfig,
) -> Result<(), Failure> {
    policy
        .check_env(model, config, &file.display().to_string())
        .map_err(|e| usage(format!("--policy mlp:{e}")))
}

/// A trained policy file read with the environment it runs in: the file's own environment
/// (`env_config`) under the user's configuration file and overrides.
pub struct TrainedPolicy {
    /// The policy.
    pub policy: MlpPolicy,
    /// The environment's configuration, validated.
    pub config: EnvConfig,
    /// The file's entries that applied (the user set none of their keys).
    pub inherited: Vec<(String, String)>,
}

impl TrainedPolicy {
    /// Reads `file` and builds its configuration under `configuration`.
    pub fn load(file: &std::path::Path, configuration: &ConfigArgs) -> Result<Self, Failure> {
        let policy = read_mlp(file)?;
        let base = &policy.metadata().env_config;
        let config = configuration.config_over(
            base,
            &format!("--policy mlp:{}: its env_config", file.display()),
        )?;
        let inherited = configuration
            .inherited(base)?
            .into_iter()
            .cloned()
            .collect();
        Ok(Self {
            policy,
            config,
            inherited,
        })
    }
}

impl PolicyArgs {
    /// The environment's configuration for this policy: `env`'s, over the trained policy's own
    /// environment when the policy is `mlp:FILE`.
    pub fn config(&self, env: &EnvArgs) -> Result<EnvConfig, Failure> {
        match &self.policy {
            PolicyChoice::Mlp(file) => Ok(TrainedPolicy::load(file, &env.configuration)?.config),
            _ => env.config(),
        }
    }

    /// The chosen policy for `env`'s robot (the random one seeded with `--seed`); a trained
    /// policy is checked against the environment's robot and action layout.
    pub fn make<B: Backend>(&self, env: &Env<B>) -> Result<Box<dyn Policy>, Failure> {
        Ok(match &self.policy {
            PolicyChoice::Stand => Box::new(Stand),
            PolicyChoice::Random => Box::new(RandomPolicy::new(self.seed)),
            PolicyChoice::Trot => Box::new(
                Trot::from_profile(env.model())
                    .map_err(|e| usage(format!("--policy trot: {e}")))?,
            ),
            PolicyChoice::Mlp(file) => {
                let policy = read_mlp(file)?;
                check_mlp(&policy, file, env.model(), env.config())?;
                Box::new(policy)
            }
        })
    }
}
