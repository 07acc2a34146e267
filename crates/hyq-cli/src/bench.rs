//! `hyq bench`: env steps per second of one environment under uniformly random joint targets,
//! and the share of the step's time in each part.
//!
//! # Workload
//! The anchors' `env_random` case (`bench/anchors/`, docs/benchmarks.md): one env, one
//! thread; every env step takes a fresh action drawn uniformly from the action space (with the
//! default `normalized` actions: joint targets uniform within the joint limits), drawn before
//! the timed region in blocks of [`BLOCK`] so the policy is not timed; an episode that ends is
//! reset inside the timed region. The episode ends by the environment's rules (see
//! [`BenchReport::episodes_ended`] for why they ended), t_max = 1000 by default.
//!
//! # Passes
//! 1. The throughput pass, with the per-part timing off: `env_steps_per_s` (wall clock) and
//!    `env_steps_per_s_cpu` (the process's CPU time, `CLOCK_PROCESS_CPUTIME_ID`, which is the
//!    better estimate of an idle core on a loaded machine: the anchors report both).
//! 2. The timing pass: the same workload again (same seed, same actions) with
//!    `Env::set_timing(true)`, giving the shares of physics, actuator, observation, spec
//!    evaluation and the rest. Its own rate is reported too (`timed_pass`): the difference is
//!    the cost of the timers.
//!
//! # A trained policy (`--policy mlp:FILE`, one env)
//! The `env_mlp` workload: the same passes with the trained policy choosing every action from
//! the step's observation (in the environment it was trained in, as `hyq run` applies it). Its
//! actions depend on the state, so they cannot be drawn ahead: the forward pass is inside the
//! timed region, and the rates are those of the closed loop.
//!
//! # Batched mode (`--num-envs N`, N ≥ 2)
//! N envs in a [`VecEnv`] (the vector env the Python binding uses) on a pool of `--threads T`
//! threads (default N, capped at the machine's cores), same workload per env (env i's actions
//! from its own random stream seeded seed + i, Gymnasium's next-step autoreset). One pass, no
//! per-part timing; the report is a [`VecBenchReport`]. Comparing `--threads 1` with
//! `--threads 2` at N = 2 measures how the vector env scales.
//!
//! # A mix of engines (`--backends A,B,...`)
//! The batched mode on one vector env whose env i runs on the (i mod length)-th engine of the
//! list (`VecEnv<hyq_engines::AnyBackend>`), e.g. `--backends rapier,dart,mujoco --num-envs 6`;
//! the report's `backend` is the list. Every env is its own task of the pool, so the threads
//! share the engines' different costs. `--backends rapier` runs one engine through the mixed
//! backend, against `--backend rapier`, which names the engine's own type: the difference is the
//! cost of the mixed backend's dispatch.
//!
//! # JSON (`--json`): one object, keys stable (`schema_version` 1)
//! See [`BenchReport`] and [`VecBenchReport`]; every key is documented there and in the
//! crate's README.

use std::time::{Duration, Instant};

use std::fmt::Write as _;

use clap::Args;
use cpu_time::ProcessTime;
use hyq_engines::{AnyBackend, AnyOptions};
use hyq_env::{
    AutoReset, Env, MlpPolicy, Policy, RandomPolicy, Reason, ResetOptions, StepTiming, VecEnv,
    VecStepOut,
};
use hyq_physics::Backend;
use serde::Serialize;

use crate::Failure;
use crate::backend::{BackendChoice, not_built, parse_backend_list, with_backend};
use crate::options::{EnvArgs, PolicyChoice, make_env, read_mlp, usage};
use crate::output::{print, print_json_line};

/// Actions drawn ahead of the timed region at a time.
pub const BLOCK: usize = 1000;

