//! A policy on several backends, closed loop: each engine runs the same policy from its own
//! observations, so what the report measures is the sim-to-sim gap a user of the policy meets
//! (train on one engine, evaluate on the others), under the same rules.
//!
//! Per engine, `episodes` episodes as `hyq run --policy … --episodes N --seed S` runs them (the
//! first reset seeded with S, later ones continuing its streams): distance walked toward the
//! goal (K − D^T), the trunk's travel along the start-to-goal direction, D^T, the return, the
//! steps and how each episode ended. Per pair of engines, the first episode over time: trunk
//! position, orientation and worst-joint divergence (RMS and max) and when the two trunks were
//! first 1 cm and 10 cm apart.
//!
//! Closed-loop runs part by nature: each engine's small differences change the observation,
//! which changes the next action. So this comparison is **not** judged against the ledger (whose
//! tolerances are for identical action scripts) and has no pass or fail; it states the gap.
//!
//! To tell physics from feedback apart, the first engine's first-episode actions are also
//! replayed open loop on every engine (the first one included: its replay must reproduce its
//! closed-loop run exactly, a check of the replay itself). What another engine does with the
//! very same actions is the physics' share of the gap. The replay is skipped in the `delta`
//! action mode, whose targets depend on the simulated joint angles.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use hyq_env::{ActionMode, EnvConfig, EpisodeRandomization, Policy, Reason};
use hyq_physics::{Backend, RobotModel};
use serde::Serialize;

use crate::error::CompareError;
use crate::estimates::{Columns, PairRatios, Rates, Stats, rate_text, ratio_text};
use crate::gait::{self, Figure, GaitEpisode, GaitStats};
use crate::metrics::{Divergence, compare_trajectories};
use crate::plot::{COLOURS, PAIR_COLOURS, Panel, plot_panels};
use crate::randomized::{RandomizedSide, drew_alike};
use crate::report::{PLOT_FILE, prepare_output_dir, sig, thin, write_report_files};
use crate::run::{Trajectory, build_env, run_episode, run_script};
use crate::velocity::{VelocityEpisode, VelocityStats};

/// The most episodes per engine a policy comparison runs.
pub const MAX_EPISODES: u32 = 1000;

/// The trunk distances (m) at which a pair's first episode counts as "apart".
pub const APART_M: [f64; 2] = [0.01, 0.1];

/// What a policy comparison runs.
#[derive(Clone, Debug, PartialEq)]
pub struct PolicySpec {
    /// The policy as the user named it (e.g. `mlp:assets/policies/hyq_walk.safetensors`).
    pub policy: String,
    /// The first reset's seed.
    pub seed: u64,
    /// Episodes per engine (1..=[`MAX_EPISODES`]).
    pub episodes: u32,
    /// The configuration as applied, for the report: `key=value` with where it came from.
    pub configuration: Vec<String>,
}

/// A policy comparison made ready to run: the robot, the environment's configuration (the same
/// on every engine) and the policy, cloned fresh for each engine.
pub struct PolicyPlan<P> {
    model: Arc<RobotModel>,
    config: EnvConfig,
    policy: P,
    spec: PolicySpec,
}

/// One engine's closed-loop episodes.
pub struct PolicySide {
    label: String,
    first: Trajectory,
    episodes: Vec<EpisodeOutcome>,
    /// Each episode's foot contact flags (`first.num_feet` per sample), for the pairs' contact
    /// agreement.
    foot_contacts: Vec<Vec<bool>>,
}

impl PolicySide {
    /// The first episode, sampled at every env step.
    pub fn first_episode(&self) -> &Trajectory {
        &self.first
    }

    /// Every episode's outcome.
    pub fn episodes(&self) -> &[EpisodeOutcome] {
        &self.episodes
    }
}

/// How one episode ended.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EpisodeOutcome {
    /// 1 for the first.
    pub episode: u32,
    /// Env steps taken.
    pub steps: u64,
    /// Σ reward.
    #[serde(rename = "return")]
    pub ret: f64,
    /// Every reason that held on the last step.
    pub end_reasons: Vec<Reason>,
    /// K = D^0 (m).
    pub initial_distance_m: f64,
    /// D^T (m).
    pub final_distance_m: f64,
    /// K − D^T: how much closer to the goal the trunk ended than it started (m).
    pub distance_walked_m: f64,
    /// The trunk's displacement along the start-to-goal direction in the ground plane (m):
    /// unlike K − D^T it keeps growing past the goal.
    pub travel_m: f64,
    /// C^T (m).
    pub final_position: [f64; 3],
    /// `[randomize]`'s draws for the episode and its pushes, when it is on (else not written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub randomize: Option<EpisodeRandomization>,
    /// The episode's gait diagnostics.
    pub gait: GaitEpisode,
    /// Under `task.kind = "velocity"`, the task's figures (else not written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub velocity: Option<VelocityEpisode>,
}

impl EpisodeOutcome {
    fn of(episode: u32, t: &Trajectory) -> Self {
        let start = t.positions.first().copied().unwrap_or([f64::NAN; 3]);
        let end = t.positions.last().copied().unwrap_or([f64::NAN; 3]);
        Self {
            episode,
            steps: t.end_step,
            ret: t.sums.ret,
            end_reasons: t.reasons.iter().collect(),
            initial_distance_m: t.initial_distance_m,
            final_distance_m: t.final_distance_m,
            distance_walked_m: t.initial_distance_m - t.final_distance_m,
            travel_m: travel(start, end, t.goal),
            final_position: end,
            randomize: t.randomize.clone(),
            gait: gait::episode(
                &t.feet(&t.foot_contacts()),
                t.env_dt,
                &t.actions,
                &t.action_low,
                &t.action_high,
            ),
            velocity: VelocityEpisode::of(t),
        }
    }
}

