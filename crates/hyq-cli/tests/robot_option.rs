//! Invariant: every command that builds an environment takes `--robot NAME|PROFILE.toml`
//! (default `hyq`) and names the robot in its header and its JSON records: the bundled ANYmal C
//! by name, and a third robot (an 8-joint, 2-foot fixture with its own joint names) by profile
//! path, run, bench, soak, render and compare. A robot that is neither a bundled name nor a
//! usable profile is one error line naming it, status 2, before anything runs. The bundled Go1
//! (from MJCF) runs by name and by its profile's path.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::path::{Path, PathBuf};

use common::{hyq, hyq_ok, one_json_line, stderr, usage_error_naming};

/// The 8-joint fixture robot (hyq-env's test fixture): its profile copied next to a URDF made
/// from the bundled ANYmal C with the four HAA joints fixed. Returns the profile's path.
fn eight_joint_profile() -> PathBuf {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("robot-8dof");
    std::fs::create_dir_all(&dir).unwrap();
    let mut urdf = std::fs::read_to_string(root.join("assets/anymal_c/anymal_c.urdf")).unwrap();
    for leg in ["LF", "LH", "RF", "RH"] {
        let revolute = format!("<joint name=\"{leg}_HAA\" type=\"revolute\">");
        assert!(urdf.contains(&revolute), "{revolute}");
        urdf = urdf.replace(
            &revolute,
            &format!("<joint name=\"{leg}_HAA\" type=\"fixed\">"),
        );
    }
    std::fs::write(dir.join("anymal_c_8dof.urdf"), urdf).unwrap();
    let profile = dir.join("profile.toml");
    std::fs::copy(
        root.join("crates/hyq-env/tests/fixtures/anymal_c_8dof/profile.toml"),
        &profile,
    )
    .unwrap();
    profile
}

#[test]
fn run_names_the_robot_in_its_title_and_its_json_summary() {
    let out = hyq_ok(&[
        "run",
        "--robot",
        "anymal_c",
        "--set",
        "task.max_time_steps=50",
    ]);
    assert_eq!(
        out.lines().next().unwrap(),
        "hyq run: anymal_c on rapier, policy trot, seed 0"
    );
    let json = hyq_ok(&[
        "run",
        "--robot",
        "anymal_c",
        "--json",
        "--set",
        "task.max_time_steps=50",
    ]);
    let summary = one_json_line(&json);
    assert_eq!(summary["robot"], "anymal_c");
    assert_eq!(summary["steps"], 50);
    // The default is HyQ.
    let summary = one_json_line(&hyq_ok(&[
        "run",
        "--json",
        "--set",
        "task.max_time_steps=5",
    ]));
    assert_eq!(summary["robot"], "hyq");
}

#[test]
fn bench_and_soak_name_the_robot() {
    let r = one_json_line(&hyq_ok(&[
        "bench", "--robot", "anymal_c", "--steps", "20", "--json",
    ]));
    assert_eq!(r["robot"], "anymal_c");
    let text = hyq_ok(&["bench", "--robot", "anymal_c", "--steps", "20"]);
    assert!(
        text.starts_with("hyq bench: anymal_c on the rapier backend"),
        "{text}"
    );
    let r = one_json_line(&hyq_ok(&[
        "bench",
        "--robot",
        "anymal_c",
        "--steps",
        "10",
        "--num-envs",
        "2",
        "--json",
    ]));
    assert_eq!(r["robot"], "anymal_c");
    let r = one_json_line(&hyq_ok(&[
        "soak", "--robot", "anymal_c", "--steps", "200", "--json",
    ]));
    assert_eq!(r["robot"], "anymal_c");
}

#[test]
fn a_third_robot_from_a_profile_path_runs_through_run_bench_and_render() {
    let profile = eight_joint_profile();
    let profile = profile.to_str().unwrap();
    let summary = one_json_line(&hyq_ok(&[
        "run",
        "--robot",
        profile,
        "--policy",
        "trot",
        "--json",
        "--set",
        "task.max_time_steps=300",
    ]));
    assert_eq!(summary["robot"], "anymal_c_8dof");
    assert_eq!(summary["steps"], 300, "{summary}");
    let dx = summary["final_position"][0].as_f64().unwrap()
        - summary["initial_position"][0].as_f64().unwrap();
    assert!(dx > 0.1, "the 8-joint robot's trot moved {dx} m in 3 s");

    let record = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("robot-8dof.jsonl");
    hyq_ok(&[
        "run",
        "--robot",
        profile,
        "--policy",
        "random",
        "--set",
        "task.max_time_steps=5",
        "--record",
        record.to_str().unwrap(),
    ]);
    let first: serde_json::Value = serde_json::from_str(
        std::fs::read_to_string(&record)
            .unwrap()
            .lines()
            .next()
            .unwrap(),
    )
    .unwrap();
    assert_eq!(first["robot"], "anymal_c_8dof");
    // 2·8 joint rows + 2 foot flags + 11 trunk rows; 8 actions.
    assert_eq!(first["obs"].as_array().unwrap().len(), 29);
    assert_eq!(first["action"].as_array().unwrap().len(), 8);

    let r = one_json_line(&hyq_ok(&[
        "bench", "--robot", profile, "--steps", "20", "--json",
    ]));
    assert_eq!(r["robot"], "anymal_c_8dof");

    let png = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("robot-8dof.gif");
    let _ = std::fs::remove_file(&png);
    hyq_ok(&[
        "render",
        "--robot",
        profile,
        "--seconds",
        "0.05",
        "--width",
        "160",
        "--height",
        "120",
        "--out",
        png.to_str().unwrap(),
    ]);
    assert!(std::fs::metadata(&png).unwrap().len() > 0);
}

