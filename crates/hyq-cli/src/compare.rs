//! `hyq compare`: the same action sequence on two or three physics backends, and a report of
//! where they agree and where they drift apart (hyq-compare): `report.md`, `report.json` and
//! `trunk_x_z.png` in `--out DIR`; with three backends the top-level report sets the three
//! side by side and each pair's full report is in `DIR/<a>_vs_<b>/`. With `--policy mlp:FILE`
//! instead of `--scenario`, a trained policy runs closed loop on every backend (hyq-compare's
//! `policy` module), loaded and checked as `hyq run --policy` loads it; that report states the
//! gap and is not judged against the ledger.
//!
//! Exit status: 0 when the reports are written, whatever they found; with `--strict`, 1 (after
//! writing the reports) when any metric is outside the ledger, so CI can gate on it; 2 for bad
//! input (unknown scenario or backend, seconds ≤ 0, an unwritable `--out`, an unreadable or
//! invalid `--ledger`, a bad policy file or one trained for another layout, a backend that cannot
//! be built, such as a MuJoCo library that cannot be loaded), reported before anything runs; 1
//! for a failure while running.

use std::fmt::Write as _;
use std::path::PathBuf;

use clap::Args;
use clap::builder::TypedValueParser as _;
use hyq_compare::policy::MAX_EPISODES;
use hyq_compare::{
    ComparisonSpec, DEFAULT_ONE_STEP_STATES, Ledger, MARKDOWN_FILE, Plan, PolicyPlan, PolicyReport,
    PolicySpec, Report, Scenario, check_seconds, compare_all, parse_override, prepare_output_dir,
};
use hyq_env::TerrainKind;

use crate::Failure;
use crate::backend::{BackendChoice, not_built, parse_backend_list, with_backend};
use crate::options::{ConfigArgs, PolicyChoice, RobotArgs, TrainedPolicy, check_mlp, usage};
use crate::output;

/// Episodes per backend of a policy comparison unless `--episodes` says otherwise: enough for
/// a 95 % interval of ±5 % or better on each engine's mean travel for every committed walker
/// trained without randomisation (the most any needs is about 52, docs/transfer.md's
/// "The default episode count").
const DEFAULT_EPISODES: u32 = 60;

