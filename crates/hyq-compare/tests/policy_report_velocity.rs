//! Invariant: under `task.kind = "velocity"` a policy comparison gives each engine's
//! forward-speed and yaw-rate tracking errors, and for commanded stands the feet's mean speed
//! and the trunk's drift, each as `{"mean", "ci95"}` over the episodes, beside the fall rate
//! (k of n with Wilson's interval), in report.json and report.md; the spec's task writes none
//! of it. Known answers on every engine: the standing policy (the PD actuator holding the
//! standing pose) told to stand stands (errors, feet speed and drift near 0, no falls), and told
//! to walk at 0.3 m/s and turn at 0.5 rad/s it still stands, so its errors are the command.

#![allow(clippy::unwrap_used)]

use hyq_compare::{PolicyPlan, PolicyReport, PolicySpec};
use hyq_env::{EnvConfig, Stand};
use hyq_physics::Backend;
use hyq_rapier::RapierBackend;
use serde_json::Value;

const EPISODES: u32 = 3;

/// The standing policy's plan: `EPISODES` episodes of 1 s with reset noise, seed 11, the
/// velocity task at the fixed command (`vx` m/s, `yaw` rad/s) or, with `None`, the spec's task.
fn plan(command: Option<(f64, f64)>) -> PolicyPlan<Stand> {
    let mut keys = vec![
        ("task.max_time_steps".to_owned(), "100".to_owned()),
        ("reset.joint_noise_rad".to_owned(), "0.02".to_owned()),
    ];
    if let Some((vx, yaw)) = command {
        keys.push(("task.kind".into(), "\"velocity\"".into()));
        keys.push(("command.lin_vel_x".into(), format!("[{vx:?}, {vx:?}]")));
        keys.push(("command.lin_vel_y".into(), "[0.0, 0.0]".into()));
        keys.push(("command.ang_vel_yaw".into(), format!("[{yaw:?}, {yaw:?}]")));
    }
    let config = EnvConfig::load(None, &keys).unwrap();
    let spec = PolicySpec {
        policy: "stand".into(),
        seed: 11,
        episodes: EPISODES,
        configuration: Vec::new(),
    };
    PolicyPlan::new(hyq_physics::bundled::hyq(), config, Stand, spec).unwrap()
}

fn report<B: Backend>(command: Option<(f64, f64)>) -> (PolicyReport, Value) {
    let plan = plan(command);
    let side = plan.run_side::<B>(B::NAME).unwrap();
    let report = plan.report(&[side], &[]);
    let json = serde_json::from_str(&report.to_json()).unwrap();
    (report, json)
}

/// A figure's mean after checking it is `{"mean", "ci95"}` with the mean inside, over `n`
/// episodes.
fn figure(v: &Value, n: u64) -> f64 {
    let mean = v["mean"].as_f64().unwrap();
    let ci = v["ci95"].as_array().unwrap();
    let (lo, hi) = (ci[0].as_f64().unwrap(), ci[1].as_f64().unwrap());
    assert!(lo <= mean && mean <= hi, "{v}");
    assert_eq!(v["episodes"], n, "{v}");
    mean
}

fn a_commanded_stand_stands<B: Backend>() {
    let (report, json) = report::<B>(Some((0.0, 0.0)));
    let v = &json["sides"][0]["velocity"];
    let n = u64::from(EPISODES);
    for key in ["forward_error_mps", "yaw_error_radps"] {
        let e = figure(&v[key], n);
        assert!((0.0..0.02).contains(&e), "{}: {key} {e}", B::NAME);
    }
    let feet = figure(&v["standing_feet_speed_mps"], n);
    assert!((0.0..0.02).contains(&feet), "{}: feet {feet} m/s", B::NAME);
    let drift = figure(&v["standing_drift_m"], n);
    assert!((0.0..0.02).contains(&drift), "{}: drift {drift} m", B::NAME);
    let fell = &json["sides"][0]["rates"]["fell"];
    assert_eq!((fell["k"].as_u64(), fell["n"].as_u64()), (Some(0), Some(n)));
    // Every episode carries its own figures.
    assert!(json["sides"][0]["episodes"][0]["velocity"]["standing"]["drift_m"].is_f64());
    let md = report.to_markdown("test");
    assert!(md.contains("## Velocity task") && md.contains("zero command: trunk drift (m)"));
}

fn a_standing_robot_misses_a_walk_and_turn_command_by_the_command<B: Backend>() {
    let (_, json) = report::<B>(Some((0.3, 0.5)));
    let v = &json["sides"][0]["velocity"];
    let n = u64::from(EPISODES);
    let forward = figure(&v["forward_error_mps"], n);
    assert!(
        (forward - 0.3).abs() < 0.02,
        "{}: forward {forward}",
        B::NAME
    );
    let yaw = figure(&v["yaw_error_radps"], n);
    assert!((yaw - 0.5).abs() < 0.02, "{}: yaw {yaw}", B::NAME);
    // Not a commanded stand: no stand figures.
    assert!(v.get("standing_drift_m").is_none(), "{v}");
    assert!(v.get("standing_feet_speed_mps").is_none(), "{v}");
}

#[test]
fn rapier_a_commanded_stand_stands() {
    a_commanded_stand_stands::<RapierBackend>();
}

#[test]
fn rapier_a_standing_robot_misses_a_walk_and_turn_command_by_the_command() {
    a_standing_robot_misses_a_walk_and_turn_command_by_the_command::<RapierBackend>();
}

#[test]
fn the_spec_task_writes_no_velocity_figures() {
    let (report, json) = report::<RapierBackend>(None);
    assert!(json["sides"][0].get("velocity").is_none());
    assert!(json["sides"][0]["episodes"][0].get("velocity").is_none());
    assert!(!report.to_markdown("test").contains("Velocity task"));
}

#[test]
fn the_velocity_figures_repeat_byte_for_byte() {
    let (a, _) = report::<RapierBackend>(Some((0.3, 0.5)));
    let (b, _) = report::<RapierBackend>(Some((0.3, 0.5)));
    assert_eq!(a.to_json(), b.to_json());
}

#[cfg(feature = "dart")]
#[test]
fn dart_a_commanded_stand_stands_and_misses_a_walk_by_the_command() {
    a_commanded_stand_stands::<hyq_dart::DartBackend>();
    a_standing_robot_misses_a_walk_and_turn_command_by_the_command::<hyq_dart::DartBackend>();
}

#[cfg(feature = "mujoco")]
#[test]
fn mujoco_a_commanded_stand_stands_and_misses_a_walk_by_the_command() {
    a_commanded_stand_stands::<hyq_mujoco::MujocoBackend>();
    a_standing_robot_misses_a_walk_and_turn_command_by_the_command::<hyq_mujoco::MujocoBackend>();
}