/// The displacement from `start` to `end` along the direction from `start` to `goal`, in the
/// ground plane (m); 0 when the goal is straight above or below the start.
fn travel(start: [f64; 3], end: [f64; 3], goal: [f64; 3]) -> f64 {
    let d = [goal[0] - start[0], goal[1] - start[1]];
    let m = [end[0] - start[0], end[1] - start[1]];
    let norm = d[0].hypot(d[1]);
    if norm < 1e-12 {
        0.0
    } else {
        (d[0] * m[0] + d[1] * m[1]) / norm
    }
}

impl<P: Policy + Clone> PolicyPlan<P> {
    /// Checks `spec` and keeps what every engine runs.
    pub fn new(
        model: Arc<RobotModel>,
        config: EnvConfig,
        policy: P,
        spec: PolicySpec,
    ) -> Result<Self, CompareError> {
        if !(1..=MAX_EPISODES).contains(&spec.episodes) {
            return Err(CompareError::Episodes {
                value: spec.episodes,
            });
        }
        config.validate()?;
        Ok(Self {
            model,
            config,
            policy,
            spec,
        })
    }

    /// What is run.
    pub fn spec(&self) -> &PolicySpec {
        &self.spec
    }

    /// Runs the episodes on backend `B`, labelled `label`, with a fresh copy of the policy.
    pub fn run_side<B: Backend>(&self, label: &str) -> Result<PolicySide, CompareError> {
        let mut env = build_env::<B>(label, self.model.clone(), self.config.clone())?;
        let mut policy = self.policy.clone();
        let mut first = None;
        let mut episodes = Vec::with_capacity(self.spec.episodes as usize);
        let mut foot_contacts = Vec::with_capacity(self.spec.episodes as usize);
        for k in 0..self.spec.episodes {
            let seed = (k == 0).then_some(self.spec.seed);
            let traj = run_episode(label, &mut env, seed, None, |env, action| {
                policy.act(&env.policy_input(), action);
                true
            })?;
            episodes.push(EpisodeOutcome::of(k + 1, &traj));
            foot_contacts.push(traj.foot_contacts());
            if first.is_none() {
                first = Some(traj);
            }
        }
        let first = first.ok_or(CompareError::Episodes { value: 0 })?;
        Ok(PolicySide {
            label: label.to_owned(),
            first,
            episodes,
            foot_contacts,
        })
    }

    /// Whether the open-loop replay means anything: not in the `delta` action mode, where the
    /// same actions give targets that depend on each engine's joint angles.
    pub fn replays(&self) -> bool {
        self.config.action.mode != ActionMode::Delta
    }

    /// Replays `source`'s first-episode actions open loop on backend `B`, labelled `label`:
    /// the same first reset, the same actions, no policy.
    pub fn replay<B: Backend>(
        &self,
        label: &str,
        source: &PolicySide,
    ) -> Result<Trajectory, CompareError> {
        let mut env = build_env::<B>(label, self.model.clone(), self.config.clone())?;
        run_script(label, &mut env, self.spec.seed, None, &source.first.actions)
    }

    /// The report of `sides` (each ran this plan) and of the replays of the first side's
    /// actions (`replays[k]` on the engine of `sides[k]`; empty when not replayed).
    pub fn report(&self, sides: &[PolicySide], replays: &[Trajectory]) -> PolicyReport {
        let seed = self.spec.seed;
        let pairs = pairs_of(sides, seed);
        let replay = sides.first().filter(|_| !replays.is_empty()).map(|src| {
            let runs = replays
                .iter()
                .map(|r| {
                    let d = compare_trajectories(&src.first, r);
                    let outcome = EpisodeOutcome::of(1, r);
                    ReplayRun {
                        label: r.label.clone(),
                        steps: outcome.steps,
                        ret: outcome.ret,
                        end_reasons: outcome.end_reasons,
                        distance_walked_m: outcome.distance_walked_m,
                        travel_m: outcome.travel_m,
                        trunk_position: d.trunk_position,
                        joint_angles: d.joint_angles,
                    }
                })
                .collect();
            ReplayReport {
                source: src.label.clone(),
                actions: src.first.end_step,
                runs,
            }
        });
        let traces = sides
            .iter()
            .map(|s| Trace::of(&s.first))
            .chain(replays.iter().map(Trace::of))
            .collect();
        PolicyReport {
            robot: self.model.name().to_owned(),
            policy: self.spec.policy.clone(),
            seed: self.spec.seed,
            episodes: self.spec.episodes,
            max_steps: self.config.task.max_time_steps,
            env_dt_s: self.config.env_dt(),
            configuration: self.spec.configuration.clone(),
            drew_alike: drew_alike(
                sides
                    .iter()
                    .map(|s| s.episodes.iter().map(|e| e.randomize.as_ref())),
            ),
            sides: sides.iter().map(|s| side_report(s, seed)).collect(),
            pairs,
            replay,
            traces,
        }
    }
}

