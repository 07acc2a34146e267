//! Invariant: `hyq model` writes the robot the environment simulates, under the configuration
//! given: the MJCF has one actuator of the chosen kind per joint in action order and the MuJoCo
//! backend's solver and contact settings (`[physics.mujoco]`), the URDF has
//! the chosen capsule form, the JSON facts hold the joints in action order with the
//! configuration's gains, sub-steps and t_max; over `[terrain]` the MJCF's ground is the
//! height field the environment's first episode runs on; `--out` writes the file and prints
//! nothing; bad input is a one-line error.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq, hyq_ok, scratch, stderr, usage_error_naming};

const JOINTS: [&str; 12] = [
    "lf_haa", "lf_hfe", "lf_kfe", "lh_haa", "lh_hfe", "lh_kfe", "rf_haa", "rf_hfe", "rf_kfe",
    "rh_haa", "rh_hfe", "rh_kfe",
];

fn count(text: &str, needle: &str) -> usize {
    text.matches(needle).count()
}

#[test]
fn mjcf_has_one_actuator_of_the_chosen_kind_per_joint_in_action_order() {
    let servos = hyq_ok(&["model", "--format", "mjcf"]);
    assert!(servos.starts_with("<mujoco model=\"hyq\">"), "{servos}");
    assert_eq!(count(&servos, "<position "), 12);
    assert_eq!(count(&servos, "kp=\"1000\" kv=\"20\""), 12);
    let order: Vec<usize> = JOINTS
        .iter()
        .map(|j| servos.find(&format!("<position name=\"{j}\"")).unwrap())
        .collect();
    assert!(order.windows(2).all(|w| w[0] < w[1]), "{order:?}");
    let motors = hyq_ok(&["model", "--format", "mjcf", "--actuators", "motor"]);
    assert_eq!(count(&motors, "<motor "), 12);
    assert_eq!(count(&motors, "<position "), 0);
    let none = hyq_ok(&["model", "--format", "mjcf", "--actuators", "none"]);
    assert!(!none.contains("<actuator>"));
    let fine = hyq_ok(&["model", "--format", "mjcf", "--set", "physics.dt=0.0005"]);
    assert!(fine.contains("timestep=\"0.0005\""));
}

#[test]
fn mjcf_writes_the_terrains_height_field() {
    let flat = hyq_ok(&["model", "--format", "mjcf"]);
    assert!(!flat.contains("<hfield") && flat.contains("type=\"plane\""));
    let rough = hyq_ok(&[
        "model",
        "--format",
        "mjcf",
        "--set",
        "terrain.kind=\"rough\"",
        "--set",
        "terrain.size_m=[2.0, 1.0]",
        "--set",
        "terrain.resolution_m=0.1",
        // The goal on the field: a field not under the goal is refused.
        "--set",
        "goal.distance_m=0.9",
    ]);
    // 21 x 11 heights: MuJoCo's rows run along y, its columns along x.
    assert!(
        rough.contains("<hfield name=\"terrain\" nrow=\"11\" ncol=\"21\""),
        "{rough}"
    );
    assert!(rough.contains("type=\"hfield\"") && !rough.contains("type=\"plane\""));
    usage_error_naming(
        &[
            "model",
            "--format",
            "mjcf",
            "--set",
            "terrain.kind=\"heightfield\"",
            "--set",
            "terrain.file=\"no-such-heights.npy\"",
        ],
        &["terrain.file", "no-such-heights.npy"],
    );
}

#[test]
fn mjcf_carries_the_mujoco_backends_solver_settings() {
    // The backend's defaults: 10 no-slip iterations, 2 ms contacts and limits (MuJoCo's own
    // are 0 and 20 ms).
    let xml = hyq_ok(&["model", "--format", "mjcf"]);
    assert!(xml.contains("noslip_iterations=\"10\""), "{xml}");
    assert_eq!(count(&xml, "solref=\"0.002 1\""), 1, "{xml}");
    let xml = hyq_ok(&[
        "model",
        "--format",
        "mjcf",
        "--set",
        "physics.mujoco.noslip_iterations=3",
        "--set",
        "physics.mujoco.cone=\"elliptic\"",
    ]);
    assert!(
        xml.contains("noslip_iterations=\"3\"") && xml.contains("cone=\"elliptic\""),
        "{xml}"
    );
    usage_error_naming(
        &[
            "model",
            "--format",
            "mjcf",
            "--set",
            "physics.mujoco.impratio=0",
        ],
        &["mujoco.impratio"],
    );
}