/// `hyq bench` arguments.
#[derive(Debug, Args)]
pub struct BenchArgs {
    #[command(flatten)]
    env: EnvArgs,
    /// Env steps per pass (two passes: throughput, then per-part timing).
    #[arg(long, default_value_t = 20_000, value_parser = clap::value_parser!(u64).range(1..))]
    steps: u64,
    /// Seed of the random actions and of the first reset.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// The actions: random (the `env_random` workload), or mlp:FILE, a trained policy file run
    /// closed-loop in the environment it was trained in (the `env_mlp` workload; one env).
    #[arg(long, default_value = "random", value_parser = parse_bench_policy, value_name = "POLICY")]
    policy: PolicyChoice,
    /// Print one JSON object on stdout instead of text.
    #[arg(long)]
    json: bool,
    /// Envs stepped together in a vector env (batched mode when ≥ 2); `--steps` then counts
    /// vector steps, each of N env steps.
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..=hyq_env::MAX_ENVS as u64))]
    num_envs: u64,
    /// A mix of engines (batched mode): a comma-separated list of backends assigned round-robin
    /// to the N envs (env i on the (i mod length)-th), e.g. rapier,dart,mujoco; each must be
    /// built in, and N at least the list's length. Instead of --backend.
    #[arg(long, value_name = "A,B,...", value_parser = parse_backend_list_arg, conflicts_with = "backend")]
    backends: Option<BackendList>,
    /// Threads of the vector env's pool (batched mode only; default: N, at most the number of
    /// cores).
    #[arg(long, value_parser = clap::value_parser!(u64).range(1..=hyq_env::MAX_THREADS as u64))]
    threads: Option<u64>,
}

/// `--backends`: the engines of a mix, in slot order.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BackendList(Vec<BackendChoice>);

fn parse_backend_list_arg(s: &str) -> Result<BackendList, String> {
    parse_backend_list(s).map(BackendList)
}

fn parse_bench_policy(text: &str) -> Result<PolicyChoice, String> {
    match text.parse()? {
        choice @ (PolicyChoice::Random | PolicyChoice::Mlp(_)) => Ok(choice),
        other => Err(format!(
            "{other} is not a bench workload: expected random or mlp:FILE"
        )),
    }
}

/// How the episodes that ended during a pass ended (a step may have several reasons).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Ended {
    /// §6.1.
    pub reached: u64,
    /// §6.2.
    pub joint_limit: u64,
    /// §6.3.
    pub fell: u64,
    /// §6.4.
    pub timeout: u64,
    /// A non-finite physics state.
    pub diverged: u64,
}

impl Ended {
    /// Counts one episode that ended for `reason`.
    pub fn add(&mut self, reason: Reason) {
        match reason {
            Reason::Reached => self.reached += 1,
            Reason::JointLimit => self.joint_limit += 1,
            Reason::Fell => self.fell += 1,
            Reason::Timeout => self.timeout += 1,
            Reason::Diverged => self.diverged += 1,
        }
    }
}

/// The share of the timed pass's step time in each part (fractions summing to 1).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Shares {
    /// The engine's sub-steps, contact reads and state reads.
    pub physics: f64,
    /// The shared PD actuator (every sub-step).
    pub actuator: f64,
    /// The trunk acceleration and writing the observation.
    pub observation: f64,
    /// hyq-spec's rewards, penalties and terminations.
    pub spec: f64,
    /// Everything else inside `Env::step` (action mapping, contact latching, bookkeeping).
    pub other: f64,
}

/// The rates of the timing pass.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct TimedPass {
    /// Env steps per wall-clock second with the per-part timers on.
    pub env_steps_per_s: f64,
    /// Env steps per CPU second with the per-part timers on.
    pub env_steps_per_s_cpu: f64,
}

