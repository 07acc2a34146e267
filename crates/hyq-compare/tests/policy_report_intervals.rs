//! Invariant: a policy comparison reports every figure with its uncertainty, in one shape:
//! each engine's mean of travel, K − D^T, D^T, return and episode length with a 95 % interval
//! around it, each end reason's rate with its Wilson interval (`k`, `n`), and every pair's
//! ratio of means with its interval; the same inputs give the same report byte for byte.

#![allow(clippy::unwrap_used)]

use hyq_compare::{PolicyPlan, PolicyReport, PolicySpec};
use hyq_env::{EnvConfig, Trot};
use hyq_rapier::RapierBackend;
use serde_json::Value;

/// The trot on rapier twice, 6 short episodes each with reset noise, seed 7.
fn report() -> PolicyReport {
    let model = hyq_physics::bundled::hyq();
    let mut config = EnvConfig::default();
    config.task.max_time_steps = 150;
    config.reset.joint_noise_rad = 0.05;
    config.reset.yaw_noise_deg = 5.0;
    let policy = Trot::from_profile(&model).unwrap();
    let spec = PolicySpec {
        policy: "trot".into(),
        seed: 7,
        episodes: 6,
        configuration: Vec::new(),
    };
    let plan = PolicyPlan::new(model, config, policy, spec).unwrap();
    let sides = [
        plan.run_side::<RapierBackend>("a").unwrap(),
        plan.run_side::<RapierBackend>("b").unwrap(),
    ];
    plan.report(&sides, &[])
}

fn interval(v: &Value) -> (f64, f64, f64) {
    let mean = v["mean"].as_f64().unwrap();
    let ci = v["ci95"].as_array().unwrap();
    (mean, ci[0].as_f64().unwrap(), ci[1].as_f64().unwrap())
}

#[test]
fn every_figure_is_a_mean_with_its_interval_and_every_rate_gives_k_and_n() {
    let r = report();
    let json: Value = serde_json::from_str(&r.to_json()).unwrap();
    let side = &json["sides"][0];
    for figure in [
        "travel_m",
        "distance_walked_m",
        "final_distance_m",
        "return",
        "steps",
    ] {
        let (mean, lo, hi) = interval(&side[figure]);
        assert!(lo <= mean && mean <= hi, "{figure}: {}", side[figure]);
    }
    // Reset noise makes the episodes differ: travel's interval has width.
    let (_, lo, hi) = interval(&side["travel_m"]);
    assert!(hi > lo, "{}", side["travel_m"]);
    let rates = &side["rates"];
    for reason in ["reached", "fell", "joint_limit", "timeout", "diverged"] {
        let (mean, lo, hi) = interval(&rates[reason]);
        let (k, n) = (
            rates[reason]["k"].as_u64().unwrap(),
            rates[reason]["n"].as_u64().unwrap(),
        );
        assert_eq!(n, 6, "{reason}");
        assert_eq!(mean, k as f64 / 6.0, "{reason}");
        assert!(
            0.0 <= lo && lo <= mean && mean <= hi && hi <= 1.0,
            "{reason}: {}",
            rates[reason]
        );
    }
    // Every episode ends somehow: the rates cover them all.
    let ended: u64 = ["reached", "fell", "joint_limit", "timeout", "diverged"]
        .iter()
        .map(|r| rates[r]["k"].as_u64().unwrap())
        .sum();
    assert!(ended >= 6, "{rates}");
    // The same engine twice: each ratio is 1 exactly and its interval the point 1.
    let ratios = &json["pairs"][0]["ratios"];
    for figure in ["travel_m", "distance_walked_m", "steps"] {
        assert_eq!(interval(&ratios[figure]), (1.0, 1.0, 1.0), "{figure}");
        assert_eq!(ratios[figure]["excludes_one"], false);
    }
    let md = r.to_markdown("hyq compare …");
    for text in [
        "trunk travel toward the goal (m): mean [95 % CI]",
        "episode length (steps): mean [95 % CI]",
        "| fell | 0 of 6 (0 %) [0 %, 39 %] |",
        "| b / a | 1.000 [1.000, 1.000] |",
        "10,000 resamples seeded with 7",
    ] {
        assert!(md.contains(text), "report.md lacks {text:?}:\n{md}");
    }
}

#[test]
fn the_same_inputs_give_the_same_report_byte_for_byte() {
    let (a, b) = (report(), report());
    assert_eq!(a.to_json(), b.to_json());
    assert_eq!(a.to_markdown("c"), b.to_markdown("c"));
}