/// One engine's summary; every interval's resampling is seeded with `seed`.
fn side_report(s: &PolicySide, seed: u64) -> PolicySideReport {
    let e = &s.episodes;
    let mut ends: Vec<(String, u32)> = Vec::new();
    for o in e {
        let name = o
            .end_reasons
            .iter()
            .map(|r| r.as_str())
            .collect::<Vec<_>>()
            .join("+");
        let name = if name.is_empty() {
            "none".to_owned()
        } else {
            name
        };
        match ends.iter_mut().find(|(n, _)| *n == name) {
            Some((_, c)) => *c += 1,
            None => ends.push((name, 1)),
        }
    }
    ends.sort();
    PolicySideReport {
        label: s.label.clone(),
        engine: s.first.engine.to_owned(),
        distance_walked_m: Stats::of(&column(e, |o| o.distance_walked_m), seed),
        travel_m: Stats::of(&column(e, |o| o.travel_m), seed),
        final_distance_m: Stats::of(&column(e, |o| o.final_distance_m), seed),
        ret: Stats::of(&column(e, |o| o.ret), seed),
        steps: Stats::of(&column(e, |o| o.steps as f64), seed),
        rates: Rates::of(e.iter().map(|o| o.end_reasons.as_slice())),
        gait: GaitStats::of(&e.iter().map(|o| o.gait).collect::<Vec<_>>(), seed),
        velocity: VelocityStats::of(&e.iter().map(|o| o.velocity).collect::<Vec<_>>(), seed),
        ended_by: ends
            .into_iter()
            .map(|(reasons, episodes)| EndCount { reasons, episodes })
            .collect(),
        randomized: RandomizedSide::of(
            e.iter()
                .map(|o| (o.end_reasons.contains(&Reason::Fell), o.randomize.as_ref())),
        ),
        episodes: e.clone(),
    }
}

/// Every pair of `sides`; the ratios' resampling is seeded with `seed`.
fn pairs_of(sides: &[PolicySide], seed: u64) -> Vec<PolicyPair> {
    let mut pairs = Vec::new();
    for i in 0..sides.len() {
        for j in i + 1..sides.len() {
            let (a, b) = (&sides[i], &sides[j]);
            let d = compare_trajectories(&a.first, &b.first);
            let apart = |m: f64| {
                d.series[0]
                    .iter()
                    .position(|e| *e >= m || e.is_nan())
                    .map(|t| t as f64 * a.first.env_dt)
            };
            let (ca, cb) = (columns(&a.episodes), columns(&b.episodes));
            let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len().max(1) as f64;
            pairs.push(PolicyPair {
                labels: [a.label.clone(), b.label.clone()],
                samples: d.samples,
                trunk_position: d.trunk_position,
                trunk_orientation: d.trunk_orientation,
                joint_angles: d.joint_angles,
                apart_1cm_s: apart(APART_M[0]),
                apart_10cm_s: apart(APART_M[1]),
                distance_walked_gap_m: mean(&cb.distance_walked_m) - mean(&ca.distance_walked_m),
                travel_gap_m: mean(&cb.travel_m) - mean(&ca.travel_m),
                return_gap: mean(&cb.ret) - mean(&ca.ret),
                ratios: PairRatios::of(&ca, &cb, seed),
                contact_agreement: contact_agreement(a, b, seed),
                divergence_m: d.series[0].clone(),
            });
        }
    }
    pairs
}

/// The foot-contact pattern agreement of `a`'s and `b`'s episodes, episode by episode.
fn contact_agreement(a: &PolicySide, b: &PolicySide, seed: u64) -> Option<Figure> {
    if a.first.num_feet != b.first.num_feet {
        return None;
    }
    let shares = a
        .foot_contacts
        .iter()
        .zip(&b.foot_contacts)
        .map(|(x, y)| gait::contact_agreement(a.first.num_feet, x, y));
    Figure::of(shares, seed)
}

/// One figure of every episode, in order.
fn column(episodes: &[EpisodeOutcome], f: impl Fn(&EpisodeOutcome) -> f64) -> Vec<f64> {
    episodes.iter().map(f).collect()
}

/// The figures a pair's ratios compare, a column each.
fn columns(episodes: &[EpisodeOutcome]) -> Columns {
    Columns {
        travel_m: column(episodes, |o| o.travel_m),
        distance_walked_m: column(episodes, |o| o.distance_walked_m),
        ret: column(episodes, |o| o.ret),
        steps: column(episodes, |o| o.steps as f64),
    }
}

/// How many episodes ended for a set of reasons.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct EndCount {
    /// The reasons, joined with `+` (`timeout`, `fell`, `fell+joint_limit`).
    pub reasons: String,
    /// Episodes.
    pub episodes: u32,
}

/// One engine's episodes, summarised.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PolicySideReport {
    /// The label.
    pub label: String,
    /// The engine (`Backend::NAME`).
    pub engine: String,
    /// K − D^T (m).
    pub distance_walked_m: Stats,
    /// Trunk travel along the start-to-goal direction (m).
    pub travel_m: Stats,
    /// D^T (m).
    pub final_distance_m: Stats,
    /// The return.
    #[serde(rename = "return")]
    pub ret: Stats,
    /// Steps per episode.
    pub steps: Stats,
    /// How often the episodes ended for each reason, with Wilson intervals (absent for no
    /// episodes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub rates: Option<Rates>,
    /// The gait diagnostics over the episodes (see [`crate::gait`]).
    pub gait: GaitStats,
    /// Under `task.kind = "velocity"`, the task's figures over the episodes (see
    /// [`crate::velocity`]; else not written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub velocity: Option<VelocityStats>,
    /// How the episodes ended.
    pub ended_by: Vec<EndCount>,
    /// With `[randomize]` on, the falls and pushes (else not written).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub randomized: Option<RandomizedSide>,
    /// Every episode.
    pub episodes: Vec<EpisodeOutcome>,
}

