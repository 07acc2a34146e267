//! `hyq run`: episodes of a policy on the environment, a per-episode summary, and optionally a
//! JSONL record of every step (hyq-env's `StepRecord` schema) and per-episode reward plots.
//!
//! Defaults: one episode of the scripted trot, seed 0, the rapier backend and the default
//! configuration (t_max = 1000 env steps = 10 s simulated; goal 5 m ahead; k_exp = 5).
//!
//! Seeds: the first episode resets the environment with `--seed S`; later episodes reset
//! unseeded, continuing its random streams (Gymnasium's semantics), so a run of N episodes is
//! reproducible from S alone. The random policy draws from its own stream seeded with S.

use std::io::Write;
use std::path::PathBuf;

use clap::Args;
use hyq_env::{
    Env, EpisodeRandomization, Policy, Reason, ResetOptions, Step, StepInfo, StepRecord, TermSums,
};
use hyq_physics::Backend;
use hyq_spec::terms::terms_of;
use hyq_spec::{REWARD_TERMS, RewardTerm, TaskConfig, TermKind};
use serde::Serialize;

use crate::Failure;
use crate::backend::with_backend;
use crate::options::{EnvArgs, PolicyArgs, make_env, usage};
use indicatif::ProgressBar;

use crate::output::{OutputFile, print, print_json_line, print_line, progress_bar};
use crate::plot::LivePlots;
use crate::table::Table;

/// `hyq run` arguments.
#[derive(Debug, Args)]
pub struct RunArgs {
    #[command(flatten)]
    env: EnvArgs,
    #[command(flatten)]
    policy: PolicyArgs,
    /// Episodes to run (each ends by the spec's rules: reached, joint limit, fall or timeout).
    #[arg(long, default_value_t = 1, value_parser = clap::value_parser!(u64).range(1..))]
    episodes: u64,
    /// Write every env step as one JSON object per line to FILE (hyq-env's StepRecord schema).
    #[arg(long, value_name = "FILE.jsonl")]
    record: Option<PathBuf>,
    /// Write two PNG plots per episode into DIR (created if missing): every reward term and the
    /// cumulative reward over time, and D_n with the spec's §4.3 curve (see `hyq plot`).
    #[arg(long, value_name = "DIR")]
    plot: Option<PathBuf>,
    /// Print the per-episode summaries as JSON lines on stdout instead of a table.
    #[arg(long)]
    json: bool,
}

/// One episode's summary (a table row, or one JSON line with `--json`).
#[derive(Clone, Debug, Serialize)]
pub struct EpisodeSummary {
    /// The backend's name.
    pub backend: &'static str,
    /// The robot's name.
    pub robot: String,
    /// The policy's name.
    pub policy: &'static str,
    /// The episode number (1 for the first).
    pub episode: u64,
    /// Env steps taken.
    pub steps: u64,
    /// Simulated time (s): steps × Δt_env.
    pub simulated_s: f64,
    /// Σ reward.
    #[serde(rename = "return")]
    pub ret: f64,
    /// Σ of each reward and penalty term.
    pub terms: TermSums,
    /// The mean of each multiplier over the steps, as `mean_<name>` (an opt-in one only when
    /// it is on).
    #[serde(flatten)]
    pub multipliers: MultiplierMeans,
    /// Gymnasium's flags on the last step.
    pub terminated: bool,
    /// See `terminated`.
    pub truncated: bool,
    /// Every reason that held on the last step.
    pub reasons: Vec<Reason>,
    /// D^0 = K (m).
    pub initial_distance_to_goal: f64,
    /// D^T (m).
    pub final_distance_to_goal: f64,
    /// C^0 (m).
    pub initial_position: [f64; 3],
    /// C^T (m).
    pub final_position: [f64; 3],
    /// G (m).
    pub goal: [f64; 3],
    /// When `[randomize]` is on: the episode's drawn values and its pushes (else not written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub randomize: Option<EpisodeRandomization>,
    /// Under `task.kind = "velocity"`: how well the commands were followed and the sum of
    /// each of the task's terms (else not written; `ret` is then the task's return).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub velocity: Option<VelocitySummary>,
    /// When `[regularizers]` is on: what the gait regularisers added to the return and the
    /// sum of each term that is on, unscaled (else not written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub regularizers: Option<RegularizerSummary>,
}

