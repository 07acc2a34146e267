//! Invariant: bad input to `hyq compare` (an unknown scenario or backend, seconds that are not
//! a positive number, an unwritable `--out`, a bad ledger or override, DART asked for in a build
//! without it) prints exactly one line `hyq: error: …` naming the value, nothing on stdout, exits
//! with status 2, and is caught before any simulation runs.

#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq, scratch, stderr, stdout};

/// The `--out` of the calls refused before any output: a path that exists on no machine.
const OUT: &str = "/nonexistent/out";

fn usage_error(args: &[&str]) -> String {
    let out = hyq(args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "hyq {args:?}: {err}");
    assert!(stdout(&out).is_empty(), "hyq {args:?}: {}", stdout(&out));
    assert_eq!(err.lines().count(), 1, "hyq {args:?}:\n{err}");
    assert!(err.starts_with("hyq: error: "), "{err}");
    err
}

fn compare(extra: &[&str]) -> Vec<String> {
    let out = scratch("compare_bad_input_out");
    let mut args: Vec<String> = [
        "compare",
        "--backends",
        "rapier,rapier",
        "--scenario",
        "stand",
    ]
    .iter()
    .map(|s| s.to_string())
    .collect();
    if !extra.contains(&"--out") {
        args.extend(["--out".to_owned(), out.display().to_string()]);
    }
    args.extend(extra.iter().map(|s| s.to_string()));
    args
}

fn usage_error_of(extra: &[&str]) -> String {
    let args = compare(extra);
    let refs: Vec<&str> = args.iter().map(String::as_str).collect();
    usage_error(&refs)
}

#[test]
fn unknown_scenario_and_backend_are_named() {
    let e = usage_error(&["compare", "--scenario", "moonwalk", "--out", OUT]);
    assert!(
        e.contains("moonwalk") && e.contains("stand") && e.contains("reach"),
        "{e}"
    );
    let e = usage_error(&[
        "compare",
        "--backends",
        "rapier,bullet",
        "--scenario",
        "stand",
        "--out",
        OUT,
    ]);
    assert!(
        e.contains("bullet") && e.contains("rapier, dart, mujoco"),
        "{e}"
    );
    let e = usage_error(&[
        "compare",
        "--backends",
        "rapier",
        "--scenario",
        "stand",
        "--out",
        OUT,
    ]);
    assert!(e.contains("two backends"), "{e}");
}

#[test]
fn seconds_must_be_a_positive_number() {
    for bad in ["0", "-1", "nan", "abc", "1e9"] {
        let arg = format!("--seconds={bad}");
        let e = usage_error(&["compare", "--scenario", "stand", &arg, "--out", OUT]);
        assert!(e.contains(bad) || e.contains("NaN"), "{bad}: {e}");
        assert!(e.contains("--seconds"), "{e}");
    }
}

#[test]
fn an_unwritable_out_dir_is_named_before_anything_runs() {
    let file = scratch("compare_out_is_a_file");
    std::fs::write(&file, "not a directory").unwrap();
    let inside = file.join("reports");
    let e = usage_error_of(&["--out", inside.to_str().unwrap()]);
    assert!(
        e.contains("--out") && e.contains(inside.to_str().unwrap()),
        "{e}"
    );
}

#[test]
fn bad_ledger_and_overrides_are_named() {
    let e = usage_error_of(&["--ledger", "/nonexistent/ledger.toml"]);
    assert!(e.contains("/nonexistent/ledger.toml"), "{e}");
    let ledger = scratch("compare_bad_ledger.toml");
    std::fs::write(&ledger, "[default]\nreturn_diff = 1\n").unwrap();
    let e = usage_error_of(&["--ledger", ledger.to_str().unwrap()]);
    assert!(e.contains("[default] has no tolerance for"), "{e}");
    let e = usage_error_of(&["--set-b", "physics.gravity"]);
    assert!(
        e.contains("physics.gravity") && e.contains("KEY=VALUE"),
        "{e}"
    );
    let e = usage_error_of(&["--set", "physics.no_such_key=1"]);
    assert!(e.contains("no_such_key"), "{e}");
    // The same actions cannot be fed to both sides in delta mode, and the run length is
    // --seconds, not t_max.
    let e = usage_error_of(&["--set", "action.mode=delta"]);
    assert!(e.contains("delta"), "{e}");
    let e = usage_error_of(&["--set-b", "task.max_time_steps=7"]);
    assert!(
        e.contains("max_time_steps=7") && e.contains("seconds"),
        "{e}"
    );
}

#[cfg(not(feature = "dart"))]
#[test]
fn dart_without_the_feature_says_how_to_build_it() {
    let e = usage_error(&[
        "compare",
        "--backends",
        "rapier,dart",
        "--scenario",
        "trot",
        "--out",
        OUT,
    ]);
    assert!(e.contains("--backends rapier,dart"), "{e}");
    assert!(e.contains("--features dart"), "{e}");
    assert!(e.contains("apt-get install"), "{e}");
}

#[cfg(not(feature = "mujoco"))]
#[test]
fn mujoco_without_the_feature_says_how_to_build_it() {
    let e = usage_error(&[
        "compare",
        "--backends",
        "rapier,mujoco",
        "--scenario",
        "trot",
        "--out",
        "/nonexistent/x",
    ]);
    assert!(e.contains("--backends rapier,mujoco"), "{e}");
    assert!(e.contains("--features mujoco"), "{e}");
    assert!(e.contains("cargo xtask setup mujoco"), "{e}");
}
