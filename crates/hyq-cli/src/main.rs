//! `hyq`: the command-line front of the HyQ walk-to-goal environment.
//!
//! One module per subcommand (`run`, `bench`, `soak`, `render`, `plot`, `compare`, `model`, `robot`), each with its
//! clap arguments and an `execute` function; the environment options every subcommand shares
//! (backend, configuration file, `--set` overrides, policy and seed) live in [`options`], the
//! choice of physics backend in [`backend`], and the JSON line and progress bar several of them
//! print in [`output`].
//!
//! Errors never panic and never print more than one line: `hyq: error: <what was wrong>` on
//! stderr and exit status 2 for a usage error (bad option, bad value), 1 for anything else. A
//! closed stdout (`hyq run | head -1`) ends a command quietly with status 0; output files are
//! replaced only by a command that finished (see [`output`]).

mod backend;
mod bench;
mod compare;
mod model;
mod options;
mod output;
mod plot;
mod policy_summary;
mod render;
mod robot;
mod run;
mod soak;
mod table;

use std::io::{IsTerminal as _, Write};
use std::process::ExitCode;

use clap::{Parser, Subcommand};

/// The `hyq` command line.
#[derive(Debug, Parser)]
#[command(
    name = "hyq",
    version,
    about = "The HyQ walk-to-goal environment: run it, record it, benchmark it.",
    long_about = "The HyQ walk-to-goal environment: run it with a scripted or random policy, \
                  record every step as JSON lines, benchmark it, soak-test it.\n\n\
                  Start with `hyq run`: one 10 s episode of the scripted trot on the rapier \
                  backend, then a summary of where it got and what it earned."
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Run episodes with a policy and print a per-episode summary (optionally record every step).
    Run(run::RunArgs),
    /// Measure env steps per second under random joint targets, and where the time goes.
    Bench(bench::BenchArgs),
    /// Random actions for many steps: no panic, no NaN anywhere; prints the observed ranges.
    Soak(soak::SoakArgs),
    /// Feed the same actions to two or three physics backends and report where they agree and
    /// differ; or run a trained policy closed loop on each and report the gap (--policy).
    Compare(compare::CompareArgs),
    /// Render an episode (CPU, headless) to an animated GIF or PNG frames.
    Render(render::RenderArgs),
    /// Plot a recorded JSONL run: every reward term, the cumulative reward, and D_n with R_e(D_n).
    ///
    /// Two PNGs per episode. Give the run's --config and --set: the record does not hold the
    /// configuration, and k_exp (for the R_e curve) and the env step (for the time axis) are
    /// read from them.
    Plot(plot::PlotArgs),
    /// Write the simulated robot for other tools: MuJoCo's MJCF, URDF, or the facts a simulator
    /// loop needs (JSON).
    Model(model::ModelArgs),
    /// Bring a robot: `hyq robot init FILE` drafts a robot profile from a URDF or MJCF file,
    /// every value commented with where it came from.
    Robot(robot::RobotArgs),
}

/// A failure of the command, already worded for the user, with its exit status.
#[derive(Debug)]
pub struct Failure {
    /// 2 for usage errors, 1 otherwise.
    pub status: u8,
    /// The message (one line).
    pub message: String,
}

impl Failure {
    /// stdout was closed by its reader (`hyq run | head -1`): the command stops, quietly and
    /// successfully, as if the reader had read everything; nothing is printed.
    pub fn closed_stdout() -> Self {
        Failure {
            status: 0,
            message: String::new(),
        }
    }
}

/// The longest error line printed (bytes, about three screen lines): a message echoing a value
/// of 120 KB (twice) was one line of 240 KB.
const MAX_ERROR_BYTES: usize = 300;

/// `line` cut to [`MAX_ERROR_BYTES`] when longer: its start and its end (where the reason is),
/// with how much was left out between them.
fn capped(line: &str) -> String {
    if line.len() <= MAX_ERROR_BYTES {
        return line.to_owned();
    }
    let keep = MAX_ERROR_BYTES / 2;
    let mut head = keep;
    while !line.is_char_boundary(head) {
        head -= 1;
    }
    let mut tail = line.len() - keep;
    while !line.is_char_boundary(tail) {
        tail += 1;
    }
    format!(
        "{} […{} bytes left out…] {}",
        &line[..head],
        tail - head,
        &line[tail..]
    )
}

/// Prints `message` as the one error line `hyq` ever prints, folding any line breaks and
/// cutting a very long one ([`capped`]).
fn print_error(message: &str) {
    let line = capped(&hyq_physics::one_line(message));
    // Nothing is left to do if stderr is closed too.
    let _ = writeln!(std::io::stderr().lock(), "hyq: error: {line}");
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => return clap_exit(e),
    };
    let result: Result<(), Failure> = match cli.command {
        Command::Run(args) => run::execute(args),
        Command::Bench(args) => bench::execute(args),
        Command::Soak(args) => soak::execute(args),
        Command::Compare(args) => compare::execute(args),
        Command::Render(args) => render::execute(args),
        Command::Plot(args) => plot::execute(args),
        Command::Model(args) => model::execute(args),
        Command::Robot(args) => robot::execute(args),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(failure) => exit_with(&failure),
    }
}

/// Ends the command with `failure`: its one line (none for a closed stdout) and its status.
fn exit_with(failure: &Failure) -> ExitCode {
    if !failure.message.is_empty() {
        print_error(&failure.message);
    }
    ExitCode::from(failure.status)
}

/// Help and version go to stdout with status 0; a usage error becomes one line naming what was
/// wrong (clap's first line: the unknown option, the invalid value and what it accepts), with a
/// pointer to `--help`, and status 2.
fn clap_exit(e: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => {
            // Through the one stdout writer: a closed pipe ends quietly, a full stdout
            // (`hyq --version > /dev/full`) is one error line and status 1. Styled only on a
            // terminal, as clap itself does.
            let rendered = e.render();
            let text = if std::io::stdout().is_terminal() {
                rendered.ansi().to_string()
            } else {
                rendered.to_string()
            };
            match output::print(&text) {
                Ok(()) => ExitCode::SUCCESS,
                Err(failure) => exit_with(&failure),
            }
        }
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            // The help goes to stderr; there is nothing left to say if that fails too.
            let _ = e.print();
            ExitCode::from(2)
        }
        _ => {
            // clap's message is the lines before its usage block (the error, then e.g. the
            // possible values); its tips and usage are left to `--help`.
            let rendered = e.render().to_string();
            let what: Vec<&str> = rendered
                .lines()
                .map(str::trim)
                .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
                .filter(|l| !l.is_empty() && !l.starts_with("tip:"))
                .collect();
            let what = what.join(" ");
            let what = what.strip_prefix("error: ").unwrap_or(&what);
            print_error(&format!("{what} (see `hyq --help`)"));
            ExitCode::from(2)
        }
    }
}