/// The gait regularisers' part of an episode's summary.
#[derive(Clone, Debug, Default, Serialize)]
pub struct RegularizerSummary {
    /// Σ over the steps of what they added to the reward (Σ scale · term · Δt_env).
    pub reward: f64,
    /// The sum over the steps of each term that is on, unscaled, by its name.
    pub terms: std::collections::BTreeMap<&'static str, f64>,
}

impl RegularizerSummary {
    /// Adds a step's report.
    fn add(&mut self, r: &hyq_env::RegularizerInfo) {
        self.reward += r.reward;
        for (name, value) in r.terms.iter() {
            *self.terms.entry(name).or_default() += value;
        }
    }
}

/// The velocity task's part of an episode's summary.
#[derive(Clone, Debug, Default, Serialize)]
pub struct VelocitySummary {
    /// The mean of |c_x − v_x| over the steps (m/s): forward-speed tracking error.
    pub mean_abs_lin_vel_x_error: f64,
    /// The mean of |c_y − v_y| over the steps (m/s).
    pub mean_abs_lin_vel_y_error: f64,
    /// The mean of |c_yaw − ω_z| over the steps (rad/s).
    pub mean_abs_yaw_rate_error: f64,
    /// The sum over the steps of each term, unscaled, by hyq-tasks' term name.
    pub terms: std::collections::BTreeMap<&'static str, f64>,
}

impl VelocitySummary {
    /// Adds a step's `info` (`steps` counted so far, this one included).
    fn add(&mut self, v: &hyq_env::VelocityInfo, steps: u64) {
        let mean = |m: &mut f64, x: f64| *m += (x - *m) / steps.max(1) as f64;
        mean(
            &mut self.mean_abs_lin_vel_x_error,
            (v.command[0] - v.lin_vel[0]).abs(),
        );
        mean(
            &mut self.mean_abs_lin_vel_y_error,
            (v.command[1] - v.lin_vel[1]).abs(),
        );
        mean(
            &mut self.mean_abs_yaw_rate_error,
            (v.command[2] - v.ang_vel[2]).abs(),
        );
        for (name, value) in hyq_tasks::TERM_NAMES.iter().zip(v.terms.to_array()) {
            *self.terms.entry(name).or_default() += value;
        }
    }
}

/// The mean of each multiplier (`hyq_spec::REWARD_TERMS` of kind `Multiplier`) over an
/// episode's steps, written as `mean_m_yaw`, `mean_m_pitch`, …; an opt-in multiplier (the
/// height penalty) only when the configuration switches it on.
#[derive(Clone, Debug)]
pub struct MultiplierMeans {
    sums: TermSums,
    task: TaskConfig,
}

impl MultiplierMeans {
    /// The multipliers reported under `task`, with their means.
    pub fn iter(&self) -> impl Iterator<Item = (&'static RewardTerm, f64)> + '_ {
        terms_of(TermKind::Multiplier)
            .filter(|t| t.is_reported(&self.task))
            .map(|t| (t, self.sums.mean(t.name).unwrap_or_default()))
    }
}

impl Serialize for MultiplierMeans {
    fn serialize<S: serde::Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        use serde::ser::SerializeMap;
        let mut map = s.serialize_map(None)?;
        for (term, mean) in self.iter() {
            map.serialize_entry(&format!("mean_{}", term.name), &mean)?;
        }
        map.end()
    }
}

/// Runs `hyq run`.
pub fn execute(args: RunArgs) -> Result<(), Failure> {
    let model = args.env.model()?;
    let config = args.policy.config(&args.env)?;
    with_backend!(args.env.backend, B => {
        let env = make_env::<B>(model, config)?;
        run_episodes(env, &args)
    })
}

/// Runs the episodes, then prints their summary table (or each summary as a JSON line while it
/// runs) and puts the record and the plots in place.
fn run_episodes<B: Backend>(env: Env<B>, args: &RunArgs) -> Result<(), Failure> {
    let policy = args.policy.make(&env)?;
    // Every check first; the outputs are written beside their targets and put in place only
    // when the run has finished.
    let outputs = Outputs::open(&env, args, policy.name())?;
    let t_max = env.config().task.max_time_steps;
    let mut run = Run {
        bar: progress_bar(args.episodes.saturating_mul(t_max)),
        action: vec![0.0; env.action_space().len()],
        env,
        policy,
        outputs,
        args,
        t_max,
    };
    let mut summaries = Vec::new();
    for episode in 0..args.episodes {
        let summary = run.episode(episode)?;
        if args.json {
            run.bar
                .suspend(|| print_json_line(&summary, "an episode summary"))?;
        }
        summaries.push(summary);
    }
    let Run {
        env,
        policy,
        outputs,
        bar,
        ..
    } = run;
    let plots_written = outputs.finish(args)?;
    bar.finish_and_clear();
    if !args.json {
        print_line(&format!(
            "hyq run: {} on {}, policy {}, seed {}",
            env.model().name(),
            B::NAME,
            policy.name(),
            args.policy.seed
        ))?;
        print(&summary_table(&summaries))?;
        if let Some(dir) = &args.plot {
            print_line(&format!("wrote {plots_written} plots to {}", dir.display()))?;
        }
    }
    Ok(())
}