/// `hyq bench --json`: one object. Keys are stable; new keys may be added, none removed or
/// renamed without raising `schema_version`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct BenchReport {
    /// 1.
    pub schema_version: u32,
    /// `"env_random"` (the anchors' case this reproduces) or `"env_mlp"` (`--policy mlp:FILE`).
    pub workload: &'static str,
    /// The backend's name (`"rapier"`, `"dart"`, `"mujoco"`).
    pub backend: &'static str,
    /// The robot's name (its profile's `name`: `"hyq"`, `"anymal_c"`, ...).
    pub robot: String,
    /// `"release"` or `"debug"` (a build with debug assertions): compare only release figures.
    pub profile: &'static str,
    /// The action mode (`"normalized"` unless configured otherwise).
    pub action_mode: String,
    /// Physics sub-steps per env step.
    pub substeps_per_env_step: u32,
    /// The physics time step (s).
    pub dt: f64,
    /// The seed.
    pub seed: u64,
    /// Env steps timed (per pass).
    pub steps: u64,
    /// Wall-clock seconds of the throughput pass.
    pub seconds: f64,
    /// Process CPU seconds of the throughput pass.
    pub cpu_seconds: f64,
    /// steps / seconds.
    pub env_steps_per_s: f64,
    /// steps / cpu_seconds.
    pub env_steps_per_s_cpu: f64,
    /// env_steps_per_s × substeps_per_env_step.
    pub physics_steps_per_s: f64,
    /// Resets inside the throughput pass (episodes that ended).
    pub resets: u64,
    /// Why those episodes ended.
    pub episodes_ended: Ended,
    /// Where the step's time goes (from the timing pass).
    pub shares: Shares,
    /// The timing pass's own rates.
    pub timed_pass: TimedPass,
}

/// `hyq bench --num-envs N --json` (N ≥ 2): one object, keys stable like [`BenchReport`]'s.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct VecBenchReport {
    /// 1.
    pub schema_version: u32,
    /// `"env_random_vec"`: `env_random` in every env of a vector env.
    pub workload: &'static str,
    /// The backend's name (`"rapier"`, `"dart"`, `"mujoco"`), or with `--backends` the list
    /// as given (`"rapier,dart,mujoco"`: env i on the (i mod length)-th).
    pub backend: String,
    /// The robot's name (its profile's `name`: `"hyq"`, `"anymal_c"`, ...).
    pub robot: String,
    /// `"release"` or `"debug"`.
    pub profile: &'static str,
    /// N, the envs in the vector env.
    pub num_envs: u64,
    /// Threads in the vector env's pool.
    pub threads: u64,
    /// Physics sub-steps per env step.
    pub substeps_per_env_step: u32,
    /// The seed (env i's is seed + i).
    pub seed: u64,
    /// Vector steps timed.
    pub steps: u64,
    /// Env steps timed: steps × N (autoreset steps included: they cost a reset each).
    pub env_steps: u64,
    /// Wall-clock seconds.
    pub seconds: f64,
    /// Process CPU seconds (all threads, including the pool's idle waits that spin).
    pub cpu_seconds: f64,
    /// env_steps / seconds: the throughput the caller sees.
    pub env_steps_per_s: f64,
    /// env_steps / cpu_seconds: throughput per CPU second.
    pub env_steps_per_s_cpu: f64,
    /// Episodes that ended (each is reset on its env's next step).
    pub resets: u64,
}

/// One pass's measurements.
#[derive(Default)]
struct Pass {
    wall: Duration,
    cpu: Duration,
    resets: u64,
    ended: Ended,
    timing: StepTiming,
}

