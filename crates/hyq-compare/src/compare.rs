//! One comparison: the scenario's script on two backends, the measurements, the one-step
//! comparison from shared states, and the ledger's verdict on each metric.

use std::sync::Arc;

use hyq_env::EnvConfig;
use hyq_physics::{Backend, RobotModel};

use crate::error::CompareError;
use crate::ledger::{Ledger, Metric};
use crate::metrics::{
    OneStepErrors, OneStepSummary, TrajectoryComparison, compare_trajectories, one_step_errors,
    sample_indices, summarise_one_step,
};
use crate::report::{Check, OneStepReport, Report, Series, SideReport};
use crate::run::{Trajectory, build_env, one_step, run_script, standing_height};
use crate::scenario::{Scenario, check_seconds};

/// The default number of shared states in the one-step comparison.
pub const DEFAULT_ONE_STEP_STATES: usize = 50;

/// What to compare: the scenario, its seed and length, the number of shared states, and
/// configuration overrides (dotted `KEY`, `VALUE` pairs as `EnvConfig::set_all` takes them).
#[derive(Clone, Debug, PartialEq)]
pub struct ComparisonSpec {
    /// The scenario.
    pub scenario: Scenario,
    /// The seed of both resets and of the random policy.
    pub seed: u64,
    /// Simulated seconds; `None` for the scenario's default.
    pub seconds: Option<f64>,
    /// Shared states sampled from the first backend's run for the one-step comparison.
    pub one_step_states: usize,
    /// Overrides applied to both sides, after the scenario's configuration.
    pub overrides: Vec<(String, String)>,
    /// Overrides applied to the second side only, after `overrides` (e.g. a perturbation).
    pub overrides_b: Vec<(String, String)>,
}

impl ComparisonSpec {
    /// The scenario with its defaults: seed 0, default length, 50 shared states, no overrides.
    pub fn new(scenario: Scenario) -> Self {
        Self {
            scenario,
            seed: 0,
            seconds: None,
            one_step_states: DEFAULT_ONE_STEP_STATES,
            overrides: Vec::new(),
            overrides_b: Vec::new(),
        }
    }

    /// The run length (s).
    pub fn seconds(&self) -> f64 {
        self.seconds.unwrap_or(self.scenario.default_seconds())
    }
}

/// A parsed `KEY=VALUE` override, as the CLI's `--set` takes it.
pub fn parse_override(item: &str) -> Result<(String, String), CompareError> {
    let (key, value) = item.split_once('=').ok_or_else(|| CompareError::Override {
        item: item.to_owned(),
        reason: "expected TABLE.KEY=VALUE, e.g. physics.ground_friction=0.8".into(),
    })?;
    if key.trim().is_empty() {
        return Err(CompareError::Override {
            item: item.to_owned(),
            reason: "the key before `=` is empty".into(),
        });
    }
    Ok((key.trim().to_owned(), value.trim().to_owned()))
}

/// Override pairs as the command line writes them (`KEY=VALUE`).
fn written(pairs: &[(String, String)]) -> impl Iterator<Item = String> + '_ {
    pairs.iter().map(|(k, v)| format!("{k}={v}"))
}

fn apply(config: &mut EnvConfig, overrides: &[(String, String)]) -> Result<(), CompareError> {
    if overrides.is_empty() {
        return Ok(());
    }
    let pairs: Vec<(&str, &str)> = overrides
        .iter()
        .map(|(k, v)| (k.as_str(), v.as_str()))
        .collect();
    config.set_all(&pairs).map_err(|e| CompareError::Override {
        item: written(overrides).collect::<Vec<_>>().join(" "),
        reason: e.to_string(),
    })
}

/// The configuration of one side: the scenario's, then the shared overrides, then the side's.
/// The script's length stays the scenario's even if an override changes `max_time_steps`.
fn side_config(
    spec: &ComparisonSpec,
    base: &EnvConfig,
    own: &[(String, String)],
) -> Result<EnvConfig, CompareError> {
    let mut config = base.clone();
    apply(&mut config, &spec.overrides)?;
    apply(&mut config, own)?;
    Ok(config)
}

