//! Invariant: an episode is started by reset and ended by the rules; stepping before the first
//! reset or after the end (without reset) is an error naming the problem that changes nothing,
//! t counts env steps from 1, t_max = N truncates after exactly N steps, and reset reports
//! t = 0 with no reward.

mod common;

use common::{reset, scripted, stand_action};
use hyq_env::{EnvError, Reason, ResetOptions};

#[test]
fn step_before_reset_is_an_error() {
    let mut env = scripted(&[]);
    let err = env.step(&[0.0; 12]).err();
    assert!(matches!(err, Some(EnvError::NotReset)), "{err:?}");
    assert!(
        err.map(|e| e.to_string())
            .unwrap_or_default()
            .contains("before reset")
    );
    assert!(env.needs_reset());
}

#[test]
fn max_time_steps_n_truncates_after_exactly_n_steps_then_steps_are_errors() {
    for n in [1u64, 3] {
        let mut env = scripted(&[("task.max_time_steps", &n.to_string())]);
        reset(&mut env, 0);
        let a = stand_action(&env);
        for t in 1..=n {
            let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
            assert_eq!(s.info.t, t);
            assert_eq!(s.truncated, t == n, "t = {t}");
            assert!(!s.terminated);
            assert_eq!(s.info.reasons.contains(Reason::Timeout), t == n);
        }
        let obs = env.observation().to_vec();
        match env.step(&a) {
            Err(EnvError::EpisodeOver {
                episode,
                t,
                reasons,
            }) => {
                assert_eq!((episode, t), (1, n));
                assert!(reasons.contains(Reason::Timeout));
            }
            other => panic!("expected EpisodeOver, got {other:?}"),
        }
        assert_eq!(env.observation(), obs.as_slice());
        assert!(env.needs_reset());
        let r = env
            .reset(None, &ResetOptions::default())
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((r.info.episode, r.info.t), (2, 0));
        assert!(env.step(&a).is_ok());
    }
}

#[test]
fn reset_reports_t_zero_no_reward_and_the_episode_facts() {
    let mut env = scripted(&[]);
    let r = env
        .reset(Some(3), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    let info = r.info.clone();
    let obs = r.observation.to_vec();
    assert_eq!((info.episode, info.t), (1, 0));
    assert_eq!(info.reward.total, 0.0);
    assert!(info.reasons.is_empty());
    let model = env.model().clone();
    assert_eq!(info.initial_position, [0.0, 0.0, model.spawn_height()]);
    assert_eq!(info.goal, [5.0, 0.0, model.standing_height()]);
    let k = ((5.0f64).powi(2) + (model.spawn_height() - model.standing_height()).powi(2)).sqrt();
    assert_eq!(info.distance_to_goal, k);
    assert_eq!(info.d_n, 1.0);
    assert_eq!(info.joint_targets.as_slice(), model.standing_pose());
    // Observation after reset: standing angles, zero speeds, no contact, level, zero
    // acceleration, the spawn position.
    let layout = env.observation_layout().clone();
    assert_eq!(&obs[layout.joint_angles()], model.standing_pose());
    assert!(obs[layout.joint_speeds()].iter().all(|v| *v == 0.0));
    assert!(obs[layout.foot_contacts()].iter().all(|v| *v == 0.0));
    assert_eq!(obs[layout.trunk_contact()], 0.0);
    assert_eq!(&obs[layout.trunk_rotation()], &[1.0, 0.0, 0.0, 0.0]);
    assert_eq!(&obs[layout.trunk_acceleration()], &[0.0, 0.0, 0.0]);
    assert_eq!(&obs[layout.trunk_position()], &info.initial_position);
    let f32s: Vec<f32> = obs.iter().map(|v| *v as f32).collect();
    assert_eq!(env.observation_f32(), f32s.as_slice());
}

#[test]
fn a_goal_at_the_start_is_refused_at_build_and_at_reset_naming_the_goal() {
    let model = hyq_physics::bundled::hyq();
    let at_spawn = format!("[0, 0, {}]", model.spawn_height());
    let config = common::config(&[("goal.mode", "fixed"), ("goal.position", &at_spawn)]);
    let err = hyq_env::Env::<hyq_env::testing::ScriptedBackend>::new(model, config).err();
    let msg = err.map(|e| e.to_string()).unwrap_or_default();
    assert!(msg.contains("goal (0, 0, 0.6003)"), "{msg}");

    let mut env = scripted(&[]);
    let err = env
        .reset(
            Some(0),
            &ResetOptions {
                goal: Some([0.0, 0.0, env.model().spawn_height()]),
                ..ResetOptions::default()
            },
        )
        .err();
    assert!(matches!(err, Some(EnvError::Episode(_))), "{err:?}");
    assert!(env.needs_reset(), "a failed reset starts no episode");
}

#[test]
fn a_goal_at_the_start_is_refused_with_r_n_and_r_e_off_too_since_d_n_is_always_reported() {
    let model = hyq_physics::bundled::hyq();
    let at_spawn = format!("[0, 0, {}]", model.spawn_height());
    let config = common::config(&[
        ("task.exp_rew_scaling", "off"),
        ("goal.mode", "fixed"),
        ("goal.position", &at_spawn),
    ]);
    let err = hyq_env::Env::<hyq_env::testing::ScriptedBackend>::new(model, config).err();
    let msg = err.map(|e| e.to_string()).unwrap_or_default();
    assert!(msg.contains("goal") && msg.contains("D_n"), "{msg}");

    let mut env = scripted(&[("task.exp_rew_scaling", "off")]);
    let err = env
        .reset(
            Some(0),
            &ResetOptions {
                goal: Some([0.0, 0.0, env.model().spawn_height()]),
                ..ResetOptions::default()
            },
        )
        .err();
    assert!(matches!(err, Some(EnvError::Config(_))), "{err:?}");
    assert!(env.needs_reset(), "a failed reset starts no episode");
}

#[test]
fn the_reward_is_the_composition_of_its_reported_terms() {
    let mut env = scripted(&[
        ("task.norm_rew_scaling", "10"),
        ("task.base_rew_scaling", "2"),
    ]);
    reset(&mut env, 0);
    // Move the trunk towards the goal at 1 m/s with a little yaw rate.
    env.backend_mut().set_script(|w| {
        w.trunk.linvel.x = 1.0;
        w.trunk.angvel.z = 0.5;
        Ok(())
    });
    for _ in 0..20 {
        let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(s.reward, s.info.reward.total);
        assert_eq!(s.reward, s.info.reward.compose());
        assert!(s.info.reward.r_n > 0.0 && s.info.reward.r_b > 0.0);
        let p = &s.observation[36..39];
        let g = s.info.goal;
        let d = ((g[0] - p[0]).powi(2) + (g[1] - p[1]).powi(2) + (g[2] - p[2]).powi(2)).sqrt();
        assert!((s.info.distance_to_goal - d).abs() < 1e-12);
    }
    assert!(env.info().reward.m_yaw < 1.0, "yawed past 2.5 degrees");
}
