//! `hyq compare`: the same action sequence on two physics backends, and a report of where they
//! agree and where they drift apart (hyq-compare): `report.md`, `report.json` and
//! `trunk_x_z.png` in `--out DIR`.
//!
//! Exit status: 0 when the reports are written, whatever they found; with `--strict`, 1 (after
//! writing the reports) when any metric is outside the ledger, so CI can gate on it; 2 for bad
//! input (unknown scenario or backend, seconds ≤ 0, an unwritable `--out`, an unreadable or
//! invalid `--ledger`), reported before anything runs; 1 for a failure while running.

use std::io::Write as _;
use std::path::PathBuf;

use clap::builder::TypedValueParser as _;
use clap::{Args, ValueEnum as _};
use hyq_compare::{
    ComparisonSpec, DEFAULT_ONE_STEP_STATES, Ledger, MARKDOWN_FILE, Report, Scenario,
    check_seconds, parse_override, prepare_output_dir,
};

use crate::Failure;
use crate::backend::{BackendChoice, not_built, with_backend};
use crate::options::{robot, usage};

/// `hyq compare` arguments.
#[derive(Debug, Args)]
pub struct CompareArgs {
    /// The two backends, comma-separated: rapier,dart or rapier,mujoco (the point of the
    /// command), or the same one twice (a self-check: exact agreement, or the effect of --set-b).
    #[arg(long, value_name = "A,B", default_value = "rapier,dart", value_parser = parse_backends)]
    backends: BackendPair,
    /// The scenario (see `docs/backend-comparison.md`): stand (hold the pose), fall (a pushed
    /// robot tips over), limit (lf_hfe driven to its limit), trot (the scripted trot), random (random
    /// actions), reach (the trot to a goal on its path).
    #[arg(long, value_parser = clap::builder::PossibleValuesParser::new(Scenario::NAMES)
        .try_map(|s| s.parse::<Scenario>()))]
    scenario: Scenario,
    /// Seed of both resets and of the random policy.
    #[arg(long, default_value_t = 0)]
    seed: u64,
    /// Simulated seconds (default: the scenario's: stand 5, fall 3, limit 3, trot 10, random 5,
    /// reach 10). The ledger's tolerances are measured at the defaults.
    #[arg(long, value_parser = parse_seconds)]
    seconds: Option<f64>,
    /// The directory to write report.md, report.json and trunk_x_z.png into (created if
    /// missing; existing reports in it are replaced).
    #[arg(long, value_name = "DIR")]
    out: PathBuf,
    /// A ledger file of known divergences instead of the built-in one
    /// (crates/hyq-compare/ledger.toml).
    #[arg(long, value_name = "FILE")]
    ledger: Option<PathBuf>,
    /// Exit with status 1 (after writing the reports) if any metric is outside the ledger.
    #[arg(long)]
    strict: bool,
    /// Shared states sampled from the first backend's run for the one-step comparison.
    #[arg(long, default_value_t = DEFAULT_ONE_STEP_STATES,
        value_parser = clap::value_parser!(u64).range(1..=1000).map(|v| v as usize))]
    one_step_states: usize,
    /// Override one configuration value on both sides, after the scenario's configuration:
    /// `table.key=value`. Repeatable.
    #[arg(long = "set", value_name = "TABLE.KEY=VALUE")]
    set: Vec<String>,
    /// Override one configuration value on the second backend only (e.g. a perturbation:
    /// `--set-b physics.gravity=[0,0,-10.791]`). Repeatable.
    #[arg(long = "set-b", value_name = "TABLE.KEY=VALUE")]
    set_b: Vec<String>,
}

/// Two backends.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct BackendPair(BackendChoice, BackendChoice);

fn parse_backends(s: &str) -> Result<BackendPair, String> {
    let names: Vec<&str> = s.split(',').map(str::trim).collect();
    if names.len() != 2 {
        return Err(format!(
            "expected two backends separated by a comma (e.g. rapier,dart), got {s:?}"
        ));
    }
    let pick = |name: &str| {
        BackendChoice::from_str(name, false).map_err(|_| {
            format!("unknown backend {name:?} (possible backends: rapier, dart, mujoco)")
        })
    };
    Ok(BackendPair(pick(names[0])?, pick(names[1])?))
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
    let BackendPair(a, b) = args.backends;
    if let Some(missing) = [a, b].into_iter().find(|c| !c.built()) {
        return Err(not_built(
            missing,
            &format!("--backends {},{}", a.name(), b.name()),
        ));
    }
    let ledger = match &args.ledger {
        Some(path) => Ledger::from_file(path),
        None => Ledger::built_in(),
    }
    .map_err(|e| usage(format!("--ledger: {e}")))?;
    let parse_all = |flag: &str, items: &[String]| {
        items
            .iter()
            .map(|i| parse_override(i).map_err(|e| usage(format!("{flag}: {e}"))))
            .collect::<Result<Vec<_>, Failure>>()
    };
    let spec = ComparisonSpec {
        scenario: args.scenario,
        seed: args.seed,
        seconds: args.seconds,
        one_step_states: args.one_step_states,
        overrides: parse_all("--set", &args.set)?,
        overrides_b: parse_all("--set-b", &args.set_b)?,
    };
    prepare_output_dir(&args.out).map_err(|e| usage(format!("--out: {e}")))?;

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
            hyq_compare::compare::<A, B>(robot(), &spec, labels, &ledger).map_err(|e| {
                // Overrides and the configuration they make are checked only when the
                // comparison builds it: those are bad input too.
                use hyq_compare::CompareError as E;
                let status = match e {
                    E::Override { .. } | E::Config(_) | E::StateDependentActions { .. } => 2,
                    _ => 1,
                };
                Failure { status, message: e.to_string() }
            })
        })
    })?;
    report
        .write(&args.out, &command_line())
        .map_err(|e| Failure {
            status: 1,
            message: e.to_string(),
        })?;
    print_summary(&report, &args);
    if args.strict && report.flagged > 0 {
        let names: Vec<&str> = report.flags().map(|c| c.metric.name()).collect();
        return Err(Failure {
            status: 1,
            message: format!(
                "--strict: {} metric(s) outside the ledger ({}); see {}",
                report.flagged,
                names.join(", "),
                args.out.join(MARKDOWN_FILE).display()
            ),
        });
    }
    Ok(())
}

/// Prints the summary on stdout. A closed stdout (e.g. piped into `head`) is not an error of
/// the comparison: the reports are already written, so write failures are ignored.
fn print_summary(report: &Report, args: &CompareArgs) {
    let mut out = std::io::stdout().lock();
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
}