/// Two engines' first episodes over time, and the gap between their episode means.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PolicyPair {
    /// The two labels.
    pub labels: [String; 2],
    /// Samples both first episodes lived through (reset + steps).
    pub samples: usize,
    /// Trunk position divergence (m).
    pub trunk_position: Divergence,
    /// Trunk orientation divergence (rad).
    pub trunk_orientation: Divergence,
    /// Worst joint's angle divergence (rad).
    pub joint_angles: Divergence,
    /// When the two trunks were first 1 cm apart (s); absent if never.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub apart_1cm_s: Option<f64>,
    /// When they were first 10 cm apart (s); absent if never.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub apart_10cm_s: Option<f64>,
    /// Mean K − D^T of the second minus the first (m).
    pub distance_walked_gap_m: f64,
    /// Mean travel of the second minus the first (m).
    pub travel_gap_m: f64,
    /// Mean return of the second minus the first.
    pub return_gap: f64,
    /// The second's means over the first's, with their intervals.
    pub ratios: PairRatios,
    /// The share of steps on which all feet's contact flags agree, episode k of one engine
    /// against episode k of the other (the same reset), over the episodes; absent if no
    /// episode pair shares a step.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_agreement: Option<Figure>,
    /// e_p(t) of the first episodes, per sample (m).
    #[serde(skip)]
    pub divergence_m: Vec<f64>,
}

/// The first engine's first-episode actions replayed open loop on every engine.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReplayReport {
    /// The engine whose closed-loop actions are replayed.
    pub source: String,
    /// Actions replayed (the source episode's steps).
    pub actions: u64,
    /// Per engine, the first one (the source itself) included.
    pub runs: Vec<ReplayRun>,
}

/// One engine under the replayed actions.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ReplayRun {
    /// The engine's label.
    pub label: String,
    /// Steps taken (fewer than the actions if the episode ended first).
    pub steps: u64,
    /// The return.
    #[serde(rename = "return")]
    pub ret: f64,
    /// How it ended.
    pub end_reasons: Vec<Reason>,
    /// K − D^T (m).
    pub distance_walked_m: f64,
    /// Trunk travel along the start-to-goal direction (m).
    pub travel_m: f64,
    /// Trunk position against the source's closed-loop first episode (m).
    pub trunk_position: Divergence,
    /// Worst joint's angle against it (rad).
    pub joint_angles: Divergence,
}

/// A first episode's trunk position over time, thinned to at most
/// [`crate::SERIES_POINTS`] + 1 points in the JSON file.
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct Trace {
    /// The run's label.
    pub label: String,
    /// Time (s).
    pub time_s: Vec<f64>,
    /// Trunk x, y, z (m).
    pub position_m: Vec<[f64; 3]>,
}

impl Trace {
    fn of(t: &Trajectory) -> Self {
        Self {
            label: t.label.clone(),
            time_s: (0..t.len()).map(|k| k as f64 * t.env_dt).collect(),
            position_m: t.positions.clone(),
        }
    }

    fn thinned(&self) -> Self {
        let idx = thin(self.time_s.len());
        Self {
            label: self.label.clone(),
            time_s: idx.iter().map(|&i| self.time_s[i]).collect(),
            position_m: idx.iter().map(|&i| self.position_m[i]).collect(),
        }
    }
}

/// A policy comparison (see the module docs).
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct PolicyReport {
    /// The robot's name.
    pub robot: String,
    /// The policy as named.
    pub policy: String,
    /// The first reset's seed.
    pub seed: u64,
    /// Episodes per engine.
    pub episodes: u32,
    /// t_max (env steps).
    pub max_steps: u64,
    /// Δt_env (s).
    pub env_dt_s: f64,
    /// The configuration as applied (`key=value (source)`).
    pub configuration: Vec<String>,
    /// With `[randomize]` on, whether every engine drew the same values in each episode (they
    /// must: the draws depend on the seed alone); not written when it is off.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub drew_alike: Option<bool>,
    /// Per engine.
    pub sides: Vec<PolicySideReport>,
    /// Per pair of engines, in the order (1, 2), (1, 3), (2, 3).
    pub pairs: Vec<PolicyPair>,
    /// The open-loop replay; absent when not run (the `delta` action mode).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub replay: Option<ReplayReport>,
    /// The first episodes' trunk positions: every engine closed loop, then every replay.
    pub traces: Vec<Trace>,
}

impl PolicyReport {
    /// The report as pretty JSON, its traces thinned.
    pub fn to_json(&self) -> String {
        let mut thinned = self.clone();
        thinned.traces = self.traces.iter().map(Trace::thinned).collect();
        match serde_json::to_string_pretty(&thinned) {
            Ok(s) => s,
            // Numbers, strings, bools and lists of those; a non-finite number becomes null.
            Err(e) => unreachable!("a policy report serialises to JSON: {e}"),
        }
    }

    /// Writes `report.json`, `report.md` and `trunk_x_z.png` into `dir` (created if missing);
    /// returns the three paths.
    pub fn write(
        &self,
        dir: impl AsRef<Path>,
        command: &str,
    ) -> Result<[PathBuf; 3], CompareError> {
        let dir = dir.as_ref();
        prepare_output_dir(dir)?;
        write_report_files(dir, self.to_json(), self.to_markdown(command), |png| {
            plot_policy(self, png)
        })
    }