#[test]
fn urdf_writes_capsules_as_asked() {
    let capsules = hyq_ok(&["model", "--format", "urdf"]);
    assert!(capsules.contains("<robot name=\"hyq\">"));
    assert_eq!(count(&capsules, "<capsule "), 8);
    assert_eq!(count(&capsules, "type=\"revolute\""), 12);
    let cylinders = hyq_ok(&["model", "--format", "urdf", "--capsules", "cylinder"]);
    assert_eq!(count(&cylinders, "<capsule "), 0);
    assert_eq!(count(&cylinders, "<cylinder "), 8);
    // The thigh capsule (radius 0.039, cap centres 0.318 apart) as a cylinder spans its caps.
    assert!(
        cylinders.contains("<cylinder radius=\"0.039\" length=\"0.396\"/>"),
        "{cylinders}"
    );
}

#[test]
fn json_facts_follow_the_configuration() {
    let text = hyq_ok(&[
        "model",
        "--format",
        "json",
        "--set",
        "control.sim_steps_per_env_step=5",
        "--set",
        "control.kp=800",
        "--set",
        "task.max_time_steps=200",
    ]);
    let facts: serde_json::Value = serde_json::from_str(&text).unwrap();
    assert_eq!(facts["schema_version"], 1);
    assert_eq!(facts["substeps"], 5);
    assert_eq!(facts["max_env_steps"], 200);
    assert_eq!(facts["dt"], 0.001);
    assert_eq!(facts["joint_limit_margin"], 0.01);
    let joints = facts["joints"].as_array().unwrap();
    let names: Vec<&str> = joints.iter().map(|j| j["name"].as_str().unwrap()).collect();
    assert_eq!(names, JOINTS);
    for j in joints {
        assert_eq!(j["kp"], 800.0);
        assert_eq!(j["kd"], 20.0);
        assert_eq!(j["effort"], 150.0);
        let (lo, hi, stand) = (
            j["lower"].as_f64().unwrap(),
            j["upper"].as_f64().unwrap(),
            j["standing"].as_f64().unwrap(),
        );
        assert!(lo < stand && stand < hi, "{j}");
    }
    let feet: Vec<&str> = facts["feet"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f["link"].as_str().unwrap())
        .collect();
    assert_eq!(
        feet,
        ["lf_lowerleg", "lh_lowerleg", "rf_lowerleg", "rh_lowerleg"]
    );
    // Every tracked shape index points at a shape of its link; the feet at spheres.
    let links = facts["links"].as_array().unwrap();
    for foot in facts["feet"].as_array().unwrap() {
        let link = links.iter().find(|l| l["name"] == foot["link"]).unwrap();
        for s in foot["shapes"].as_array().unwrap() {
            let shape = &link["collisions"][s.as_u64().unwrap() as usize];
            assert_eq!(shape["shape"], "sphere", "{shape}");
        }
    }
    assert_eq!(facts["spawn"]["position"][2], 0.6003);
    assert_eq!(facts["spawn"]["q"].as_array().unwrap().len(), 12);
    assert!((facts["total_mass"].as_f64().unwrap() - 86.774).abs() < 1e-9);
}

#[test]
fn out_writes_the_file_and_prints_nothing() {
    let path = scratch("model_out.xml");
    let out = hyq(&["model", "--format", "mjcf", "--out", path.to_str().unwrap()]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(out.stdout.is_empty());
    let written = std::fs::read_to_string(&path).unwrap();
    assert_eq!(written, hyq_ok(&["model", "--format", "mjcf"]));
}

#[test]
fn bad_input_is_a_one_line_error() {
    usage_error_naming(&["model"], &["--format"]);
    usage_error_naming(
        &["model", "--format", "sdf"],
        &["sdf", "mjcf", "urdf", "json"],
    );
    usage_error_naming(
        &["model", "--format", "mjcf", "--set", "control.kp=500"],
        &["--actuators position", "control.kp"],
    );
    usage_error_naming(
        &["model", "--format", "json", "--set", "physics.dt=-1"],
        &["physics.dt"],
    );
    let out = hyq(&[
        "model",
        "--format",
        "json",
        "--out",
        "/nonexistent/dir/hyq.json",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("hyq: error: cannot write /nonexistent/dir/hyq.json"),
        "{err}"
    );
}