/// `hyq compare` arguments.
#[derive(Debug, Args)]
#[command(group(clap::ArgGroup::new("what").required(true).args(["scenario", "policy"])))]
pub struct CompareArgs {
    /// The backends, comma-separated: two (rapier,dart or rapier,mujoco; or the same one twice,
    /// a self-check: exact agreement, or the effect of --set-b) or three different ones
    /// (rapier,dart,mujoco: every pair compared, one report).
    #[arg(long, value_name = "A,B[,C]", default_value = "rapier,dart", value_parser = parse_backends)]
    backends: Backends,
    /// The scenario (see `docs/backend-comparison.md`): stand (hold the pose), fall (a pushed
    /// robot tips over), limit (the first [gait] leg's hip joint, lf_hfe on the bundled robots,
    /// driven to its limit), trot (the scripted trot), random (random
    /// actions), reach (the trot to a goal on its path). Required unless --policy is given.
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(Scenario::NAMES)
        .try_map(|s| s.parse::<Scenario>()))]
    scenario: Option<Scenario>,
    /// Instead of a scenario, a trained policy (mlp:FILE, e.g.
    /// mlp:assets/policies/hyq_walk.safetensors), closed loop: on each backend it acts on that
    /// backend's own observations, in the environment it was trained in (its action mode and
    /// reward settings apply unless --config or --set sets the key), for --episodes episodes;
    /// the first episode's actions on the first backend are also replayed open loop on every
    /// backend. The report states the gap; it is not judged against the ledger.
    #[arg(long, value_name = "mlp:FILE", value_parser = parse_policy)]
    policy: Option<PolicyChoice>,
    /// Episodes per backend with --policy (default 60: a travel interval within ±5 % for the
    /// committed walkers; the first reset seeded with --seed, the later ones continuing its
    /// streams, as `hyq run --episodes N`).
    #[arg(long, value_parser = clap::value_parser!(u32).range(1..=i64::from(MAX_EPISODES)))]
    episodes: Option<u32>,
    /// With --policy: a TOML configuration file (as `hyq run --config`); its keys win over the
    /// policy file's environment. Episode length: task.max_time_steps (1000 by default, 10 s).
    #[arg(long, value_name = "FILE")]
    config: Option<PathBuf>,
    /// The robot.
    #[command(flatten)]
    robot: RobotArgs,
    /// Seed of both resets and of the random policy.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Simulated seconds (default: the scenario's: stand 5, fall 3, limit 3, trot 10, random 5,
    /// reach 10). The ledger's tolerances are measured at the defaults.
    #[arg(long, value_parser = parse_seconds, conflicts_with = "policy")]
    seconds: Option<f64>,
    /// The directory to write report.md, report.json and trunk_x_z.png into (created if
    /// missing; existing reports in it are replaced).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// A ledger file of known divergences instead of the built-in one
    /// (crates/hyq-compare/ledger.toml).
    #[arg(long, value_name = "FILE", conflicts_with = "policy")]
    ledger: Option<PathBuf>,
    /// Exit with status 1 (after writing the reports) if any metric is outside the ledger.
    #[arg(long, conflicts_with = "policy")]
    strict: bool,
    /// Shared states sampled from the first backend's run for the one-step comparison.
    #[arg(long, default_value_t = DEFAULT_ONE_STEP_STATES, conflicts_with = "policy",
        value_parser = clap::value_parser!(u64).range(1..=1000).map(|v| v as usize))]
    one_step_states: usize,
    /// Override one configuration value on every side, after the scenario's configuration (or
    /// the policy's environment and --config): `table.key=value`. Repeatable.
    #[arg(long = "set", value_name = "TABLE.KEY=VALUE")]
    set: Vec<String>,
    /// Override one configuration value on the second backend only (e.g. a perturbation:
    /// `--set-b physics.gravity=[0,0,-10.791]`); two backends only. Repeatable.
    #[arg(
        long = "set-b",
        value_name = "TABLE.KEY=VALUE",
        conflicts_with = "policy"
    )]
    set_b: Vec<String>,
    /// The ground on every side: `--set terrain.kind="KIND"` with the `[terrain]` table's
    /// defaults (rough: ±5 cm bumps 0.4 m apart, seed 0; slope: 10° rising towards the goal;
    /// stairs: 10 cm steps 30 cm deep from 1 m ahead), tuned further with --set. The ledger's
    /// entries measured on that ground judge the scenarios (docs/terrain.md).
    #[arg(long, value_name = "KIND", value_parser = generated_terrains())]
    terrain: Option<String>,
}

/// `--terrain`'s values: every ground kind a name alone builds (hyq-env's list of them).
fn generated_terrains() -> clap::builder::PossibleValuesParser {
    let kinds = TerrainKind::ALL.into_iter().filter(|k| k.is_generated());
    clap::builder::PossibleValuesParser::new(kinds.map(TerrainKind::as_str))
}

impl CompareArgs {
    /// `--terrain KIND` as the first `--set`, so that a later --set tunes it.
    fn terrain_as_set(mut self) -> Self {
        if let Some(kind) = self.terrain.take() {
            self.set.insert(0, format!("terrain.kind=\"{kind}\""));
        }
        self
    }
}

/// The backends to compare: two, or three different ones.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Backends(Vec<BackendChoice>);

fn parse_backends(s: &str) -> Result<Backends, String> {
    if !(2..=3).contains(&s.split(',').count()) {
        return Err(format!(
            "expected two or three backends separated by commas (e.g. rapier,dart or \
             rapier,dart,mujoco), got {s:?}"
        ));
    }
    let choices = parse_backend_list(s)?;
    if choices.len() == 3
        && (choices[0] == choices[1] || choices[0] == choices[2] || choices[1] == choices[2])
    {
        return Err(format!(
            "three backends must differ (a self-check compares one backend twice: A,A), got {s:?}"
        ));
    }
    Ok(Backends(choices))
}

fn parse_policy(text: &str) -> Result<PolicyChoice, String> {
    match text.parse::<PolicyChoice>()? {
        PolicyChoice::Mlp(file) => Ok(PolicyChoice::Mlp(file)),
        other => Err(format!(
            "{other} is a scripted policy: compare runs it as a scenario (--scenario); \
             --policy takes a trained policy, mlp:FILE"
        )),
    }
}

fn parse_seconds(s: &str) -> Result<f64, String> {
    let value: f64 = s
        .trim()
        .parse()
        .map_err(|_| format!("{s:?} is not a number of seconds"))?;
    check_seconds(value).map_err(|e| e.to_string())?;
    Ok(value)
}