    /// The Markdown report; `command` is the command line that produced it: the run's
    /// description, the per-engine table, the pairs, the open-loop replay, every episode and
    /// the plot.
    pub fn to_markdown(&self, command: &str) -> String {
        let mut m = String::new();
        self.markdown_header(&mut m, command);
        self.markdown_per_engine(&mut m);
        self.markdown_velocity(&mut m);
        self.markdown_gait(&mut m);
        self.markdown_randomized(&mut m);
        self.markdown_pairs(&mut m);
        self.markdown_replay(&mut m);
        self.markdown_episodes(&mut m);
        // Writing into a String cannot fail.
        let _ = writeln!(
            m,
            "\n## Plot\n\n![first episode: trunk x per engine, closed loop and replayed; trunk position divergence per pair]({PLOT_FILE})"
        );
        m
    }

    /// The title, the robot, the command, how the episodes ran, the configuration and why the
    /// report is not judged.
    fn markdown_header(&self, w: &mut String, command: &str) {
        let labels: Vec<&str> = self.sides.iter().map(|s| s.label.as_str()).collect();
        // Writing into a String cannot fail.
        let _ = writeln!(
            w,
            "# Policy comparison: {}, policy `{}`\n",
            labels.join(" vs "),
            self.policy
        );
        let _ = writeln!(w, "Robot: `{}`.\n", self.robot);
        let _ = writeln!(w, "```\n{command}\n```\n");
        let _ = writeln!(
            w,
            "Closed loop: on each engine the policy acts on that engine's own observations. {} episode(s) per engine, the first reset seeded with {} and the later ones continuing its streams (as `hyq run --episodes {} --seed {}`), at most {} env steps of {} s each.\n",
            self.episodes, self.seed, self.episodes, self.seed, self.max_steps, self.env_dt_s
        );
        if !self.configuration.is_empty() {
            let _ = writeln!(w, "Configuration on every engine:\n");
            for c in &self.configuration {
                let _ = writeln!(w, "- `{c}`");
            }
            let _ = writeln!(w);
        }
        let _ = writeln!(
            w,
            "**Not judged against the ledger.** Closed-loop runs part by nature (every difference changes the next observation and so the next action), so no tolerance fits them: this report states the gap, it does not pass or fail. The ledger judges identical action scripts (`--scenario`).\n"
        );
    }

    /// Each engine's episode statistics, a column per engine.
    fn markdown_per_engine(&self, w: &mut String) {
        let labels: Vec<&str> = self.sides.iter().map(|s| s.label.as_str()).collect();
        // Writing into a String cannot fail.
        let _ = writeln!(w, "## Per engine ({} episodes each)\n", self.episodes);
        let _ = writeln!(w, "| | {} |", labels.join(" | "));
        let _ = writeln!(w, "|---|{}", "---|".repeat(labels.len()));
        let mut row = |name: &str, f: &dyn Fn(&PolicySideReport) -> String| {
            let cells: Vec<String> = self.sides.iter().map(f).collect();
            let _ = writeln!(w, "| {name} | {} |", cells.join(" | "));
        };
        row("trunk travel toward the goal (m): mean [95 % CI]", &|s| {
            s.travel_m.text(3)
        });
        row("K − D^T (m): mean [95 % CI]", &|s| {
            s.distance_walked_m.text(3)
        });
        row("D^T (m): mean [95 % CI]", &|s| s.final_distance_m.text(3));
        row("return: mean [95 % CI]", &|s| s.ret.text(3));
        row("episode length (steps): mean [95 % CI]", &|s| {
            s.steps.text(1)
        });
        let spread = |s: &Stats| format!("{:.3} [{:.3}, {:.3}]", s.sd, s.min, s.max);
        row("trunk travel (m): sd [min, max]", &|s| spread(&s.travel_m));
        row("K − D^T (m): sd [min, max]", &|s| {
            spread(&s.distance_walked_m)
        });
        for k in 0..5 {
            let name = self
                .sides
                .iter()
                .find_map(|s| s.rates.map(|r| r.named()[k].0))
                .unwrap_or("");
            row(name, &|s| {
                s.rates
                    .map_or_else(|| "—".to_owned(), |r| rate_text(r.named()[k].1))
            });
        }
        row("ended by", &|s| {
            s.ended_by
                .iter()
                .map(|e| format!("{} {}", e.reasons, e.episodes))
                .collect::<Vec<_>>()
                .join(", ")
        });
        let _ = writeln!(
            w,
            "\nIntervals: a mean's is the percentile bootstrap of the episodes (10,000 resamples seeded with {}), a rate's (k of n episodes) is Wilson's; both 95 %. An episode can end for several reasons at once.",
            self.seed
        );
    }

