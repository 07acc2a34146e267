//! Invariant: all randomness comes from the reset seed through two separate ChaCha8 streams
//! (goals, reset noise): the same seed gives the same goals and reset states; an unseeded reset
//! continues the stream reproducibly (Gymnasium's semantics); switching the noise on does not
//! move the goals; the default goal is 5 m along +x from the spawn point at the profile's
//! standing height; fixed goals are used as given.

mod common;

use common::scripted;
use hyq_env::ResetOptions;

fn goals_and_states(
    overrides: &[(&str, &str)],
    seeds: &[Option<u64>],
) -> Vec<([f64; 3], Vec<f64>, f64)> {
    let mut env = scripted(overrides);
    seeds
        .iter()
        .map(|seed| {
            let r = env
                .reset(*seed, &ResetOptions::default())
                .unwrap_or_else(|e| panic!("{e}"));
            (r.info.goal, r.observation[..12].to_vec(), r.info.yaw)
        })
        .collect()
}

const RANDOM: &[(&str, &str)] = &[
    ("goal.mode", "random"),
    ("goal.distance_range_m", "[2, 8]"),
    ("goal.heading_range_deg", "[-90, 90]"),
];

#[test]
fn the_default_goal_is_ahead_at_the_standing_height() {
    let mut env = scripted(&[("reset.spawn_xy_m", "[1.5, -2]"), ("goal.distance_m", "3")]);
    let r = env
        .reset(Some(9), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let model = hyq_physics::bundled::hyq();
    assert_eq!(r.info.goal, [4.5, -2.0, model.standing_height()]);
    assert_eq!(r.info.initial_position, [1.5, -2.0, model.spawn_height()]);
}

#[test]
fn fixed_goals_and_reset_option_goals_are_used_as_given() {
    let mut env = scripted(&[("goal.mode", "fixed"), ("goal.position", "[1, 2, 0.3]")]);
    let r = env
        .reset(Some(0), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.info.goal, [1.0, 2.0, 0.3]);
    let r = env
        .reset(
            None,
            &ResetOptions {
                goal: Some([-3.0, 0.5, 0.7]),
                ..ResetOptions::default()
            },
        )
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.info.goal, [-3.0, 0.5, 0.7]);
}

#[test]
fn random_goals_are_reproducible_from_the_seed_and_within_their_ranges() {
    let seeds = [Some(42), None, None, Some(7), None];
    let a = goals_and_states(RANDOM, &seeds);
    let b = goals_and_states(RANDOM, &seeds);
    assert_eq!(a, b);
    let model = hyq_physics::bundled::hyq();
    for (goal, _, _) in &a {
        let d = goal[0].hypot(goal[1]);
        assert!((2.0..=8.0).contains(&d), "{d}");
        assert!(goal[0] >= -1e-12, "heading within ±90°: {goal:?}");
        assert_eq!(goal[2], model.standing_height());
    }
    // Different draws within a stream, and for different seeds.
    assert_ne!(a[0].0, a[1].0);
    assert_ne!(a[1].0, a[2].0);
    assert_ne!(a[0].0, a[3].0);
}

#[test]
fn unseeded_resets_continue_the_seeded_stream() {
    // Seed 42 then two unseeded resets equals the same sequence in a fresh env, whatever
    // happened in between (steps do not draw from the streams).
    let mut env = scripted(RANDOM);
    let mut goals = Vec::new();
    for (i, seed) in [Some(42), None, None].into_iter().enumerate() {
        let r = env
            .reset(seed, &ResetOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        goals.push(r.info.goal);
        for _ in 0..i * 3 {
            env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
        }
    }
    let fresh = goals_and_states(RANDOM, &[Some(42), None, None]);
    assert_eq!(goals, fresh.iter().map(|g| g.0).collect::<Vec<_>>());
    // Reseeding with 42 restarts the stream.
    let r = env
        .reset(Some(42), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(r.info.goal, goals[0]);
}

#[test]
fn an_env_never_seeded_behaves_as_seed_zero() {
    let unseeded = goals_and_states(RANDOM, &[None, None]);
    let zero = goals_and_states(RANDOM, &[Some(hyq_env::DEFAULT_SEED), None]);
    assert_eq!(unseeded, zero);
}

#[test]
fn reset_noise_has_its_own_stream_and_leaves_the_goals_alone() {
    let noisy: Vec<(&str, &str)> = RANDOM
        .iter()
        .copied()
        .chain([
            ("reset.joint_noise_rad", "0.05"),
            ("reset.yaw_noise_deg", "10"),
        ])
        .collect();
    let seeds = [Some(5), None, None];
    let quiet = goals_and_states(RANDOM, &seeds);
    let noisy_a = goals_and_states(&noisy, &seeds);
    let noisy_b = goals_and_states(&noisy, &seeds);
    assert_eq!(noisy_a, noisy_b, "noise is reproducible");
    let model = hyq_physics::bundled::hyq();
    for ((q_goal, q_angles, q_yaw), (n_goal, n_angles, n_yaw)) in quiet.iter().zip(&noisy_a) {
        assert_eq!(q_goal, n_goal, "noise must not move the goals");
        assert_eq!(q_angles.as_slice(), model.standing_pose());
        assert_eq!(*q_yaw, 0.0);
        assert_ne!(n_angles, q_angles);
        for (n, s) in n_angles.iter().zip(model.standing_pose()) {
            assert!((n - s).abs() <= 0.05 + 1e-6, "{n} vs {s}");
        }
        assert!(n_yaw.abs() <= 10f64.to_radians() + 1e-9 && *n_yaw != 0.0);
    }
    assert_ne!(noisy_a[0].1, noisy_a[1].1);
}

#[test]
fn a_spawn_yaw_is_applied_and_reported() {
    let mut env = scripted(&[("reset.yaw_deg", "10")]);
    let r = env
        .reset(Some(0), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    assert!((r.info.yaw - 10f64.to_radians()).abs() < 1e-12);
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert!((s.info.reward.m_yaw - 10f64.to_radians().cos()).abs() < 1e-12);
}
