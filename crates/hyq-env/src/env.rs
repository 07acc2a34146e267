//! The environment: the spec's rules (hyq-spec) joined to a physics backend (hyq-physics).
//!
//! One env step (spec §3, §6.3):
//!
//! 1. the action is checked (length, finiteness, range) before anything changes, then mapped to
//!    joint targets q* ([`crate::action`]);
//! 2. `sim_steps_per_env_step` physics sub-steps of `dt` run, the shared PD actuator
//!    (`hyq_physics::apply_pd_to_valid_targets`: the targets were checked once, in step 1)
//!    computing the joint torques before every one;
//! 3. each tracked body's ground contact is OR-latched over all the sub-steps: a foot or trunk
//!    that touched the ground in any sub-step reads 1 (rows 24–28), and the trunk's latched flag
//!    is the §6.3 fall fact;
//! 4. the trunk acceleration is a^t = (v^t − v^{t−1}) / Δt_env (rows 33–35), v the trunk frame
//!    origin's linear velocity at the end of the step, Δt_env = sub-steps × dt; 0 after reset;
//! 5. hyq-spec's [`EpisodeRules::evaluate_step`] gives the reward breakdown and the
//!    terminations; the observation is written through hyq-spec's [`ObservationLayout`] from
//!    named fields.
//!
//! C^t, the trunk centre of the spec, is the origin of the trunk's URDF link frame (as reported
//! by every backend), the same point whose velocity gives the acceleration.
//!
//! # Divergence
//! When a sub-step fails with a backend error (`PhysicsError::Diverged` or any other), or a
//! reading after the step is not finite, the episode ends with the reason `diverged`
//! (`terminated = true`; the typed cause, a [`Divergence`], in `info.divergence`) and nothing non-finite is emitted: the observation is the last finite
//! one (the previous step's, unchanged), the reward is 0 with every term 0 and every multiplier
//! 1, and distance, D_n, roll, pitch and yaw keep their previous values. `timeout` is reported too
//! if t ≥ t_max. The env must then be reset.

use std::sync::Arc;
use std::time::{Duration, Instant};

use hyq_physics::na::{Point3, Vector3};
use hyq_physics::{
    Actuator, Backend, PdScratch, PhysicsError, RobotModel, RobotState, TargetDelay, TrunkState,
    apply_pd_to_valid_targets,
};
use hyq_spec::distance::StartGoalDistance;
use hyq_spec::observation::trunk_acceleration;
use hyq_spec::robot::Bounds;
use hyq_spec::{
    Clipping, EpisodeRules, JointDescription, JointRange, Observation, ObservationError,
    ObservationLayout, RewardBreakdown, RobotDescription, StepOutcome, StepSnapshot,
    TrunkDescription, roll_pitch_yaw,
};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;

use crate::action::{ActionScalar, ActionSpace};
use crate::config::{ConfigError, EnvConfig, ObservationExtra, in_world, outside_world_reason};
use crate::divergence::Divergence;
use crate::error::EnvError;
use crate::goal::{GoalSampler, episode_rules, sample_reset_state};
use crate::info::{Reason, Reasons, StepInfo};
use crate::randomize::{EpisodeDraw, RandomizeInfo, Randomizer, check_for_robot};
use crate::regularizers::Regularizers;
use crate::terrain::Ground;
use crate::velocity::VelocityTask;

/// Options for one [`Env::reset`] (Gymnasium's `options`). Everything unset follows the
/// configuration.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ResetOptions {
    /// This episode's goal G (m, world), instead of the configured goal. No goal is drawn from
    /// the goal stream.
    pub goal: Option<[f64; 3]>,
    /// This episode's initial state, instead of the standing pose at the spawn point with the
    /// configured noise. No noise is drawn from the noise stream.
    pub state: Option<RobotState>,
}

/// The result of [`Env::step`]: the observation (f64 and f32, both borrowed from the env's
/// buffers), the reward, Gymnasium's two flags, and the info.
#[derive(Clone, Copy, Debug)]
pub struct Step<'a> {
    /// The observation, f64, in the §3 order.
    pub observation: &'a [f64],
    /// The same observation rounded to f32.
    pub observation_f32: &'a [f32],
    /// The reward (`info.reward.total`).
    pub reward: f64,
    /// Reached, joint limit, fell or diverged.
    pub terminated: bool,
    /// Timeout and not terminated.
    pub truncated: bool,
    /// Everything else.
    pub info: &'a StepInfo,
}

/// The result of [`Env::reset`]: the first observation and the info (t = 0).
#[derive(Clone, Copy, Debug)]
pub struct Reset<'a> {
    /// The observation, f64.
    pub observation: &'a [f64],
    /// The observation, f32.
    pub observation_f32: &'a [f32],
    /// Episode, goal, initial position, distance, attitude; reward terms 0.
    pub info: &'a StepInfo,
}

/// Time spent in each part of [`Env::step`], summed over the steps since timing was switched
/// on (see [`Env::set_timing`]).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct StepTiming {
    /// Env steps timed.
    pub steps: u64,
    /// Whole `step` calls, from entry to return.
    pub total: Duration,
    /// The shared actuator: reading q and q̇, the PD law, storing the torques (every sub-step).
    pub actuator: Duration,
    /// The engine's sub-steps, the contact reads after each, and the state reads at the end.
    pub physics: Duration,
    /// The trunk acceleration and writing the f64 and f32 observations.
    pub observation: Duration,
    /// hyq-spec's `evaluate_step`: rewards, penalties, terminations.
    pub spec: Duration,
}

impl StepTiming {
    /// The time not in any named part (action mapping, latching, bookkeeping).
    pub fn other(&self) -> Duration {
        self.total
            .saturating_sub(self.actuator + self.physics + self.observation + self.spec)
    }
}

