//! Invariant: `--policy mlp:FILE` replays a trained policy file in the environment it was
//! trained in (its metadata's action mode and reward settings apply unless `--config` or
//! `--set` sets the key), gives the same episodes bit for bit on every run, and refuses a bad
//! file (missing, of another format, trained for another layout or action mode, holding a
//! non-finite weight) with one line naming the file and the mismatch, exit status 2, before
//! anything runs or any output is written.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{
    committed_policy, edited_policy, hyq, hyq_ok, policy_arg, scratch, stderr, stdout,
    usage_error_naming,
};

fn short_run(policy: &str, extra: &[&str]) -> String {
    let mut args = vec![
        "run",
        "--policy",
        policy,
        "--seed",
        "3",
        "--set",
        "task.max_time_steps=150",
        "--set",
        "reset.joint_noise_rad=0.05",
        "--json",
    ];
    args.extend_from_slice(extra);
    hyq_ok(&args)
}

#[test]
fn the_committed_policy_replays_the_same_episode_bit_for_bit() {
    let policy = policy_arg(&committed_policy());
    let first = short_run(&policy, &[]);
    let second = short_run(&policy, &[]);
    assert_eq!(first, second);
    let summary: serde_json::Value = serde_json::from_str(first.trim()).unwrap();
    assert_eq!(summary["policy"], "mlp");
    assert_eq!(summary["steps"], 150, "{summary}");
    // The policy moves the trunk: it is not standing still.
    let moved = summary["final_position"][0].as_f64().unwrap()
        - summary["initial_position"][0].as_f64().unwrap();
    let dy = summary["final_position"][1].as_f64().unwrap()
        - summary["initial_position"][1].as_f64().unwrap();
    assert!(moved.hypot(dy) > 0.05, "{summary}");
}

#[test]
fn the_trained_environment_applies_unless_the_user_sets_a_key() {
    let policy = policy_arg(&committed_policy());
    // The file says fall_penalty = 5 and the offset action mode: the run works without any
    // --set, which it could not in the default normalized mode (the check would refuse it).
    let inherited = short_run(&policy, &[]);
    // A key the user sets wins over the file's: the normalised reward's scale 1 instead of the
    // file's 10 scales r_n by a tenth on the same trajectory (rewards do not move the robot).
    let overridden = short_run(&policy, &["--set", "task.norm_rew_scaling=1"]);
    let a: serde_json::Value = serde_json::from_str(inherited.trim()).unwrap();
    let b: serde_json::Value = serde_json::from_str(overridden.trim()).unwrap();
    assert_eq!(a["final_position"], b["final_position"]);
    let (r_a, r_b) = (
        a["terms"]["r_n"].as_f64().unwrap(),
        b["terms"]["r_n"].as_f64().unwrap(),
    );
    assert!(r_a.abs() > 1e-3, "{a}");
    assert!((r_b * 10.0 - r_a).abs() <= 1e-9 * r_a.abs(), "{r_a} {r_b}");
    // The same through a --config file.
    let config = scratch("norm_one.toml");
    std::fs::write(&config, "[task]\nnorm_rew_scaling = 1.0\n").unwrap();
    let from_file = short_run(&policy, &["--config", config.to_str().unwrap()]);
    assert_eq!(from_file, overridden);
}

#[test]
fn a_missing_file_or_another_format_is_refused_naming_the_file() {
    let missing = scratch("no_such_policy.safetensors");
    let arg = policy_arg(&missing);
    usage_error_naming(
        &["run", "--policy", &arg],
        &["no_such_policy.safetensors", "cannot read"],
    );
    let text = scratch("policy.txt");
    std::fs::write(&text, "not a policy\n").unwrap();
    let arg = policy_arg(&text);
    usage_error_naming(&["run", "--policy", &arg], &["policy.txt", "safetensors"]);
    let gif = scratch("refused.gif");
    usage_error_naming(
        &["render", "--policy", &arg, "--out", gif.to_str().unwrap()],
        &["policy.txt"],
    );
    assert!(!gif.exists(), "a refused render wrote its output");
    let out = hyq(&["run", "--policy", "mlp:"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
}

#[test]
fn a_mismatched_layout_or_action_mode_is_refused_before_anything_is_written() {
    let policy = policy_arg(&committed_policy());
    let record = scratch("refused.jsonl");
    usage_error_naming(
        &[
            "run",
            "--policy",
            &policy,
            "--set",
            "action.mode=\"normalized\"",
            "--record",
            record.to_str().unwrap(),
        ],
        &[
            "hyq_walk.safetensors",
            "action.mode",
            "offset",
            "normalized",
        ],
    );
    assert!(!record.exists(), "a refused run wrote its record");
    usage_error_naming(
        &[
            "run",
            "--policy",
            &policy,
            "--set",
            "action.max_offset_rad=0.3",
        ],
        &["hyq_walk.safetensors", "max_offset_rad", "0.5", "0.3"],
    );

    let other_robot = edited_policy("other_robot.safetensors", |h, _| {
        h["__metadata__"]["robot"] = "anymal".into();
    });
    usage_error_naming(
        &["run", "--policy", &policy_arg(&other_robot)],
        &["other_robot.safetensors", "anymal"],
    );
    let swapped = edited_policy("swapped_joints.safetensors", |h, _| {
        let joints: Vec<String> =
            serde_json::from_str(h["__metadata__"]["action"].as_str().unwrap()).unwrap();
        let mut swapped = joints.clone();
        swapped.swap(0, 1);
        h["__metadata__"]["action"] = serde_json::to_string(&swapped).unwrap().into();
    });
    usage_error_naming(
        &["run", "--policy", &policy_arg(&swapped)],
        &["swapped_joints.safetensors", "action value 0"],
    );
}

#[test]
fn a_non_finite_weight_is_refused_naming_the_tensor() {
    let nan = edited_policy("nan_weight.safetensors", |h, data| {
        let start = h["layers.0.weight"]["data_offsets"][0].as_u64().unwrap() as usize;
        data[start + 4..start + 8].copy_from_slice(&f32::NAN.to_le_bytes());
    });
    let out = hyq(&["run", "--policy", &policy_arg(&nan)]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(stdout(&out).is_empty());
    let err = stderr(&out);
    assert_eq!(err.lines().count(), 1, "{err}");
    for word in ["nan_weight.safetensors", "layers.0.weight", "non-finite"] {
        assert!(err.contains(word), "`{word}` not in: {err}");
    }
}

#[test]
fn bench_runs_the_trained_policy_closed_loop_in_its_environment() {
    let policy = policy_arg(&committed_policy());
    let out = hyq_ok(&["bench", "--policy", &policy, "--steps", "200", "--json"]);
    let report: serde_json::Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(report["workload"], "env_mlp", "{report}");
    assert_eq!(report["action_mode"], "offset", "{report}");
    assert_eq!(report["steps"], 200, "{report}");
    assert!(
        report["env_steps_per_s"].as_f64().unwrap() > 0.0,
        "{report}"
    );
    usage_error_naming(
        &["bench", "--policy", &policy, "--num-envs", "2"],
        &["--num-envs", "one env"],
    );
    usage_error_naming(
        &["bench", "--policy", "trot"],
        &["trot", "random", "mlp:FILE"],
    );
    let text = scratch("bench_policy.txt");
    std::fs::write(&text, "not a policy\n").unwrap();
    usage_error_naming(
        &["bench", "--policy", &policy_arg(&text)],
        &["bench_policy.txt", "safetensors"],
    );
}
