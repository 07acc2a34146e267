//! Invariant: the committed velocity policies (`assets/policies/hyq_velocity.safetensors` for
//! HyQ, `anymal_c_velocity.safetensors` for ANYmal C) follow a fixed forward command of 0.3 and
//! of 0.6 m/s and stand at a zero command on every engine built in: `hyq run --seed 1000`, 5 s
//! at each speed with the summary's mean |c_x − v_x| within the task's target of 0.1 m/s, 10 s
//! at zero with the trunk's horizontal drift within the target of 0.2 m, each episode running
//! out its time (no fall). Their seed-1000 figures on rapier / DART / MuJoCo: HyQ's errors
//! 0.039 / 0.027 / 0.027 m/s at 0.3 and 0.032 / 0.034 / 0.033 at 0.6, drift 0.120 / 0.124 /
//! 0.080 m; ANYmal C's 0.047 / 0.056 / 0.049 and 0.031 / 0.034 / 0.030, drift 0.037 / 0.038 /
//! 0.031 m. The 100-episode figures with their intervals are in docs/velocity.md.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq_ok, one_json_line};

/// The task's target for the forward-speed error (m/s), docs/velocity.md.
const TARGET_MPS: f64 = 0.1;

/// The task's target for the trunk's drift over 10 s at a zero command (m), docs/velocity.md.
const TARGET_DRIFT_M: f64 = 0.2;

/// Each committed velocity policy's file stem and its robot.
const POLICIES: [(&str, &str); 2] = [("hyq_velocity", "hyq"), ("anymal_c_velocity", "anymal_c")];

/// Runs `policy` on `robot` at a fixed forward command of `speed` m/s for `steps` steps on
/// `backend` and returns the run's summary, after asserting it ran them all.
fn run(policy: &str, robot: &str, backend: &str, speed: f64, steps: u32) -> serde_json::Value {
    let file = format!(
        "mlp:{}/../../assets/policies/{policy}.safetensors",
        env!("CARGO_MANIFEST_DIR")
    );
    let command = format!("command.lin_vel_x=[{speed}, {speed}]");
    let length = format!("task.max_time_steps={steps}");
    let summary = one_json_line(&hyq_ok(&[
        "run",
        "--robot",
        robot,
        "--backend",
        backend,
        "--policy",
        &file,
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
        &length,
        "--json",
    ]));
    assert_eq!(
        summary["steps"], steps,
        "{policy} on {backend} at {speed}: {summary}"
    );
    assert_eq!(summary["reasons"], serde_json::json!(["timeout"]));
    summary
}

/// Asserts `policy` tracks `speed` m/s within [`TARGET_MPS`] over 5 s.
fn follows(policy: &str, robot: &str, backend: &str, speed: f64) {
    let summary = run(policy, robot, backend, speed, 500);
    let error = summary["velocity"]["mean_abs_lin_vel_x_error"]
        .as_f64()
        .unwrap();
    println!("{policy} on {backend} at {speed} m/s: forward error {error:.3} m/s");
    assert!(
        error <= TARGET_MPS,
        "{policy} on {backend} at {speed} m/s: {error}"
    );
}

/// Asserts `policy` keeps its trunk within [`TARGET_DRIFT_M`] of its start over 10 s at a
/// zero command.
fn stands(policy: &str, robot: &str, backend: &str) {
    let summary = run(policy, robot, backend, 0.0, 1000);
    let xy = |key: &str| [0, 1].map(|i| summary[key][i].as_f64().unwrap());
    let (start, end) = (xy("initial_position"), xy("final_position"));
    let drift = (end[0] - start[0]).hypot(end[1] - start[1]);
    println!("{policy} on {backend} at a zero command: drift {drift:.3} m");
    assert!(
        drift <= TARGET_DRIFT_M,
        "{policy} on {backend}: drift {drift}"
    );
}

#[test]
fn the_committed_velocity_policies_follow_forward_commands_and_stand_on_every_engine_built_in() {
    let mut engines = vec!["rapier"];
    if cfg!(feature = "dart") {
        engines.push("dart");
    }
    if cfg!(feature = "mujoco") {
        engines.push("mujoco");
    }
    for (policy, robot) in POLICIES {
        for backend in &engines {
            for speed in [0.3, 0.6] {
                follows(policy, robot, backend, speed);
            }
            stands(policy, robot, backend);
        }
    }
}