/// Laps of a step's parts for [`StepTiming`]: while timing is on, [`Stopwatch::lap`] adds the
/// time since the previous lap to a part's sum; while it is off, a stopwatch reads no clock and
/// does nothing, so one code path serves both (rapier's counters `Timer`, switched at run time
/// rather than at compile time).
#[derive(Clone, Copy, Debug)]
struct Stopwatch(Option<Instant>);

impl Stopwatch {
    /// A stopwatch running from now if `on`, else one that does nothing.
    fn start(on: bool) -> Self {
        Self(on.then(Instant::now))
    }

    /// Adds the time since the start or the previous lap to `part`.
    fn lap(&mut self, part: &mut Duration) {
        if let Some(last) = &mut self.0 {
            let now = Instant::now();
            *part += now - *last;
            *last = now;
        }
    }

    /// Starts the next lap now, leaving the time since the previous one out of every part.
    fn restart(&mut self) {
        if let Some(last) = &mut self.0 {
            *last = Instant::now();
        }
    }
}

/// The per-episode state.
#[derive(Clone, Debug)]
struct Episode {
    rules: EpisodeRules,
    /// K, which [`episode_rules`] guarantees.
    k: StartGoalDistance,
    done: bool,
}

/// What `[randomize]` adds to an environment: the draws, the actuator the episode's scales
/// apply to, the actuator's delay, and the observation as the policy sees it.
#[derive(Clone, Debug)]
struct Robustness {
    randomizer: Randomizer,
    /// The configured actuator, which each episode's scales multiply.
    base_actuator: Actuator,
    delay: TargetDelay,
    /// Whether observation noise is on (else the policy sees the true observation).
    noisy: bool,
    /// The observation with its noise, when `noisy`.
    seen: Vec<f64>,
}

/// The HyQ walk-to-goal environment on backend `B` (see the crate docs for the env card).
pub struct Env<B: Backend> {
    backend: B,
    model: Arc<RobotModel>,
    config: EnvConfig,
    options: B::Options,
    actuator: Actuator,
    space: ActionSpace,
    robot: RobotDescription,
    layout: ObservationLayout,
    goals: GoalSampler,
    /// The ground of each episode.
    ground: Ground,
    /// The observation's groups beyond the spec's rows, in layout order.
    extras: Vec<ObservationExtra>,
    /// The height scan's points in the trunk's heading frame (m), if it is observed.
    scan: Vec<[f64; 2]>,
    env_dt: f64,
    trunk_tracked: usize,
    num_feet: usize,

    seeded: bool,
    goal_rng: ChaCha8Rng,
    noise_rng: ChaCha8Rng,
    terrain_rng: ChaCha8Rng,
    episodes: u64,
    episode: Option<Episode>,

    scratch: PdScratch,
    /// The robot's state at the end of the last step or reset (after a divergence, the last
    /// finite one).
    state: RobotState,
    substep_contacts: Vec<bool>,
    /// The contacts latched over the sub-steps of the step being taken.
    latching: Vec<bool>,
    /// The latched contacts of the last step (all false after reset), tracked order: what the
    /// observation's contact rows hold.
    contacts: Vec<bool>,
    obs: Vec<f64>,
    obs_next: Vec<f64>,
    obs_f32: Vec<f32>,
    info: StepInfo,
    /// `[randomize]`'s state, when any option is on.
    robustness: Option<Box<Robustness>>,
    /// The velocity task's state, under `task.kind = "velocity"`.
    velocity: Option<Box<VelocityTask>>,
    /// The gait regularisers' state, when `[regularizers]` is on.
    regularizers: Option<Box<Regularizers>>,

    timing_on: bool,
    timing: StepTiming,
}

/// The error for a reset option (`what`) at `point`, outside the world.
fn outside_world(what: &str, point: Point3<f64>) -> ConfigError {
    ConfigError::Invalid {
        key: what.to_owned(),
        value: format!("{:?}", [point.x, point.y, point.z]),
        expected: outside_world_reason(),
    }
}

/// The number of rows of the velocity task's group in `layout` (0 if it has none).
fn task_rows(layout: &ObservationLayout) -> usize {
    layout
        .groups()
        .last()
        .filter(|g| g.name == crate::velocity::GROUP)
        .map_or(0, |g| g.rows.len())
}

/// The goal stream's ChaCha stream number (the reset noise uses [`NOISE_STREAM`]).
const GOAL_STREAM: u64 = 0;
/// The reset-noise stream's ChaCha stream number.
const NOISE_STREAM: u64 = 1;
/// The terrain stream's ChaCha stream number: rough ground drawn per episode.
const TERRAIN_STREAM: u64 = 2;
/// The seed an environment that was never given one behaves as if reset with.
pub const DEFAULT_SEED: u64 = 0;

fn stream(seed: u64, stream: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(stream);
    rng
}

/// The rules' view of `model`: joints with their limits and speed limits, the feet and the
/// trunk, with the declared bounds of the trunk rows from the robot's profile
/// (`[observation]`) where it gives them, else the spec's §3 bounds (HyQ's).
fn robot_description(model: &RobotModel) -> Result<RobotDescription, ConfigError> {
    let bad = |what: String| ConfigError::Invalid {
        key: "robot".into(),
        value: model.name().to_owned(),
        expected: what,
    };
    let joints = model
        .joints()
        .iter()
        .map(|j| {
            Ok(JointDescription {
                name: j.name.clone(),
                range: JointRange::new(j.lower, j.upper).map_err(|e| bad(e.to_string()))?,
                velocity_limit: j.velocity,
            })
        })
        .collect::<Result<Vec<_>, ConfigError>>()?;
    let tracked = model.tracked();
    let feet = tracked[..model.num_feet()]
        .iter()
        .map(|t| t.name.clone())
        .collect();
    let spec = TrunkDescription::spec();
    let bounds = |given: Option<[[f64; 2]; 3]>, spec: [Bounds; 3]| {
        given.map_or(spec, |b| b.map(|[min, max]| Bounds { min, max }))
    };
    let given = model.observation_bounds();
    let trunk = TrunkDescription {
        name: tracked[model.trunk_tracked_index()].name.clone(),
        acceleration: bounds(given.and_then(|b| b.trunk_acceleration), spec.acceleration),
        position: bounds(given.and_then(|b| b.trunk_position), spec.position),
    };
    RobotDescription::new(joints, feet, trunk).map_err(|e| bad(e.to_string()))
}