/// Runs `hyq bench`.
pub fn execute(args: BenchArgs) -> Result<(), Failure> {
    let model = args.env.model()?;
    let mlp = match &args.policy {
        PolicyChoice::Mlp(file) => Some((read_mlp(file)?, file.display().to_string())),
        _ => None,
    };
    let config = match &mlp {
        Some((policy, file)) => args.env.configuration.config_over(
            &policy.metadata().env_config,
            &format!("--policy mlp:{file}: its env_config"),
        )?,
        None => args.env.config()?,
    };
    if mlp.is_some() && args.num_envs >= 2 {
        return Err(usage(format!(
            "--policy {} runs one env: leave out --num-envs {}",
            args.policy, args.num_envs
        )));
    }
    if let Some(list) = &args.backends {
        if mlp.is_some() {
            return Err(usage(format!(
                "--policy {} runs one env on one engine: leave out --backends",
                args.policy
            )));
        }
        return bench_mix(&args, &list.0, model, config);
    }
    if args.num_envs >= 2 {
        let threads = pool_threads(&args);
        return with_backend!(args.env.backend, B => {
            let n = usize::try_from(args.num_envs)
                .map_err(|_| usage(format!("--num-envs {}: too many", args.num_envs)))?;
            let vec = VecEnv::<B>::new(model, config, n, AutoReset::NextStep)
                .map_err(|e| usage(format!("cannot build the {} vector env: {e}", B::NAME)))?;
            let t = usize::try_from(threads)
                .map_err(|_| usage(format!("--threads {threads}: too many")))?;
            let mut vec = vec
                .with_threads(t)
                .map_err(|e| failure(format!("vector env: {e}")))?;
            let report = bench_vec(&mut vec, args.steps, args.seed, threads)?;
            print_vec_report(&report, args.json)
        });
    }
    if args.threads.is_some() {
        return Err(usage("--threads needs --num-envs N with N ≥ 2"));
    }
    with_backend!(args.env.backend, B => {
        let mut env = make_env::<B>(model, config)?;
        let mlp = match mlp {
            Some((policy, file)) => {
                policy
                    .check_env(env.model(), env.config(), &file)
                    .map_err(|e| usage(format!("--policy mlp:{e}")))?;
                Some(policy)
            }
            None => None,
        };
        let report = bench_with(&mut env, args.steps, args.seed, mlp)?;
        print_report(&report, args.json)
    })
}

/// The vector env's threads: `--threads`, else N capped at the machine's cores.
fn pool_threads(args: &BenchArgs) -> u64 {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get() as u64);
    args.threads.unwrap_or(args.num_envs.min(cores))
}

/// `hyq bench --backends A,B,...`: the batched pass on a vector env whose env i runs on the
/// (i mod length)-th engine of `list` (one `VecEnv<AnyBackend>`).
fn bench_mix(
    args: &BenchArgs,
    list: &[BackendChoice],
    model: std::sync::Arc<hyq_physics::RobotModel>,
    config: hyq_env::EnvConfig,
) -> Result<(), Failure> {
    let names: Vec<&str> = list.iter().map(|c| c.name()).collect();
    let option = format!("--backends {}", names.join(","));
    if let Some(choice) = list.iter().find(|c| !c.built()) {
        return Err(not_built(*choice, &option));
    }
    if args.num_envs < list.len() as u64 {
        return Err(usage(format!(
            "{option} needs --num-envs of at least {} (one env per listed engine), got {}",
            list.len(),
            args.num_envs
        )));
    }
    let n = usize::try_from(args.num_envs)
        .map_err(|_| usage(format!("--num-envs {}: too many", args.num_envs)))?;
    let physics = config.physics.clone();
    let vec = VecEnv::<AnyBackend>::with_options(model, config, n, AutoReset::NextStep, |i| {
        let name = names[i % names.len()];
        // Every name was checked to be built above, so each reads to Some.
        Ok(AnyOptions::read(name, &physics)?.unwrap_or_default())
    })
    .map_err(|e| usage(format!("cannot build the {option} vector env: {e}")))?;
    let threads = pool_threads(args);
    let t =
        usize::try_from(threads).map_err(|_| usage(format!("--threads {threads}: too many")))?;
    let mut vec = vec
        .with_threads(t)
        .map_err(|e| failure(format!("vector env: {e}")))?;
    let mut report = bench_vec(&mut vec, args.steps, args.seed, threads)?;
    report.backend = names.join(",");
    print_vec_report(&report, args.json)
}

