//! Invariant: the field's URDF robots (`a1`, `go1_urdf`, `anymal_b`, `laikago`) are bundled
//! names of every command that builds an environment: `hyq run --robot NAME --policy trot`
//! runs each for its full 10 s episode, ended by the time limit, names the robot in its JSON
//! summary and brings it at least 1 m closer to the goal (the profiles' trots walk 2.3 to
//! 4.2 m on rapier). So does the bundled Go1 from MJCF (`go1`), on every engine built in (its
//! trot comes 3.08 / 2.84 / 3.29 m closer on rapier / DART / MuJoCo), and the committed Go1 walker
//! (`assets/policies/go1_walk.safetensors`) walks its seed-1000 episode at least 1.5 m closer
//! (2.19 / 3.63 / 3.77 m; over 100 episodes from that seed its means are 2.38 / 3.39 / 3.35 m,
//! docs/training.md).

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq_ok, one_json_line};

/// Runs `hyq run --robot NAME --backend BACKEND --policy trot` and asserts the episode ran its
/// 10 s and brought the trunk at least 1 m closer to the goal.
fn trots_a_metre(name: &str, backend: &str) {
    walks_at_least(name, backend, "trot", "0", 1.0);
}

/// Runs `hyq run --robot NAME --backend BACKEND --policy POLICY --seed SEED` and asserts the
/// episode ran its 10 s and brought the trunk at least `metres` closer to the goal.
fn walks_at_least(name: &str, backend: &str, policy: &str, seed: &str, metres: f64) {
    let summary = one_json_line(&hyq_ok(&[
        "run",
        "--robot",
        name,
        "--backend",
        backend,
        "--policy",
        policy,
        "--seed",
        seed,
        "--json",
    ]));
    assert_eq!(summary["robot"], name);
    assert_eq!(summary["steps"], 1000, "{name} on {backend}: {summary}");
    assert_eq!(
        summary["reasons"],
        serde_json::json!(["timeout"]),
        "{name} on {backend}"
    );
    let progress = summary["initial_distance_to_goal"].as_f64().unwrap()
        - summary["final_distance_to_goal"].as_f64().unwrap();
    println!("{name} on {backend}: {policy} progress {progress:.3} m");
    assert!(progress >= metres, "{name} on {backend}: {progress} m");
}

#[test]
fn each_field_robot_trots_by_name() {
    for name in ["a1", "go1_urdf", "anymal_b", "laikago"] {
        trots_a_metre(name, "rapier");
    }
}

#[test]
fn go1_from_mjcf_trots_on_every_engine_built_in() {
    trots_a_metre("go1", "rapier");
    #[cfg(feature = "dart")]
    trots_a_metre("go1", "dart");
    #[cfg(feature = "mujoco")]
    trots_a_metre("go1", "mujoco");
}

#[test]
fn the_committed_go1_walker_walks_on_every_engine_built_in() {
    let policy = format!(
        "mlp:{}/../../assets/policies/go1_walk.safetensors",
        env!("CARGO_MANIFEST_DIR")
    );
    walks_at_least("go1", "rapier", &policy, "1000", 1.5);
    #[cfg(feature = "dart")]
    walks_at_least("go1", "dart", &policy, "1000", 1.5);
    #[cfg(feature = "mujoco")]
    walks_at_least("go1", "mujoco", &policy, "1000", 1.5);
}
