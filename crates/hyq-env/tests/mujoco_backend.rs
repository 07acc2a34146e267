//! Invariant (with `--features mujoco`, which needs MuJoCo's library from `cargo xtask setup
//! mujoco`): the environment runs unchanged on MuJoCo; the same seed and actions give
//! bit-identical results there too, across resets; standing settles at the profile's standing
//! height with four feet down; the trot walks forward; and `[physics.mujoco]` reaches the
//! backend (a bad value is an error naming the table and the key).
#![cfg(feature = "mujoco")]

mod common;

use common::{config, env, reset, trot_until_truncated};
use hyq_env::policy::{Policy, RandomPolicy, Stand};
use hyq_env::{Env, ResetOptions, StepRecord};
use hyq_mujoco::MujocoBackend;

fn mujoco(overrides: &[(&str, &str)]) -> Env<MujocoBackend> {
    env(overrides)
}

fn run_random(steps: usize) -> Vec<String> {
    let mut env = mujoco(&[
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
fn same_seed_and_actions_give_bit_identical_results_on_mujoco() {
    let a = run_random(90);
    let b = run_random(90);
    assert_eq!(a, b);
    assert!(a.iter().any(|r| r.contains("\"episode\":2")));
}

#[test]
fn standing_on_mujoco_settles_at_the_profile_height() {
    let mut env = mujoco(&[]);
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
fn trot_walks_forward_on_mujoco_too() {
    let mut env = mujoco(&[]);
    reset(&mut env, 0);
    let t = trot_until_truncated(&mut env);
    assert_eq!(t, 1000);
    let p = env.trunk().pose.translation.vector;
    println!("after the trot on MuJoCo: x {} m, y {} m", p.x, p.y);
    assert!(p.x > 3.0, "only {} m forward in 10 s", p.x);
    assert!(p.y.abs() < 1.5, "drifted {} m sideways", p.y);
}

#[test]
fn the_mujoco_table_reaches_the_backend() {
    // Softer ground contacts (MuJoCo's own default) make HyQ stand lower.
    let stand = |overrides: &[(&str, &str)]| {
        let mut env = mujoco(overrides);
        reset(&mut env, 0);
        let mut a = vec![0.0; 12];
        for _ in 0..100 {
            Stand.act(&env.policy_input(), &mut a);
            env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        }
        env.trunk().pose.translation.z
    };
    let stiff = stand(&[]);
    let soft = stand(&[("physics.mujoco.contact_solref", "[0.02, 1]")]);
    assert!(soft < stiff - 1e-3, "soft {soft} m, stiff {stiff} m");
    let bad = config(&[("physics.mujoco.cone", "\"round\"")]);
    let msg = Env::<MujocoBackend>::new(hyq_physics::bundled::hyq(), bad)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(
        msg.contains("physics.mujoco") && msg.contains("round"),
        "{msg}"
    );
}
