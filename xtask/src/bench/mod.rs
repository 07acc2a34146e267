//! `cargo xtask bench-vs-anchors`: the project's benchmark and the anchors' (the same workload
//! in MuJoCo and in DART, driven from Python by `bench/anchors/`), run side by side in one
//! run, with the ratios the speed targets are stated in.
//!
//! What it does, in order:
//! 1. sets up (or reuses) the anchors' Python virtual environment, `target/anchor-venv` unless
//!    `--venv DIR` (relative: to the workspace root) or `$HYQ_ANCHOR_VENV` says otherwise, with
//!    the versions pinned in `bench/anchors/requirements.txt`;
//! 2. builds `hyq` in release mode, with every backend of [`SEQUENCE`] whose engine is
//!    installed (DART when its headers are, MuJoCo when `cargo xtask setup mujoco` has put it
//!    in `target/mujoco` or `$MUJOCO_DIR`);
//! 3. writes the anchors' models afresh with that `hyq` (`hyq model`): `hyq.xml` (MJCF with
//!    position servos), `hyq.urdf` (capsules as cylinders, for DART's loader) and `hyq.json`
//!    (the facts the scripts read), into `target/anchor-models/`, so they are always the robot
//!    the environment simulates;
//! 4. repeats `--reps` times the measurements of [`SEQUENCE`], in its order, so that every
//!    repetition sees the same machine load: `hyq bench` on rapier; MuJoCo from Python (the
//!    env loop `env_random` and MuJoCo's own loop `c_loop`); `hyq bench` on MuJoCo; `hyq bench`
//!    on DART; DART from Python (Bullet detector, with `world.step()` timed alone in a second
//!    pass, and the ODE detector); the rapier vector env of 2 envs on 1 thread, then on 2
//!    threads;
//! 5. prints, and writes to `target/bench-vs-anchors.md`, a Markdown report: the CPU model, the
//!    load, the median, min and max of every figure, and each ratio against its target (the
//!    median of the per-repetition ratios, each taken within one repetition, and their min and
//!    max). The raw JSON lines go to `target/bench-vs-anchors.jsonl`.
//!
//! Single-env rates are CPU-time rates (env steps per CPU second of the process), the better
//! estimate of an idle core on a shared machine; the anchors report both kinds and the same
//! kind is compared. The vector env's scaling is a wall-clock ratio (that is what parallelism
//! buys), so it is only meaningful when two cores are free: the load average is printed with it.
//!
//! Split by phase: [`args`] (the command's arguments), [`plan`] (what is measured, in order),
//! [`venv`] (the anchors' Python), [`run`] (the commands and their figures), [`stats`]
//! (medians, ratios, verdicts) and [`report`] (the Markdown).
//!
//! # Adding a backend
//! A new `hyq bench --backend X` row takes: two [`plan::Series`] (its rate and its spec share)
//! with their labels in `Series::label` and places in `Series::ALL`; a [`plan::HyqBackend`] in
//! [`plan::SEQUENCE`] (with the cargo feature that builds it in); and, if it has one, its target
//! in [`stats::TARGETS`]. Whether this machine can measure it comes from its row in
//! hyq-engines.

mod args;
mod command;
mod plan;
mod report;
mod run;
mod stats;
#[cfg(test)]
mod tests;
mod venv;

use std::path::PathBuf;

use args::parse;
use report::{Host, markdown};
use stats::Rep;

use crate::workspace::workspace_root;

/// The anchor harness, relative to the workspace root.
pub const ANCHORS_DIR: &str = "bench/anchors";

/// Where the anchors' models are written, in the target directory.
pub const MODELS_DIR: &str = "anchor-models";

/// The anchors' default virtual environment, in the target directory (git-ignored).
pub const DEFAULT_VENV: &str = "anchor-venv";

/// `cargo xtask bench-vs-anchors`: prepares (the anchors' Python, the release build, the
/// models), measures every repetition, then reports.
pub fn bench_vs_anchors(args: &[String]) -> Result<(), String> {
    let root = workspace_root();
    let args = parse(
        args,
        &root,
        std::env::var_os("HYQ_ANCHOR_VENV").map(PathBuf::from),
    )?;
    let mut host = Host::now();
    let setup = run::Setup::prepare(&args, &root, &mut host)?;
    let mut raw = String::new();
    let mut reps: Vec<Rep> = Vec::new();
    for rep in 1..=args.reps {
        println!("repetition {rep}/{}", args.reps);
        let r = setup.repetition(&args, &mut raw)?;
        let line: Vec<String> = r
            .iter()
            .map(|(s, x)| format!("{s:?} {}", report::fmt_value(*s, *x)))
            .collect();
        println!("  {}", line.join(", "));
        reps.push(r);
    }
    host.load_end = command::shell("cut -d' ' -f1-3 /proc/loadavg");

    let report = markdown(&host, &reps);
    println!("\n{report}");
    report::write_reports(&root, &report, &raw)
}
