//! Invariant: actions map onto joint targets exactly as documented for each mode (normalized
//! [−1, 1] onto each joint's range, absolute radians clipped to the limits, delta from the
//! angle at the start of the step, offset from the robot's standing pose), out-of-range values
//! are clipped or refused as configured, and a refused action (wrong length, NaN or infinity,
//! out of range under "error") names the index and value and changes nothing in the
//! environment.

mod common;

use common::{reset, scripted};
use hyq_env::{ActionError, EnvError};

#[test]
fn normalized_maps_minus_one_to_lower_and_one_to_upper_linearly() {
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    let joints = env.model().joints().to_vec();
    let mut a = vec![0.0; 12];
    a[0] = -1.0;
    a[1] = 1.0;
    a[2] = 0.5;
    let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
    let t = &s.info.joint_targets;
    assert_eq!(t[0], joints[0].lower);
    assert_eq!(t[1], joints[1].upper);
    let expected = joints[2].lower + 0.75 * (joints[2].upper - joints[2].lower);
    assert!((t[2] - expected).abs() < 1e-15, "{} vs {expected}", t[2]);
    for i in 3..12 {
        let mid = 0.5 * (joints[i].lower + joints[i].upper);
        assert!((t[i] - mid).abs() < 1e-15, "joint {i}: {} vs {mid}", t[i]);
    }
    assert!(!s.info.action_clipped);
}

#[test]
fn normalized_values_outside_the_space_are_clipped_and_reported() {
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    let mut a = vec![0.0; 12];
    a[4] = 3.0;
    a[5] = -7.5;
    env.step(&a).unwrap_or_else(|e| panic!("{e}"));
    let joints = env.model().joints();
    assert!(env.info().action_clipped);
    assert_eq!(env.info().joint_targets[4], joints[4].upper);
    assert_eq!(env.info().joint_targets[5], joints[5].lower);
}

#[test]
fn out_of_range_error_mode_refuses_naming_index_and_value() {
    let mut env = scripted(&[("action.out_of_range", "error")]);
    reset(&mut env, 0);
    let mut a = vec![0.0; 12];
    a[7] = 1.25;
    match env.step(&a) {
        Err(EnvError::Action(ActionError::OutOfRange {
            index,
            value,
            joint,
            ..
        })) => {
            assert_eq!((index, value), (7, 1.25));
            assert_eq!(joint, "rf_hfe");
        }
        other => panic!("expected OutOfRange, got {other:?}"),
    }
    let msg = env
        .step(&a)
        .err()
        .map(|e| e.to_string())
        .unwrap_or_default();
    assert!(msg.contains("action[7]") && msg.contains("1.25"), "{msg}");
}

#[test]
fn absolute_targets_are_radians_clipped_to_the_limits() {
    let mut env = scripted(&[("action.mode", "absolute")]);
    reset(&mut env, 0);
    let joints = env.model().joints().to_vec();
    let mut a: Vec<f64> = env.model().standing_pose().to_vec();
    a[0] = 0.1;
    a[2] = -10.0;
    let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.info.joint_targets[0], 0.1);
    assert_eq!(s.info.joint_targets[2], joints[2].lower);
    assert_eq!(s.info.joint_targets[1], a[1]);
    assert!(s.info.action_clipped);
    assert_eq!(env.action_space().low()[2], joints[2].lower);
}

#[test]
fn delta_moves_from_the_angle_at_the_start_of_the_step() {
    let mut env = scripted(&[("action.mode", "delta"), ("action.max_delta_rad", "0.05")]);
    reset(&mut env, 0);
    // One step so that the joints are not exactly at the standing pose.
    env.step(&[0.3; 12]).unwrap_or_else(|e| panic!("{e}"));
    let start = env.joint_angles().to_vec();
    let mut a = vec![0.0; 12];
    a[0] = 1.0;
    a[3] = -0.5;
    a[6] = 2.0; // clipped to 1
    let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
    let t = &s.info.joint_targets;
    assert_eq!(t[0], start[0] + 0.05);
    assert_eq!(t[3], start[3] - 0.025);
    assert_eq!(t[6], start[6] + 0.05);
    assert_eq!(t[1], start[1]);
}

