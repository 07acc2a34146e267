//! Invariant: `hyq run` prints one summary per episode: as a table by default (a title naming
//! the robot, backend, policy and seed, then header, rule, one
//! row per episode naming the steps, return, each reward term's sum, the reasons and the
//! distance to the goal), or with `--json` one JSON object per line whose numbers agree with
//! the episode (the return is the sum of the terms composed per step; a timeout at t_max).

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::hyq_ok;
use serde_json::Value;

#[test]
fn the_default_run_is_one_ten_second_trot_episode_in_a_table() {
    let out = hyq_ok(&["run"]);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 4, "title, header, rule, one episode:\n{out}");
    assert_eq!(lines[0], "hyq run: hyq on rapier, policy trot, seed 0");
    let lines = &lines[1..];
    for column in [
        "episode",
        "steps",
        "return",
        "r_b",
        "r_n",
        "r_e",
        "r_reach",
        "joint_penalty",
        "fall_penalty",
        "end",
        "distance_m",
    ] {
        assert!(
            lines[0].split_whitespace().any(|c| c == column),
            "no `{column}` column: {}",
            lines[0]
        );
    }
    assert!(lines[1].chars().all(|c| c == '-' || c == ' '));
    let row: Vec<&str> = lines[2].split_whitespace().collect();
    assert_eq!(&row[..3], &["1", "1000", "10.00"], "{}", lines[2]);
    assert!(lines[2].contains("timeout"), "{}", lines[2]);
}

#[test]
fn json_lines_carry_the_same_summary_per_episode() {
    let out = hyq_ok(&[
        "run",
        "--json",
        "--policy",
        "random",
        "--episodes",
        "2",
        "--seed",
        "3",
        "--set",
        "task.max_time_steps=40",
        "--set",
        "task.norm_rew_scaling=10",
    ]);
    let episodes: Vec<Value> = out
        .lines()
        .map(|l| serde_json::from_str(l).unwrap_or_else(|e| panic!("{e}: {l}")))
        .collect();
    assert_eq!(episodes.len(), 2, "{out}");
    for (i, e) in episodes.iter().enumerate() {
        assert_eq!(e["episode"], i as u64 + 1);
        assert_eq!(e["backend"], "rapier");
        assert_eq!(e["policy"], "random");
        let steps = e["steps"].as_u64().unwrap();
        let reasons: Vec<&str> = e["reasons"]
            .as_array()
            .unwrap()
            .iter()
            .map(|r| r.as_str().unwrap())
            .collect();
        assert!(!reasons.is_empty());
        if reasons == ["timeout"] {
            assert_eq!(steps, 40);
            assert_eq!(e["truncated"], true);
            assert_eq!(e["terminated"], false);
        } else {
            assert!(steps <= 40);
            assert_eq!(e["terminated"], true);
        }
        let terms = &e["terms"];
        for key in [
            "r_b",
            "r_n",
            "r_e",
            "r_reach",
            "joint_penalty",
            "fall_penalty",
        ] {
            assert!(terms[key].is_f64(), "terms.{key}: {terms}");
        }
        // Σ r_n telescopes to k_norm (D^0 − D^T) / K (spec §4.2).
        let d0 = e["initial_distance_to_goal"].as_f64().unwrap();
        let dt = e["final_distance_to_goal"].as_f64().unwrap();
        let r_n = terms["r_n"].as_f64().unwrap();
        assert!(
            (r_n - 10.0 * (d0 - dt) / d0).abs() < 1e-12,
            "Σ r_n {r_n} vs {}",
            10.0 * (d0 - dt) / d0
        );
        // Level enough while flailing for 0.4 s that the multipliers are 1 most of the time,
        // and the return is the terms' sum when they are.
        let m = e["mean_m_yaw"].as_f64().unwrap() * e["mean_m_pitch"].as_f64().unwrap();
        let sum = ["r_b", "r_n", "r_e", "r_reach"]
            .iter()
            .map(|k| terms[*k].as_f64().unwrap())
            .sum::<f64>()
            - terms["joint_penalty"].as_f64().unwrap()
            - terms["fall_penalty"].as_f64().unwrap();
        let ret = e["return"].as_f64().unwrap();
        if m == 1.0 {
            assert!((ret - sum).abs() < 1e-9, "return {ret} vs terms {sum}");
        }
        let goal = e["goal"].as_array().unwrap();
        assert_eq!(goal[0].as_f64(), Some(5.0));
    }
}

