//! Invariant (with `--features mujoco`, which needs `cargo xtask setup mujoco`): every
//! subcommand that takes a backend runs on MuJoCo and says so: `run` (the trot walks forward),
//! `bench` (its JSON names the backend, physics is most of the step), `soak` (random actions
//! emit only finite numbers), `render` (frames are written) and `compare --backends
//! rapier,mujoco` (the three reports are written; the ledger has no rapier-vs-MuJoCo entries
//! yet, so only the run and what both engines did are checked).
#![cfg(feature = "mujoco")]
#![allow(clippy::unwrap_used)]

mod common;

use common::{hyq_ok, one_json_line, scratch};
use serde_json::Value;

#[test]
fn run_trots_forward_on_mujoco() {
    let out = hyq_ok(&[
        "run",
        "--backend",
        "mujoco",
        "--json",
        "--set",
        "task.max_time_steps=200",
    ]);
    let e: Value = serde_json::from_str(out.trim()).unwrap();
    assert_eq!(e["backend"], "mujoco");
    assert_eq!(e["steps"], 200);
    assert_eq!(e["reasons"], serde_json::json!(["timeout"]));
    let dx = e["final_position"][0].as_f64().unwrap() - e["initial_position"][0].as_f64().unwrap();
    // After the gait's 1 s ramp the trot carries HyQ forward (about 0.5 m in 2 s).
    assert!(dx > 0.2, "the trot walks forward on MuJoCo ({dx} m in 2 s)");
}

#[test]
fn bench_and_soak_run_on_mujoco() {
    let r = one_json_line(&hyq_ok(&[
        "bench",
        "--backend",
        "mujoco",
        "--steps",
        "300",
        "--json",
    ]));
    assert_eq!(r["backend"], "mujoco");
    assert_eq!(r["steps"], 300);
    let physics = r["shares"]["physics"].as_f64().unwrap();
    assert!(physics > 0.5, "physics share {physics}");

    let out = hyq_ok(&[
        "soak",
        "--backend",
        "mujoco",
        "--steps",
        "3000",
        "--seed",
        "2",
        "--json",
    ]);
    let s: Value = serde_json::from_str(out.trim()).unwrap_or_else(|e| panic!("{e}: {out}"));
    assert_eq!(s["steps"], 3000);
    assert_eq!(s["non_finite"], 0);
}

#[test]
fn render_writes_frames_on_mujoco() {
    let out = scratch("render_mujoco.gif");
    let stdout = hyq_ok(&[
        "render",
        "--backend",
        "mujoco",
        "--seconds",
        "0.2",
        "--fps",
        "10",
        "--width",
        "64",
        "--height",
        "48",
        "--out",
        out.to_str().unwrap(),
    ]);
    assert!(stdout.contains("wrote 3 frames"), "{stdout}");
    assert!(std::fs::metadata(&out).unwrap().len() > 0);
}

#[test]
fn compare_rapier_with_mujoco_writes_the_reports() {
    let dir = scratch("compare_mujoco");
    let _ = std::fs::remove_dir_all(&dir);
    let out = hyq_ok(&[
        "compare",
        "--backends",
        "rapier,mujoco",
        "--scenario",
        "limit",
        "--one-step-states",
        "5",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.contains("rapier ended joint_limit"), "{out}");
    assert!(out.contains("mujoco ended joint_limit"), "{out}");
    let json: Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap();
    assert_eq!(json["engines"][1], "mujoco");
    for file in ["report.md", "report.json", "trunk_x_z.png"] {
        assert!(dir.join(file).is_file(), "{file} not written");
    }
}