/// The command line as run, for the report (arguments with spaces quoted).
fn command_line() -> String {
    let mut words = vec!["hyq".to_owned()];
    words.extend(std::env::args().skip(1).map(|a| {
        if a.is_empty() || a.contains(char::is_whitespace) {
            format!("'{a}'")
        } else {
            a
        }
    }));
    words.join(" ")
}

/// Runs `hyq compare`.
pub fn execute(args: CompareArgs) -> Result<(), Failure> {
    let args = args.terrain_as_set();
    let choices = args.backends.0.clone();
    let model = args.robot.model()?;
    if let Some(missing) = choices.iter().copied().find(|c| !c.built()) {
        let names: Vec<&str> = choices.iter().map(|c| c.name()).collect();
        return Err(not_built(
            missing,
            &format!("--backends {}", names.join(",")),
        ));
    }
    let scenario = match (&args.policy, args.scenario) {
        (Some(PolicyChoice::Mlp(file)), _) => {
            return execute_policy(&args, file, &choices, model);
        }
        (_, scenario) => checked_scenario(&args, scenario)?,
    };
    let ledger = match &args.ledger {
        Some(path) => Ledger::from_file(path),
        None => Ledger::built_in(),
    }
    .map_err(|e| usage(format!("--ledger: {e}")))?;
    let spec = comparison_spec(&args, scenario)?;
    // The plan checks the overrides and the configuration they make, so a bad --set is refused
    // before --out is created.
    let plan = Plan::new(model, &spec).map_err(compare_failure)?;
    prepare_output_dir(&args.out).map_err(|e| usage(format!("--out: {e}")))?;

    if choices.len() > 2 {
        return execute_many(&args, &choices, &plan, &ledger);
    }
    let (a, b) = (choices[0], choices[1]);
    let (name_a, name_b) = (a.name(), b.name());
    // The second side of a self-comparison is labelled apart, so the report's columns and the
    // plot's legend can be told apart.
    let label_b = if name_a == name_b {
        format!("{name_b} (B)")
    } else {
        name_b.to_owned()
    };
    let labels = [name_a, label_b.as_str()];
    let report: Report = with_backend!(a, A => {
        with_backend!(b, B => {
            plan.compare_two::<A, B>(labels, &ledger).map_err(compare_failure)
        })
    })?;
    written(report.write(&args.out, &command_line()))?;
    print_summary(&report, &args)?;
    if args.strict && report.flagged > 0 {
        let names: Vec<&str> = report.flags().map(|c| c.metric.name()).collect();
        return Err(strict_failure(report.flagged, &names, &args));
    }
    Ok(())
}

/// The scenario of a scenario comparison (`scenario`, as `--scenario` gave it), refusing the
/// flags that go with a policy comparison only, and `--set-b` beside three backends.
fn checked_scenario(args: &CompareArgs, scenario: Option<Scenario>) -> Result<Scenario, Failure> {
    let scenario = match scenario {
        Some(_) if args.episodes.is_some() || args.config.is_some() => {
            let flag = if args.episodes.is_some() {
                "--episodes"
            } else {
                "--config"
            };
            return Err(usage(format!(
                "{flag} goes with --policy mlp:FILE; a scenario sets its own episode and \
                 configuration (change it with --set)"
            )));
        }
        Some(scenario) => scenario,
        // clap requires one of the two and parse_policy takes only mlp:FILE.
        None => return Err(usage("give --scenario NAME or --policy mlp:FILE")),
    };
    if args.backends.0.len() > 2 && !args.set_b.is_empty() {
        return Err(usage(
            "--set-b: overrides the second backend of a two-backend comparison; with three \
             backends use --set (every side)",
        ));
    }
    Ok(scenario)
}

/// The scenario comparison's specification: `scenario` with the seed, length and sampling of
/// `args`, and its `--set` and `--set-b` overrides parsed (a bad one names its flag).
fn comparison_spec(args: &CompareArgs, scenario: Scenario) -> Result<ComparisonSpec, Failure> {
    let parse_all = |flag: &str, items: &[String]| {
        items
            .iter()
            .map(|i| parse_override(i).map_err(|e| usage(format!("{flag}: {e}"))))
            .collect::<Result<Vec<_>, Failure>>()
    };
    Ok(ComparisonSpec {
        scenario,
        seed: args.seed,
        seconds: args.seconds,
        one_step_states: args.one_step_states,
        overrides: parse_all("--set", &args.set)?,
        overrides_b: parse_all("--set-b", &args.set_b)?,
    })
}