/// The observation layout of `model` (the §3 rows, named and bounded for this robot), as an
/// environment on any backend has it with the default configuration, without building one.
pub fn observation_layout_of(model: &RobotModel) -> Result<ObservationLayout, ConfigError> {
    robot_description(model).map(|robot| ObservationLayout::new(&robot))
}

/// The observation layout of `model` under `config`: the §3 rows, then the groups of
/// `observation.extra` (see [`crate::observation`]).
pub fn observation_layout_for(
    model: &RobotModel,
    config: &EnvConfig,
) -> Result<ObservationLayout, ConfigError> {
    let robot = robot_description(model)?;
    let layout = crate::observation::extend(
        ObservationLayout::new(&robot),
        &config.observation,
        &robot.trunk().name,
    );
    Ok(with_task_rows(layout, model, config))
}

/// `layout` with the task's own rows appended: the velocity task's group under
/// `task.kind = "velocity"`, nothing for the spec's task.
fn with_task_rows(
    layout: ObservationLayout,
    model: &RobotModel,
    config: &EnvConfig,
) -> ObservationLayout {
    match config.task.kind {
        crate::config::TaskKind::Goal => layout,
        crate::config::TaskKind::Velocity => crate::velocity::extend_layout(layout, model, config),
    }
}

/// The `[randomize]` state of an environment of `model` with `config` and its configured
/// `actuator`, or `None` when nothing is randomised; errors if the ranges do not fit the robot.
fn robustness(
    model: &RobotModel,
    config: &EnvConfig,
    actuator: &Actuator,
) -> Result<Option<Box<Robustness>>, ConfigError> {
    if config.randomize.is_off() {
        return Ok(None);
    }
    check_for_robot(model, &config.randomize)?;
    let randomizer = Randomizer::new(
        &config.randomize,
        DEFAULT_SEED,
        model,
        &config.physics.params,
    );
    Ok(Some(Box::new(Robustness {
        noisy: randomizer.noisy(),
        randomizer,
        base_actuator: actuator.clone(),
        delay: TargetDelay::new(model.num_joints()),
        seen: vec![0.0; observation_layout_for(model, config)?.len()],
    })))
}

/// The actuator of `model` with `config`'s `[control]` gains (the robot's own where a key is
/// unset) and velocity limit, refusing gains that do not give one value per joint.
fn actuator(model: &RobotModel, config: &EnvConfig) -> Result<Actuator, EnvError> {
    let n = model.num_joints();
    let gains = |key: &str, g: &crate::config::Gains, profile: &[f64]| {
        g.resolve(profile).ok_or_else(|| ConfigError::Invalid {
            key: key.to_owned(),
            value: g.to_string(),
            expected: format!("one gain per joint: {n} values"),
        })
    };
    let kp = gains("control.kp", &config.control.kp, model.kp())?;
    let kd = gains("control.kd", &config.control.kd, model.kd())?;
    let mut actuator = Actuator::with_gains(model, &kp, &kd)?;
    actuator.set_velocity_limit(config.control.velocity_limit);
    Ok(actuator)
}

/// The info of an environment not yet reset, with room for `n` joint targets: every field
/// neutral, overwritten by the first reset.
fn info_before_reset(n: usize) -> StepInfo {
    StepInfo {
        episode: 0,
        t: 0,
        reward: RewardBreakdown::NEUTRAL,
        reasons: Reasons::NONE,
        joint_at_limit: None,
        divergence: None,
        distance_to_goal: 0.0,
        d_n: 1.0,
        roll: 0.0,
        pitch: 0.0,
        yaw: 0.0,
        goal: [0.0; 3],
        initial_position: [0.0; 3],
        joint_targets: vec![0.0; n],
        action_clipped: false,
        randomize: None,
        velocity: None,
        regularizers: None,
    }
}

impl<B: Backend> Env<B> {
    /// Builds an environment for `model` on backend `B` with `config`: validates the whole
    /// configuration for this robot (gains per joint, the fixed goal against the spawn point,
    /// the engine table `[physics.<B::NAME>]`), then builds the backend.
    ///
    /// The environment must be [`Env::reset`] before its first step.
    pub fn new(model: Arc<RobotModel>, config: EnvConfig) -> Result<Self, EnvError> {
        config.validate()?;
        let options: B::Options = config.physics.engine_options(B::NAME)?;
        Self::build(model, config, options)
    }

    /// As [`Env::new`], with the backend's options given instead of read from
    /// `[physics.<B::NAME>]`: a backend that wraps several engines (hyq-engines' `AnyBackend`)
    /// takes the engine of this env from them.
    pub fn with_options(
        model: Arc<RobotModel>,
        config: EnvConfig,
        options: B::Options,
    ) -> Result<Self, EnvError> {
        config.validate()?;
        Self::build(model, config, options)
    }

