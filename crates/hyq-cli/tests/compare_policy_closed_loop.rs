//! Invariant: `hyq compare --policy mlp:FILE` runs a trained policy closed loop on every backend
//! given, each episode exactly as `hyq run --policy mlp:FILE --episodes N --seed S` runs it on
//! that backend, in the environment the policy file names unless `--config` or `--set` sets a
//! key; it writes report.md, report.json and trunk_x_z.png, the same bytes for the same command;
//! the first backend's actions replayed open loop reproduce its own run exactly; and a bad
//! policy file (missing, another format, another layout or action mode, a non-finite weight) is
//! one line naming the file, exit status 2, before anything runs or the output directory is made.
//! With `[randomize]` on (`--set randomize.*`), every engine draws what `hyq run` draws, and the
//! report says so and counts each engine's falls and pushes; off, neither report nor summary
//! mentions it.

#![allow(clippy::unwrap_used)]

mod common;

use std::path::{Path, PathBuf};

use common::{
    committed_policy, edited_policy, hyq, hyq_ok, policy_arg, scratch, stderr, stdout,
    usage_error_naming,
};
use serde_json::Value;

fn fresh_dir(name: &str) -> PathBuf {
    let dir = scratch(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn read_json(dir: &Path) -> Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap()
}

/// A short self-comparison of the committed policy (120 steps, 2 episodes, reset noise on so
/// that the episodes differ), with `extra` arguments, into `dir`.
/// The short comparison's episodes: two of 120 steps from seed 7, with reset noise.
const EPISODES: [&str; 8] = [
    "--episodes",
    "2",
    "--seed",
    "7",
    "--set",
    "task.max_time_steps=120",
    "--set",
    "reset.joint_noise_rad=0.05",
];

/// `hyq run --json` of the committed policy over the short comparison's [`EPISODES`] with
/// `extra` arguments: one summary per episode.
fn hyq_run_json(extra: &[&str]) -> Vec<Value> {
    let policy = policy_arg(&committed_policy());
    let mut args = vec!["run", "--policy", &policy, "--json"];
    args.extend_from_slice(&EPISODES);
    args.extend_from_slice(extra);
    hyq_ok(&args)
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect()
}

fn short_compare(dir: &Path, extra: &[&str]) -> String {
    let policy = policy_arg(&committed_policy());
    let mut args = vec![
        "compare",
        "--backends",
        "rapier,rapier",
        "--policy",
        &policy,
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(&EPISODES);
    args.extend_from_slice(extra);
    hyq_ok(&args)
}

#[test]
fn each_backend_runs_the_episodes_hyq_run_runs_and_the_report_is_written() {
    let dir = fresh_dir("compare_policy_report");
    let out = short_compare(&dir, &[]);
    assert!(out.contains("not judged against the ledger"), "{out}");
    for file in ["report.md", "report.json", "trunk_x_z.png"] {
        assert!(dir.join(file).is_file(), "{file} not written");
    }
    let json = read_json(&dir);
    assert_eq!(json["robot"], "hyq");
    assert_eq!(json["episodes"], 2);
    assert_eq!(json["max_steps"], 120);
    let sides = json["sides"].as_array().unwrap();
    assert_eq!(sides.len(), 2);
    assert_eq!(sides[1]["label"], "rapier (B)");

    // The same episodes as `hyq run`, to the bit (JSON numbers round-trip f64 exactly).
    let runs = hyq_run_json(&[]);
    for side in sides {
        let episodes = side["episodes"].as_array().unwrap();
        assert_eq!(episodes.len(), 2);
        for (e, r) in episodes.iter().zip(&runs) {
            assert_eq!(e["return"], r["return"], "{e} vs {r}");
            assert_eq!(e["steps"], r["steps"]);
            assert_eq!(e["end_reasons"], r["reasons"]);
            assert_eq!(e["final_distance_m"], r["final_distance_to_goal"]);
            assert_eq!(e["final_position"], r["final_position"]);
        }
    }
    // Reset noise makes the two episodes differ: the second is not a copy of the first.
    let e = sides[0]["episodes"].as_array().unwrap();
    assert_ne!(e[0]["final_position"], e[1]["final_position"]);
    // The policy walks in 1.2 s: the trunk travels toward the goal.
    assert!(e[0]["travel_m"].as_f64().unwrap() > 0.3, "{}", e[0]);

    // One engine against itself: no gap at all, and the open-loop replay of the first
    // backend's actions gives back its run exactly.
    let pair = &json["pairs"][0];
    assert_eq!(pair["trunk_position"]["max"], 0.0, "{pair}");
    // Never apart: the key is absent (the reports hold no null).
    assert!(pair.get("apart_1cm_s").is_none(), "{pair}");
    assert_eq!(common::first_null(&json, "report"), None);
    let replay = &json["replay"];
    assert_eq!(replay["source"], "rapier");
    assert_eq!(replay["actions"], 120);
    for run in replay["runs"].as_array().unwrap() {
        assert_eq!(run["trunk_position"]["max"], 0.0, "{run}");
        assert_eq!(run["steps"], 120);
    }

    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    for section in [
        "# Policy comparison: rapier vs rapier (B)",
        "**Not judged against the ledger.**",
        "## Per engine (2 episodes each)",
        "## Per pair",
        "## Open loop: rapier's actions replayed",
        "## Episodes",
        "trunk_x_z.png",
    ] {
        assert!(md.contains(section), "report.md lacks {section:?}");
    }
    // `[randomize]` off: the reports and the summaries say nothing of it.
    let written = std::fs::read_to_string(dir.join("report.json")).unwrap();
    let run = serde_json::to_string(&runs).unwrap();
    for text in [&md, &written, &run, &out] {
        assert!(!text.to_lowercase().contains("randomi"), "{text}");
    }
    let png = std::fs::read(dir.join("trunk_x_z.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
}

/// The randomisation the comparison's tests turn on: a friction, mass and gain draw, a delay,
/// and pushes.
const RANDOMIZED: [&str; 12] = [
    "--set",
    "randomize.ground_friction=[0.5, 1.25]",
    "--set",
    "randomize.trunk_added_mass_kg=[-5.0, 5.0]",
    "--set",
    "randomize.kp_scale=[0.9, 1.1]",
    "--set",
    "randomize.actuator_delay_substeps=[0, 2]",
    "--set",
    "randomize.push_interval_s=[0.3, 0.5]",
    "--set",
    "randomize.push_velocity_xy_mps=[0.5, 0.5]",
];

#[test]
fn with_randomisation_every_engine_draws_what_hyq_run_draws() {
    let dir = fresh_dir("compare_policy_randomized");
    let out = short_compare(&dir, &RANDOMIZED);
    let json = read_json(&dir);
    let sides = json["sides"].as_array().unwrap();
    let runs = hyq_run_json(&RANDOMIZED);
    assert_eq!(json["drew_alike"], true);
    for side in sides {
        let episodes = side["episodes"].as_array().unwrap();
        for (e, r) in episodes.iter().zip(&runs) {
            assert!(r["randomize"]["pushes"].as_u64().unwrap() >= 2, "{r}");
            assert_eq!(e["randomize"], r["randomize"], "the run's draws and pushes");
            assert_eq!(e["return"], r["return"]);
        }
        // The fall count is the episodes whose reasons hold `fell`.
        let fell = episodes
            .iter()
            .filter(|e| {
                e["end_reasons"]
                    .as_array()
                    .unwrap()
                    .contains(&"fell".into())
            })
            .count();
        let randomized = &side["randomized"];
        assert_eq!(randomized["fell"], fell, "{randomized}");
        assert_eq!(randomized["fall_rate_pct"], 50.0 * fell as f64);
        let pushes: u64 = runs
            .iter()
            .map(|r| r["randomize"]["pushes"].as_u64().unwrap())
            .sum();
        assert_eq!(randomized["pushes_mean"], pushes as f64 / 2.0);
    }
    let e = sides[0]["episodes"].as_array().unwrap();
    assert_ne!(
        e[0]["randomize"], e[1]["randomize"],
        "each episode draws anew"
    );
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(
        md.contains("every engine drew the same values in each episode"),
        "{md}"
    );
    assert!(
        md.contains("| fell (episodes ending with `fell`) |"),
        "{md}"
    );
    assert!(
        out.contains("randomised: every engine drew the same values"),
        "{out}"
    );
    assert!(out.contains(" pushes per episode"), "{out}");
    for run in json["replay"]["runs"].as_array().unwrap() {
        assert_eq!(
            run["trunk_position"]["max"], 0.0,
            "the replay draws alike: {run}"
        );
    }
}

#[test]
fn the_same_command_writes_the_same_bytes() {
    let dir = fresh_dir("compare_policy_twice");
    let read = |dir: &Path| {
        ["report.md", "report.json", "trunk_x_z.png"].map(|f| std::fs::read(dir.join(f)).unwrap())
    };
    short_compare(&dir, &["--set", "reset.yaw_noise_deg=5"]);
    let first = read(&dir);
    std::fs::remove_dir_all(&dir).unwrap();
    short_compare(&dir, &["--set", "reset.yaw_noise_deg=5"]);
    assert!(first == read(&dir), "a second run wrote other bytes");
}

#[test]
fn the_policy_files_environment_applies_unless_the_user_sets_a_key() {
    let inherited = fresh_dir("compare_policy_inherited");
    short_compare(&inherited, &[]);
    let a = read_json(&inherited);
    // The file's configuration is listed as applied, and it is what ran: the offset action
    // mode (the default normalized mode would be refused by the policy's check).
    let configuration: Vec<&str> = a["configuration"]
        .as_array()
        .unwrap()
        .iter()
        .map(|c| c.as_str().unwrap())
        .collect();
    for entry in [
        "action.mode=\"offset\" (the policy file)",
        "task.norm_rew_scaling=10.0 (the policy file)",
        "task.max_time_steps=120 (--set)",
    ] {
        assert!(configuration.contains(&entry), "{configuration:?}");
    }
    // A key the user sets wins: k_norm 1 instead of the file's 10 changes the return, not the
    // motion (rewards do not move the robot).
    let overridden = fresh_dir("compare_policy_overridden");
    short_compare(&overridden, &["--set", "task.norm_rew_scaling=1"]);
    let b = read_json(&overridden);
    let listed = b["configuration"].to_string();
    assert!(!listed.contains("norm_rew_scaling=10.0"), "{listed}");
    assert!(
        listed.contains("task.norm_rew_scaling=1 (--set)"),
        "{listed}"
    );
    let (ea, eb) = (&a["sides"][0]["episodes"][0], &b["sides"][0]["episodes"][0]);
    assert_eq!(ea["final_position"], eb["final_position"]);
    assert_ne!(ea["return"], eb["return"]);
    // The same through a --config file.
    let config = scratch("compare_norm_one.toml");
    std::fs::write(&config, "[task]\nnorm_rew_scaling = 1.0\n").unwrap();
    let from_file = fresh_dir("compare_policy_config_file");
    short_compare(&from_file, &["--config", config.to_str().unwrap()]);
    assert_eq!(read_json(&from_file)["sides"], b["sides"]);
}

/// `hyq compare --policy FILE …` must fail as a usage error naming `words`, print nothing on
/// stdout, and leave no output directory behind.
fn refused(name: &str, policy: &Path, extra: &[&str], words: &[&str]) {
    let dir = fresh_dir(name);
    let arg = policy_arg(policy);
    let mut args = vec![
        "compare",
        "--backends",
        "rapier,rapier",
        "--policy",
        &arg,
        "--out",
        dir.to_str().unwrap(),
    ];
    args.extend_from_slice(extra);
    usage_error_naming(&args, words);
    assert!(stdout(&hyq(&args)).is_empty());
    assert!(!dir.exists(), "a refused comparison made {}", dir.display());
}

#[test]
fn a_bad_policy_file_is_refused_naming_it_before_anything_runs() {
    refused(
        "refused_missing",
        &scratch("no_such_policy.safetensors"),
        &[],
        &["no_such_policy.safetensors", "cannot read"],
    );
    let text = scratch("compare_policy.txt");
    std::fs::write(&text, "not a policy\n").unwrap();
    refused(
        "refused_format",
        &text,
        &[],
        &["compare_policy.txt", "safetensors"],
    );
    refused(
        "refused_mode",
        &committed_policy(),
        &["--set", "action.mode=\"normalized\""],
        &[
            "hyq_walk.safetensors",
            "action.mode",
            "offset",
            "normalized",
        ],
    );
    refused(
        "refused_robot",
        &committed_policy(),
        &["--robot", "anymal_c"],
        &["hyq_walk.safetensors", "anymal_c"],
    );
    let swapped = edited_policy("compare_swapped_joints.safetensors", |h, _| {
        let joints: Vec<String> =
            serde_json::from_str(h["__metadata__"]["action"].as_str().unwrap()).unwrap();
        let mut swapped = joints.clone();
        swapped.swap(0, 1);
        h["__metadata__"]["action"] = serde_json::to_string(&swapped).unwrap().into();
    });
    refused(
        "refused_layout",
        &swapped,
        &[],
        &["compare_swapped_joints.safetensors", "action value 0"],
    );
    let nan = edited_policy("compare_nan_weight.safetensors", |h, data| {
        let start = h["layers.0.weight"]["data_offsets"][0].as_u64().unwrap() as usize;
        data[start..start + 4].copy_from_slice(&f32::INFINITY.to_le_bytes());
    });
    refused(
        "refused_non_finite",
        &nan,
        &[],
        &[
            "compare_nan_weight.safetensors",
            "layers.0.weight",
            "non-finite",
        ],
    );
}

#[test]
fn scenario_and_ledger_options_do_not_mix_with_a_policy() {
    let policy = policy_arg(&committed_policy());
    let dir = fresh_dir("compare_policy_mixed");
    let out = dir.to_str().unwrap();
    for (extra, word) in [
        (&["--scenario", "trot"][..], "--scenario"),
        (&["--strict"][..], "--strict"),
        (&["--seconds", "1"][..], "--seconds"),
    ] {
        let mut args = vec![
            "compare",
            "--backends",
            "rapier,rapier",
            "--policy",
            &policy,
        ];
        args.extend_from_slice(extra);
        args.extend(["--out", out]);
        usage_error_naming(&args, &[word]);
    }
    usage_error_naming(
        &[
            "compare",
            "--backends",
            "rapier,rapier",
            "--policy",
            "trot",
            "--out",
            out,
        ],
        &["trot", "--scenario", "mlp:FILE"],
    );
    usage_error_naming(
        &[
            "compare",
            "--backends",
            "rapier,rapier",
            "--scenario",
            "stand",
            "--episodes",
            "3",
            "--out",
            out,
        ],
        &["--episodes", "--policy"],
    );
    let err = stderr(&hyq(&[
        "compare",
        "--backends",
        "rapier,rapier",
        "--out",
        out,
    ]));
    assert!(
        err.contains("--scenario") && err.contains("--policy"),
        "{err}"
    );
    assert!(!dir.exists());
}

/// With DART built in: the real two-engine comparison, closed loop and randomised, draws the
/// same values on both, states a gap, and the replay of rapier's actions on rapier is still
/// exact while DART's differs.
#[cfg(feature = "dart")]
#[test]
fn rapier_and_dart_part_and_the_report_says_by_how_much() {
    let dir = fresh_dir("compare_policy_dart");
    let policy = policy_arg(&committed_policy());
    let mut args = vec![
        "compare",
        "--backends",
        "rapier,dart",
        "--policy",
        &policy,
        "--episodes",
        "1",
        "--set",
        "task.max_time_steps=150",
        "--out",
        dir.to_str().unwrap(),
    ];
    // Randomised, both engines draw the same values.
    args.extend_from_slice(&RANDOMIZED);
    hyq_ok(&args);
    let json = read_json(&dir);
    assert_eq!(json["drew_alike"], true);
    let draws = |side: usize| json["sides"][side]["episodes"][0]["randomize"].clone();
    assert!(draws(0)["kp_scale"].is_array(), "{}", draws(0));
    assert_eq!(draws(0)["kp_scale"], draws(1)["kp_scale"]);
    let pair = &json["pairs"][0];
    assert!(
        pair["trunk_position"]["max"].as_f64().unwrap() > 0.0,
        "{pair}"
    );
    let runs = json["replay"]["runs"].as_array().unwrap();
    assert_eq!(runs[0]["label"], "rapier");
    assert_eq!(runs[0]["trunk_position"]["max"], 0.0);
    assert_eq!(runs[1]["label"], "dart");
    assert!(runs[1]["trunk_position"]["max"].as_f64().unwrap() > 0.0);
}
