//! Invariant: `[randomize.obs_noise]` reaches the velocity task's rows as it reaches the spec's:
//! `base_lin_vel`, `base_ang_vel` and `projected_gravity` put noise on those rows and
//! `joint_angle` on the joint offsets (q − q₀), while the command and last-action rows, known
//! exactly, stay true; turning one of the task's keys on changes no other row's noise (every
//! row takes its draws whatever is on); the rules still see the truth; and under the spec's
//! task the keys have no rows to reach, so its noisy observation is what it was without them.

use std::ops::Range;

use hyq_env::{Env, EnvConfig, ResetOptions};
use hyq_physics::bundled;
use hyq_rapier::RapierBackend;

/// The observation the policy saw and the true one after 5 zero-action steps from seed 4.
fn observations(pairs: &[(&str, &str)]) -> (Vec<f64>, Vec<f64>) {
    let config = EnvConfig::load(None, pairs).unwrap_or_else(|e| panic!("{e}"));
    let mut env =
        Env::<RapierBackend>::new(bundled::hyq(), config).unwrap_or_else(|e| panic!("{e}"));
    env.reset(Some(4), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let a = vec![0.0; env.action_space().len()];
    for _ in 0..5 {
        env.step(&a).unwrap_or_else(|e| panic!("{e}"));
    }
    (env.observation().to_vec(), env.true_observation().to_vec())
}

/// The rows where `a` and `b` differ.
fn differing(a: &[f64], b: &[f64]) -> Vec<usize> {
    (0..a.len()).filter(|&i| a[i] != b[i]).collect()
}

const VELOCITY: (&str, &str) = ("task.kind", "velocity");
/// The spec's 39 rows of HyQ, then the task's: velocities, gravity, command, offsets, actions.
const SPEC: usize = 39;
const LIN: Range<usize> = SPEC..SPEC + 3;
const ANG: Range<usize> = SPEC + 3..SPEC + 6;
const GRAVITY: Range<usize> = SPEC + 6..SPEC + 9;
const OFFSETS: Range<usize> = SPEC + 12..SPEC + 24;

#[test]
fn each_task_key_puts_noise_on_its_rows_and_only_there() {
    let (_, truth) = observations(&[VELOCITY]);
    for (key, rows) in [
        ("randomize.obs_noise.base_lin_vel", LIN),
        ("randomize.obs_noise.base_ang_vel", ANG),
        ("randomize.obs_noise.projected_gravity", GRAVITY),
    ] {
        let (seen, rules) = observations(&[VELOCITY, (key, "0.1")]);
        assert_eq!(rules, truth, "{key}: the rules see the truth");
        assert_eq!(differing(&seen, &truth), rows.collect::<Vec<_>>(), "{key}");
        assert!(seen.iter().all(|v| v.is_finite()));
    }
}

#[test]
fn the_joint_angle_noise_reaches_the_offsets_and_not_the_command_or_actions() {
    let (seen, truth) = observations(&[VELOCITY, ("randomize.obs_noise.joint_angle", "0.01")]);
    let expected: Vec<usize> = (0..12).chain(OFFSETS).collect();
    assert_eq!(differing(&seen, &truth), expected);
    // Each row draws its own noise: an offset row does not repeat its joint row's.
    assert_ne!(
        seen[OFFSETS.start] - truth[OFFSETS.start],
        seen[0] - truth[0]
    );
}

#[test]
fn a_task_key_changes_no_other_rows_noise() {
    let base = [VELOCITY, ("randomize.obs_noise.joint_speed", "0.5")];
    let (a, _) = observations(&base);
    let (b, _) = observations(&[
        base[0],
        base[1],
        ("randomize.obs_noise.base_lin_vel", "0.1"),
    ]);
    assert_eq!(differing(&a, &b), LIN.collect::<Vec<_>>());
}

#[test]
fn under_the_spec_task_the_task_keys_reach_no_row() {
    let (a, _) = observations(&[("randomize.obs_noise.joint_speed", "0.5")]);
    let (b, truth) = observations(&[
        ("randomize.obs_noise.joint_speed", "0.5"),
        ("randomize.obs_noise.base_lin_vel", "0.1"),
        ("randomize.obs_noise.projected_gravity", "0.1"),
    ]);
    assert_eq!(a, b);
    assert_eq!(truth.len(), SPEC);
}
