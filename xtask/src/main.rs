//! Project automation, run as `cargo xtask <command>` (the cargo-xtask convention: the alias lives
//! in `.cargo/config.toml`, so nothing needs installing).
//!
//! `cargo xtask test` is the project's one test command: the README names it and `.ci/run` runs
//! it. It runs every test the machine can run, says loudly what it could not run and why, and
//! fails when a part that was required (`--require dart`, `--require mujoco`, `--require
//! python`) cannot run.

mod bench;
mod cli;
mod codegen;
mod docs;
#[cfg(test)]
mod feature_sets;
mod fuzz;
mod mujoco;
mod python;
mod regen;
mod rllib;
mod shape;
mod soak;
mod stages;
#[cfg(test)]
mod standalone;
mod train;
mod vendor;
mod workspace;

use std::process::ExitCode;

const HELP: &str = "\
cargo xtask <command>

commands:
  test [--require dart|mujoco|python|all]... [--with rllib|train]...
                                        run every test of the workspace: the Rust crates (rapier
                                        backend), the DART backend when DART is installed, the
                                        MuJoCo backend when MuJoCo is set up, the Python package
                                        when its tools are installed; --require makes a part
                                        that cannot run a failure (CI uses it); --with rllib
                                        adds a two-iteration RLlib run of
                                        examples/rllib_scale_out.py (a 6.1 GB venv of its own);
                                        --with train adds the training examples' tests
                                        (crates/hyq-py/tests_train: the rsl_rl adapter, both
                                        trainers, the exports; a 5.4 GB venv of its own,
                                        $HYQ_TRAIN_VENV or target/train-venv)
  setup mujoco                          download MuJoCo 4.0.0's C library and headers from the
                                        package index (pip, pinned sha256) into target/mujoco
                                        (or $MUJOCO_DIR), for the MuJoCo backend
  soak [--steps N] [--backend rapier|dart|mujoco] [--seed S]
                                        random actions for N env steps (default 10^6) in a
                                        release build of `hyq`: no panic, no NaN in any output;
                                        prints the episodes and the observed range of each row
  bench-vs-anchors [--reps R] [--steps N] [--vec-steps N] [--anchor-steps N]
                   [--venv DIR] [--no-dart] [--no-mujoco]
                                        the speed targets: hyq bench (rapier, DART when
                                        installed, MuJoCo when set up, the vector env on 1 and
                                        2 threads) and the anchors in bench/anchors (MuJoCo,
                                        DART from Python, on models `hyq model` writes into
                                        target/anchor-models) interleaved R times (default 5);
                                        the anchors' venv is target/anchor-venv (or --venv DIR,
                                        $HYQ_ANCHOR_VENV); prints medians, min/max and ratios
                                        and writes target/bench-vs-anchors.md
  fuzz [--seconds N] [--cases N] [--seed S] [config|profile|urdf|mjcf|policy|records|ledger]...
                                        fuzz every loader of a user's file (all targets, or
                                        those named) for N seconds each (default 60) in a
                                        release build: no panic, abort or hang, a one-line
                                        error or a result whose every derived number is finite;
                                        a failing input is saved to crates/hyq-fuzz/corpus/,
                                        whose inputs `test` replays (it also runs each target
                                        briefly)
  vendor-check [--no-tests]             vendor/rapier3d is the published rapier3d plus
                                        vendor/patches (and the notices), and rapier's
                                        multibody tests pass on it (also a stage of `test`)
  vendor-diff                           prints what vendor/rapier3d holds beyond the published
                                        crate and vendor/patches, as an upstream-ready patch
  codegen [--check]                     write the documents' tables made from the code (the
                                        info and step record schemas, the reward terms, the
                                        configuration's tables); --check fails if one is stale
  regen-reports [--dev]                 remake every comparison report under docs/comparison
                                        and every image under docs/media with the command each
                                        states (one build of hyq with every engine, release or
                                        --dev), then fail if git sees any file changed
  help                                  this text
";

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.first().map(String::as_str) {
        Some("test") => stages::test(&args[1..]),
        Some("setup") => mujoco::setup(&args[1..]),
        Some("soak") => soak::soak(&args[1..]),
        Some("bench-vs-anchors") => bench::bench_vs_anchors(&args[1..]),
        Some("fuzz") => fuzz::fuzz(&args[1..]),
        Some("vendor-check") => vendor::vendor_check(&args[1..]),
        Some("vendor-diff") => vendor::vendor_diff(&args[1..]),
        Some("codegen") => codegen::codegen(&args[1..]),
        Some("regen-reports") => regen::regen_reports(&args[1..]),
        Some("help") | Some("--help") | Some("-h") | None => {
            print!("{HELP}");
            Ok(())
        }
        Some(other) => Err(format!(
            "unknown xtask command `{other}` (try `cargo xtask help`)"
        )),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("xtask: error: {message}");
            ExitCode::FAILURE
        }
    }
}