/// A report's writing as the command's result: a failure to write is status 1 (the run itself
/// went through; the disk refused it).
fn written<T>(result: Result<T, hyq_compare::CompareError>) -> Result<T, Failure> {
    result.map_err(|e| Failure {
        status: 1,
        message: e.to_string(),
    })
}

/// A comparison's error as a failure: overrides and the configuration they make are checked
/// only when the comparison builds it, and are bad input too (status 2); the rest status 1.
fn compare_failure(e: hyq_compare::CompareError) -> Failure {
    use hyq_compare::CompareError as E;
    let status = match e {
        E::Override { .. }
        | E::Build { .. }
        | E::Config(_)
        | E::StateDependentActions { .. }
        | E::Scenario { .. } => 2,
        _ => 1,
    };
    Failure {
        status,
        message: e.to_string(),
    }
}

fn strict_failure(flagged: usize, names: &[&str], args: &CompareArgs) -> Failure {
    Failure {
        status: 1,
        message: format!(
            "--strict: {flagged} metric(s) outside the ledger ({}); see {}",
            names.join(", "),
            args.out.join(MARKDOWN_FILE).display()
        ),
    }
}

/// `hyq compare` with three backends: each runs the plan once, every pair is compared.
fn execute_many(
    args: &CompareArgs,
    choices: &[BackendChoice],
    plan: &Plan,
    ledger: &Ledger,
) -> Result<(), Failure> {
    let mut sides = Vec::with_capacity(choices.len());
    for &choice in choices {
        let side = with_backend!(choice, B => {
            plan.run_side::<B>(choice.name(), &[]).map_err(compare_failure)
        })?;
        sides.push(side);
    }
    let report = compare_all(plan, &mut sides, ledger).map_err(compare_failure)?;
    written(report.write(&args.out, &command_line()))?;
    let mut out = String::new();
    let end = |s: &hyq_compare::SideReport| {
        let r: Vec<&str> = s.end_reasons.iter().map(|r| r.as_str()).collect();
        format!("{} {} at step {}", s.label, r.join("+"), s.end_step)
    };
    let ends: Vec<String> = report.sides.iter().map(end).collect();
    let _ = writeln!(
        out,
        "scenario {} on {} (seed {}, {} s): {}",
        report.scenario,
        report.robot,
        report.seed,
        report.seconds,
        ends.join(", ")
    );
    for p in &report.pairs {
        let _ = writeln!(
            out,
            "{} vs {}: trunk position divergence rms {:.4} m, max {:.4} m; return diff {:.3}; {} metric(s) outside the ledger",
            p.labels[0],
            p.labels[1],
            p.trunk_position.rms,
            p.trunk_position.max,
            p.return_diff,
            p.flagged
        );
    }
    let _ = writeln!(out, "reports written to {}", args.out.display());
    output::print(&out)?;
    if args.strict && report.flagged > 0 {
        let names: Vec<&str> = report
            .pairs
            .iter()
            .flat_map(|p| p.flagged_metrics.iter().map(String::as_str))
            .collect();
        return Err(strict_failure(report.flagged, &names, args));
    }
    Ok(())
}

/// `hyq compare --policy mlp:FILE`: the trained policy closed loop on every backend, and its
/// first backend's first-episode actions replayed open loop on each.
fn execute_policy(
    args: &CompareArgs,
    file: &std::path::Path,
    choices: &[BackendChoice],
    model: std::sync::Arc<hyq_physics::RobotModel>,
) -> Result<(), Failure> {
    let plan = policy_plan(args, file, model)?;
    prepare_output_dir(&args.out).map_err(|e| usage(format!("--out: {e}")))?;
    let labels = side_labels(choices);
    let mut sides = Vec::with_capacity(choices.len());
    for (&choice, label) in choices.iter().zip(&labels) {
        let side = with_backend!(choice, B => {
            plan.run_side::<B>(label).map_err(compare_failure)
        })?;
        sides.push(side);
    }
    let mut replays = Vec::new();
    if plan.replays() {
        for (&choice, label) in choices.iter().zip(&labels) {
            let run = with_backend!(choice, B => {
                plan.replay::<B>(label, &sides[0]).map_err(compare_failure)
            })?;
            replays.push(run);
        }
    }
    let report = plan.report(&sides, &replays);
    written(report.write(&args.out, &command_line()))?;
    print_policy_summary(&report, args)
}

