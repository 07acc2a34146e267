//! Invariant: the distance-based rewards telescope. Over any path of trunk positions
//! C^0, C^1, …, C^T (any direction, any number of steps),
//!
//! - Σ r_b = k_base · (D^0 − D^T),
//! - Σ r_n = k_norm · (1 − D_n^T),
//! - Σ r_e = R_e(D_n^T) − R_e(1) = R_e(D_n^T),
//!
//! so the return depends only on where the episode ends, never on the route (no reward can be
//! farmed by walking back and forth). Checked on [`EpisodeRules::evaluate_step`], the function
//! the environment calls, with paths aimed at D_n near 0, 1 and 9.

mod common;

use common::{
    d_n_near_boundaries, direction, hyq_ranges, level_snapshot, mid_angles, rules, start_and_goal,
    step,
};
use hyq_spec::nalgebra::Point3;
use hyq_spec::reward::exponential::cumulative_exponential_reward;
use hyq_spec::{EpisodeRules, TaskConfig};
use proptest::prelude::*;

/// Per-step sums of r_b, r_n and r_e along `path` (which starts after C^0), and the final D^T
/// and D_n^T.
fn run_path(rules: &EpisodeRules, path: &[Point3<f64>]) -> ([f64; 3], f64, f64) {
    let ranges = hyq_ranges();
    let angles = mid_angles(&ranges);
    let mut previous = rules.initial();
    let mut sums = [0.0; 3];
    let (mut d, mut d_n) = (f64::NAN, f64::NAN);
    for (i, position) in path.iter().enumerate() {
        let snapshot = level_snapshot(i as u64 + 1, previous, *position, &angles, &ranges);
        let outcome = step(rules, &snapshot);
        sums[0] += outcome.reward.r_b;
        sums[1] += outcome.reward.r_n;
        sums[2] += outcome.reward.r_e;
        d = outcome.distance;
        d_n = outcome.normalised_distance.unwrap_or(f64::NAN);
        previous = *position;
    }
    (sums, d, d_n)
}

/// Σ r_b = k_base · (D^0 − D^T).
fn check_base_telescopes(sum: f64, k_base: f64, d_0: f64, d_t: f64, steps: usize) {
    let expected = k_base * (d_0 - d_t);
    let tol = 1e-12 * k_base * (1.0 + d_0 + d_t) * steps as f64;
    assert!(
        (sum - expected).abs() <= tol,
        "Σ r_b = {sum}, k_base·(D^0 − D^T) = {expected}"
    );
}

/// Σ r_n = k_norm · (1 − D_n^T).
fn check_normalised_telescopes(sum: f64, k_norm: f64, d_n_t: f64, steps: usize) {
    let expected = k_norm * (1.0 - d_n_t);
    let tol = 1e-12 * k_norm * (1.0 + d_n_t) * steps as f64;
    assert!(
        (sum - expected).abs() <= tol,
        "Σ r_n = {sum}, k_norm·(1 − D_n^T) = {expected}"
    );
}

/// Σ r_e = R_e(D_n^T), since R_e(D_n^0) = R_e(1) = 0.
fn check_exponential_telescopes(sum: f64, k_exp: f64, d_n_t: f64, steps: usize) {
    let expected = cumulative_exponential_reward(d_n_t, k_exp);
    let scale = 1.0 + (k_exp.exp() / k_exp) + 0.5 * d_n_t;
    let tol = 1e-12 * scale * steps as f64;
    assert!(
        (sum - expected).abs() <= tol,
        "Σ r_e = {sum}, R_e(D_n^T) = {expected}"
    );
}

/// A path of `len` positions whose normalised distances are drawn near 0, 1 and 9.
fn path_strategy() -> impl Strategy<Value = (Point3<f64>, Point3<f64>, Vec<Point3<f64>>)> {
    start_and_goal().prop_flat_map(|(start, goal)| {
        let k = (goal - start).norm();
        let point =
            (d_n_near_boundaries(), direction()).prop_map(move |(d_n, dir)| goal + dir * (d_n * k));
        (Just(start), Just(goal), prop::collection::vec(point, 1..60))
    })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

    #[test]
    fn sums_depend_only_on_the_end_of_the_path(
        (start, goal, path) in path_strategy(),
        k_base in 0.01f64..100.0,
        k_norm in 0.01f64..100.0,
        k_exp in 0.1f64..10.0,
    ) {
        let config = TaskConfig {
            base_rew_scaling: Some(k_base),
            norm_rew_scaling: Some(k_norm),
            exp_rew_scaling: Some(k_exp),
            ..TaskConfig::default()
        };
        let rules = rules(&config, start, goal);
        let (sums, d_t, d_n_t) = run_path(&rules, &path);
        let d_0 = (goal - start).norm();
        check_base_telescopes(sums[0], k_base, d_0, d_t, path.len());
        check_normalised_telescopes(sums[1], k_norm, d_n_t, path.len());
        check_exponential_telescopes(sums[2], k_exp, d_n_t, path.len());
    }
}

#[test]
fn walking_straight_to_the_goal_earns_exactly_the_scales() {
    // The ruled rewards of a whole walk from start to goal: k_norm for r_n (the spec's Figure 4
    // rises to its scale) and (e^k − 1)/k ≈ 29.48 for r_e with k = 5.
    let start = Point3::new(0.0, 0.0, 0.62);
    let goal = Point3::new(5.0, 0.0, 0.62);
    let config = TaskConfig {
        norm_rew_scaling: Some(10.0),
        ..TaskConfig::default()
    };
    let rules = rules(&config, start, goal);
    let path: Vec<_> = (1..=100)
        .map(|i| Point3::new(0.05 * i as f64, 0.0, 0.62))
        .collect();
    let (sums, d_t, d_n_t) = run_path(&rules, &path);
    assert!(d_t.abs() < 1e-12 && d_n_t.abs() < 1e-12);
    assert!((sums[1] - 10.0).abs() < 1e-12, "Σ r_n = {}", sums[1]);
    assert!(
        (sums[2] - 29.482_631_820_515_32).abs() < 1e-10,
        "Σ r_e = {}",
        sums[2]
    );
    assert_eq!(sums[0], 0.0, "r_b is off by default");
}
