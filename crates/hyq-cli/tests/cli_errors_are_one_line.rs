//! Invariant: bad input to `hyq` (an unknown option or subcommand, an unknown configuration key,
//! an invalid value, an unreadable or unwritable file, a malformed `--set`, a backend not built
//! in) never panics: it prints exactly one line, `hyq: error: …`, on stderr, naming what was
//! wrong, prints nothing on stdout, and exits with a non-zero status.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq, scratch, stderr, stdout};

/// Runs `hyq args`, checks the one-line error contract, and returns the error line.
fn one_line_error(args: &[&str]) -> String {
    let out = hyq(args);
    let err = stderr(&out);
    assert!(
        !out.status.success(),
        "hyq {args:?} succeeded: {}",
        stdout(&out)
    );
    assert!(
        matches!(out.status.code(), Some(1) | Some(2)),
        "hyq {args:?}: exit status {:?} (a panic exits with 101)",
        out.status.code()
    );
    assert!(
        stdout(&out).is_empty(),
        "hyq {args:?} printed on stdout: {}",
        stdout(&out)
    );
    assert!(!err.contains("panicked"), "hyq {args:?} panicked: {err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(
        lines.len(),
        1,
        "hyq {args:?}: expected one error line, got:\n{err}"
    );
    assert!(lines[0].starts_with("hyq: error: "), "{}", lines[0]);
    lines[0].to_owned()
}

fn assert_names(line: &str, words: &[&str]) {
    for w in words {
        assert!(line.contains(w), "the error does not name `{w}`: {line}");
    }
}

#[test]
fn unknown_option_and_subcommand() {
    let line = one_line_error(&["run", "--episodez", "2"]);
    assert_names(&line, &["--episodez"]);
    let line = one_line_error(&["walk"]);
    assert_names(&line, &["walk"]);
}

#[test]
fn invalid_option_values() {
    let line = one_line_error(&["run", "--policy", "moonwalk"]);
    assert_names(&line, &["moonwalk", "--policy", "stand", "random", "trot"]);
    let line = one_line_error(&["run", "--episodes", "0"]);
    assert_names(&line, &["0", "--episodes"]);
    let line = one_line_error(&["bench", "--steps", "many"]);
    assert_names(&line, &["many", "--steps"]);
    let line = one_line_error(&["run", "--backend", "bullet"]);
    assert_names(&line, &["bullet", "rapier", "dart"]);
}

#[test]
fn unknown_configuration_keys() {
    let line = one_line_error(&["run", "--set", "task.fall_penalti=1"]);
    assert_names(&line, &["task.fall_penalti", "fall_penalti"]);
    let line = one_line_error(&["run", "--set", "tusk.fall_penalty=1"]);
    assert_names(&line, &["tusk"]);

    let path = scratch("unknown_key.toml");
    std::fs::write(&path, "[task]\nfall_penalty = 1.0\nwalk_faster = true\n").unwrap();
    let line = one_line_error(&["run", "--config", path.to_str().unwrap()]);
    assert_names(&line, &["walk_faster", "unknown_key.toml"]);
}

#[test]
fn invalid_configuration_values() {
    let line = one_line_error(&["run", "--set", "task.fall_penalty=-1"]);
    assert_names(&line, &["fall_penalty", "-1"]);
    let line = one_line_error(&["run", "--set", "task.max_time_steps=0"]);
    assert_names(&line, &["max_time_steps", "0"]);
    let line = one_line_error(&[
        "bench",
        "--steps",
        "10",
        "--set",
        "control.sim_steps_per_env_step=0",
    ]);
    assert_names(&line, &["sim_steps_per_env_step", "0"]);
    let line = one_line_error(&["run", "--set", "goal.distance_m=fast"]);
    assert_names(&line, &["goal.distance_m", "fast"]);

    let path = scratch("bad_value.toml");
    std::fs::write(&path, "[reset]\nyaw_deg = 400.0\n").unwrap();
    let line = one_line_error(&["run", "--config", path.to_str().unwrap()]);
    assert_names(&line, &["reset.yaw_deg", "400"]);

    let path = scratch("not_toml.toml");
    std::fs::write(&path, "[task\nfall_penalty = \n").unwrap();
    let line = one_line_error(&["soak", "--steps", "1", "--config", path.to_str().unwrap()]);
    assert_names(&line, &["not_toml.toml"]);
}

#[test]
fn malformed_set_syntax() {
    let line = one_line_error(&["run", "--set", "task.fall_penalty"]);
    assert_names(&line, &["--set", "task.fall_penalty", "TABLE.KEY=VALUE"]);
    let line = one_line_error(&["run", "--set", "=3"]);
    assert_names(&line, &["--set", "=3"]);
    let line = one_line_error(&["run", "--set", "fall_penalty=3"]);
    assert_names(&line, &["fall_penalty", "table.name"]);
}

#[test]
fn unreadable_and_unwritable_files() {
    let missing = scratch("does_not_exist.toml");
    let line = one_line_error(&["run", "--config", missing.to_str().unwrap()]);
    assert_names(&line, &["does_not_exist.toml"]);

    let dir = scratch("a_directory.toml");
    let _ = std::fs::remove_dir(&dir);
    std::fs::create_dir(&dir).unwrap();
    let line = one_line_error(&["run", "--config", dir.to_str().unwrap()]);
    assert_names(&line, &["a_directory.toml"]);

    let nowhere = scratch("no_such_dir").join("steps.jsonl");
    let line = one_line_error(&["run", "--record", nowhere.to_str().unwrap()]);
    assert_names(&line, &["--record", "steps.jsonl"]);
}

#[cfg(not(feature = "dart"))]
#[test]
fn dart_backend_not_built_says_how_to_build_it() {
    for sub in [
        &["run"][..],
        &["bench", "--steps", "1"],
        &["soak", "--steps", "1"],
    ] {
        let mut args = sub.to_vec();
        args.extend(["--backend", "dart"]);
        let line = one_line_error(&args);
        assert_names(&line, &["dart", "--features dart", "cargo build"]);
    }
}

#[cfg(not(feature = "mujoco"))]
#[test]
fn mujoco_backend_not_built_says_how_to_build_it() {
    for sub in [
        &["run"][..],
        &["bench", "--steps", "1"],
        &["soak", "--steps", "1"],
    ] {
        let mut args = sub.to_vec();
        args.extend(["--backend", "mujoco"]);
        let line = one_line_error(&args);
        assert_names(
            &line,
            &["mujoco", "--features mujoco", "cargo xtask setup mujoco"],
        );
    }
}
