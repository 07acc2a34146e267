//! Spec §7.9: observation noise changes what the policy sees, never what the rules see. With
//! the same seed and actions, an environment with noise and one without give bit for bit the
//! same rewards, terminations, info and physics; the noisy observation is the true one plus
//! noise of the configured size, on the configured rows only, the quaternion within [−1, 1],
//! the contact flags 0 or 1.

mod common;

use common::{rapier, reset};
use hyq_env::Env;
use hyq_env::policy::{Policy, RandomPolicy};
use hyq_rapier::RapierBackend;

const STEPS: usize = 120;

/// Per step: the reward, the reasons, the info's distance and attitude, the true observation
/// and the one the policy saw.
type Run = Vec<(f64, bool, bool, [f64; 4], Vec<f64>, Vec<f64>)>;

fn run(env: &mut Env<RapierBackend>) -> Run {
    let mut policy = RandomPolicy::new(4);
    let mut action = vec![0.0; 12];
    reset(env, 8);
    let mut out = Vec::new();
    for _ in 0..STEPS {
        // The actions come from the true observation, so both runs take the same ones.
        policy.act(&env.policy_input(), &mut action);
        let s = env.step(&action).unwrap_or_else(|e| panic!("{e}"));
        let i = s.info;
        let (reward, terminated, truncated) = (s.reward, s.terminated, s.truncated);
        let info = [i.distance_to_goal, i.roll, i.pitch, i.yaw];
        out.push((
            reward,
            terminated,
            truncated,
            info,
            env.true_observation().to_vec(),
            env.observation().to_vec(),
        ));
        if terminated || truncated {
            reset(env, 9);
        }
    }
    out
}

#[test]
fn noise_changes_the_observation_only() {
    let base = [("task.max_time_steps", "50")];
    let noisy_keys = [
        ("task.max_time_steps", "50"),
        ("randomize.obs_noise.joint_angle", "0.05"),
        ("randomize.obs_noise.joint_speed", "0.5"),
        ("randomize.obs_noise.quaternion", "0.2"),
        ("randomize.obs_noise.trunk_accel", "1.0"),
        ("randomize.obs_noise.trunk_position", "0.02"),
        ("randomize.obs_noise.contact_flip", "0.1"),
    ];
    let clean = run(&mut rapier(&base));
    let mut noisy_env = rapier(&noisy_keys);
    let layout = noisy_env.observation_layout().clone();
    let noisy = run(&mut noisy_env);
    let mut flips = 0usize;
    let mut flags = 0usize;
    for (step, (c, n)) in clean.iter().zip(&noisy).enumerate() {
        assert_eq!(c.0.to_bits(), n.0.to_bits(), "step {step}: reward");
        assert_eq!((c.1, c.2), (n.1, n.2), "step {step}: terminations");
        assert_eq!(c.3, n.3, "step {step}: info");
        assert_eq!(c.4, n.4, "step {step}: the true observation");
        assert_eq!(c.4, c.5, "without noise the policy sees the truth");
        let (truth, seen) = (&n.4, &n.5);
        for i in layout.trunk_rotation() {
            assert!(
                (-1.0..=1.0).contains(&seen[i]),
                "quaternion row {i}: {}",
                seen[i]
            );
        }
        for i in layout.foot_contacts().chain([layout.trunk_contact()]) {
            assert!(
                seen[i] == 0.0 || seen[i] == 1.0,
                "flag row {i}: {}",
                seen[i]
            );
            flags += 1;
            flips += usize::from(seen[i] != truth[i]);
        }
        for i in layout.joint_angles() {
            assert_ne!(
                seen[i], truth[i],
                "step {step}: joint angle row {i} has noise"
            );
        }
    }
    // 5 flags × 120 steps at p = 0.1: 60 flips expected, σ ≈ 7.3.
    assert!(
        (30..=90).contains(&flips),
        "{flips} of {flags} flags flipped"
    );
}

#[test]
fn gaussian_and_uniform_noise_have_the_configured_size() {
    let sample = |distribution: &str| {
        let mut env = rapier(&[
            ("task.max_time_steps", "400"),
            ("randomize.obs_noise.joint_speed", "0.3"),
            ("randomize.obs_noise.distribution", distribution),
        ]);
        let layout = env.observation_layout().clone();
        let stand = common::stand_action(&env);
        reset(&mut env, 2);
        let mut errors = Vec::new();
        for _ in 0..400 {
            env.step(&stand).unwrap_or_else(|e| panic!("{e}"));
            let (truth, seen) = (env.true_observation(), env.observation());
            errors.extend(layout.joint_speeds().map(|i| seen[i] - truth[i]));
            for i in layout.joint_angles() {
                assert_eq!(seen[i], truth[i], "joint angles have no noise");
            }
        }
        errors
    };
    let std = |e: &[f64]| (e.iter().map(|x| x * x).sum::<f64>() / e.len() as f64).sqrt();
    let gaussian = sample("\"gaussian\"");
    // 4800 samples: the standard deviation is 0.3 within a few percent.
    assert!(
        (std(&gaussian) / 0.3 - 1.0).abs() < 0.05,
        "{}",
        std(&gaussian)
    );
    let uniform = sample("\"uniform\"");
    assert!(uniform.iter().all(|e| e.abs() <= 0.3));
    // U(−0.3, 0.3) has standard deviation 0.3/√3.
    assert!((std(&uniform) / (0.3 / 3f64.sqrt()) - 1.0).abs() < 0.05);
}
