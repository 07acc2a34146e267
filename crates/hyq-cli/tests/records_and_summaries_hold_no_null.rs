//! Invariant: `hyq run` never writes `null` where a number belongs, neither in the step record
//! (`--record`) nor in the summary (`--json`): a configuration that could make a number
//! non-finite or undefined (a huge k_exp, a goal so far that D overflows, a goal at the start
//! with r_n and r_e off, so that D_n = D / K is undefined) is refused before the run, as a usage
//! error (status 2) naming the key; every configuration that runs gives numbers.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{first_null, hyq, scratch, stderr, stdout};

/// Runs `hyq run --json --record … <sets>`: either a usage error naming `key`, or every line
/// of the record and of the summary is free of null.
fn refused_or_without_null(name: &str, sets: &[&str], key: &str) -> bool {
    let record = scratch(&format!("{name}.jsonl"));
    let mut args = vec!["run", "--json", "--record", record.to_str().unwrap()];
    for s in sets {
        args.extend(["--set", s]);
    }
    let out = hyq(&args);
    if out.status.code() == Some(2) {
        let err = stderr(&out);
        assert!(
            err.contains(key),
            "{name}: the error does not name {key}: {err}"
        );
        assert_eq!(err.lines().count(), 1, "{err}");
        return true;
    }
    assert!(out.status.success(), "{name}: {}", stderr(&out));
    let text = std::fs::read_to_string(&record).unwrap();
    for (source, body) in [("record", text.as_str()), ("summary", &stdout(&out))] {
        for (i, line) in body.lines().enumerate() {
            let v: serde_json::Value = serde_json::from_str(line).unwrap();
            if let Some(path) = first_null(&v, "") {
                panic!("{name}: {source} line {} holds null at {path}", i + 1);
            }
        }
    }
    false
}

#[test]
fn configurations_that_would_emit_null_are_refused_and_the_rest_give_numbers() {
    let refused = [
        // r_e overflowed to +inf at t = 854, then NaN.
        (
            "k-exp-1000",
            &["task.exp_rew_scaling=1000", "task.max_time_steps=900"][..],
            "task.exp_rew_scaling",
        ),
        // D = inf from the first step: every reward NaN.
        (
            "far-goal",
            &[
                "task.max_time_steps=3",
                "task.exp_rew_scaling=off",
                "task.base_rew_scaling=1",
                "goal.mode=fixed",
                "goal.position=[1e308, 1e308, 0]",
            ][..],
            "goal.position",
        ),
        // K = 0 with r_n and r_e off: D_n undefined, written as null.
        (
            "goal-at-start",
            &[
                "task.max_time_steps=3",
                "task.exp_rew_scaling=off",
                "goal.mode=fixed",
                "goal.position=[0, 0, 0.6003]",
            ][..],
            "goal",
        ),
    ];
    for (name, sets, key) in refused {
        assert!(
            refused_or_without_null(name, sets, key),
            "{name}: expected a usage error naming {key}"
        );
    }
    // The largest accepted values run and give numbers.
    for (name, sets) in [
        (
            "largest-k-exp",
            &["task.exp_rew_scaling=500", "task.max_time_steps=300"][..],
        ),
        (
            "largest-scalings",
            &[
                "task.base_rew_scaling=1e12",
                "task.norm_rew_scaling=1e12",
                "task.fall_penalty=1e12",
                "task.max_time_steps=300",
            ][..],
        ),
        (
            "exp-off",
            &["task.exp_rew_scaling=off", "task.max_time_steps=50"][..],
        ),
    ] {
        assert!(
            !refused_or_without_null(name, sets, "-"),
            "{name} was refused"
        );
    }
}