#[test]
fn delta_targets_stay_within_the_limits() {
    let mut env = scripted(&[("action.mode", "delta"), ("action.max_delta_rad", "10")]);
    reset(&mut env, 0);
    let s = env.step(&[1.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    let targets = s.info.joint_targets.clone();
    for (t, j) in targets.iter().zip(env.model().joints()) {
        assert_eq!(*t, j.upper, "{}", j.name);
    }
}

#[test]
fn offset_zero_holds_the_standing_pose_and_scales_from_it() {
    let mut env = scripted(&[("action.mode", "offset"), ("action.max_offset_rad", "0.25")]);
    reset(&mut env, 0);
    // One step so that the joints are not exactly at the standing pose: offset mode must not
    // read the current angle.
    env.step(&[0.3; 12]).unwrap_or_else(|e| panic!("{e}"));
    let standing = env.model().standing_pose().to_vec();
    let s = env.step(&[0.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.info.joint_targets, standing);
    let mut a = vec![0.0; 12];
    a[1] = 1.0;
    a[2] = -0.5;
    a[4] = 3.0; // clipped to 1
    let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
    let t = &s.info.joint_targets;
    assert_eq!(t[1], standing[1] + 0.25);
    assert_eq!(t[2], standing[2] - 0.125);
    assert_eq!(t[4], standing[4] + 0.25);
    assert_eq!(t[0], standing[0]);
    assert!(s.info.action_clipped);
    let space = env.action_space();
    assert_eq!((space.low()[0], space.high()[0]), (-1.0, 1.0));
}

#[test]
fn offset_targets_stay_within_the_limits() {
    let mut env = scripted(&[("action.mode", "offset"), ("action.max_offset_rad", "10")]);
    reset(&mut env, 0);
    let s = env.step(&[-1.0; 12]).unwrap_or_else(|e| panic!("{e}"));
    let targets = s.info.joint_targets.clone();
    for (t, j) in targets.iter().zip(env.model().joints()) {
        assert_eq!(*t, j.lower, "{}", j.name);
    }
}

#[test]
fn f32_actions_map_like_f64_actions() {
    let mut a = scripted(&[]);
    let mut b = scripted(&[]);
    reset(&mut a, 0);
    reset(&mut b, 0);
    let x32: Vec<f32> = (0..12).map(|i| -0.9 + 0.15 * i as f32).collect();
    let x64: Vec<f64> = x32.iter().map(|v| f64::from(*v)).collect();
    let ta = a.step(&x32).map(|s| s.info.joint_targets.clone());
    let tb = b.step(&x64).map(|s| s.info.joint_targets.clone());
    assert_eq!(ta.ok(), tb.ok());
}

#[test]
fn refused_actions_name_the_problem_and_change_nothing() {
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    env.step(&[0.1; 12]).unwrap_or_else(|e| panic!("{e}"));
    let obs = env.observation().to_vec();
    let info = env.info().clone();
    let substeps = env.backend().substeps();
    let q = env.joint_angles().to_vec();

    let mut nan = vec![0.0; 12];
    nan[9] = f64::NAN;
    let mut inf = vec![0.0f32; 12];
    inf[11] = f32::NEG_INFINITY;
    let cases: Vec<(Result<(), EnvError>, &str)> = vec![
        (env.step(&[0.0; 11]).map(|_| ()), "11 values"),
        (env.step(&[0.0; 13]).map(|_| ()), "13 values"),
        (env.step(&nan).map(|_| ()), "action[9] (rh_haa) is NaN"),
        (env.step(&inf).map(|_| ()), "action[11] (rh_kfe) is -inf"),
    ];
    for (result, needle) in cases {
        let msg = match result {
            Err(e @ EnvError::Action(_)) => e.to_string(),
            other => panic!("expected an action error for {needle}, got {other:?}"),
        };
        assert!(msg.contains(needle), "{msg:?} should contain {needle:?}");
    }
    assert_eq!(env.observation(), obs.as_slice());
    assert_eq!(env.info(), &info);
    assert_eq!(env.backend().substeps(), substeps);
    assert_eq!(env.joint_angles(), q.as_slice());
    // And the env still steps normally.
    let s = env.step(&[0.1; 12]).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(s.info.t, info.t + 1);
}

#[test]
fn action_for_targets_inverts_the_mapping() {
    for mode in ["normalized", "absolute", "delta", "offset"] {
        let mut env = scripted(&[
            ("action.mode", mode),
            ("action.max_delta_rad", "2"),
            ("action.max_offset_rad", "2"),
        ]);
        reset(&mut env, 0);
        let targets: Vec<f64> = env
            .model()
            .joints()
            .iter()
            .map(|j| j.lower + 0.3 * (j.upper - j.lower))
            .collect();
        let mut a = vec![0.0; 12];
        env.action_space()
            .action_for_targets(&targets, env.joint_angles(), &mut a);
        let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        for (got, want) in s.info.joint_targets.iter().zip(&targets) {
            assert!((got - want).abs() < 1e-12, "{mode}: {got} vs {want}");
        }
    }
}