    /// [`Env::new`] after the configuration was validated and the options read.
    fn build(
        model: Arc<RobotModel>,
        config: EnvConfig,
        options: B::Options,
    ) -> Result<Self, EnvError> {
        let n = model.num_joints();
        let actuator = actuator(&model, &config)?;
        let space = ActionSpace::new(&model, &config.action);
        let robot = robot_description(&model)?;
        let layout = crate::observation::extend(
            ObservationLayout::new(&robot),
            &config.observation,
            &robot.trunk().name,
        );
        let layout = with_task_rows(layout, &model, &config);
        let velocity = VelocityTask::new(&model, &config, DEFAULT_SEED);
        let goals = GoalSampler::new(&config, &model);
        let ground = Ground::new(&config, &model)?;
        // A fixed goal can be checked against the spawn point once, here, rather than fail at
        // every reset.
        goals.check(&config.task)?;
        crate::goal::check_spawn_fits(&model, &config.reset)?;
        let robustness = robustness(&model, &config, &actuator)?;
        let mut backend = B::build(model.clone(), &config.physics.params, &options)?;
        backend.set_terrain(ground.terrain())?;
        let extras = config.observation.groups();
        let scan = if extras.contains(&ObservationExtra::HeightScan) {
            config.observation.scan_points()
        } else {
            Vec::new()
        };
        let tracked = model.tracked().len();
        let obs_len = layout.len();
        let mut env = Self {
            env_dt: config.env_dt(),
            trunk_tracked: model.trunk_tracked_index(),
            num_feet: model.num_feet(),
            seeded: false,
            goal_rng: stream(DEFAULT_SEED, GOAL_STREAM),
            noise_rng: stream(DEFAULT_SEED, NOISE_STREAM),
            terrain_rng: stream(DEFAULT_SEED, TERRAIN_STREAM),
            episodes: 0,
            episode: None,
            scratch: PdScratch::new(n),
            state: backend.state(),
            substep_contacts: vec![false; tracked],
            latching: vec![false; tracked],
            contacts: vec![false; tracked],
            obs: vec![0.0; obs_len],
            obs_next: vec![0.0; obs_len],
            obs_f32: vec![0.0; obs_len],
            info: info_before_reset(n),
            robustness,
            velocity,
            regularizers: Regularizers::new(&model, &config),
            timing_on: false,
            timing: StepTiming::default(),
            backend,
            model,
            config,
            options,
            actuator,
            space,
            robot,
            extras,
            scan,
            layout,
            goals,
            ground,
        };
        env.backend.read_state(&mut env.state);
        Ok(env)
    }

    /// Starts an episode and returns its first observation.
    ///
    /// `seed`: `Some(s)` reseeds the environment's random streams from `s` (one ChaCha8 stream
    /// for goals, another for reset noise, so switching noise on does not move the goals);
    /// `None` continues the streams where the previous reset left them, so a run of unseeded
    /// resets after a seeded one is reproducible (Gymnasium's semantics). An environment never
    /// seeded behaves as if its first reset had seed [`DEFAULT_SEED`].
    ///
    /// The robot starts at rest at the standing pose, trunk level at the spawn point and height,
    /// with the configured yaw and noise, unless `options` gives a state or a goal. On error the
    /// streams, the robot and the previous episode are left as they were.
    pub fn reset(
        &mut self,
        seed: Option<u64>,
        options: &ResetOptions,
    ) -> Result<Reset<'_>, EnvError> {
        let mut rngs = match seed {
            Some(s) => [GOAL_STREAM, NOISE_STREAM, TERRAIN_STREAM].map(|k| stream(s, k)),
            None => [
                self.goal_rng.clone(),
                self.noise_rng.clone(),
                self.terrain_rng.clone(),
            ],
        };
        let (ground, state, goal) = self.draw_episode(options, &mut rngs)?;
        let requested_rules = self.check_start(&state, goal)?;
        self.backend.set_terrain(ground.terrain())?;
        if !self.begin_varied_episode(seed, &state)? {
            self.backend.set_state(&state)?;
        }