/// FNV-1a (64 bit) of the script's bits: a short fingerprint saying which actions were fed.
fn fingerprint(script: &[f64]) -> String {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for v in script {
        for byte in v.to_bits().to_le_bytes() {
            h ^= u64::from(byte);
            h = h.wrapping_mul(0x0000_0100_0000_01b3);
        }
    }
    format!("{h:016x}")
}

/// A comparison made ready to run: the scenario's configuration and the action script every
/// side receives, for one robot.
pub struct Plan {
    model: Arc<RobotModel>,
    spec: ComparisonSpec,
    seconds: f64,
    steps: u64,
    base: EnvConfig,
    script: Vec<f64>,
    start: Option<hyq_physics::RobotState>,
}

impl Plan {
    /// Checks `spec` for `model` and builds the scenario's configuration and action script.
    pub fn new(model: Arc<RobotModel>, spec: &ComparisonSpec) -> Result<Self, CompareError> {
        let seconds = spec.seconds();
        check_seconds(seconds)?;
        if !(1..=1000).contains(&spec.one_step_states) {
            return Err(CompareError::OneStepStates {
                value: spec.one_step_states,
            });
        }
        let scenario = spec.scenario;
        let base = scenario.config(&model, seconds)?;
        let config_a = side_config(spec, &base, &[])?;
        let config_b = side_config(spec, &base, &spec.overrides_b)?;
        let steps = base.task.max_time_steps;
        // The episode length is the script's: an override of t_max would leave a side without
        // actions (longer) or cut the comparison short on one side only (shorter).
        for config in [&config_a, &config_b] {
            if config.task.max_time_steps != steps {
                return Err(CompareError::Override {
                    item: format!("task.max_time_steps={}", config.task.max_time_steps),
                    reason:
                        "the episode length comes from the run length (seconds), not an override"
                            .into(),
                });
            }
        }
        // The script is built from the first side's action space; the second side must read
        // actions the same way or "the same actions" would mean different targets.
        if config_a.action != config_b.action {
            return Err(CompareError::Override {
                item: "action.*".into(),
                reason: "the two sides must share the action configuration".into(),
            });
        }
        let script = scenario.actions(&model, &config_a, spec.seed, steps)?;
        let start = scenario.initial_state(&model);
        Ok(Self {
            model,
            spec: spec.clone(),
            seconds,
            steps,
            base,
            script,
            start,
        })
    }

    /// Runs the two sides, `A` with the shared overrides and `B` with `--set-b`'s too,
    /// labelled `labels`, and compares them against `ledger` ([`compare`] on a plan already
    /// checked).
    pub fn compare_two<A: Backend, B: Backend>(
        &self,
        labels: [&str; 2],
        ledger: &Ledger,
    ) -> Result<Report, CompareError> {
        let mut a = self.run_side::<A>(labels[0], &[])?;
        let mut b = self.run_side::<B>(labels[1], &self.spec.overrides_b)?;
        self.pair(&mut a, &mut b, ledger)
    }

    /// The robot.
    pub fn model(&self) -> &Arc<RobotModel> {
        &self.model
    }

    /// What is compared.
    pub fn spec(&self) -> &ComparisonSpec {
        &self.spec
    }

    /// Runs one side on backend `B`, labelled `label`, with the side's own overrides `own`
    /// (after the shared ones): the script's episode and the standing height. The side keeps
    /// its environment for the one-step comparison ([`Plan::pair`]).
    pub fn run_side<B: Backend>(
        &self,
        label: &str,
        own: &[(String, String)],
    ) -> Result<Side, CompareError> {
        let config = side_config(&self.spec, &self.base, own)?;
        let mut env = build_env::<B>(label, self.model.clone(), config)?;
        let traj = run_script(
            label,
            &mut env,
            self.spec.seed,
            self.start.as_ref(),
            &self.script,
        )?;
        // Standing height under the side's physics (the default task and control, with the
        // side's overrides).
        let stand = side_config(&self.spec, &EnvConfig::default(), own)?;
        let height = standing_height::<B>(label, self.model.clone(), stand)?;
        Ok(Side {
            traj,
            height,
            own: own.to_vec(),
            env: Box::new(env),
        })
    }

