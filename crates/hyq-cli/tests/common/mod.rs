//! Helpers shared by the CLI tests: run the built `hyq` binary as a process, and scratch files.
#![allow(dead_code)]

use std::path::PathBuf;
use std::process::{Command, Output};

/// The output of `hyq args…`, run as a process with no terminal (no progress bar).
pub fn hyq(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hyq"))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run hyq: {e}"))
}

/// stdout as text.
pub fn stdout(out: &Output) -> String {
    String::from_utf8(out.stdout.clone()).expect("stdout is UTF-8")
}

/// stderr as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8(out.stderr.clone()).expect("stderr is UTF-8")
}

/// `hyq args…`, which must succeed; returns stdout.
pub fn hyq_ok(args: &[&str]) -> String {
    let out = hyq(args);
    assert!(
        out.status.success(),
        "hyq {args:?} failed ({}): {}",
        out.status,
        stderr(&out)
    );
    stdout(&out)
}

/// A fresh path in this test target's scratch directory (the file is removed if it exists).
pub fn scratch(name: &str) -> PathBuf {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_file(&path);
    path
}
