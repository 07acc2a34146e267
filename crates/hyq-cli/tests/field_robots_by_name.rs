//! Invariant: the field's URDF robots (`a1`, `go1_urdf`, `anymal_b`, `laikago`) are bundled
//! names of every command that builds an environment: `hyq run --robot NAME --policy trot`
//! runs each for its full 10 s episode, ended by the time limit, names the robot in its JSON
//! summary and brings it at least 1 m closer to the goal (the profiles' trots walk 2.3 to
//! 4.2 m on rapier).

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq_ok, one_json_line};

#[test]
fn each_field_robot_trots_by_name() {
    for name in ["a1", "go1_urdf", "anymal_b", "laikago"] {
        let summary = one_json_line(&hyq_ok(&[
            "run", "--robot", name, "--policy", "trot", "--json",
        ]));
        assert_eq!(summary["robot"], name);
        assert_eq!(summary["steps"], 1000, "{name}: {summary}");
        assert_eq!(summary["reasons"], serde_json::json!(["timeout"]), "{name}");
        let progress = summary["initial_distance_to_goal"].as_f64().unwrap()
            - summary["final_distance_to_goal"].as_f64().unwrap();
        println!("{name}: trot progress {progress:.3} m");
        assert!(progress >= 1.0, "{name}: {progress} m");
    }
}
