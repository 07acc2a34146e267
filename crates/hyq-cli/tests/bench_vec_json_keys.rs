//! Invariant: `hyq bench --num-envs N --json` (the batched mode `cargo xtask bench-vs-anchors`
//! reads for the vector env's scaling) prints one JSON object with the documented keys, rates
//! consistent with N × steps env steps and the seconds reported, and the pool size asked for;
//! `--threads` without a vector env is a usage error that says so.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{assert_has_keys, hyq_ok, one_json_line};

#[test]
fn batched_bench_json_has_the_documented_keys_and_consistent_numbers() {
    for threads in ["1", "2"] {
        let out = hyq_ok(&[
            "bench",
            "--num-envs",
            "2",
            "--threads",
            threads,
            "--steps",
            "150",
            "--json",
            "--set",
            "task.max_time_steps=50",
        ]);
        let r = one_json_line(&out);
        assert_has_keys(
            &r,
            &[
                "schema_version",
                "workload",
                "backend",
                "profile",
                "num_envs",
                "threads",
                "substeps_per_env_step",
                "seed",
                "steps",
                "env_steps",
                "seconds",
                "cpu_seconds",
                "env_steps_per_s",
                "env_steps_per_s_cpu",
                "resets",
            ],
        );
        assert_eq!(r["schema_version"], 1);
        assert_eq!(r["workload"], "env_random_vec");
        assert_eq!(r["num_envs"], 2);
        assert_eq!(r["threads"].to_string(), threads);
        assert_eq!(r["env_steps"], 300);
        let f = |k: &str| r[k].as_f64().unwrap();
        assert!((f("env_steps_per_s") - 300.0 / f("seconds")).abs() < 1e-6 * f("env_steps_per_s"));
        assert!(
            (f("env_steps_per_s_cpu") - 300.0 / f("cpu_seconds")).abs()
                < 1e-6 * f("env_steps_per_s_cpu")
        );
        // Episodes of 50 steps: each env ends at least twice in 150 vector steps (a step
        // spent on an autoreset does not advance the episode).
        assert!(f("resets") >= 4.0, "{r}");
    }
}

#[test]
fn threads_without_a_vector_env_is_a_usage_error() {
    let out = common::hyq(&["bench", "--threads", "2", "--steps", "10"]);
    assert_eq!(out.status.code(), Some(2), "{out:?}");
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("--threads needs --num-envs"), "{err}");
}