#[test]
fn an_unknown_robot_or_an_unusable_profile_is_one_error_line() {
    usage_error_naming(
        &["run", "--robot", "anymal"],
        &["--robot anymal", "hyq", "anymal_c"],
    );
    usage_error_naming(
        &["bench", "--robot", "no/such/profile.toml"],
        &["no/such/profile.toml"],
    );
    usage_error_naming(
        &[
            "compare",
            "--robot",
            "anymal",
            "--scenario",
            "stand",
            "--backends",
            "rapier,rapier",
            "--out",
            env!("CARGO_TARGET_TMPDIR"),
        ],
        &["anymal"],
    );
    // A profile with an unknown key names the file and the key.
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("robot-bad");
    std::fs::create_dir_all(&dir).unwrap();
    let bad = dir.join("profile.toml");
    std::fs::write(&bad, "name = \"x\"\nurdf = \"x.urdf\"\ncolour = \"red\"\n").unwrap();
    let out = hyq(&["soak", "--robot", bad.to_str().unwrap()]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let err = stderr(&out);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.contains("profile.toml") && err.contains("colour"),
        "{err}"
    );
}

#[test]
fn compare_runs_every_scenario_on_anymal_c_and_names_it() {
    for scenario in ["stand", "fall", "limit", "trot", "random", "reach"] {
        let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(format!("cmp-anymal-{scenario}"));
        hyq_ok(&[
            "compare",
            "--robot",
            "anymal_c",
            "--backends",
            "rapier,rapier",
            "--scenario",
            scenario,
            "--seconds",
            "0.3",
            "--one-step-states",
            "3",
            "--strict",
            "--out",
            dir.to_str().unwrap(),
        ]);
        let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
        assert!(md.contains("Robot: `anymal_c`."), "{md}");
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap())
                .unwrap();
        assert_eq!(json["robot"], "anymal_c");
        if scenario == "reach" {
            // The goal's height is ANYmal C's standing height, from its profile.
            assert!(md.contains("0.5341) m"), "{md}");
        }
    }
}

#[test]
fn go1_from_mjcf_runs_by_name_by_profile_and_as_an_mjcf_file_alone() {
    let summary = one_json_line(&hyq_ok(&[
        "run",
        "--robot",
        "go1",
        "--policy",
        "stand",
        "--json",
        "--set",
        "task.max_time_steps=50",
    ]));
    assert_eq!(summary["robot"], "go1");
    assert_eq!(summary["steps"], 50);
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("../..");
    let mjcf = root.join("assets/go1/go1.xml");
    // The MJCF file alone (a `home` keyframe and a <position> actuator on every joint): its
    // profile drafted in memory, standing where the bundled profile says (same pose, same
    // gains), within 1 mm.
    let summary = one_json_line(&hyq_ok(&[
        "run",
        "--robot",
        mjcf.to_str().unwrap(),
        "--policy",
        "stand",
        "--json",
        "--set",
        "task.max_time_steps=100",
    ]));
    assert_eq!(summary["robot"], "go1");
    let z = summary["final_position"][2].as_f64().unwrap_or(f64::NAN);
    assert!((z - 0.2634).abs() < 1e-3, "stood at {z}: {summary}");
    // An MJCF file without a keyframe has no standing pose: one line, pointing at
    // `hyq robot init`.
    let text = std::fs::read_to_string(&mjcf).unwrap();
    let start = text.find("<keyframe>").unwrap();
    let end = text.find("</keyframe>").unwrap() + "</keyframe>".len();
    let no_key = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("go1-no-keyframe.xml");
    std::fs::write(&no_key, format!("{}{}", &text[..start], &text[end..])).unwrap();
    usage_error_naming(
        &["run", "--robot", no_key.to_str().unwrap()],
        &["go1-no-keyframe.xml", "no keyframe", "hyq robot init"],
    );
    // The bundled profile, used by path, reads the MJCF beside it.
    let profile = root.join("assets/go1/profile.toml");
    let summary = one_json_line(&hyq_ok(&[
        "run",
        "--robot",
        profile.to_str().unwrap(),
        "--policy",
        "stand",
        "--json",
        "--set",
        "task.max_time_steps=5",
    ]));
    assert_eq!(summary["robot"], "go1");
}