#[cfg(feature = "dart")]
#[test]
fn the_dart_backend_runs_when_built_in() {
    let out = hyq_ok(&[
        "run",
        "--backend",
        "dart",
        "--json",
        "--set",
        "task.max_time_steps=200",
    ]);
    let e: Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(e["backend"], "dart");
    assert_eq!(e["steps"], 200);
    assert_eq!(e["reasons"], serde_json::json!(["timeout"]));
    let dx = e["final_position"][0].as_f64().unwrap() - e["initial_position"][0].as_f64().unwrap();
    // After the gait's 1 s ramp the trot carries HyQ forward (about 0.5 m in 2 s).
    assert!(
        dx > 0.2,
        "the trot walks forward on DART too ({dx} m in 2 s)"
    );
}

#[test]
fn large_sums_are_printed_in_short_scientific_form_small_ones_with_three_decimals() {
    // The largest accepted scalings give sums of order 1e11 to 1e12, which used to be printed
    // with all their digits.
    let out = hyq_ok(&[
        "run",
        "--set",
        "task.max_time_steps=100",
        "--set",
        "task.base_rew_scaling=1e12",
        "--set",
        "task.norm_rew_scaling=1e12",
    ]);
    let row: Vec<&str> = out.lines().nth(3).unwrap().split_whitespace().collect();
    // return, r_b, r_n: large, in the form 1.234e11; r_e: small, with three decimals.
    for cell in &row[3..6] {
        let (mantissa, exponent) = cell.split_once('e').unwrap_or_else(|| panic!("{out}"));
        assert!(
            mantissa.len() <= 6 && exponent.parse::<i32>().is_ok(),
            "{cell}: {out}"
        );
    }
    assert!(
        !row[6].contains('e') && row[6].split_once('.').unwrap().1.len() == 3,
        "{out}"
    );
}

/// With `[regularizers]` on, the summary says what they added and each term's sum, the return
/// is the spec's terms' return plus that, and `--plot` draws them; off, none of it is written.
#[test]
fn regularizers_are_summed_and_plotted_only_when_on() {
    let base = [
        "run",
        "--json",
        "--set",
        "task.max_time_steps=60",
        "--set",
        "task.norm_rew_scaling=10",
    ];
    let plain: Value = serde_json::from_str(hyq_ok(&base).trim()).unwrap();
    assert!(plain.get("regularizers").is_none(), "{plain}");
    let dir = std::env::temp_dir().join(format!("hyq-reg-plots-{}", std::process::id()));
    let dir_arg = dir.display().to_string();
    let mut args = base.to_vec();
    args.extend([
        "--set",
        "regularizers.preset=legged_gym",
        "--set",
        "regularizers.foot_slip=-0.1",
        "--plot",
        &dir_arg,
    ]);
    let on: Value = serde_json::from_str(hyq_ok(&args).trim()).unwrap();
    let reg = &on["regularizers"];
    let terms = reg["terms"].as_object().unwrap();
    let names: Vec<&str> = terms.keys().map(String::as_str).collect();
    let mut want = vec![
        "action_rate",
        "collision",
        "feet_air_time",
        "foot_slip",
        "joint_acc",
        "torques",
    ];
    want.sort_unstable();
    assert_eq!(names, want, "the terms that are on, no other");
    let added = reg["reward"].as_f64().unwrap();
    assert!(added < 0.0 && added.is_finite(), "{reg}");
    // The spec's part is the plain run's (the same physics); the return adds the regularisers.
    assert_eq!(on["terms"], plain["terms"]);
    let (ret, plain_ret) = (
        on["return"].as_f64().unwrap(),
        plain["return"].as_f64().unwrap(),
    );
    assert!(
        (ret - (plain_ret + added)).abs() < 1e-9,
        "{ret} vs {plain_ret} + {added}"
    );
    assert!(dir.join("episode_001_regularizers.png").is_file());
    assert!(dir.join("episode_001_rewards.png").is_file());
    std::fs::remove_dir_all(&dir).unwrap();
}
