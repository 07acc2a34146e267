//! Invariant: every command that reads a user's file refuses a FIFO at once with one line
//! `hyq: error: … is not a regular file …` and status 2. Opening a FIFO with no writer used to
//! block `hyq` forever (the configuration, the robot profile and its URDF, a policy, `hyq plot`'s
//! records, `hyq compare`'s ledger). Each command runs with a deadline: a command that waits
//! again is killed and fails the test instead of hanging it.
#![cfg(unix)]
// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

use common::scratch;

/// A FIFO at `path` that no one writes to.
fn mkfifo(path: &Path) {
    let _ = std::fs::remove_file(path);
    let status = Command::new("mkfifo").arg(path).status().unwrap();
    assert!(status.success(), "mkfifo {}", path.display());
}

/// `hyq args…` within 20 s (killed and failed otherwise): its status and stderr.
fn hyq_within_deadline(args: &[&str]) -> (Option<i32>, String) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_hyq"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let start = Instant::now();
    while child.try_wait().unwrap().is_none() {
        if start.elapsed() > Duration::from_secs(20) {
            child.kill().ok();
            child.wait().ok();
            panic!("hyq {args:?} is still waiting after 20 s");
        }
        std::thread::sleep(Duration::from_millis(20));
    }
    let out = child.wait_with_output().unwrap();
    (out.status.code(), String::from_utf8(out.stderr).unwrap())
}

#[test]
fn every_loader_refuses_a_fifo_at_once() {
    let fifo = scratch("fifo-input.toml");
    mkfifo(&fifo);
    let f = fifo.to_str().unwrap();
    let robot_dir = scratch("fifo-robot");
    let _ = std::fs::remove_dir_all(&robot_dir);
    std::fs::create_dir_all(&robot_dir).unwrap();
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/hyq");
    std::fs::copy(assets.join("profile.toml"), robot_dir.join("profile.toml")).unwrap();
    mkfifo(&robot_dir.join("hyq.urdf"));
    let profile = robot_dir.join("profile.toml");
    let out = scratch("fifo-out");
    let policy = format!("mlp:{f}");
    let cases: [&[&str]; 6] = [
        &["run", "--config", f],
        &["run", "--robot", f],
        &["run", "--robot", profile.to_str().unwrap()],
        &["run", "--policy", &policy],
        &["plot", f, "--out", out.to_str().unwrap()],
        &[
            "compare",
            "--scenario",
            "stand",
            "--backends",
            "rapier,rapier",
            "--seconds",
            "0.1",
            "--ledger",
            f,
            "--out",
            out.to_str().unwrap(),
        ],
    ];
    for args in cases {
        let (status, err) = hyq_within_deadline(args);
        assert_eq!(status, Some(2), "hyq {args:?}: {err}");
        assert_eq!(err.lines().count(), 1, "hyq {args:?}: one line, got {err}");
        assert!(
            err.starts_with("hyq: error: ") && err.contains("is not a regular file"),
            "hyq {args:?}: {err}"
        );
    }
}