    /// Under the velocity task, each engine's tracking errors, its commanded stands' feet
    /// speed and drift, and its falls; nothing under the spec's task.
    fn markdown_velocity(&self, w: &mut String) {
        if self.sides.iter().all(|s| s.velocity.is_none()) {
            return;
        }
        let labels: Vec<&str> = self.sides.iter().map(|s| s.label.as_str()).collect();
        // Writing into a String cannot fail.
        let _ = writeln!(w, "\n## Velocity task\n");
        let _ = writeln!(w, "| | {} |", labels.join(" | "));
        let _ = writeln!(w, "|---|{}", "---|".repeat(labels.len()));
        let mut row = |name: &str, f: fn(&VelocityStats) -> Option<Figure>, dp: usize| {
            let cells: Vec<String> = self
                .sides
                .iter()
                .map(|s| figure_text(s.velocity.and_then(|v| f(&v)), 1.0, dp, self.episodes))
                .collect();
            let _ = writeln!(w, "| {name} | {} |", cells.join(" | "));
        };
        row(
            "forward-speed error, mean abs(c_x − v_x) (m/s)",
            |v| v.forward_error_mps,
            3,
        );
        row(
            "yaw-rate error, mean abs(c_yaw − ω_z) (rad/s)",
            |v| v.yaw_error_radps,
            3,
        );
        row(
            "zero command: feet's mean speed (m/s)",
            |v| v.standing_feet_speed_mps,
            3,
        );
        row("zero command: trunk drift (m)", |v| v.standing_drift_m, 3);
        let fell: Vec<String> = self
            .sides
            .iter()
            .map(|s| {
                s.rates
                    .map_or_else(|| "—".to_owned(), |r| rate_text(&r.fell))
            })
            .collect();
        let _ = writeln!(w, "| fell | {} |", fell.join(" | "));
        let _ = writeln!(
            w,
            "\nEach error: per episode, the mean over its steps of the gap between the command the step was judged by and the trunk's velocity in its own frame after the step; then the mean over the episodes with its 95 % bootstrap interval (seeded with {}). Zero command: only the episodes whose command was zero on every step (k of n when not all); the feet's speed is their collision spheres' centres' travel per step over Δt_env, averaged over feet and steps; the drift is the trunk's horizontal distance from its start to its end. Fell: k of n episodes with Wilson's 95 % interval.",
            self.seed
        );
    }

    /// Each engine's gait diagnostics, and each pair's foot-contact pattern agreement.
    fn markdown_gait(&self, w: &mut String) {
        let labels: Vec<&str> = self.sides.iter().map(|s| s.label.as_str()).collect();
        // Writing into a String cannot fail.
        let _ = writeln!(w, "\n## Gait\n");
        let _ = writeln!(w, "| | {} |", labels.join(" | "));
        let _ = writeln!(w, "|---|{}", "---|".repeat(labels.len()));
        let mut row = |name: &str, f: fn(&GaitStats) -> Option<Figure>, scale: f64, dp: usize| {
            let cells: Vec<String> = self
                .sides
                .iter()
                .map(|s| figure_text(f(&s.gait), scale, dp, self.episodes))
                .collect();
            let _ = writeln!(w, "| {name} | {} |", cells.join(" | "));
        };
        row("foot slip per stance step (mm)", |g| g.foot_slip_mm, 1.0, 2);
        row(
            "actions at their bounds (%)",
            |g| g.actions_at_bounds,
            100.0,
            1,
        );
        row(
            "action change per step, mean abs(a_t − a_t−1)",
            |g| g.action_change,
            1.0,
            4,
        );
        row("stance duration (s)", |g| g.stance_s, 1.0, 3);
        let _ = writeln!(
            w,
            "\nEach: the mean over the episodes of each episode's figure, with its 95 % bootstrap interval (seeded with {}); (k of n): only k episodes had the figure. Foot slip: the horizontal travel of a foot sphere's centre over an env step on which the foot touched the ground on that step and the one before. Actions at their bounds: the share of action components (every joint, every step) at or beyond the action space's ends. Stance duration: complete stance phases only (a swing before and after inside the episode).\n",
            self.seed
        );
        let _ = writeln!(
            w,
            "| pair | foot-contact pattern agreement (% of steps) |\n|---|---|"
        );
        for p in &self.pairs {
            let _ = writeln!(
                w,
                "| {} vs {} | {} |",
                p.labels[0],
                p.labels[1],
                figure_text(p.contact_agreement, 100.0, 1, self.episodes)
            );
        }
        let _ = writeln!(
            w,
            "\nAgreement: the share of the steps both engines' episode k lived through (the same reset) on which every foot's contact flag is the same on both, over the episodes."
        );
    }

    /// With `[randomize]` on: whether every engine drew alike, and each engine's falls and
    /// pushes; nothing when it is off.
    fn markdown_randomized(&self, w: &mut String) {
        let Some(alike) = self.drew_alike else {
            return;
        };
        // Writing into a String cannot fail.
        let _ = writeln!(w, "\n## Randomisation\n");
        let _ = writeln!(w, "{}\n", crate::randomized::line(alike, "every engine"));
        let labels: Vec<&str> = self.sides.iter().map(|s| s.label.as_str()).collect();
        let _ = writeln!(w, "| | {} |", labels.join(" | "));
        let _ = writeln!(w, "|---|{}", "---|".repeat(labels.len()));
        let cell = |s: &PolicySideReport, f: &dyn Fn(&RandomizedSide) -> String| {
            s.randomized.as_ref().map_or_else(|| "—".to_owned(), f)
        };
        let fell: Vec<String> = self
            .sides
            .iter()
            .map(|s| cell(s, &|r| r.fell_text(s.episodes.len())))
            .collect();
        let _ = writeln!(
            w,
            "| fell (episodes ending with `fell`) | {} |",
            fell.join(" | ")
        );
        let pushes: Vec<String> = self
            .sides
            .iter()
            .map(|s| {
                cell(s, &|r| {
                    format!("{:.2} [{}, {}]", r.pushes_mean, r.pushes_min, r.pushes_max)
                })
            })
            .collect();
        let _ = writeln!(
            w,
            "| pushes per episode, mean [min, max] | {} |",
            pushes.join(" | ")
        );
    }

