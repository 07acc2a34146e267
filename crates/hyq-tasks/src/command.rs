//! `[command]`: the velocity command (forward speed v_x, sideways speed v_y, both m/s in the
//! trunk's heading frame, and yaw rate ω_z, rad/s) and how it is drawn and redrawn.
//!
//! Two rules, one per anchor:
//! - `uniform` (legged_gym `_resample_commands`): every component drawn from U(lo, hi) of its
//!   range; a forward/sideways command whose norm is below `min_lin_vel_mps` becomes 0
//!   (legged_gym's is 0.2 m/s; the default 0 keeps every drawn command).
//! - `keep_zero` (Playground `sample_command`): each component keeps its value with probability
//!   ½, else becomes y·z with y ~ U(lo, hi) and z ~ Bernoulli(b), b its
//!   `keep_nonzero_probability`. A reset draws every component from U(lo, hi).
//!
//! Both then give the standing command (all three 0) with probability `standing_probability`
//! (Isaac Lab's `rel_standing_envs`, 0.02; mjlab's 0.1; legged_gym has none, the default 0).
//! A command is redrawn every `resampling_time_s` (`timing = "fixed"`, legged_gym) or after an
//! exponentially distributed time of that mean (`"exponential"`, Playground). A range with
//! lo = hi fixes that component (`command.lin_vel_x = [0.5, 0.5]`), exactly.
//!
//! Every draw takes the same count of numbers from the stream whatever they turn out to be, so
//! the stream stays aligned and a seed gives the same commands on every engine.

use rand::RngExt;
use rand_chacha::ChaCha8Rng;
use serde::{Deserialize, Serialize};

use crate::error::{ConfigError, check_in, check_range};

/// The largest commanded speed (m/s) or yaw rate (rad/s) a range may reach.
pub const COMMAND_MAX: f64 = 10.0;
/// The longest resampling time (s).
pub const RESAMPLING_TIME_MAX_S: f64 = 1.0e6;

/// One command: v_x, v_y (m/s, heading frame) and ω_z (rad/s).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct Command {
    /// Forward speed (m/s).
    pub lin_vel_x: f64,
    /// Sideways speed, to the left (m/s).
    pub lin_vel_y: f64,
    /// Yaw rate, counter-clockwise seen from above (rad/s).
    pub ang_vel_yaw: f64,
}

impl Command {
    /// The standing command.
    pub const ZERO: Command = Command {
        lin_vel_x: 0.0,
        lin_vel_y: 0.0,
        ang_vel_yaw: 0.0,
    };

    /// The three components in observation order.
    pub fn as_array(&self) -> [f64; 3] {
        [self.lin_vel_x, self.lin_vel_y, self.ang_vel_yaw]
    }

    /// The norm of all three components (m/s and rad/s taken as numbers), which gates the
    /// gait terms (see docs/velocity.md).
    pub fn norm(&self) -> f64 {
        let [x, y, w] = self.as_array();
        (x * x + y * y + w * w).sqrt()
    }
}

/// How a command is redrawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ResamplingRule {
    /// legged_gym: every component from its range.
    #[default]
    Uniform,
    /// Playground: each component kept with probability ½, else redrawn or zeroed.
    KeepZero,
}

/// When a command is redrawn.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ResamplingTiming {
    /// Every `resampling_time_s` (legged_gym).
    #[default]
    Fixed,
    /// After an exponential time of mean `resampling_time_s` (Playground).
    Exponential,
}

