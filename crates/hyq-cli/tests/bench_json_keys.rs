//! Invariant: `hyq bench --json` prints one JSON object with the documented, stable keys
//! (`cargo xtask bench-vs-anchors` reads them): the backend, the wall-clock and CPU-time rates
//! (consistent with the steps and seconds reported), the resets and why, and the time shares of
//! physics, actuator, observation, spec evaluation and the rest, which sum to 1.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{assert_has_keys, hyq_ok, one_json_line};

#[test]
fn bench_json_has_the_documented_keys_and_consistent_numbers() {
    let out = hyq_ok(&[
        "bench",
        "--steps",
        "300",
        "--json",
        "--set",
        "task.max_time_steps=100",
    ]);
    let r = one_json_line(&out);
    assert_has_keys(
        &r,
        &[
            "schema_version",
            "workload",
            "backend",
            "profile",
            "action_mode",
            "substeps_per_env_step",
            "dt",
            "seed",
            "steps",
            "seconds",
            "cpu_seconds",
            "env_steps_per_s",
            "env_steps_per_s_cpu",
            "physics_steps_per_s",
            "resets",
            "episodes_ended",
            "shares",
            "timed_pass",
        ],
    );
    assert_eq!(r["schema_version"], 1);
    assert_eq!(r["workload"], "env_random");
    assert_eq!(r["backend"], "rapier");
    assert_eq!(r["action_mode"], "normalized");
    assert_eq!(r["steps"], 300);
    let f = |k: &str| {
        r[k].as_f64()
            .unwrap_or_else(|| panic!("{k} is not a number"))
    };
    assert!((f("env_steps_per_s") - 300.0 / f("seconds")).abs() < 1e-6 * f("env_steps_per_s"));
    assert!(
        (f("env_steps_per_s_cpu") - 300.0 / f("cpu_seconds")).abs()
            < 1e-6 * f("env_steps_per_s_cpu")
    );
    assert!(f("env_steps_per_s") > 0.0 && f("env_steps_per_s_cpu") > 0.0);
    assert!(
        (f("physics_steps_per_s") - 10.0 * f("env_steps_per_s")).abs()
            < 1e-6 * f("physics_steps_per_s")
    );
    // t_max = 100 and 300 steps: at least two timeouts (or earlier ends), each reset.
    assert!(r["resets"].as_u64().unwrap() >= 2);
    let ended = &r["episodes_ended"];
    let total: u64 = ["reached", "joint_limit", "fell", "timeout", "diverged"]
        .iter()
        .map(|k| {
            ended[*k]
                .as_u64()
                .unwrap_or_else(|| panic!("episodes_ended.{k}"))
        })
        .sum();
    assert!(total >= r["resets"].as_u64().unwrap());
    let shares = &r["shares"];
    let sum: f64 = ["physics", "actuator", "observation", "spec", "other"]
        .iter()
        .map(|k| shares[*k].as_f64().unwrap_or_else(|| panic!("shares.{k}")))
        .sum();
    assert!((sum - 1.0).abs() < 1e-9, "shares sum to {sum}");
    assert!(
        shares["physics"].as_f64().unwrap() > 0.5,
        "the engine dominates: {shares}"
    );
    assert!(r["timed_pass"]["env_steps_per_s"].as_f64().unwrap() > 0.0);
}

#[test]
fn bench_text_names_the_rates() {
    let out = hyq_ok(&["bench", "--steps", "50"]);
    assert!(
        out.contains("env steps/s (wall)") && out.contains("env steps/s (CPU)"),
        "{out}"
    );
    assert!(out.contains("physics") && out.contains("spec"), "{out}");
}