    /// Each pair's divergence over the first episodes and the gaps between their means.
    fn markdown_pairs(&self, w: &mut String) {
        // Writing into a String cannot fail.
        let _ = writeln!(w, "\n## Per pair\n");
        let _ = writeln!(
            w,
            "The first episodes over time (same first reset on both engines), and the gap between the engines' episode means (second minus first).\n"
        );
        let _ = writeln!(
            w,
            "| pair | trunk position RMS / max | orientation RMS / max | worst joint RMS / max | 1 cm apart at | 10 cm apart at | K − D^T gap | travel gap | return gap |\n|---|---|---|---|---|---|---|---|---|"
        );
        let when = |t: Option<f64>| t.map_or("never".to_owned(), |t| format!("{t:.2} s"));
        for p in &self.pairs {
            let _ = writeln!(
                w,
                "| {} vs {} | {} / {} m | {} / {} rad | {} / {} rad | {} | {} | {:+.3} m | {:+.3} m | {:+.3} |",
                p.labels[0],
                p.labels[1],
                sig(p.trunk_position.rms),
                sig(p.trunk_position.max),
                sig(p.trunk_orientation.rms),
                sig(p.trunk_orientation.max),
                sig(p.joint_angles.rms),
                sig(p.joint_angles.max),
                when(p.apart_1cm_s),
                when(p.apart_10cm_s),
                p.distance_walked_gap_m,
                p.travel_gap_m,
                p.return_gap
            );
        }
        self.markdown_ratios(w);
    }

    /// Each pair's ratio of means with its interval.
    fn markdown_ratios(&self, w: &mut String) {
        // Writing into a String cannot fail.
        let _ = writeln!(
            w,
            "\nThe ratio of the engines' episode means (second over first) with its 95 % interval (paired bootstrap: episode k started from the same reset on both engines). ≠ 1: the interval excludes 1, the two engines' means differ at the 95 % level. —: no ratio (the first engine's resampled means reach 0 or change sign).\n"
        );
        let _ = writeln!(
            w,
            "| pair | trunk travel | K − D^T | return | episode length |\n|---|---|---|---|---|"
        );
        for p in &self.pairs {
            let r = &p.ratios;
            let _ = writeln!(
                w,
                "| {} / {} | {} | {} | {} | {} |",
                p.labels[1],
                p.labels[0],
                ratio_text(r.travel_m.as_ref()),
                ratio_text(r.distance_walked_m.as_ref()),
                ratio_text(r.ret.as_ref()),
                ratio_text(r.steps.as_ref())
            );
        }
    }

    /// The first engine's first-episode actions replayed open loop on every engine.
    fn markdown_replay(&self, w: &mut String) {
        // Writing into a String cannot fail.
        let _ = writeln!(
            w,
            "\n## Open loop: {} actions replayed\n",
            self.replay_title()
        );
        match &self.replay {
            None => {
                let _ = writeln!(
                    w,
                    "Not run: in the `delta` action mode the same actions give targets that depend on each engine's joint angles."
                );
            }
            Some(r) => {
                let _ = writeln!(
                    w,
                    "{}'s first episode ({} actions) fed unchanged to every engine from the same first reset, no policy in the loop: what each engine's physics does with the very same actions. The replay on {} itself must match its closed-loop run exactly (a check of the replay).\n",
                    r.source, r.actions, r.source
                );
                let _ = writeln!(
                    w,
                    "| engine | steps | ended by | K − D^T | trunk travel | return | trunk position vs {}'s closed loop, RMS / max | worst joint, RMS / max |\n|---|---|---|---|---|---|---|---|",
                    r.source
                );
                for run in &r.runs {
                    let _ = writeln!(
                        w,
                        "| {} | {} | {} | {:.3} m | {:.3} m | {:.3} | {} / {} m | {} / {} rad |",
                        run.label,
                        run.steps,
                        reasons(&run.end_reasons),
                        run.distance_walked_m,
                        run.travel_m,
                        run.ret,
                        sig(run.trunk_position.rms),
                        sig(run.trunk_position.max),
                        sig(run.joint_angles.rms),
                        sig(run.joint_angles.max)
                    );
                }
            }
        }
    }

    /// Every episode of every engine.
    fn markdown_episodes(&self, w: &mut String) {
        // Writing into a String cannot fail.
        let _ = writeln!(w, "\n## Episodes\n");
        let _ = writeln!(
            w,
            "| engine | episode | steps | return | K − D^T | trunk travel | D^T | ended by |\n|---|---|---|---|---|---|---|---|"
        );
        for s in &self.sides {
            for e in &s.episodes {
                let _ = writeln!(
                    w,
                    "| {} | {} | {} | {:.3} | {:.3} m | {:.3} m | {:.3} m | {} |",
                    s.label,
                    e.episode,
                    e.steps,
                    e.ret,
                    e.distance_walked_m,
                    e.travel_m,
                    e.final_distance_m,
                    reasons(&e.end_reasons)
                );
            }
        }
    }

    fn replay_title(&self) -> String {
        match &self.replay {
            Some(r) => format!("{}'s", r.source),
            None => "the first engine's".to_owned(),
        }
    }
}

/// "2.31 [2.10, 2.52]" (the figure times `scale`, `dp` places), with "(k of n)" when only k of
/// the `episodes` had it; a dash when none did.
fn figure_text(f: Option<Figure>, scale: f64, dp: usize, episodes: u32) -> String {
    let Some(f) = f else {
        return "—".to_owned();
    };
    let scaled = Stats {
        mean: f.stats.mean * scale,
        ci95: f.stats.ci95.map(|c| c.map(|v| v * scale)),
        ..f.stats
    };
    let text = scaled.text(dp);
    if f.episodes == episodes as usize {
        text
    } else {
        format!("{text} ({} of {episodes})", f.episodes)
    }
}