/// `[command]`: the ranges and the resampling. Defaults are legged_gym's base configuration.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct CommandConfig {
    /// The forward speed's range [lo, hi] (m/s), within ±10. (default: `[-1.0, 1.0]`)
    pub lin_vel_x: [f64; 2],
    /// The sideways speed's range [lo, hi] (m/s), within ±10. (default: `[-1.0, 1.0]`)
    pub lin_vel_y: [f64; 2],
    /// The yaw rate's range [lo, hi] (rad/s), within ±10. (default: `[-1.0, 1.0]`)
    pub ang_vel_yaw: [f64; 2],
    /// The time between redraws, or its mean (s), in (0, 1e6]. (default: `10.0`)
    pub resampling_time_s: f64,
    /// How a command is redrawn. (default: `"uniform"`)
    pub resampling: ResamplingRule,
    /// When it is redrawn. (default: `"fixed"`)
    pub timing: ResamplingTiming,
    /// The probability, in [0, 1], that a draw is the standing command. (default: `0.0`)
    pub standing_probability: f64,
    /// Under `uniform`, a forward/sideways command of smaller norm (m/s) becomes 0, in [0, 10].
    /// (default: `0.0`; legged_gym's is 0.2)
    pub min_lin_vel_mps: f64,
    /// Under `keep_zero`, each component's probability, in [0, 1], that a redraw is non-zero.
    /// (default: Playground's `[0.9, 0.25, 0.5]`)
    pub keep_nonzero_probability: [f64; 3],
}

impl Default for CommandConfig {
    fn default() -> Self {
        Self {
            lin_vel_x: [-1.0, 1.0],
            lin_vel_y: [-1.0, 1.0],
            ang_vel_yaw: [-1.0, 1.0],
            resampling_time_s: 10.0,
            resampling: ResamplingRule::Uniform,
            timing: ResamplingTiming::Fixed,
            standing_probability: 0.0,
            min_lin_vel_mps: 0.0,
            keep_nonzero_probability: [0.9, 0.25, 0.5],
        }
    }
}

impl CommandConfig {
    /// Checks every key against its range; the error names the first bad key.
    pub fn validate(&self) -> Result<(), ConfigError> {
        check_range("command.lin_vel_x", self.lin_vel_x, COMMAND_MAX)?;
        check_range("command.lin_vel_y", self.lin_vel_y, COMMAND_MAX)?;
        check_range("command.ang_vel_yaw", self.ang_vel_yaw, COMMAND_MAX)?;
        let t = self.resampling_time_s;
        if !(t.is_finite() && t > 0.0 && t <= RESAMPLING_TIME_MAX_S) {
            return Err(ConfigError::new(
                "command.resampling_time_s",
                t,
                &format!("must be a finite number in (0, {RESAMPLING_TIME_MAX_S}]"),
            ));
        }
        check_in(
            "command.standing_probability",
            self.standing_probability,
            0.0,
            1.0,
        )?;
        check_in(
            "command.min_lin_vel_mps",
            self.min_lin_vel_mps,
            0.0,
            COMMAND_MAX,
        )?;
        for b in self.keep_nonzero_probability {
            check_in("command.keep_nonzero_probability", b, 0.0, 1.0)?;
        }
        Ok(())
    }

    /// The three ranges in observation order.
    pub fn ranges(&self) -> [[f64; 2]; 3] {
        [self.lin_vel_x, self.lin_vel_y, self.ang_vel_yaw]
    }
}

/// `lo + (hi − lo)·u`, exactly `lo` when lo = hi.
fn lerp([lo, hi]: [f64; 2], u: f64) -> f64 {
    if lo == hi { lo } else { lo + (hi - lo) * u }
}

/// A first command for an episode: every component from U(lo, hi) (both rules), then the
/// `uniform` rule's small-command zeroing and the standing draw. Takes 4 numbers from `rng`.
pub fn initial_command(config: &CommandConfig, rng: &mut ChaCha8Rng) -> Command {
    let u: [f64; 4] = std::array::from_fn(|_| rng.random::<f64>());
    let ranges = config.ranges();
    let c = std::array::from_fn(|i| lerp(ranges[i], u[i]));
    finish(config, c, u[3])
}

