//! Invariant: the committed velocity policy (`assets/policies/hyq_velocity.safetensors`) follows
//! a fixed forward command of 0.3 and of 0.6 m/s on every engine built in: `hyq run --seed 1000`
//! for 5 s, its summary's mean |c_x − v_x| is within the task's target of 0.1 m/s and the
//! episode runs out its time (no fall). Its seed-1000 errors are 0.039 / 0.027 / 0.027 m/s at 0.3
//! and 0.032 / 0.034 / 0.033 at 0.6 on rapier / DART / MuJoCo; the 100-episode figures with their
//! intervals are in docs/velocity.md.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq_ok, one_json_line};

/// The task's target for the forward-speed error (m/s), docs/velocity.md.
const TARGET_MPS: f64 = 0.1;

/// Runs the policy at a fixed forward command of `speed` m/s for 500 steps on `backend` and
/// asserts it ran them all and tracked the command within [`TARGET_MPS`].
fn follows(backend: &str, speed: f64) {
    let policy = format!(
        "mlp:{}/../../assets/policies/hyq_velocity.safetensors",
        env!("CARGO_MANIFEST_DIR")
    );
    let command = format!("command.lin_vel_x=[{speed}, {speed}]");
    let summary = one_json_line(&hyq_ok(&[
        "run",
        "--backend",
        backend,
        "--policy",
        &policy,
        "--seed",
        "1000",
        "--set",
        &command,
        "--set",
        "command.lin_vel_y=[0, 0]",
        "--set",
        "command.ang_vel_yaw=[0, 0]",
        "--set",
        "command.resampling=\"uniform\"",
        "--set",
        "command.standing_probability=0",
        "--set",
        "task.max_time_steps=500",
        "--json",
    ]));
    assert_eq!(summary["steps"], 500, "{backend} at {speed}: {summary}");
    assert_eq!(summary["reasons"], serde_json::json!(["timeout"]));
    let error = summary["velocity"]["mean_abs_lin_vel_x_error"]
        .as_f64()
        .unwrap();
    println!("{backend} at {speed} m/s: forward error {error:.3} m/s");
    assert!(error <= TARGET_MPS, "{backend} at {speed} m/s: {error}");
}

#[test]
fn the_committed_velocity_policy_follows_forward_commands_on_every_engine_built_in() {
    let mut engines = vec!["rapier"];
    if cfg!(feature = "dart") {
        engines.push("dart");
    }
    if cfg!(feature = "mujoco") {
        engines.push("mujoco");
    }
    for backend in engines {
        for speed in [0.3, 0.6] {
            follows(backend, speed);
        }
    }
}
