//! `hyq-fuzz [--seconds N] [--cases N] [--seed S] [TARGET...]`: runs the fuzz targets (all, or
//! those named) for N seconds each (default 60) or N cases, whichever comes first, and saves
//! an input that fails to `corpus/<target>/` (where the crate's tests replay it). `cargo xtask
//! fuzz` runs it. Status 0 when nothing was found (or for `--help`), 1 on a finding, 2 for bad
//! arguments.

use std::process::ExitCode;
use std::time::{Duration, SystemTime, UNIX_EPOCH};

use hyq_fuzz::{Finding, Plan, Target, corpus_dir, run};

/// The usage line, its targets listed from [`Target::ALL`] so that none is left out.
fn usage() -> String {
    let names: Vec<&str> = Target::ALL.iter().map(|t| t.name()).collect();
    format!(
        "usage: hyq-fuzz [--seconds N] [--cases N] [--seed S] [TARGET...] (targets: {})",
        names.join(", ")
    )
}

/// What the arguments ask for: a run, or the usage (`--help`, `-h`).
enum Request {
    Run(Args),
    Help,
}

struct Args {
    seconds: f64,
    cases: u64,
    seed: u64,
    targets: Vec<Target>,
}

fn parse(args: &[String]) -> Result<Request, String> {
    let now = SystemTime::now()
        .duration_since(UNIX_EPOCH)
        .map_or(0, |d| d.as_secs());
    let mut parsed = Args {
        seconds: 60.0,
        cases: u64::MAX,
        seed: now,
        targets: Vec::new(),
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        let mut value = |name: &str| {
            it.next()
                .ok_or_else(|| format!("{name} needs a value; {}", usage()))
                .cloned()
        };
        match arg.as_str() {
            "--seconds" => {
                parsed.seconds = value("--seconds")?
                    .parse()
                    .ok()
                    .filter(|s: &f64| s.is_finite() && *s > 0.0 && *s <= 1e6)
                    .ok_or("--seconds: expected a number of seconds, up to 1e6")?;
            }
            "--cases" => {
                parsed.cases = value("--cases")?
                    .parse()
                    .map_err(|_| "--cases: expected a whole number")?;
            }
            "--seed" => {
                parsed.seed = value("--seed")?
                    .parse()
                    .map_err(|_| "--seed: expected a whole number")?;
            }
            "--help" | "-h" => return Ok(Request::Help),
            name => parsed.targets.push(
                Target::by_name(name)
                    .ok_or_else(|| format!("unknown target {name:?}; {}", usage()))?,
            ),
        }
    }
    if parsed.targets.is_empty() {
        parsed.targets = Target::ALL.to_vec();
    }
    Ok(Request::Run(parsed))
}

/// Saves a finding's input to its target's corpus, named by its content, and says where.
fn keep(finding: &Finding, target: Target) -> String {
    let dir = corpus_dir(target);
    let hash = finding.input.iter().fold(0xcbf2_9ce4_8422_2325u64, |h, b| {
        (h ^ u64::from(*b)).wrapping_mul(0x0100_0000_01b3)
    });
    let path = dir.join(format!("found-{hash:016x}"));
    match std::fs::create_dir_all(&dir).and_then(|()| std::fs::write(&path, &finding.input)) {
        Ok(()) => format!("saved to {}", path.display()),
        Err(e) => format!("could not be saved to {}: {e}", path.display()),
    }
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let args = match parse(&args) {
        Ok(Request::Run(a)) => a,
        Ok(Request::Help) => {
            println!("{}", usage());
            return ExitCode::SUCCESS;
        }
        Err(e) => {
            eprintln!("hyq-fuzz: error: {e}");
            return ExitCode::from(2);
        }
    };
    let scratch = match tempfile::tempdir() {
        Ok(d) => d,
        Err(e) => {
            eprintln!("hyq-fuzz: error: no scratch directory: {e}");
            return ExitCode::from(1);
        }
    };
    let plan = Plan {
        seed: args.seed,
        cases: args.cases,
        time: Some(Duration::from_secs_f64(args.seconds)),
    };
    let mut found = false;
    for target in args.targets {
        // Printed first, so that an abort (which ends the process) can be replayed.
        println!(
            "{}: seed {}, up to {} s (replay: hyq-fuzz --seed {} {})",
            target.name(),
            plan.seed,
            args.seconds,
            plan.seed,
            target.name()
        );
        match run(target, &plan, scratch.path()) {
            Ok(tally) => println!(
                "{}: {} inputs, {} accepted, nothing found",
                target.name(),
                tally.cases,
                tally.accepted
            ),
            Err(finding) => {
                found = true;
                println!("FOUND {finding}; the input {}", keep(&finding, target));
            }
        }
    }
    if found {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

#[cfg(test)]
mod tests {
    //! The usage names every target, and `--help` asks for it rather than naming a target.
    use super::*;

    #[test]
    fn help_is_the_usage_and_the_usage_names_every_target() {
        for target in Target::ALL {
            assert!(usage().contains(target.name()), "{}", usage());
        }
        for flag in ["--help", "-h"] {
            let args = [flag.to_owned()];
            assert!(matches!(parse(&args), Ok(Request::Help)), "{flag}");
        }
        let args = ["bogus".to_owned()];
        let Err(e) = parse(&args) else {
            panic!("an unknown target is refused")
        };
        assert!(
            e.contains("unknown target \"bogus\"") && e.contains("heights"),
            "{e}"
        );
    }
}