/// The batched pass: `steps` vector steps of `vec` under random actions.
pub fn bench_vec<B: Backend>(
    vec: &mut VecEnv<B>,
    steps: u64,
    seed: u64,
    threads: u64,
) -> Result<VecBenchReport, Failure> {
    let n = vec.num_envs();
    let (obs_len, act_len) = (vec.observation_len(), vec.action_len());
    let mut policies: Vec<RandomPolicy> = (0..n)
        .map(|i| RandomPolicy::new(seed.wrapping_add(i as u64)))
        .collect();
    let mut actions = vec![0.0; BLOCK * n * act_len];
    let mut observations = vec![0.0f32; n * obs_len];
    let mut rewards = vec![0.0; n];
    let mut terminated = vec![false; n];
    let mut truncated = vec![false; n];
    vec.reset(Some(seed), &mut observations)
        .map_err(|e| failure(format!("reset: {e}")))?;
    let (mut wall, mut cpu, mut resets) = (Duration::ZERO, Duration::ZERO, 0u64);
    let mut left = steps;
    while left > 0 {
        let block = left.min(BLOCK as u64) as usize;
        draw_actions(vec, &mut policies, &mut actions, block);
        let cpu0 = cpu_now()?;
        let wall0 = Instant::now();
        for step_actions in actions.chunks_exact(n * act_len).take(block) {
            vec.step(
                step_actions,
                VecStepOut {
                    observations: &mut observations,
                    rewards: &mut rewards,
                    terminated: &mut terminated,
                    truncated: &mut truncated,
                },
            )
            .map_err(|e| failure(format!("vector step: {e}")))?;
            resets += terminated
                .iter()
                .zip(&truncated)
                .filter(|(a, b)| **a || **b)
                .count() as u64;
        }
        wall += wall0.elapsed();
        cpu += cpu_now()?.saturating_sub(cpu0);
        left -= block as u64;
    }
    let env_steps = steps * n as u64;
    let rate = |s: f64| {
        if s > 0.0 {
            env_steps as f64 / s
        } else {
            f64::INFINITY
        }
    };
    Ok(VecBenchReport {
        schema_version: 1,
        workload: "env_random_vec",
        backend: B::NAME.to_owned(),
        robot: vec.env(0).model().name().to_owned(),
        profile: if cfg!(debug_assertions) {
            "debug"
        } else {
            "release"
        },
        num_envs: n as u64,
        threads,
        substeps_per_env_step: vec.env(0).config().control.sim_steps_per_env_step,
        seed,
        steps,
        env_steps,
        seconds: wall.as_secs_f64(),
        cpu_seconds: cpu.as_secs_f64(),
        env_steps_per_s: rate(wall.as_secs_f64()),
        env_steps_per_s_cpu: rate(cpu.as_secs_f64()),
        resets,
    })
}

/// The random actions of the next `block` vector steps into `actions` (step by step, env by
/// env), outside the timed part. As in the single-env pass, the random policy reads only the
/// action space.
fn draw_actions<B: Backend>(
    vec: &VecEnv<B>,
    policies: &mut [RandomPolicy],
    actions: &mut [f64],
    block: usize,
) {
    let act_len = vec.action_len();
    let input = vec.env(0).policy_input();
    for step_actions in actions
        .chunks_exact_mut(policies.len() * act_len)
        .take(block)
    {
        for (policy, action) in policies
            .iter_mut()
            .zip(step_actions.chunks_exact_mut(act_len))
        {
            policy.act(&input, action);
        }
    }
}

fn print_vec_report(r: &VecBenchReport, json: bool) -> Result<(), Failure> {
    if json {
        return print_json_line(r, "a bench report");
    }
    let mut t = String::new();
    let _ = writeln!(
        t,
        "hyq bench: {} on the {} backend, {} build, workload {} ({} envs, {} pool threads, {} sub-steps each)",
        r.robot, r.backend, r.profile, r.workload, r.num_envs, r.threads, r.substeps_per_env_step
    );
    let _ = writeln!(
        t,
        "  {} vector steps ({} env steps) in {:.3} s wall, {:.3} s CPU, {} resets",
        r.steps, r.env_steps, r.seconds, r.cpu_seconds, r.resets
    );
    let _ = writeln!(
        t,
        "  {:.0} env steps/s (wall), {:.0} env steps/s (CPU)",
        r.env_steps_per_s, r.env_steps_per_s_cpu
    );
    print(&t)
}