    /// Compares two sides that ran this plan: the trajectories, the one-step comparison (the
    /// shared states sampled from `a`'s run) and every metric against `ledger`.
    pub fn pair(
        &self,
        a: &mut Side,
        b: &mut Side,
        ledger: &Ledger,
    ) -> Result<Report, CompareError> {
        let spec = &self.spec;
        let scenario = spec.scenario;
        let errors = one_step_comparison(a, b, spec.one_step_states)?;
        let one_step_summary = summarise_one_step(&errors);
        let (traj_a, traj_b) = (&a.traj, &b.traj);

        let trajectory = compare_trajectories(traj_a, traj_b);
        let sides = [
            side_report(traj_a, a.height, &spec.overrides, &a.own),
            side_report(traj_b, b.height, &spec.overrides, &b.own),
        ];
        let values = metric_values(
            traj_a,
            traj_b,
            &trajectory,
            &one_step_summary,
            [a.height, b.height],
        );
        let env_dt = self.base.env_dt();
        let series = Series::from_runs(traj_a, traj_b).with_divergences(&trajectory, env_dt);
        let engines = [traj_a.engine, traj_b.engine];
        let robot = self.model.name();
        // The ledger's entries for the ground both sides share (`--set terrain.kind=...`).
        let terrain = side_config(spec, &self.base, &[])?.terrain.kind.as_str();
        let checks: Vec<Check> = values
            .iter()
            .map(|(metric, value)| {
                let (tolerance, source) =
                    ledger.tolerance_on(robot, engines, scenario, terrain, *metric);
                Check {
                    metric: *metric,
                    value: *value,
                    tolerance,
                    // A NaN never passes.
                    within: *value <= tolerance,
                    source,
                }
            })
            .collect();
        Ok(Report {
            robot: robot.to_owned(),
            scenario,
            description: scenario.description(&self.model),
            seed: spec.seed,
            seconds: self.seconds,
            env_dt_s: env_dt,
            script_steps: self.steps,
            script_fingerprint: fingerprint(&self.script),
            overrides: written(&spec.overrides).collect(),
            overrides_b: written(&b.own).collect(),
            engines: [engines[0].to_owned(), engines[1].to_owned()],
            ledger: ledger.origin.clone(),
            sides,
            trajectory,
            one_step: OneStepReport {
                states: errors.len(),
                states_in_contact: errors.iter().filter(|e| e.in_contact).count(),
                sub_steps: 1,
                summary: one_step_summary,
                per_state: errors,
            },
            flagged: checks.iter().filter(|c| !c.within).count(),
            checks,
            series,
        })
    }
}

/// The one-step comparison of two sides: `states` states sampled from `a`'s run, each with the
/// joint targets that followed it, stepped once on each side; the errors per state.
fn one_step_comparison(
    a: &mut Side,
    b: &mut Side,
    states: usize,
) -> Result<Vec<OneStepErrors>, CompareError> {
    let (traj_a, traj_b) = (&a.traj, &b.traj);
    let picked = sample_indices(traj_a, states);
    let shared: Vec<(u64, &hyq_physics::RobotState, &[f64])> = picked
        .iter()
        .map(|&t| (t as u64, &traj_a.states[t], traj_a.targets_after(t)))
        .collect();
    let after_a = a.env.one_step(&traj_a.label, &shared)?;
    let after_b = b.env.one_step(&traj_b.label, &shared)?;
    Ok(after_a
        .iter()
        .zip(&after_b)
        .map(|(x, y)| one_step_errors(x, y))
        .collect())
}

/// One side of a comparison after its run: the trajectory, the standing height, and the
/// environment kept for the one-step comparison.
pub struct Side {
    traj: Trajectory,
    height: f64,
    own: Vec<(String, String)>,
    env: Box<dyn OneStepper>,
}

impl Side {
    /// What the side did.
    pub fn trajectory(&self) -> &Trajectory {
        &self.traj
    }

    /// Its standing height (m).
    pub fn standing_height(&self) -> f64 {
        self.height
    }