/// The policy comparison's plan: the trained policy of `file` and the environment it was
/// trained in, with `--config` and `--set` applied on top, each named in the report.
fn policy_plan(
    args: &CompareArgs,
    file: &std::path::Path,
    model: std::sync::Arc<hyq_physics::RobotModel>,
) -> Result<PolicyPlan<hyq_env::MlpPolicy>, Failure> {
    let configuration = ConfigArgs {
        config: args.config.clone(),
        set: args.set.clone(),
    };
    let trained = TrainedPolicy::load(file, &configuration)?;
    check_mlp(&trained.policy, file, &model, &trained.config)?;
    let mut applied: Vec<String> = trained
        .inherited
        .iter()
        .map(|(k, v)| format!("{k}={v} (the policy file)"))
        .collect();
    if let Some(path) = &args.config {
        applied.push(format!("--config {}", path.display()));
    }
    applied.extend(args.set.iter().map(|s| format!("{} (--set)", s.trim())));
    let spec = PolicySpec {
        policy: format!("mlp:{}", file.display()),
        seed: args.seed,
        episodes: args.episodes.unwrap_or(DEFAULT_EPISODES),
        configuration: applied,
    };
    PolicyPlan::new(model, trained.config, trained.policy, spec).map_err(compare_failure)
}

/// Each backend's label in a comparison: its name, and a self-comparison's second side's name
/// with ` (B)` to tell them apart, as in the scenario comparison.
fn side_labels(choices: &[BackendChoice]) -> Vec<String> {
    choices
        .iter()
        .enumerate()
        .map(|(k, c)| {
            if choices[..k].contains(c) {
                format!("{} (B)", c.name())
            } else {
                c.name().to_owned()
            }
        })
        .collect()
}

/// Prints the policy comparison's summary on stdout (the reports are already written), as
/// [`print_summary`] does.
fn print_policy_summary(report: &PolicyReport, args: &CompareArgs) -> Result<(), Failure> {
    let mut out = crate::policy_summary::policy_summary(report);
    // Writing into a String cannot fail.
    let _ = writeln!(
        out,
        "\nnot judged against the ledger (closed loop); reports written to {}",
        args.out.display()
    );
    output::print(&out)
}

/// Prints the summary on stdout (the reports are already written): a closed stdout (piped into
/// `head`) ends the command quietly, another write failure (`> /dev/full`) is an error.
fn print_summary(report: &Report, args: &CompareArgs) -> Result<(), Failure> {
    let mut out = String::new();
    let [a, b] = &report.sides;
    let end = |s: &hyq_compare::SideReport| {
        let r: Vec<&str> = s.end_reasons.iter().map(|r| r.as_str()).collect();
        format!("{} at step {}", r.join("+"), s.end_step)
    };
    let t = &report.trajectory;
    let _ = writeln!(
        out,
        "scenario {} (seed {}, {} s): {} ended {}, {} ended {}",
        report.scenario,
        report.seed,
        report.seconds,
        a.label,
        end(a),
        b.label,
        end(b)
    );
    let _ = writeln!(
        out,
        "trunk position divergence rms {:.4} m, max {:.4} m; orientation rms {:.4} rad, max {:.4} rad; joints rms {:.4} rad, max {:.4} rad",
        t.trunk_position.rms,
        t.trunk_position.max,
        t.trunk_orientation.rms,
        t.trunk_orientation.max,
        t.joint_angles.rms,
        t.joint_angles.max
    );
    let _ = writeln!(
        out,
        "standing height {:.4} m vs {:.4} m; return {:.3} vs {:.3}",
        a.standing_height_m, b.standing_height_m, a.sums.ret, b.sums.ret
    );
    if report.flagged == 0 {
        let _ = writeln!(out, "every metric within the ledger ({})", report.ledger);
    } else {
        for c in report.flags() {
            let _ = writeln!(
                out,
                "outside the ledger: {} = {:.6} > {:.6}",
                c.metric, c.value, c.tolerance
            );
        }
    }
    let _ = writeln!(out, "reports written to {}", args.out.display());
    output::print(&out)
}
