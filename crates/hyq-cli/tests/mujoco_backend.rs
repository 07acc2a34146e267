//! Invariant (with `--features mujoco`, which needs `cargo xtask setup mujoco`): every
//! subcommand that takes a backend runs on MuJoCo and says so: `run` (the trot walks forward),
//! `bench` (its JSON names the backend, physics is most of the step), `soak` (random actions
//! emit only finite numbers), `render` (frames are written) and `compare --backends
//! rapier,mujoco` (the three reports are written; the ledger has no rapier-vs-MuJoCo entries
//! yet, so only the run and what both engines did are checked). Bad input and output hold on
//! MuJoCo as on rapier: a configuration outside the bounds that keep every number finite is a
//! usage error, and the largest accepted one writes only numbers; a MuJoCo that cannot be
//! loaded is one error line and leaves an existing record as it was (for `compare` as for
//! `run`: the same words, exit status 2); a closed stdout ends a
//! MuJoCo command quietly.
#![cfg(feature = "mujoco")]
#![allow(clippy::unwrap_used)]

mod common;

use std::process::{Command, Stdio};

use common::{first_null, hyq, hyq_ok, one_json_line, scratch, stderr, usage_error_naming};
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

#[test]
fn configurations_beyond_the_finite_bounds_are_refused_and_the_largest_give_numbers_on_mujoco() {
    for (set, key) in [
        ("reset.spawn_xy_m=[1e5, 0]", "reset.spawn_xy_m"),
        ("task.exp_rew_scaling=1000", "task.exp_rew_scaling"),
        ("goal.position=[9, 9, 0.6]", "goal.position"),
    ] {
        usage_error_naming(&["run", "--backend", "mujoco", "--set", set], &[key]);
    }
    let record = scratch("mujoco-largest.jsonl");
    let out = hyq_ok(&[
        "run",
        "--backend",
        "mujoco",
        "--json",
        "--record",
        record.to_str().unwrap(),
        "--set",
        "task.exp_rew_scaling=500",
        "--set",
        "task.base_rew_scaling=1e12",
        "--set",
        "task.norm_rew_scaling=1e12",
        "--set",
        "task.fall_penalty=1e12",
        "--set",
        "task.max_time_steps=200",
    ]);
    let text = std::fs::read_to_string(&record).unwrap();
    assert_eq!(text.lines().count(), 200);
    for (i, line) in text.lines().chain(out.lines()).enumerate() {
        let v: Value = serde_json::from_str(line).unwrap();
        assert_eq!(
            first_null(&v, ""),
            None,
            "line {} holds null: {line}",
            i + 1
        );
    }
}

#[test]
fn a_mujoco_that_cannot_be_loaded_is_one_line_and_keeps_the_record() {
    let dir = scratch("mujoco-missing");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let record = dir.join("keep.jsonl");
    std::fs::write(&record, "precious data\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_hyq"))
        .args(["run", "--backend", "mujoco", "--record"])
        .arg(&record)
        .env("MUJOCO_DIR", dir.join("no-mujoco-here"))
        .output()
        .unwrap();
    let err = stderr(&out);
    assert!(
        !out.status.success() && out.status.code() != Some(101),
        "{err}"
    );
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(
        err.starts_with("hyq: error: ") && err.contains("MuJoCo 4.0.0"),
        "{err}"
    );
    assert_eq!(std::fs::read_to_string(&record).unwrap(), "precious data\n");
    let left: Vec<_> = std::fs::read_dir(&dir).unwrap().collect();
    assert_eq!(left.len(), 1, "no temporary file is left");
}

#[test]
fn compare_with_a_mujoco_that_cannot_be_loaded_is_a_usage_error_as_run_is() {
    let dir = scratch("mujoco-missing-compare");
    let _ = std::fs::remove_dir_all(&dir);
    let outcome = |args: &[&str]| {
        Command::new(env!("CARGO_BIN_EXE_hyq"))
            .args(args)
            .env("MUJOCO_DIR", dir.join("no-mujoco-here"))
            .output()
            .unwrap()
    };
    let run = outcome(&["run", "--backend", "mujoco"]);
    let out = dir.join("cmp");
    let compare = outcome(&[
        "compare",
        "--backends",
        "rapier,mujoco",
        "--scenario",
        "stand",
        "--out",
        out.to_str().unwrap(),
    ]);
    for o in [&run, &compare] {
        let err = stderr(o);
        assert_eq!(o.status.code(), Some(2), "{err}");
        assert_eq!(err.lines().count(), 1, "{err}");
        assert!(
            err.starts_with("hyq: error: cannot build the mujoco environment: ")
                && err.contains("MuJoCo 4.0.0"),
            "{err}"
        );
    }
    assert!(!out.join("report.md").exists());
}

#[test]
fn a_closed_stdout_ends_mujoco_commands_quietly() {
    let cases: [&[&str]; 3] = [
        &[
            "run",
            "--backend",
            "mujoco",
            "--json",
            "--set",
            "task.max_time_steps=5",
        ],
        &["soak", "--backend", "mujoco", "--steps", "50"],
        &["bench", "--backend", "mujoco", "--steps", "20"],
    ];
    for args in cases {
        let mut child = Command::new(env!("CARGO_BIN_EXE_hyq"))
            .args(args)
            .stdout(Stdio::piped())
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        drop(child.stdout.take());
        let out = child.wait_with_output().unwrap();
        let err = String::from_utf8(out.stderr).unwrap();
        assert_eq!(out.status.code(), Some(0), "hyq {args:?}: {err}");
        assert!(err.is_empty(), "hyq {args:?} printed on stderr: {err}");
    }
    // The same commands with a reader succeed (so the above is not a start-up failure).
    assert!(
        hyq(&["soak", "--backend", "mujoco", "--steps", "50"])
            .status
            .success()
    );
}
