//! Invariant: on the same backend, the same seed and the same actions give bit-identical
//! observations, rewards and infos (here on rapier, across resets, with reset noise and random
//! goals on), and switching the per-part timing on changes no result.

mod common;

use common::rapier;
use hyq_env::policy::{Policy, RandomPolicy};
use hyq_env::{ResetOptions, StepRecord};

/// Runs `steps` env steps of a seeded random policy, resetting (unseeded) whenever an episode
/// ends, and returns every step's JSON record (full f64 precision) and observation bits.
fn run(timing: bool, steps: usize) -> (Vec<String>, Vec<u64>) {
    let mut env = rapier(&[
        ("reset.joint_noise_rad", "0.03"),
        ("reset.yaw_noise_deg", "3"),
        ("goal.mode", "random"),
        ("task.max_time_steps", "60"),
        ("task.norm_rew_scaling", "10"),
        ("task.fall_penalty", "1"),
    ]);
    env.set_timing(timing);
    env.reset(Some(11), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let mut policy = RandomPolicy::new(3);
    let mut action = vec![0.0; 12];
    let (mut records, mut bits) = (Vec::new(), Vec::new());
    for _ in 0..steps {
        if env.needs_reset() {
            env.reset(None, &ResetOptions::default())
                .unwrap_or_else(|e| panic!("{e}"));
        }
        policy.act(&env.policy_input(), &mut action);
        env.step(&action).unwrap_or_else(|e| panic!("{e}"));
        records.push(StepRecord::from_env(&env, &action).to_json_line());
        bits.extend(env.observation().iter().map(|v| v.to_bits()));
        bits.push(env.info().reward.total.to_bits());
    }
    (records, bits)
}

#[test]
fn same_seed_and_actions_give_bit_identical_results() {
    let (records_a, bits_a) = run(false, 150);
    let (records_b, bits_b) = run(false, 150);
    assert_eq!(bits_a, bits_b);
    assert_eq!(records_a, records_b);
    // Episodes did end and restart within the run (t_max = 60).
    assert!(records_a.iter().any(|r| r.contains("\"episode\":3")));
}

#[test]
fn timing_changes_no_result() {
    let (records_a, bits_a) = run(false, 40);
    let (records_b, bits_b) = run(true, 40);
    assert_eq!(bits_a, bits_b);
    assert_eq!(records_a, records_b);
}

#[test]
fn a_different_seed_gives_a_different_run() {
    let (_, bits_a) = run(false, 20);
    let mut env = rapier(&[("reset.joint_noise_rad", "0.03")]);
    let r = env
        .reset(Some(12), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let other: Vec<u64> = r.observation.iter().map(|v| v.to_bits()).collect();
    assert_ne!(&bits_a[..39], other.as_slice());
}