/// What a run writes besides stdout: the live plots (`--plot`) and the JSONL record
/// (`--record`), each opened, and so checked, before the first step.
struct Outputs {
    plots: Option<LivePlots>,
    record: Option<OutputFile>,
}

impl Outputs {
    /// Opens the outputs `args` asks for; `policy` names the policy in the plots' titles.
    fn open<B: Backend>(env: &Env<B>, args: &RunArgs, policy: &str) -> Result<Self, Failure> {
        let plots = match &args.plot {
            None => None,
            Some(dir) => {
                let title = format!("{}, {policy}, seed {}", B::NAME, args.policy.seed);
                Some(LivePlots::new(dir, env.config(), title)?)
            }
        };
        let record = match &args.record {
            None => None,
            Some(path) => Some(OutputFile::create(path).map_err(|e| {
                usage(format!(
                    "--record {}: cannot create the file: {e}",
                    path.display()
                ))
            })?),
        };
        Ok(Self { plots, record })
    }

    /// Writes the step `env` has just taken with `action`: its record line and its plot point.
    fn step<B: Backend>(
        &mut self,
        env: &Env<B>,
        action: &[f64],
        args: &RunArgs,
    ) -> Result<(), Failure> {
        if let Some(out) = self.record.as_mut() {
            // Serialised straight into the buffered file: the bytes of `to_json_line`,
            // without a String per step. A failed write comes back as its io::Error.
            serde_json::to_writer(&mut *out, &StepRecord::from_env(env, action))
                .map_err(std::io::Error::from)
                .and_then(|()| out.write_all(b"\n"))
                .map_err(|e| record_error(args, e))?;
        }
        if let Some(plots) = self.plots.as_mut() {
            plots.push(env.info());
        }
        Ok(())
    }

    /// Puts the record and the plots in place; returns how many plots were written.
    fn finish(self, args: &RunArgs) -> Result<usize, Failure> {
        if let Some(out) = self.record {
            out.finish().map_err(|e| record_error(args, e))?;
        }
        match self.plots {
            Some(plots) => plots.publish(),
            None => Ok(0),
        }
    }
}

/// A run in progress: the environment, the policy and its action buffer, the outputs and the
/// progress bar.
struct Run<'a, B: Backend> {
    env: Env<B>,
    policy: Box<dyn Policy>,
    action: Vec<f64>,
    outputs: Outputs,
    bar: ProgressBar,
    args: &'a RunArgs,
    /// The task's `max_time_steps`, the progress bar's steps per episode.
    t_max: u64,
}

impl<B: Backend> Run<'_, B> {
    /// Runs episode `episode` (0 for the first, which resets with the run's seed) to its end.
    fn episode(&mut self, episode: u64) -> Result<EpisodeSummary, Failure> {
        let args = self.args;
        let seed = (episode == 0).then_some(args.policy.seed);
        let robot = self.env.model().name().to_owned();
        let task = self.env.config().task.spec;
        let reset = self
            .env
            .reset(seed, &ResetOptions::default())
            .map_err(|e| Failure {
                status: 1,
                message: format!("reset: {e}"),
            })?;
        let policy = self.policy.name();
        let mut summary = EpisodeSummary::start(B::NAME, robot, policy, task, reset.info);
        self.bar
            .set_message(format!("episode {}/{}", episode + 1, args.episodes));
        loop {
            self.policy.act(&self.env.policy_input(), &mut self.action);
            let step = self.env.step(&self.action).map_err(|e| Failure {
                status: 1,
                message: format!("step: {e}"),
            })?;
            let done = step.terminated || step.truncated;
            summary.add_step(&step, done);
            if done {
                let p = &self.env.trunk().pose.translation;
                summary.final_position = [p.x, p.y, p.z];
            }
            self.outputs.step(&self.env, &self.action, args)?;
            self.bar
                .set_position(episode * self.t_max + self.env.info().t);
            if done {
                break;
            }
        }
        if let Some(plots) = self.outputs.plots.as_mut() {
            plots.finish_episode(summary.episode)?;
        }
        summary.multipliers.sums = summary.terms;
        summary.simulated_s = summary.steps as f64 * self.env.env_dt();
        self.bar.set_position((episode + 1) * self.t_max);
        Ok(summary)
    }
}