fn reasons(r: &[Reason]) -> String {
    if r.is_empty() {
        "—".to_owned()
    } else {
        r.iter().map(|r| r.as_str()).collect::<Vec<_>>().join(" + ")
    }
}

/// "; stance 0.155 s, slip 3.86 mm": an engine's mean stance duration and foot slip per stance
/// step for the plot's legend, each left out when no episode had it.
fn gait_legend(g: &GaitStats) -> String {
    let mut text = String::new();
    // Writing into a String cannot fail.
    if let Some(f) = g.stance_s {
        let _ = write!(text, "; stance {:.3} s", f.stats.mean);
    }
    if let Some(f) = g.foot_slip_mm {
        let sep = if text.is_empty() { "; " } else { ", " };
        let _ = write!(text, "{sep}slip {:.2} mm", f.stats.mean);
    }
    text
}

/// Draws a policy comparison's plot into `path` (PNG, [`crate::PLOT_SIZE`]): every engine's
/// first-episode trunk x closed loop (its legend with the mean travel over all episodes and its
/// 95 % interval, and the mean stance duration and foot slip per stance step), the same under
/// the replayed actions, and every pair's trunk position divergence over the first episodes.
pub fn plot_policy(report: &PolicyReport, path: &Path) -> Result<(), CompareError> {
    let labels: Vec<&str> = report.sides.iter().map(|s| s.label.as_str()).collect();
    let title = format!(
        "{}: policy, closed loop, seed {}",
        labels.join(" vs "),
        report.seed
    );
    let xs: Vec<Vec<f64>> = report
        .traces
        .iter()
        .map(|t| t.position_m.iter().map(|p| p[0]).collect())
        .collect();
    // The closed-loop lines' legends carry each engine's mean travel over all its episodes
    // (not only the first, which the line shows) with its 95 % interval, and its gait.
    let legends: Vec<String> = report
        .traces
        .iter()
        .enumerate()
        .map(|(k, t)| match report.sides.get(k) {
            Some(s) => format!(
                "{}; travel, mean of {} episodes: {} m{}",
                t.label,
                s.episodes.len(),
                s.travel_m.text(2),
                gait_legend(&s.gait)
            ),
            None => t.label.clone(),
        })
        .collect();
    let lines: Vec<(&str, &[f64], &[f64])> = report
        .traces
        .iter()
        .zip(&xs)
        .zip(&legends)
        .map(|((t, x), l)| (l.as_str(), t.time_s.as_slice(), x.as_slice()))
        .collect();
    let (closed, replayed) = lines.split_at(report.sides.len().min(lines.len()));
    let source = report
        .replay
        .as_ref()
        .map_or(String::new(), |r| format!(" ({}'s actions)", r.source));
    let names: Vec<String> = report
        .pairs
        .iter()
        .map(|p| format!("{} vs {}", p.labels[0], p.labels[1]))
        .collect();
    let times: Vec<Vec<f64>> = report
        .pairs
        .iter()
        .map(|p| {
            (0..p.divergence_m.len())
                .map(|k| k as f64 * report.env_dt_s)
                .collect()
        })
        .collect();
    let d: Vec<(&str, &[f64], &[f64])> = names
        .iter()
        .zip(&times)
        .zip(&report.pairs)
        .map(|((n, t), p)| (n.as_str(), t.as_slice(), p.divergence_m.as_slice()))
        .collect();
    let open_loop = format!("trunk x, open loop{source}");
    plot_panels(
        path,
        &title,
        [
            Panel::new(
                "trunk x, closed loop (first episode)",
                "x (m)",
                closed,
                &COLOURS,
            ),
            Panel::new(&open_loop, "x (m)", replayed, &COLOURS),
            Panel::new(
                "trunk position divergence per pair, closed loop",
                "m",
                &d,
                &PAIR_COLOURS,
            ),
        ],
    )
}

#[cfg(test)]
mod tests {
    use super::{gait_legend, travel};
    use crate::estimates::Stats;
    use crate::gait::{Figure, GaitStats};

    #[test]
    fn the_legend_gives_the_gait_an_engine_has() {
        let f = |mean: f64| {
            Some(Figure {
                stats: Stats {
                    mean,
                    ..Stats::default()
                },
                episodes: 1,
            })
        };
        let both = GaitStats {
            stance_s: f(0.155),
            foot_slip_mm: f(3.856),
            ..GaitStats::default()
        };
        assert_eq!(gait_legend(&both), "; stance 0.155 s, slip 3.86 mm");
        let slip = GaitStats {
            foot_slip_mm: f(1.0),
            ..GaitStats::default()
        };
        assert_eq!(gait_legend(&slip), "; slip 1.00 mm");
        assert_eq!(gait_legend(&GaitStats::default()), "");
    }

    #[test]
    fn travel_is_the_displacement_along_the_start_to_goal_direction() {
        // Goal 5 m along +x: a step of (3, 4) counts 3 m, a step past the goal keeps counting.
        assert_eq!(travel([0.0; 3], [3.0, 4.0, 0.2], [5.0, 0.0, 0.5]), 3.0);
        assert_eq!(
            travel([1.0, 1.0, 0.0], [8.0, 1.0, 0.0], [6.0, 1.0, 0.0]),
            7.0
        );
        // Backwards is negative; a goal straight above the start gives no direction.
        assert_eq!(travel([0.0; 3], [0.0, -2.0, 0.0], [0.0, 4.0, 0.0]), -2.0);
        assert_eq!(travel([0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]), 0.0);
    }
}