fn failure(message: String) -> Failure {
    Failure { status: 1, message }
}

fn cpu_now() -> Result<Duration, Failure> {
    ProcessTime::try_now()
        .map(|t| t.as_duration())
        .map_err(|e| failure(format!("cannot read the process CPU time: {e}")))
}

/// Both passes on `env`, under random actions or, with `mlp`, the trained policy's.
pub fn bench_with<B: Backend>(
    env: &mut Env<B>,
    steps: u64,
    seed: u64,
    mut mlp: Option<MlpPolicy>,
) -> Result<BenchReport, Failure> {
    let workload = if mlp.is_some() {
        "env_mlp"
    } else {
        "env_random"
    };
    let throughput = pass(env, steps, seed, false, mlp.clone())?;
    let timed = pass(env, steps, seed, true, mlp.take())?;
    let t = &timed.timing;
    let total = t.total.as_secs_f64();
    let share = |d: Duration| {
        if total > 0.0 {
            d.as_secs_f64() / total
        } else {
            0.0
        }
    };
    let secs = throughput.wall.as_secs_f64();
    let cpu = throughput.cpu.as_secs_f64();
    let n = steps as f64;
    let rate = |s: f64| if s > 0.0 { n / s } else { f64::INFINITY };
    let config = env.config();
    let substeps = config.control.sim_steps_per_env_step;
    Ok(BenchReport {
        schema_version: 1,
        workload,
        backend: B::NAME,
        robot: env.model().name().to_owned(),
        profile: if cfg!(debug_assertions) {
            "debug"
        } else {
            "release"
        },
        action_mode: format!("{:?}", config.action.mode).to_lowercase(),
        substeps_per_env_step: substeps,
        dt: config.physics.params.dt,
        seed,
        steps,
        seconds: secs,
        cpu_seconds: cpu,
        env_steps_per_s: rate(secs),
        env_steps_per_s_cpu: rate(cpu),
        physics_steps_per_s: rate(secs) * f64::from(substeps),
        resets: throughput.resets,
        episodes_ended: throughput.ended,
        shares: Shares {
            physics: share(t.physics),
            actuator: share(t.actuator),
            observation: share(t.observation),
            spec: share(t.spec),
            other: share(t.other()),
        },
        timed_pass: TimedPass {
            env_steps_per_s: rate(timed.wall.as_secs_f64()),
            env_steps_per_s_cpu: rate(timed.cpu.as_secs_f64()),
        },
    })
}

/// One pass of `steps` env steps from a reset with `seed`.
fn pass<B: Backend>(
    env: &mut Env<B>,
    steps: u64,
    seed: u64,
    timing: bool,
    mlp: Option<MlpPolicy>,
) -> Result<Pass, Failure> {
    if let Some(policy) = mlp {
        return closed_loop_pass(env, steps, seed, timing, policy);
    }
    let n = env.action_space().len();
    let mut policy = RandomPolicy::new(seed);
    let mut actions = vec![0.0; BLOCK * n];
    start_pass(env, seed, timing)?;
    let mut result = Pass::default();
    let mut left = steps;
    while left > 0 {
        let block = left.min(BLOCK as u64) as usize;
        // The random policy reads only the action space, so one input serves the whole block.
        {
            let input = env.policy_input();
            for action in actions.chunks_exact_mut(n).take(block) {
                policy.act(&input, action);
            }
        }
        let cpu0 = cpu_now()?;
        let wall0 = Instant::now();
        for action in actions.chunks_exact(n).take(block) {
            let step = env
                .step(action)
                .map_err(|e| failure(format!("step: {e}")))?;
            if step.terminated || step.truncated {
                for reason in step.info.reasons.iter() {
                    result.ended.add(reason);
                }
                result.resets += 1;
                env.reset(None, &ResetOptions::default())
                    .map_err(|e| failure(format!("reset: {e}")))?;
            }
        }
        result.wall += wall0.elapsed();
        result.cpu += cpu_now()?.saturating_sub(cpu0);
        left -= block as u64;
    }
    result.timing = *env.timing();
    env.set_timing(false);
    Ok(result)
}