    /// The side's summary for a report (its own overrides after `shared`).
    pub fn report(&self, shared: &[(String, String)]) -> SideReport {
        side_report(&self.traj, self.height, shared, &self.own)
    }
}

/// An environment on some backend that takes one sub-step from shared states.
trait OneStepper {
    fn one_step(
        &mut self,
        label: &str,
        shared: &[(u64, &hyq_physics::RobotState, &[f64])],
    ) -> Result<Vec<crate::run::OneStepResult>, CompareError>;
}

impl<B: Backend> OneStepper for hyq_env::Env<B> {
    fn one_step(
        &mut self,
        label: &str,
        shared: &[(u64, &hyq_physics::RobotState, &[f64])],
    ) -> Result<Vec<crate::run::OneStepResult>, CompareError> {
        one_step(label, self, shared)
    }
}

/// Runs the comparison of backend `A` (labelled `labels[0]`) against backend `B`
/// (`labels[1]`), both on `model`, and checks every metric against `ledger`.
///
/// Both sides get the identical action script (see [`Scenario::actions`]). The one-step
/// comparison samples its shared states from `A`'s run.
pub fn compare<A: Backend, B: Backend>(
    model: Arc<RobotModel>,
    spec: &ComparisonSpec,
    labels: [&str; 2],
    ledger: &Ledger,
) -> Result<Report, CompareError> {
    Plan::new(model, spec)?.compare_two::<A, B>(labels, ledger)
}

fn side_report(
    traj: &Trajectory,
    standing_height_m: f64,
    shared: &[(String, String)],
    own: &[(String, String)],
) -> SideReport {
    let zs = traj.positions.iter().map(|p| p[2]);
    let mean_z = zs.clone().sum::<f64>() / traj.len().max(1) as f64;
    SideReport {
        label: traj.label.clone(),
        engine: traj.engine.to_owned(),
        end_reasons: traj.reasons.iter().collect(),
        end_step: traj.end_step,
        end_time_s: traj.end_step as f64 * traj.env_dt,
        sums: traj.sums,
        standing_height_m,
        mean_trunk_z_m: mean_z,
        final_position: traj.positions.last().copied().unwrap_or([f64::NAN; 3]),
        overrides: written(shared).chain(written(own)).collect(),
        randomize: traj.randomize.clone(),
    }
}

fn metric_values(
    a: &Trajectory,
    b: &Trajectory,
    t: &TrajectoryComparison,
    one: &[OneStepSummary],
    heights: [f64; 2],
) -> Vec<(Metric, f64)> {
    let one_max = |name: &str| {
        one.iter()
            .find(|s| s.quantity == name)
            .map_or(0.0, |s| s.max)
    };
    let worst_contact = t
        .contacts
        .iter()
        .map(|c| 100.0 - c.agreement_pct)
        .fold(0.0, f64::max);
    Metric::ALL
        .into_iter()
        .map(|m| {
            let v = match m {
                Metric::TerminationReasonMismatch => f64::from(u8::from(a.reasons != b.reasons)),
                Metric::TerminationStepDiff => a.end_step.abs_diff(b.end_step) as f64,
                Metric::TrunkPositionRms => t.trunk_position.rms,
                Metric::TrunkPositionMax => t.trunk_position.max,
                Metric::TrunkOrientationRms => t.trunk_orientation.rms,
                Metric::TrunkOrientationMax => t.trunk_orientation.max,
                Metric::JointAngleRms => t.joint_angles.rms,
                Metric::JointAngleMax => t.joint_angles.max,
                Metric::ContactDisagreementMax => worst_contact,
                Metric::ReturnDiff => (a.sums.ret - b.sums.ret).abs(),
                Metric::StandingHeightDiff => (heights[0] - heights[1]).abs(),
                Metric::OneStepQ => one_max("q"),
                Metric::OneStepQd => one_max("qd"),
                Metric::OneStepTrunkPosition => one_max("trunk_position"),
                Metric::OneStepTrunkOrientation => one_max("trunk_orientation"),
                Metric::OneStepTrunkLinvel => one_max("trunk_linvel"),
                Metric::OneStepTrunkAngvel => one_max("trunk_angvel"),
            };
            (m, v)
        })
        .collect()
}
