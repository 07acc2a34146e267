//! Invariant (with `--features dart`, which needs Debian's libdart): the environment runs
//! unchanged on DART; the same seed and actions give bit-identical results there too; standing
//! settles near the profile's standing height with four feet down; and the trot's behaviour on
//! DART is measured and bounded (see the crate docs for the figures).
#![cfg(feature = "dart")]

mod common;

use common::{env, reset, trot_until_truncated};
use hyq_dart::DartBackend;
use hyq_env::policy::{Policy, RandomPolicy, Stand};
use hyq_env::{Env, ResetOptions, StepRecord};

fn dart(overrides: &[(&str, &str)]) -> Env<DartBackend> {
    env(overrides)
}

fn run_random(steps: usize) -> Vec<String> {
    let mut env = dart(&[
        ("reset.joint_noise_rad", "0.03"),
        ("task.max_time_steps", "40"),
        ("goal.mode", "random"),
    ]);
    env.reset(Some(5), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let mut policy = RandomPolicy::new(6);
    let mut action = vec![0.0; 12];
    (0..steps)
        .map(|_| {
            if env.needs_reset() {
                env.reset(None, &ResetOptions::default())
                    .unwrap_or_else(|e| panic!("{e}"));
            }
            policy.act(&env.policy_input(), &mut action);
            env.step(&action).unwrap_or_else(|e| panic!("{e}"));
            StepRecord::from_env(&env, &action).to_json_line()
        })
        .collect()
}

#[test]
fn same_seed_and_actions_give_bit_identical_results_on_dart() {
    let a = run_random(90);
    let b = run_random(90);
    assert_eq!(a, b);
    assert!(a.iter().any(|r| r.contains("\"episode\":2")));
}

#[test]
fn standing_on_dart_settles_near_the_profile_height() {
    let mut env = dart(&[]);
    reset(&mut env, 0);
    let mut a = vec![0.0; 12];
    for _ in 0..100 {
        Stand.act(&env.policy_input(), &mut a);
        let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        assert!(!s.terminated);
    }
    let layout = env.observation_layout().clone();
    let obs = env.observation();
    let z = obs[layout.trunk_position()][2];
    assert!(
        (z - env.model().standing_height()).abs() < 1e-3,
        "settled at {z}"
    );
    assert_eq!(&obs[layout.foot_contacts()], &[1.0; 4]);
    assert_eq!(obs[layout.trunk_contact()], 0.0);
}

#[test]
fn trot_walks_forward_on_dart_too() {
    let mut env = dart(&[]);
    reset(&mut env, 0);
    let t = trot_until_truncated(&mut env);
    assert_eq!(t, 1000);
    // Measured on DART: x 4.28 m, y −0.46 m, yaw 0.18 rad (rapier: 4.32, −0.48, 0.21).
    let p = env.trunk().pose.translation.vector;
    assert!(p.x > 3.0, "only {} m forward in 10 s", p.x);
    assert!(p.y.abs() < 1.5, "drifted {} m sideways", p.y);
}
