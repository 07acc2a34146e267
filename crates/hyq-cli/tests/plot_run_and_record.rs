//! Invariant: `hyq run --plot DIR` writes two non-empty PNG plots per episode (reward terms,
//! distance), and `hyq plot FILE.jsonl` draws the same plots from the run's `--record`, byte
//! for byte, given the run's configuration and title; bad input (a missing file, a malformed
//! line, an empty file, an unwritable directory) is refused with one error line naming it.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::path::{Path, PathBuf};

use common::{hyq_ok, scratch, usage_error_naming};

fn scratch_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Decodes a PNG: its size and how many distinct colours it holds.
fn png_size_and_colours(path: &Path) -> ((u32, u32), usize) {
    let decoder = png::Decoder::new(std::io::BufReader::new(std::fs::File::open(path).unwrap()));
    let mut reader = decoder.read_info().unwrap();
    let mut buf = vec![0; reader.output_buffer_size().unwrap()];
    let info = reader.next_frame(&mut buf).unwrap();
    buf.truncate(info.buffer_size());
    let channels = info.color_type.samples();
    let mut px: Vec<&[u8]> = buf.chunks_exact(channels).collect();
    px.sort_unstable();
    px.dedup();
    ((info.width, info.height), px.len())
}

const FILES: [&str; 4] = [
    "episode_001_rewards.png",
    "episode_001_distance.png",
    "episode_002_rewards.png",
    "episode_002_distance.png",
];

#[test]
fn run_plot_writes_per_episode_pngs_and_plot_redraws_them_from_the_record() {
    let live = scratch_dir("plot_live");
    let replay = scratch_dir("plot_replay");
    let record = scratch("plot_run.jsonl");
    // Two short episodes with the reward terms all on, so that every panel has data.
    let config = [
        "--set",
        "task.max_time_steps=40",
        "--set",
        "task.base_rew_scaling=1",
        "--set",
        "task.norm_rew_scaling=10",
    ];
    let mut run = vec!["run", "--episodes", "2", "--seed", "4"];
    run.extend(config);
    let (live_s, record_s) = (live.to_str().unwrap(), record.to_str().unwrap());
    run.extend(["--record", record_s, "--plot", live_s]);
    let stdout = hyq_ok(&run);
    assert!(stdout.contains("wrote 4 plots to"), "{stdout}");

    let mut names: Vec<String> = std::fs::read_dir(&live)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    let mut expected: Vec<String> = FILES.iter().map(|s| s.to_string()).collect();
    expected.sort();
    assert_eq!(names, expected);
    for name in FILES {
        let ((w, h), colours) = png_size_and_colours(&live.join(name));
        assert!(w > 0 && h > 0);
        assert!(colours > 10, "{name}: {colours} colours (a blank plot?)");
    }

    let mut plot = vec![
        "plot",
        record_s,
        "--out",
        replay.to_str().unwrap(),
        "--title",
        "rapier, trot, seed 4",
    ];
    plot.extend(config);
    let listed = hyq_ok(&plot);
    assert_eq!(listed.lines().count(), 4, "{listed}");
    for name in FILES {
        assert!(listed.contains(name), "{listed}");
        assert_eq!(
            std::fs::read(live.join(name)).unwrap(),
            std::fs::read(replay.join(name)).unwrap(),
            "{name}: the record's plot differs from the live one"
        );
    }

    // Without --out the plots go beside the file, into `<stem>_plots/`.
    let beside = record.with_file_name("plot_run_plots");
    let _ = std::fs::remove_dir_all(&beside);
    hyq_ok(&["plot", record_s]);
    for name in FILES {
        assert!(
            beside.join(name).is_file(),
            "{}",
            beside.join(name).display()
        );
    }
}

#[test]
fn bad_plot_input_is_a_one_line_error_naming_it() {
    let missing = scratch("plot_missing.jsonl");
    usage_error_naming(
        &["plot", missing.to_str().unwrap()],
        &["plot_missing.jsonl"],
    );

    // A valid first line (from a real run), then a line missing its reward.
    let good = scratch("plot_good.jsonl");
    hyq_ok(&[
        "run",
        "--set",
        "task.max_time_steps=2",
        "--record",
        good.to_str().unwrap(),
    ]);
    let first = std::fs::read_to_string(&good).unwrap();
    let first = first.lines().next().unwrap();
    let bad = scratch("plot_bad.jsonl");
    std::fs::write(&bad, format!("{first}\n{{\"t\": 2, \"terms\": {{}}}}\n")).unwrap();
    usage_error_naming(
        &["plot", bad.to_str().unwrap()],
        &["plot_bad.jsonl", "line 2"],
    );

    let empty = scratch("plot_empty.jsonl");
    std::fs::write(&empty, "\n").unwrap();
    usage_error_naming(
        &["plot", empty.to_str().unwrap()],
        &["plot_empty.jsonl", "no step"],
    );

    // The output directory's parent is a file: the directory cannot be created.
    let blocker = scratch("plot_blocker");
    std::fs::write(&blocker, "a file, not a directory").unwrap();
    let out = blocker.join("plots");
    usage_error_naming(
        &[
            "plot",
            good.to_str().unwrap(),
            "--out",
            out.to_str().unwrap(),
        ],
        &["plot_blocker"],
    );
    usage_error_naming(
        &[
            "run",
            "--set",
            "task.max_time_steps=2",
            "--plot",
            out.to_str().unwrap(),
        ],
        &["--plot", "plot_blocker"],
    );
}
