//! Invariant: on rapier with the default configuration, the stand policy holds HyQ at the
//! profile's standing height with four feet and no trunk on the ground; the trot policy carries
//! it forward along +x for 10 s (1000 env steps) without falling or any other termination; the
//! random policy acts inside the action space and is reproducible from its seed.

mod common;

use common::{rapier, reset, trot_until_truncated};
use hyq_env::policy::{Policy, RandomPolicy, Stand};
use hyq_env::{Reason, ResetOptions};

#[test]
fn standing_settles_at_the_profile_height() {
    let mut env = rapier(&[]);
    reset(&mut env, 0);
    let mut stand = Stand;
    let mut a = vec![0.0; 12];
    let layout = env.observation_layout().clone();
    for _ in 0..100 {
        stand.act(&env.policy_input(), &mut a);
        let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        assert!(!s.terminated && !s.truncated);
    }
    let obs = env.observation();
    let z = obs[layout.trunk_position()][2];
    let nominal = env.model().standing_height();
    assert!(
        (z - nominal).abs() < 5e-4,
        "settled at {z}, profile says {nominal}"
    );
    assert_eq!(&obs[layout.foot_contacts()], &[1.0; 4]);
    assert_eq!(obs[layout.trunk_contact()], 0.0);
    let q = &obs[layout.trunk_rotation()];
    assert!(q[0] > 0.9999, "level: {q:?}");
    assert!(
        obs[layout.trunk_acceleration()]
            .iter()
            .all(|a| a.abs() < 0.05)
    );
}

#[test]
fn trot_walks_forward_for_ten_seconds_without_falling() {
    let mut env = rapier(&[("task.max_time_steps", "1000")]);
    reset(&mut env, 0);
    let t = trot_until_truncated(&mut env);
    assert!(env.info().reasons.contains(Reason::Timeout));
    assert_eq!(t, 1000);
    let p = env.trunk().pose.translation.vector;
    // Measured 4.32 m forward, 0.48 m sideways, yaw 0.2 rad (see the crate docs); the margins
    // allow for solver settings and floating-point differences between machines.
    assert!(p.x > 3.0, "only {} m forward in 10 s", p.x);
    assert!(p.y.abs() < 1.5, "drifted {} m sideways", p.y);
    assert!(p.z > 0.45, "trunk sagged to {} m", p.z);
}

#[test]
fn random_actions_are_in_the_space_and_reproducible() {
    for mode in ["normalized", "absolute", "delta", "offset"] {
        let mut env = rapier(&[("action.mode", mode)]);
        env.reset(Some(0), &ResetOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        let (mut p1, mut p2) = (RandomPolicy::new(8), RandomPolicy::new(8));
        let (mut a1, mut a2) = (vec![0.0; 12], vec![0.0; 12]);
        let mut distinct = std::collections::HashSet::new();
        for _ in 0..20 {
            let input = env.policy_input();
            p1.act(&input, &mut a1);
            p2.act(&input, &mut a2);
            assert_eq!(a1, a2);
            let space = env.action_space();
            for ((a, lo), hi) in a1.iter().zip(space.low()).zip(space.high()) {
                assert!(lo <= a && a <= hi, "{mode}: {a} outside [{lo}, {hi}]");
            }
            distinct.insert(a1[0].to_bits());
            let s = env.step(&a1).unwrap_or_else(|e| panic!("{e}"));
            assert!(!s.info.action_clipped);
            if s.terminated || s.truncated {
                env.reset(None, &ResetOptions::default())
                    .unwrap_or_else(|e| panic!("{e}"));
            }
        }
        assert!(distinct.len() > 15, "{mode}: actions barely vary");
    }
}
