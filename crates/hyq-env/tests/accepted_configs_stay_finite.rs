//! Invariant: no configuration the validator accepts makes the environment panic or emit a
//! number that is not finite. The ranges that keep every reward term and every sum over an
//! episode finite are checked when the configuration is built, each refusal naming the key, the
//! value and the reason; every position (spawn, goal, and the trunk during an episode) stays in
//! the world the engines represent faithfully; a trunk that leaves it, or an observation
//! beyond float32's range, ends the episode as `diverged` with every emitted number finite.

mod common;

use common::{config, reset, scripted};
use hyq_env::{
    EXP_REW_SCALING_MAX, EnvConfig, EnvError, JOINT_NOISE_MAX_RAD, REWARD_SCALE_MAX, Reason,
    ResetOptions, WORLD_HALF_EXTENT_M,
};

/// The error of setting `pairs` on the defaults, which must be refused.
fn refused(pairs: &[(&str, &str)]) -> String {
    let mut c = EnvConfig::default();
    match c.set_all(pairs) {
        Ok(()) => panic!("{pairs:?} was accepted"),
        Err(e) => {
            assert_eq!(c, EnvConfig::default(), "a refusal changes nothing");
            e.to_string()
        }
    }
}

fn assert_mentions(message: &str, parts: &[&str]) {
    for part in parts {
        assert!(message.contains(part), "{message:?} lacks {part:?}");
    }
    assert!(!message.contains('\n'), "one line: {message:?}");
}

#[test]
fn joint_noise_beyond_a_full_turn_is_refused_before_it_can_reach_the_sampler() {
    // 1e308 used to pass validation and panic inside the uniform sampler at reset (its range,
    // 2n, overflows).
    for value in ["1e308", "8.99e307", "7"] {
        let e = refused(&[("reset.joint_noise_rad", value)]);
        assert_mentions(&e, &["reset.joint_noise_rad", "6.28"]);
    }
    let max = JOINT_NOISE_MAX_RAD.to_string();
    let mut env = scripted(&[("reset.joint_noise_rad", &max)]);
    for seed in 0..5 {
        reset(&mut env, seed);
        assert!(env.joint_angles().iter().all(|q| q.is_finite()));
    }
}

#[test]
fn k_exp_is_bounded_so_that_e_to_the_k_and_every_sum_stay_finite() {
    // k = 1000 used to give r_e = +inf at D_n near 0, then NaN.
    for value in ["1000", "710", "501"] {
        let e = refused(&[("task.exp_rew_scaling", value)]);
        assert_mentions(&e, &["task.exp_rew_scaling", "500"]);
    }
    let c = config(&[("task.exp_rew_scaling", &EXP_REW_SCALING_MAX.to_string())]);
    assert_eq!(c.task.exp_rew_scaling, Some(EXP_REW_SCALING_MAX));
}

#[test]
fn scalings_bonus_and_penalties_are_bounded() {
    let too_big = (REWARD_SCALE_MAX * 10.0).to_string();
    for key in [
        "task.base_rew_scaling",
        "task.norm_rew_scaling",
        "task.reach_target_bonus_reward",
        "task.reach_bounds_penalty",
        "task.fall_penalty",
    ] {
        let e = refused(&[(key, &too_big)]);
        assert_mentions(&e, &[key, "1e12"]);
        config(&[(key, &REWARD_SCALE_MAX.to_string())]);
    }
    // The accepted configuration of the hanging plot: k_norm = 1.5e308.
    let e = refused(&[
        ("task.norm_rew_scaling", "1.5e308"),
        ("goal.distance_m", "1.5"),
    ]);
    assert_mentions(&e, &["task.norm_rew_scaling", "1.5e308"]);
}

#[test]
fn positions_outside_the_faithful_world_are_refused_with_the_reason() {
    let w = WORLD_HALF_EXTENT_M;
    let cases: &[(&[(&str, &str)], &str)] = &[
        (&[("reset.spawn_xy_m", "[1e5, 0]")], "reset.spawn_xy_m"),
        (&[("reset.spawn_xy_m", "[0, -1e39]")], "reset.spawn_xy_m"),
        (
            &[
                ("goal.mode", "fixed"),
                ("goal.position", "[1e308, 1e308, 0]"),
            ],
            "goal.position",
        ),
        (&[("goal.distance_m", "1e308")], "goal.distance_m"),
        (&[("goal.height_m", "1e308")], "goal.height_m"),
        (
            &[
                ("goal.mode", "random"),
                ("goal.distance_range_m", "[1e300, 1e300]"),
            ],
            "goal.distance_range_m",
        ),
        (
            &[("reset.spawn_xy_m", "[99, 0]"), ("goal.distance_m", "2")],
            "goal.distance_m",
        ),
    ];
    for (pairs, key) in cases {
        let e = refused(pairs);
        assert_mentions(&e, &[key, "100 m", "f32"]);
        // Numbers are printed in their shortest form, never as hundreds of digits.
        assert!(e.len() < 400, "{e}");
    }
    config(&[
        ("reset.spawn_xy_m", &format!("[{w}, {}]", -w)),
        ("goal.mode", "fixed"),
        ("goal.position", &format!("[{}, {w}, 0.5]", -w)),
    ]);
}

#[test]
fn a_reset_option_outside_the_world_is_refused_and_changes_nothing() {
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    let before = env.info().clone();
    for goal in [[1e200, 0.0, 0.0], [0.0, 0.0, 101.0]] {
        let options = ResetOptions {
            goal: Some(goal),
            ..ResetOptions::default()
        };
        let e = env.reset(Some(1), &options).err();
        let message = e.as_ref().map(ToString::to_string).unwrap_or_default();
        assert!(matches!(e, Some(EnvError::Config(_))), "{e:?}");
        assert_mentions(&message, &["goal", "100 m"]);
        assert_eq!(env.info(), &before);
    }
}

#[test]
fn a_trunk_leaving_the_world_ends_the_episode_as_diverged_with_finite_numbers() {
    let mut env = scripted(&[("task.norm_rew_scaling", "1e12")]);
    reset(&mut env, 0);
    env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    let before = env.observation().to_vec();
    env.backend_mut().set_script(|w| {
        w.trunk.pose.translation.x = 1e30;
        Ok(())
    });
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.terminated && s.info.reasons.contains(Reason::Diverged));
    assert_eq!(s.reward, 0.0);
    assert_eq!(s.observation, before.as_slice());
    let what = s
        .info
        .divergence
        .as_ref()
        .map(ToString::to_string)
        .unwrap_or_default();
    assert_mentions(&what, &["trunk_position_x", "1e30", "100 m"]);
}

#[test]
fn an_observation_beyond_float32_ends_the_episode_as_diverged() {
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    env.backend_mut().set_script(|w| {
        w.qd[2] = 1e39;
        Ok(())
    });
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.info.reasons.contains(Reason::Diverged));
    assert!(s.observation_f32.iter().all(|v| v.is_finite()));
    let what = s
        .info
        .divergence
        .as_ref()
        .map(ToString::to_string)
        .unwrap_or_default();
    assert_mentions(&what, &["lf_kfe_speed", "1e39", "float32"]);
}