impl EpisodeSummary {
    /// The summary of an episode of `robot` on `backend` under `policy` with the settings
    /// `task`, just reset to `info`, before its first step.
    fn start(
        backend: &'static str,
        robot: String,
        policy: &'static str,
        task: TaskConfig,
        info: &StepInfo,
    ) -> Self {
        EpisodeSummary {
            backend,
            robot,
            policy,
            episode: info.episode,
            steps: 0,
            simulated_s: 0.0,
            ret: 0.0,
            terms: TermSums::default(),
            multipliers: MultiplierMeans {
                sums: TermSums::default(),
                task,
            },
            terminated: false,
            truncated: false,
            reasons: Vec::new(),
            initial_distance_to_goal: info.distance_to_goal,
            final_distance_to_goal: info.distance_to_goal,
            initial_position: info.initial_position,
            final_position: info.initial_position,
            goal: info.goal,
            randomize: info
                .randomize
                .as_ref()
                .map(|r| EpisodeRandomization::starting(&r.draw)),
            velocity: info.velocity.map(|_| VelocitySummary::default()),
            regularizers: info.regularizers.map(|_| RegularizerSummary::default()),
        }
    }

    /// Adds a step's reward and terms; on the episode's last step (`done`), its flags, reasons
    /// and final distance (the caller adds where the trunk ended).
    fn add_step(&mut self, step: &Step<'_>, done: bool) {
        let info = step.info;
        let r = &info.reward;
        self.steps = info.t;
        self.ret += step.reward;
        self.terms.add(r);
        if let (Some(s), Some(v)) = (self.velocity.as_mut(), &info.velocity) {
            s.add(v, info.t);
        }
        if let (Some(s), Some(r)) = (self.regularizers.as_mut(), &info.regularizers) {
            s.add(r);
        }
        if done {
            self.terminated = step.terminated;
            self.truncated = step.truncated;
            self.reasons = info.reasons.iter().collect();
            self.final_distance_to_goal = info.distance_to_goal;
            if let (Some(s), Some(r)) = (self.randomize.as_mut(), &info.randomize) {
                s.pushes = r.pushes;
            }
        }
    }
}

fn record_error(args: &RunArgs, e: std::io::Error) -> Failure {
    let path = args
        .record
        .as_deref()
        .map(|p| p.display().to_string())
        .unwrap_or_default();
    Failure {
        status: 1,
        message: format!("--record {path}: cannot write: {e}"),
    }
}

/// A number for a table cell: three decimals, or in scientific form (`1.234e11`) from a
/// million up, where the decimals would say nothing and the digits would be many.
pub fn compact(v: f64) -> String {
    if v.abs() >= 1e6 {
        format!("{v:.3e}")
    } else {
        format!("{v:.3}")
    }
}

/// The per-episode table of `hyq run`: the return and the sum of every reward and penalty term
/// (`hyq_spec::REWARD_TERMS`), the end and the distance.
pub fn summary_table(summaries: &[EpisodeSummary]) -> String {
    let header: Vec<&str> = ["episode", "steps", "time_s", "return"]
        .into_iter()
        .chain(
            REWARD_TERMS
                .iter()
                .filter(|t| t.kind.is_summed())
                .map(|t| t.name),
        )
        .chain(["<end", "distance_m", "dx_m"])
        .collect();
    let mut table = Table::new(&header);
    let num = compact;
    for s in summaries {
        let end: Vec<&str> = s.reasons.iter().map(|r| r.as_str()).collect();
        let mut row = vec![
            s.episode.to_string(),
            s.steps.to_string(),
            format!("{:.2}", s.simulated_s),
            num(s.ret),
        ];
        row.extend(
            s.terms
                .iter()
                .filter(|(t, _)| t.kind.is_summed())
                .map(|(_, v)| num(v)),
        );
        row.extend([
            end.join("+"),
            format!(
                "{:.3} -> {:.3}",
                s.initial_distance_to_goal, s.final_distance_to_goal
            ),
            format!("{:.3}", s.final_position[0] - s.initial_position[0]),
        ]);
        table.row(row);
    }
    table.render()
}