/// Resets `env` with `seed` outside the timing, then turns the per-part timing on or off for
/// the pass that follows.
fn start_pass<B: Backend>(env: &mut Env<B>, seed: u64, timing: bool) -> Result<(), Failure> {
    env.set_timing(false);
    env.clear_timing();
    env.reset(Some(seed), &ResetOptions::default())
        .map_err(|e| failure(format!("reset: {e}")))?;
    env.set_timing(timing);
    Ok(())
}

/// One pass of `steps` env steps from a reset with `seed`, each action chosen by `policy` from
/// the step's observation inside the timed region.
fn closed_loop_pass<B: Backend>(
    env: &mut Env<B>,
    steps: u64,
    seed: u64,
    timing: bool,
    mut policy: MlpPolicy,
) -> Result<Pass, Failure> {
    let mut action = vec![0.0; env.action_space().len()];
    start_pass(env, seed, timing)?;
    let mut result = Pass::default();
    let cpu0 = cpu_now()?;
    let wall0 = Instant::now();
    for _ in 0..steps {
        policy.act(&env.policy_input(), &mut action);
        let step = env
            .step(&action)
            .map_err(|e| failure(format!("step: {e}")))?;
        if step.terminated || step.truncated {
            for reason in step.info.reasons.iter() {
                result.ended.add(reason);
            }
            result.resets += 1;
            env.reset(None, &ResetOptions::default())
                .map_err(|e| failure(format!("reset: {e}")))?;
        }
    }
    result.wall = wall0.elapsed();
    result.cpu = cpu_now()?.saturating_sub(cpu0);
    result.timing = *env.timing();
    env.set_timing(false);
    Ok(result)
}

fn print_report(r: &BenchReport, json: bool) -> Result<(), Failure> {
    if json {
        return print_json_line(r, "a bench report");
    }
    let mut t = String::new();
    let s = &r.shares;
    let e = &r.episodes_ended;
    let _ = writeln!(
        t,
        "hyq bench: {} on the {} backend, {} build, workload {} ({} actions, {} x {} s sub-steps)",
        r.robot, r.backend, r.profile, r.workload, r.action_mode, r.substeps_per_env_step, r.dt
    );
    let _ = writeln!(
        t,
        "  {} env steps in {:.3} s wall, {:.3} s CPU",
        r.steps, r.seconds, r.cpu_seconds
    );
    let _ = writeln!(
        t,
        "  {:.0} env steps/s (wall), {:.0} env steps/s (CPU), {:.0} physics steps/s (wall)",
        r.env_steps_per_s, r.env_steps_per_s_cpu, r.physics_steps_per_s
    );
    let _ = writeln!(
        t,
        "  {} resets: fell {}, joint_limit {}, timeout {}, reached {}, diverged {}",
        r.resets, e.fell, e.joint_limit, e.timeout, e.reached, e.diverged
    );
    let _ = writeln!(
        t,
        "  time shares: physics {:.1}%, actuator {:.1}%, observation {:.1}%, spec {:.1}%, \
         other {:.1}%  (timed pass: {:.0} env steps/s wall)",
        100.0 * s.physics,
        100.0 * s.actuator,
        100.0 * s.observation,
        100.0 * s.spec,
        100.0 * s.other,
        r.timed_pass.env_steps_per_s
    );
    if r.profile == "debug" {
        let _ = writeln!(
            t,
            "  note: a debug build; measure with `cargo run --release -p hyq-cli -- bench`"
        );
    }
    print(&t)
}
