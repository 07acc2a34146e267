//! Invariant: under `task.kind = "velocity"`, `hyq run --plot DIR` writes the velocity task's
//! plot (`episode_NNN_velocity.png`: the command, the task's reward and every task term) beside
//! the spec's two, and `hyq plot FILE.jsonl` draws all three from the run's `--record`, byte for
//! byte, listing every file it wrote; the spec's task writes no such plot.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::path::PathBuf;

use common::{hyq_ok, scratch};

fn scratch_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn names(dir: &std::path::Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

const FILES: [&str; 3] = [
    "episode_001_distance.png",
    "episode_001_rewards.png",
    "episode_001_velocity.png",
];

#[test]
fn a_velocity_run_plots_its_terms_and_the_record_redraws_them() {
    let live = scratch_dir("velocity_plot_live");
    let replay = scratch_dir("velocity_plot_replay");
    let record = scratch("velocity_plot_run.jsonl");
    let config = [
        "--set",
        "task.kind=velocity",
        "--set",
        "task.max_time_steps=60",
        "--set",
        "command.lin_vel_x=[0.4,0.4]",
    ];
    let (live_s, record_s) = (live.to_str().unwrap(), record.to_str().unwrap());
    let mut run = vec!["run", "--policy", "trot", "--episodes", "1", "--seed", "2"];
    run.extend(config);
    run.extend(["--record", record_s, "--plot", live_s]);
    let stdout = hyq_ok(&run);
    assert!(stdout.contains("wrote 3 plots to"), "{stdout}");
    assert_eq!(names(&live), FILES);

    let mut plot = vec!["plot", record_s, "--out", replay.to_str().unwrap()];
    plot.extend(["--title", "rapier, trot, seed 2"]);
    plot.extend(config);
    let listed = hyq_ok(&plot);
    assert_eq!(listed.lines().count(), 3, "{listed}");
    for name in FILES {
        assert!(listed.contains(name), "{listed}");
        assert_eq!(
            std::fs::read(live.join(name)).unwrap(),
            std::fs::read(replay.join(name)).unwrap(),
            "{name}: the record's plot differs from the live one"
        );
    }
}

#[test]
fn a_run_of_the_spec_task_writes_no_velocity_plot() {
    let live = scratch_dir("goal_plot_live");
    let stdout = hyq_ok(&[
        "run",
        "--policy",
        "trot",
        "--set",
        "task.max_time_steps=30",
        "--plot",
        live.to_str().unwrap(),
    ]);
    assert!(stdout.contains("wrote 2 plots to"), "{stdout}");
    assert_eq!(names(&live), FILES[..2]);
}