/// The command redrawn from `current` by the configured rule. Takes 10 numbers from `rng`.
pub fn resample(config: &CommandConfig, current: Command, rng: &mut ChaCha8Rng) -> Command {
    let u: [f64; 10] = std::array::from_fn(|_| rng.random::<f64>());
    let ranges = config.ranges();
    let old = current.as_array();
    let c = std::array::from_fn(|i| {
        let y = lerp(ranges[i], u[i]);
        match config.resampling {
            ResamplingRule::Uniform => y,
            ResamplingRule::KeepZero => {
                let keep = u[3 + i] < 0.5;
                let nonzero = u[6 + i] < config.keep_nonzero_probability[i];
                keep_zero(old[i], y, keep, nonzero)
            }
        }
    });
    finish(config, c, u[9])
}

/// Playground's per-component rule, `x − w·(x − y·z)`: the old value `x` when `keep`, else
/// `y` when `nonzero`, else 0.
pub fn keep_zero(x: f64, y: f64, keep: bool, nonzero: bool) -> f64 {
    match (keep, nonzero) {
        (true, _) => x,
        (false, true) => y,
        (false, false) => 0.0,
    }
}

/// The small-command zeroing (under `uniform`) and the standing draw `u_stand`.
fn finish(config: &CommandConfig, [x, y, w]: [f64; 3], u_stand: f64) -> Command {
    if u_stand < config.standing_probability {
        return Command::ZERO;
    }
    let small = config.resampling == ResamplingRule::Uniform
        && x.hypot(y) < config.min_lin_vel_mps
        && config.min_lin_vel_mps > 0.0;
    let (x, y) = if small { (0.0, 0.0) } else { (x, y) };
    Command {
        lin_vel_x: x,
        lin_vel_y: y,
        ang_vel_yaw: w,
    }
}

/// The env steps until the next redraw, at least 1: `resampling_time_s / env_dt` rounded
/// (`fixed`), or an exponential time of that mean, rounded (`exponential`). Takes one number
/// from `rng` in both timings.
pub fn steps_until_resample(config: &CommandConfig, env_dt: f64, rng: &mut ChaCha8Rng) -> u64 {
    let u = rng.random::<f64>();
    let seconds = match config.timing {
        ResamplingTiming::Fixed => config.resampling_time_s,
        // u in [0, 1): 1 − u in (0, 1], so the logarithm is finite.
        ResamplingTiming::Exponential => -config.resampling_time_s * (1.0 - u).ln(),
    };
    let steps = (seconds / env_dt).round();
    // Bounded by the configured maximum over the smallest env step, far below u64::MAX; `as`
    // saturates anyway.
    (steps as u64).max(1)
}

/// The command of an episode and its redraw schedule, on a seeded stream.
#[derive(Clone, Debug)]
pub struct CommandSampler {
    config: CommandConfig,
    env_dt: f64,
    command: Command,
    /// Env steps left before the next redraw.
    left: u64,
}

impl CommandSampler {
    /// A sampler for `config` (validated) at env step `env_dt` (s), holding the standing
    /// command until [`CommandSampler::start`].
    pub fn new(config: CommandConfig, env_dt: f64) -> Self {
        Self {
            config,
            env_dt,
            command: Command::ZERO,
            left: u64::MAX,
        }
    }

    /// Starts an episode: its first command and schedule, from `rng`.
    pub fn start(&mut self, rng: &mut ChaCha8Rng) -> Command {
        self.command = initial_command(&self.config, rng);
        self.left = steps_until_resample(&self.config, self.env_dt, rng);
        self.command
    }

    /// Counts one env step and redraws when due; returns the command the next observation
    /// holds. (The step itself is judged by the command before the call, the one its policy
    /// saw.)
    pub fn advance(&mut self, rng: &mut ChaCha8Rng) -> Command {
        self.left = self.left.saturating_sub(1);
        if self.left == 0 {
            self.command = resample(&self.config, self.command, rng);
            self.left = steps_until_resample(&self.config, self.env_dt, rng);
        }
        self.command
    }

    /// The current command.
    pub fn command(&self) -> Command {
        self.command
    }

    /// The configuration.
    pub fn config(&self) -> &CommandConfig {
        &self.config
    }
}
