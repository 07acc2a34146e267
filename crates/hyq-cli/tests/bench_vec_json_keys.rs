//! Invariant: `hyq bench --num-envs N --json` (the batched mode `cargo xtask bench-vs-anchors`
//! reads for the vector env's scaling) prints one JSON object with the documented keys, rates
//! consistent with N × steps env steps and the seconds reported, and the pool size asked for;
//! `--threads` without a vector env is a usage error that says so. `--backends A,B,...` benches
//! a mix of engines and names it; a bad mix is a one-line usage error.

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

/// `--backends A,B,...`: one vector env whose env i runs on the (i mod length)-th engine; the
/// report names the list. Run on every engine this build has (rapier always, DART with
/// `--features dart`, MuJoCo with `--features mujoco`).
#[test]
fn a_mix_of_every_built_engine_is_benched_and_named() {
    let names: Vec<&str> = hyq_engines::built().map(|e| e.name).collect();
    let list = names.join(",");
    let n = (2 * names.len()).to_string();
    let out = hyq_ok(&[
        "bench",
        "--backends",
        &list,
        "--num-envs",
        &n,
        "--threads",
        "2",
        "--steps",
        "40",
        "--json",
        "--set",
        "task.max_time_steps=15",
    ]);
    let r = one_json_line(&out);
    assert_eq!(r["backend"], list.as_str());
    assert_eq!(r["num_envs"].to_string(), n);
    assert_eq!(r["env_steps"].as_u64(), Some(40 * 2 * names.len() as u64));
    assert!(
        r["resets"].as_u64().unwrap() >= 2 * names.len() as u64,
        "{r}"
    );
    assert!(cfg!(feature = "dart") == names.contains(&"dart"));
    assert!(cfg!(feature = "mujoco") == names.contains(&"mujoco"));
}

/// A list with an engine this build lacks is the one-line not-built error `--backend` gives;
/// an unknown name, too few envs, --backend beside it and --policy are usage errors.
#[test]
fn bad_mixes_are_one_line_usage_errors() {
    let default = hyq_engines::DEFAULT.name;
    for engine in hyq_engines::ENGINES.iter().filter(|e| !e.built) {
        let list = format!("{default},{}", engine.name);
        let err = fails(&["bench", "--backends", &list, "--num-envs", "2"]);
        assert!(
            err.contains(&format!("--backends {list}: this hyq was built without")),
            "{err}"
        );
        assert!(
            err.contains(&format!("--features {}", engine.name)),
            "{err}"
        );
    }
    let err = fails(&[
        "bench",
        "--backends",
        &format!("{default},bullet"),
        "--num-envs",
        "2",
    ]);
    assert!(err.contains("unknown backend \"bullet\""), "{err}");
    let err = fails(&[
        "bench",
        "--backends",
        &format!("{default},{default}"),
        "--num-envs",
        "1",
    ]);
    assert!(err.contains("--num-envs of at least 2"), "{err}");
    let err = fails(&["bench", "--backends", default, "--backend", default]);
    assert!(err.contains("--backend"), "{err}");
    let policy = common::policy_arg(&common::committed_policy());
    let err = fails(&["bench", "--backends", default, "--policy", &policy]);
    assert!(err.contains("leave out --backends"), "{err}");
}

/// Runs `hyq args`, expecting the usage status and one line on stderr, which it returns.
fn fails(args: &[&str]) -> String {
    let out = common::hyq(args);
    assert_eq!(out.status.code(), Some(2), "{args:?}: {out:?}");
    let err = String::from_utf8_lossy(&out.stderr).into_owned();
    assert_eq!(err.trim_end().lines().count(), 1, "{args:?}: {err}");
    err
}
