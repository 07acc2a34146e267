//! Invariant: a closed stdout (`hyq run | head -1`: the reader has gone) ends every command
//! quietly, with status 0 and nothing on stderr, as ripgrep does; a stdout that cannot be
//! written for another reason (`> /dev/full`) is one error line and status 1. Neither panics.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::process::{Command, Stdio};

use common::{hyq_ok, scratch};

/// Runs `hyq args` with its stdout a pipe whose reading end is closed at once.
fn with_closed_stdout(args: &[&str]) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_hyq"))
        .args(args)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    (out.status.code(), String::from_utf8(out.stderr).unwrap())
}

#[test]
fn a_closed_stdout_ends_every_command_quietly() {
    let record = scratch("closed-stdout.jsonl");
    hyq_ok(&[
        "run",
        "--set",
        "task.max_time_steps=20",
        "--record",
        record.to_str().unwrap(),
    ]);
    let plots = scratch("closed-stdout-plots");
    let cases: [&[&str]; 9] = [
        &[
            "run",
            "--json",
            "--episodes",
            "3",
            "--set",
            "task.max_time_steps=5",
        ],
        &["run", "--set", "task.max_time_steps=5"],
        &["soak", "--steps", "50"],
        &["bench", "--steps", "20"],
        &["model", "--format", "json"],
        &["model", "--format", "mjcf"],
        &["model", "--format", "urdf"],
        &["--help"],
        &[
            "plot",
            record.to_str().unwrap(),
            "--out",
            plots.to_str().unwrap(),
        ],
    ];
    for args in cases {
        let (status, err) = with_closed_stdout(args);
        assert_eq!(status, Some(0), "hyq {args:?}: {err}");
        assert!(err.is_empty(), "hyq {args:?} printed on stderr: {err}");
    }
}

#[test]
fn a_full_stdout_is_one_error_line() {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_hyq"))
        .args(["run", "--set", "task.max_time_steps=5"])
        .stdout(full)
        .output()
        .unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("hyq: error: cannot write to stdout") && err.contains("No space left"),
        "{err}"
    );
}

/// `hyq args` with its stdout `/dev/full`: status 1 and one line saying stdout could not be
/// written.
#[track_caller]
fn full_stdout_fails(args: &[&str]) {
    let full = std::fs::OpenOptions::new()
        .write(true)
        .open("/dev/full")
        .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_hyq"))
        .args(args)
        .stdout(full)
        .output()
        .unwrap();
    let err = String::from_utf8(out.stderr).unwrap();
    assert_eq!(out.status.code(), Some(1), "hyq {args:?}: {err}");
    assert_eq!(err.lines().count(), 1, "hyq {args:?}: {err}");
    assert!(
        err.starts_with("hyq: error: cannot write to stdout") && !err.contains("panicked"),
        "hyq {args:?}: {err}"
    );
}

#[test]
fn every_command_reports_a_full_stdout() {
    // `model` panicked; `--version`, `--help` and `compare` exited 0 having written nothing.
    let reports = scratch("full-stdout-compare");
    for args in [
        &["model", "--format", "json"][..],
        &["model", "--format", "mjcf"],
        &["--version"],
        &["--help"],
        &["run", "--help"],
        &[
            "compare",
            "--scenario",
            "stand",
            "--backends",
            "rapier,rapier",
            "--seconds",
            "0.05",
            "--out",
            reports.to_str().unwrap(),
        ],
    ] {
        full_stdout_fails(args);
    }
}