        self.seeded |= seed.is_some();
        [self.goal_rng, self.noise_rng, self.terrain_rng] = rngs;
        self.ground = ground;
        self.episodes += 1;
        self.backend.read_state(&mut self.state);
        // C^0 is where the engine put the trunk, as the reset observation reports it; it can
        // differ from the requested state by the engine's rounding (rapier stores f32: about
        // 1e-8 m). The first step measures D^{t-1} from this same point, so K, D^0 and that
        // D^{t-1} are one number and Σ r_n telescopes to k_norm (1 − D_n^T) up to summation
        // rounding (from the requested point it was off by about 1e-9). The rules of the
        // requested start stand in only if this point is unusable (non-finite, which the
        // observation below reports as divergence).
        let initial = Point3::from(self.state.trunk.pose.translation.vector);
        let (rules, k) = episode_rules(&self.config.task, initial, goal).unwrap_or(requested_rules);
        let initial = rules.initial();
        if let Some(task) = self.velocity.as_deref_mut() {
            self.backend.link_poses(task.gait.poses_mut());
            task.reset(seed);
        }
        if let Some(r) = self.regularizers.as_deref_mut() {
            self.backend.link_poses(r.gait.poses_mut());
            r.reset();
        }
        self.observe_reset(&goal)?;
        self.write_reset_info(goal, initial, k);
        self.episode = Some(Episode {
            rules,
            k,
            done: false,
        });
        Ok(Reset {
            observation: self.seen(),
            observation_f32: &self.obs_f32,
            info: &self.info,
        })
    }

    /// Takes one env step with `action` (one value per joint, action order; `f64` or `f32`).
    ///
    /// Errors, with the environment unchanged: before the first reset, after the episode ended
    /// (reset first), a wrong length, a non-finite value, or an out-of-range value under
    /// `action.out_of_range = "error"`. A physics failure is not an error: it ends the episode
    /// with the reason `diverged` (see the module docs for what is emitted).
    pub fn step<A: ActionScalar>(&mut self, action: &[A]) -> Result<Step<'_>, EnvError> {
        let mut whole = Stopwatch::start(self.timing_on);
        let episode = self.episode.as_ref().ok_or(EnvError::NotReset)?;
        if episode.done {
            return Err(EnvError::EpisodeOver {
                episode: self.episodes,
                t: self.info.t,
                reasons: self.info.reasons,
            });
        }
        let (rules, k) = (episode.rules, episode.k);
        // The one check of the action: the joint targets mapped from it are finite and within
        // the joint limits, so the sub-steps use them unchecked.
        self.space.check(action)?;

        // From here on the step happens.
        self.info.action_clipped =
            self.space
                .targets(action, &self.state.q, &mut self.info.joint_targets);
        self.info.t += 1;
        if let Some(task) = self.velocity.as_deref_mut() {
            task.gait.begin_step(action.iter().map(|a| a.to_f64()));
        }
        if let Some(r) = self.regularizers.as_deref_mut() {
            r.gait.begin_step(action.iter().map(|a| a.to_f64()));
        }
        let previous = self.state.trunk;
        let mut watch = Stopwatch::start(self.timing_on);
        let outcome = self
            .run_substeps(&mut watch)
            .and_then(|()| self.finish_step(&rules, &previous, &mut watch));
        match outcome {
            Ok(outcome) => self.report(&outcome, k),
            Err(cause) => self.report_divergence(cause, previous, rules.config().max_time_steps),
        }
        self.report_velocity(rules.config().max_time_steps);
        if let Some(e) = self.episode.as_mut() {
            e.done = self.info.reasons.done();
        }
        if let (Some(r), Some(info)) = (self.robustness.as_deref(), self.info.randomize.as_mut()) {
            info.push_velocity_mps = r.randomizer.pushed();
            info.pushes = r.randomizer.pushes();
        }
        if self.timing_on {
            whole.lap(&mut self.timing.total);
            self.timing.steps += 1;
        }
        Ok(Step {
            observation: self.seen(),
            observation_f32: &self.obs_f32,
            reward: self.info.total_reward(),
            terminated: self.info.reasons.terminated(),
            truncated: self.info.reasons.truncated(),
            info: &self.info,
        })
    }

    /// Checks a reset's start `state` and `goal` before anything changes, so a refused reset
    /// leaves the environment as it was: the state valid for the robot, the trunk and the goal
    /// inside the world, and the goal far enough from the requested start. Returns the rules and
    /// K of the requested start.
    fn check_start(
        &self,
        state: &RobotState,
        goal: Point3<f64>,
    ) -> Result<(EpisodeRules, StartGoalDistance), EnvError> {
        state.validate(&self.model)?;
        let requested = Point3::from(state.trunk.pose.translation.vector);
        if !requested.iter().all(|v| in_world(*v)) {
            return Err(outside_world("reset option state's trunk position", requested).into());
        }
        if !goal.iter().all(|v| in_world(*v)) {
            return Err(outside_world("reset option goal", goal).into());
        }
        episode_rules(&self.config.task, requested, goal)
    }

    /// Writes the reset observation (zero acceleration, no contact yet) from the state the
    /// engine was just put in, and starts the actuator delay from its joint angles.
    fn observe_reset(&mut self, goal: &Point3<f64>) -> Result<(), EnvError> {
        self.latching.fill(false);
        let accel = Vector3::zeros();
        self.write_observation(accel, goal)
            .map_err(|e| PhysicsError::Diverged {
                what: e.to_string(),
            })?;
        std::mem::swap(&mut self.obs, &mut self.obs_next);
        self.contacts.fill(false);
        if let Some(r) = self.robustness.as_deref_mut() {
            r.delay.reset(&self.state.q);
        }
        self.observe();
        Ok(())
    }

    /// The reset's info: episode counted, t = 0, neutral reward, no reason, the distance from
    /// `initial` to `goal` and its D_n under `k`, the attitude read back, and the joint
    /// targets at the joint angles (the robot starts at rest).
    fn write_reset_info(&mut self, goal: Point3<f64>, initial: Point3<f64>, k: StartGoalDistance) {
        let attitude = roll_pitch_yaw(&self.state.trunk.pose.rotation);
        let d0 = (goal - initial).norm();
        let info = &mut self.info;
        info.episode = self.episodes;
        info.t = 0;
        info.reward = RewardBreakdown::NEUTRAL;
        info.reasons = Reasons::NONE;
        info.joint_at_limit = None;
        info.divergence = None;
        info.distance_to_goal = d0;
        info.d_n = k.normalise(d0);
        info.roll = attitude.roll;
        info.pitch = attitude.pitch;
        info.yaw = attitude.yaw;
        info.goal = goal.coords.into();
        info.initial_position = initial.coords.into();
        info.joint_targets.copy_from_slice(&self.state.q);
        info.action_clipped = false;
        info.randomize = self
            .robustness
            .as_deref()
            .map(|r| RandomizeInfo::at_reset(r.randomizer.draw()));
        info.velocity = self.velocity.as_deref().map(|task| task.info);
        info.regularizers = self.regularizers.as_deref().map(|r| r.info);
    }

    /// The next episode's ground, start state and goal, from the goal, noise and terrain streams
    /// `rngs` unless `options` gives the state or the goal: the ground moves on first (a new
    /// draw, the curriculum's level), then a drawn state is put down on it and a drawn goal
    /// placed over it. The environment itself is left as it is.
    fn draw_episode(
        &self,
        options: &ResetOptions,
        rngs: &mut [ChaCha8Rng; 3],
    ) -> Result<(Ground, RobotState, Point3<f64>), EnvError> {
        let [goal_rng, noise_rng, terrain_rng] = rngs;
        let mut ground = self.ground.clone();
        if ground.per_episode() {
            let progress =
                (self.episode.is_some() && self.info.t > 0).then_some(1.0 - self.info.d_n);
            ground.next_episode(terrain_rng, progress)?;
        }
        // A given state is used where it is; a drawn one is put down on the ground.
        let state = match &options.state {
            Some(s) => s.clone(),
            None => {
                let drawn = sample_reset_state(&self.model, &self.config.reset, noise_rng);
                ground.put_down(&self.model, drawn)
            }
        };
        let goal = match options.goal {
            Some(g) => Point3::from(g),
            None => ground.goal_on_ground(self.goals.sample(goal_rng)),
        };
        Ok((ground, state, goal))
    }

    /// Runs the sub-steps with the step's joint targets (as the actuator's delay serves them),
    /// after the step's push if one is due, latching contacts.
    fn run_substeps(&mut self, watch: &mut Stopwatch) -> Result<(), Divergence> {
        self.latching.fill(false);
        if let Some(r) = self.robustness.as_deref_mut() {
            // t was counted already: this step starts (t − 1) env steps after reset.
            let start = (self.info.t - 1) as f64 * self.env_dt;
            if let Some(dv) = r.randomizer.push_due(start) {
                self.backend.push_trunk(&dv)?;
            }
        }
        for s in 0..self.config.control.sim_steps_per_env_step {
            let targets = match self.robustness.as_deref() {
                Some(r) => r.delay.seen(s, &self.info.joint_targets),
                None => &self.info.joint_targets,
            };
            apply_pd_to_valid_targets(
                &mut self.backend,
                &self.actuator,
                targets,
                &mut self.scratch,
            )?;
            watch.lap(&mut self.timing.actuator);
            self.backend.step()?;
            self.backend.contacts(&mut self.substep_contacts);
            for (latched, now) in self.latching.iter_mut().zip(&self.substep_contacts) {
                *latched |= *now;
            }
            watch.lap(&mut self.timing.physics);
        }
        if let Some(r) = self.robustness.as_deref_mut() {
            r.delay.end_step(&self.info.joint_targets);
        }
        Ok(())
    }

    /// Reads the state after the sub-steps, evaluates the rules and writes the observation
    /// (step t = `info.t`, from the trunk state `previous`).
    fn finish_step(
        &mut self,
        rules: &EpisodeRules,
        previous: &TrunkState,
        watch: &mut Stopwatch,
    ) -> Result<StepOutcome, Divergence> {
        self.backend.read_state(&mut self.state);
        watch.lap(&mut self.timing.physics);
        if let Some((what, value)) = self.state.first_non_finite(&self.model) {
            return Err(Divergence::NonFiniteReading { what, value });
        }
        let position = Point3::from(self.state.trunk.pose.translation.vector);
        if let Some(axis) = position.iter().position(|v| !in_world(*v)) {
            let row = &self.layout.rows()[self.layout.trunk_position().start + axis];
            return Err(Divergence::OutsideWorld {
                row: row.name.to_string(),
                value: position[axis],
            });
        }
        if let Some(grid) = self.ground.terrain().grid()
            && !grid.contains(position.x, position.y)
        {
            let [x_min, y_min] = grid.origin();
            let [sx, sy] = grid.size();
            return Err(Divergence::OffTerrain {
                x: position.x,
                y: position.y,
                x_min,
                x_max: x_min + sx,
                y_min,
                y_max: y_min + sy,
            });
        }
        watch.restart();
        let outcome = rules.evaluate_step(&StepSnapshot {
            step: self.info.t,
            previous_position: Point3::from(previous.pose.translation.vector),
            position,
            orientation: self.state.trunk.pose.rotation,
            joint_angles: &self.state.q,
            joint_ranges: self.robot.joint_ranges(),
            trunk_contact: self.latching[self.trunk_tracked],
        })?;
        if let Some(task) = self.velocity.as_deref_mut() {
            self.backend.link_poses(task.gait.poses_mut());
            task.evaluate_step(
                &self.state.trunk,
                &self.state.q,
                &self.state.qd,
                self.scratch.torques(),
                &self.latching[..self.num_feet],
                self.latching[self.trunk_tracked],
            );
        }
        self.judge_regularizers(&rules.goal())?;
        watch.lap(&mut self.timing.spec);
        let accel = trunk_acceleration(&previous.linvel, &self.state.trunk.linvel, self.env_dt)?;
        self.write_observation(accel, &rules.goal())?;
        // The float32 observation must be finite too.
        if let Some(index) = self
            .obs_next
            .iter()
            .position(|v| v.abs() > f64::from(f32::MAX))
        {
            return Err(Divergence::BeyondFloat32 {
                index,
                name: self.layout.rows()[index].name.to_string(),
                value: self.obs_next[index],
            });
        }
        std::mem::swap(&mut self.obs, &mut self.obs_next);
        std::mem::swap(&mut self.contacts, &mut self.latching);
        self.observe();
        watch.lap(&mut self.timing.observation);
        Ok(outcome)
    }

    /// The regularisers' judgement of the step just read, when they are on (`goal`: the
    /// episode's G).
    fn judge_regularizers(&mut self, goal: &Point3<f64>) -> Result<(), Divergence> {
        let Some(r) = self.regularizers.as_deref_mut() else {
            return Ok(());
        };
        self.backend.link_poses(r.gait.poses_mut());
        r.evaluate_step(
            crate::regularizers::TrunkReading::new(&self.state.trunk, self.ground.terrain()),
            &self.state.qd,
            self.scratch.torques(),
            &self.latching[..self.num_feet],
            &self.latching[self.num_feet..],
            crate::regularizers::goal_geometry(&self.state.trunk, self.info.initial_position, goal),
        )
    }

    /// Reports a step the rules evaluated (`k`: the episode's K).
    fn report(&mut self, outcome: &StepOutcome, k: StartGoalDistance) {
        let info = &mut self.info;
        info.reward = outcome.reward;
        info.reasons = Reasons::from_spec(outcome.terminations);
        info.joint_at_limit = outcome.joint_at_limit;
        info.distance_to_goal = outcome.distance;
        info.d_n = outcome
            .normalised_distance
            .unwrap_or_else(|| k.normalise(outcome.distance));
        info.roll = outcome.attitude.roll;
        info.pitch = outcome.attitude.pitch;
        info.yaw = outcome.attitude.yaw;
        info.regularizers = self.regularizers.as_deref().map(|r| r.info);
    }

    /// Reports a diverged step: the last finite observation stays in `obs`, and so do its
    /// contacts; the distances and attitude keep their previous values, and so does the state
    /// the accessors report (`previous` trunk; the observation holds the joint angles and speeds
    /// exactly). `timeout` holds too when t reached `max_time_steps`.
    fn report_divergence(&mut self, cause: Divergence, previous: TrunkState, max_time_steps: u64) {
        self.state.trunk = previous;
        self.state
            .q
            .copy_from_slice(&self.obs[self.layout.joint_angles()]);
        self.state
            .qd
            .copy_from_slice(&self.obs[self.layout.joint_speeds()]);
        let info = &mut self.info;
        info.reward = RewardBreakdown::NEUTRAL;
        info.reasons = Reasons::NONE;
        info.reasons.insert(Reason::Diverged);
        if info.t >= max_time_steps {
            info.reasons.insert(Reason::Timeout);
        }
        info.joint_at_limit = None;
        info.divergence = Some(cause);
        if let Some(r) = self.regularizers.as_deref_mut() {
            r.diverged();
            info.regularizers = Some(r.info);
        }
    }

    /// Under the velocity task, replaces the spec's reward and end reasons with the task's
    /// (see [`crate::velocity`]) and reports its terms; `max_time_steps` is the time limit.
    fn report_velocity(&mut self, max_time_steps: u64) {
        let Some(task) = self.velocity.as_deref_mut() else {
            return;
        };
        let info = &mut self.info;
        let diverged = info.reasons.contains(Reason::Diverged);
        if diverged {
            task.diverged();
        }
        info.reward = RewardBreakdown::NEUTRAL;
        info.joint_at_limit = None;
        info.reasons = Reasons::NONE;
        if diverged {
            info.reasons.insert(Reason::Diverged);
        }
        if task.ended && !diverged {
            info.reasons.insert(Reason::Fell);
        }
        if info.t >= max_time_steps {
            info.reasons.insert(Reason::Timeout);
        }
        info.velocity = Some(task.info);
    }

    /// Writes the observation of the current state, with the contacts latched in `latching`,
    /// into `obs_next`.
    fn write_observation(
        &mut self,
        accel: Vector3<f64>,
        goal: &Point3<f64>,
    ) -> Result<(), ObservationError> {
        let trunk = &self.state.trunk;
        let observation = Observation {
            joint_angles: &self.state.q,
            joint_speeds: &self.state.qd,
            foot_contacts: &self.latching[..self.num_feet],
            trunk_contact: self.latching[self.trunk_tracked],
            trunk_rotation: trunk.pose.rotation,
            trunk_acceleration: accel,
            trunk_position: Point3::from(trunk.pose.translation.vector),
        };
        self.layout
            .write(&observation, Clipping::Off, &mut self.obs_next)?;
        // The task's rows are the last group; the extras end where they start.
        let extras_end = match self.velocity.as_deref() {
            Some(task) => {
                let start = self.layout.len() - task_rows(&self.layout);
                task.write_group(trunk, &self.state.q, &mut self.obs_next[start..]);
                start
            }
            None => self.layout.len(),
        };
        if !self.extras.is_empty() {
            let tail = &mut self.obs_next[self.layout.spec_rows().end..extras_end];
            crate::observation::write_extras(
                &self.extras,
                &self.scan,
                trunk,
                goal,
                self.ground.terrain(),
                tail,
            );
            // The groups' values come from finite state; checked like the spec's rows.
            let start = self.layout.spec_rows().end;
            if let Some((i, v)) = self.obs_next[start..]
                .iter()
                .enumerate()
                .find(|(_, v)| !v.is_finite())
            {
                let row = &self.layout.rows()[start + i];
                return Err(ObservationError::NonFinite {
                    index: row.index,
                    name: row.name.to_string(),
                    value: *v,
                });
            }
        }
        Ok(())
    }

    /// Makes the observation the policy sees from the true one in `obs`: with its noise when
    /// observation noise is on (into `Robustness::seen`), and its f32 copy.
    fn observe(&mut self) {
        let seen = match self.robustness.as_deref_mut() {
            Some(r) if r.noisy => {
                r.randomizer.observe(&self.layout, &self.obs, &mut r.seen);
                &r.seen
            }
            _ => &self.obs,
        };
        for (out, v) in self.obs_f32.iter_mut().zip(seen) {
            *out = *v as f32;
        }
    }

    /// The observation the policy sees (f64): the true one, or with its noise.
    fn seen(&self) -> &[f64] {
        match self.robustness.as_deref() {
            Some(r) if r.noisy => &r.seen,
            _ => &self.obs,
        }
    }

    /// Starts the varied episode `[randomize]` draws, if any option is on: `seed` restarts its
    /// streams; the drawn dynamics go to the backend with the episode's first `state` (one
    /// state change), the drawn scales to the actuator, the drawn delay to the delay line.
    /// Returns whether the robot was placed (else the caller places it). On error the draws
    /// are as they were.
    fn begin_varied_episode(
        &mut self,
        seed: Option<u64>,
        state: &RobotState,
    ) -> Result<bool, EnvError> {
        let Some(r) = self.robustness.as_deref_mut() else {
            return Ok(false);
        };
        let before = r.randomizer.clone();
        if let Some(s) = seed {
            r.randomizer.reseed(s);
        }
        let params = &self.config.physics.params;
        r.randomizer.begin_episode(&self.model, params);
        let draw = r.randomizer.draw();
        let outcome = (|| {
            self.actuator.scale_from(&r.base_actuator, &draw.actuator)?;
            r.delay.set_substeps(
                draw.actuator_delay_substeps,
                self.config.control.sim_steps_per_env_step,
            )?;
            if !r.randomizer.config().varies_dynamics() {
                return Ok(false);
            }
            let dynamics = draw.dynamics.dynamics(&self.model)?;
            self.backend.reset_with_dynamics(&dynamics, state)?;
            Ok(true)
        })();
        if outcome.is_err() {
            r.randomizer = before;
        }
        outcome
    }

    /// What a [`crate::policy::Policy`] needs to choose the next action.
    pub fn policy_input(&self) -> crate::policy::PolicyInput<'_> {
        crate::policy::PolicyInput {
            t: self.info.t,
            env_dt: self.env_dt,
            observation: self.seen(),
            joint_angles: &self.state.q,
            standing: self.model.standing_pose(),
            space: &self.space,
        }
    }

    /// The current observation (f64, §3 order): the last reset's or step's, as the policy
    /// sees it (with its noise when `randomize.obs_noise` is on).
    pub fn observation(&self) -> &[f64] {
        self.seen()
    }

    /// The current observation without its noise: what the simulated state gives, what the
    /// rules use (the same as [`Env::observation`] when observation noise is off).
    pub fn true_observation(&self) -> &[f64] {
        &self.obs
    }

    /// Whether observation noise is on (`randomize.obs_noise`): [`Env::observation`] is then
    /// what the policy sees and [`Env::true_observation`] what the rules see.
    pub fn observation_is_noisy(&self) -> bool {
        self.robustness.as_deref().is_some_and(|r| r.noisy)
    }

    /// This episode's drawn variations, when `[randomize]` is on.
    pub fn episode_draw(&self) -> Option<&EpisodeDraw> {
        self.robustness.as_deref().map(|r| r.randomizer.draw())
    }

    /// The velocity (m/s, world) the last step's push added to the trunk (zeros when it had
    /// none), and the pushes so far this episode, when pushes are on.
    pub fn last_push(&self) -> Option<([f64; 3], u64)> {
        let r = self.robustness.as_deref()?;
        r.randomizer
            .config()
            .pushes()
            .then(|| (r.randomizer.pushed(), r.randomizer.pushes()))
    }

    /// The current observation rounded to f32.
    pub fn observation_f32(&self) -> &[f32] {
        &self.obs_f32
    }

    /// The info of the last reset or step.
    pub fn info(&self) -> &StepInfo {
        &self.info
    }

    /// Whether the current episode has ended (or none was started): the next call must be
    /// [`Env::reset`].
    pub fn needs_reset(&self) -> bool {
        self.episode.as_ref().is_none_or(|e| e.done)
    }

    /// The validated configuration.
    pub fn config(&self) -> &EnvConfig {
        &self.config
    }

    /// The name of the engine this env runs on (the backend's `NAME`; for a backend that wraps
    /// several engines, the engine of this env).
    pub fn engine_name(&self) -> &'static str {
        self.backend.engine_name()
    }

    /// The backend's options, as read from `[physics.<B::NAME>]`.
    pub fn backend_options(&self) -> &B::Options {
        &self.options
    }

    /// The robot.
    pub fn model(&self) -> &Arc<RobotModel> {
        &self.model
    }

    /// The rules' view of the robot (joint ranges, feet, trunk).
    pub fn robot(&self) -> &RobotDescription {
        &self.robot
    }

    /// The observation layout (row names, bounds, named index ranges).
    pub fn observation_layout(&self) -> &ObservationLayout {
        &self.layout
    }

    /// The action space.
    pub fn action_space(&self) -> &ActionSpace {
        &self.space
    }

    /// The actuator (gains, limits).
    pub fn actuator(&self) -> &Actuator {
        &self.actuator
    }

    /// Δt_env = sub-steps × dt (s).
    pub fn env_dt(&self) -> f64 {
        self.env_dt
    }

    /// The joint angles at the end of the last step or reset (rad, action order).
    pub fn joint_angles(&self) -> &[f64] {
        &self.state.q
    }

    /// The trunk state at the end of the last step or reset.
    pub fn trunk(&self) -> &TrunkState {
        &self.state.trunk
    }

    /// The robot's whole state at the end of the last step or reset (after a divergence, the
    /// last finite one, as the observation reports it).
    pub fn state(&self) -> &RobotState {
        &self.state
    }

    /// Which tracked bodies (feet, then the trunk: `RobotModel::tracked`'s order) touched the
    /// ground in any sub-step of the last step, all false after reset: the flags the
    /// observation's contact rows hold, as booleans.
    pub fn contacts(&self) -> &[bool] {
        &self.contacts
    }

    /// The velocity task's current command (what the observation holds), under
    /// `task.kind = "velocity"`.
    pub fn command(&self) -> Option<hyq_tasks::Command> {
        self.velocity.as_deref().map(|t| t.command())
    }

    /// Whether the environment was ever reset with a seed.
    pub fn was_seeded(&self) -> bool {
        self.seeded
    }

    /// The ground of the current episode (flat unless `[terrain]` says otherwise).
    pub fn terrain(&self) -> &hyq_physics::Terrain {
        self.ground.terrain()
    }

    /// The terrain curriculum's level of the current episode (0 without a curriculum).
    pub fn terrain_level(&self) -> u32 {
        self.ground.level()
    }

    /// The backend.
    pub fn backend(&self) -> &B {
        &self.backend
    }

    /// The backend, mutably: for tests and tools that script a backend (see
    /// [`crate::testing`]). Changing the simulated state here bypasses the episode's
    /// bookkeeping; the next step starts from whatever state the backend is in.
    pub fn backend_mut(&mut self) -> &mut B {
        &mut self.backend
    }

    /// Switches per-part timing of [`Env::step`] on or off (off by default; two
    /// `Instant::now` calls per sub-step when on, none when off). Results are bitwise the same
    /// either way.
    pub fn set_timing(&mut self, on: bool) {
        self.timing_on = on;
    }

    /// The time summed per part since timing was switched on or last cleared.
    pub fn timing(&self) -> &StepTiming {
        &self.timing
    }

    /// Clears the timing sums.
    pub fn clear_timing(&mut self) {
        self.timing = StepTiming::default();
    }
}
