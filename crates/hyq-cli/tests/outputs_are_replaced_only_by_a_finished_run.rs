//! Invariant: an output file or directory of `hyq run --record/--plot` and `hyq render --out`
//! is replaced only by a command that finished: everything is checked before any file is
//! touched, the output is written to a hidden temporary file beside the target and renamed onto
//! it at the end, so a usage error, a failure or an interrupted run leaves what was there
//! untouched. A target that is not a regular file (a device such as /dev/full) is written in
//! place and never replaced.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Duration;

use common::{hyq, hyq_ok, scratch, stderr};

const PRECIOUS: &str = "precious data\n";

/// `path` must still hold [`PRECIOUS`].
fn assert_kept(path: &Path) {
    let bytes = std::fs::read(path).unwrap();
    assert!(
        bytes == PRECIOUS.as_bytes(),
        "{} was replaced ({} bytes now)",
        path.display(),
        bytes.len()
    );
}

/// A directory holding only a file `name` with [`PRECIOUS`] in it.
fn dir_with_precious(dir_name: &str, name: &str) -> std::path::PathBuf {
    let dir = scratch(dir_name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join(name), PRECIOUS).unwrap();
    dir
}

/// The names in `dir`, sorted.
fn names(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// Starts `hyq args`, lets it work for `after`, then kills it (as Ctrl-C or a crash would end
/// it, without any clean-up of its own).
fn killed_after(args: &[&str], after: Duration) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_hyq"))
        .args(args)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    std::thread::sleep(after);
    assert!(
        child.try_wait().unwrap().is_none(),
        "hyq {args:?} ended too soon"
    );
    child.kill().unwrap();
    child.wait().unwrap();
}

#[test]
fn a_record_survives_a_usage_error_found_after_it_was_named() {
    let dir = dir_with_precious("keep-usage", "keep.jsonl");
    let record = dir.join("keep.jsonl");
    let out = hyq(&[
        "run",
        "--record",
        record.to_str().unwrap(),
        "--plot",
        "/proc/nope",
    ]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert_kept(&record);
    assert_eq!(names(&dir), ["keep.jsonl"], "no temporary file is left");
}

#[test]
fn a_record_survives_an_interrupted_run_and_a_finished_run_replaces_it() {
    let dir = dir_with_precious("keep-killed", "keep.jsonl");
    let record = dir.join("keep.jsonl");
    let args = [
        "run",
        "--episodes",
        "50",
        "--record",
        record.to_str().unwrap(),
    ];
    killed_after(&args, Duration::from_millis(1500));
    assert_kept(&record);

    hyq_ok(&[
        "run",
        "--set",
        "task.max_time_steps=7",
        "--record",
        record.to_str().unwrap(),
    ]);
    let text = std::fs::read_to_string(&record).unwrap();
    assert_eq!(text.lines().count(), 7);
    assert!(names(&dir).contains(&"keep.jsonl".to_owned()));
}

#[test]
fn a_gif_survives_an_interrupted_render_and_a_finished_render_replaces_it() {
    let dir = dir_with_precious("keep-gif", "k.gif");
    let gif = dir.join("k.gif");
    let args = ["render", "--seconds", "10", "--out", gif.to_str().unwrap()];
    killed_after(&args, Duration::from_millis(1500));
    assert_kept(&gif);

    hyq_ok(&["render", "--seconds", "0.2", "--out", gif.to_str().unwrap()]);
    assert!(std::fs::read(&gif).unwrap().starts_with(b"GIF89a"));
}

#[test]
fn plots_survive_an_interrupted_plot_and_an_interrupted_run() {
    // 400 short episodes: plotting them all takes many seconds, the first pair a fraction of one.
    let record = scratch("keep-plots.jsonl");
    hyq_ok(&[
        "run",
        "--episodes",
        "400",
        "--set",
        "task.max_time_steps=3",
        "--record",
        record.to_str().unwrap(),
    ]);
    let dir = dir_with_precious("keep-plots", "episode_001_rewards.png");
    let args = [
        "plot",
        record.to_str().unwrap(),
        "--out",
        dir.to_str().unwrap(),
    ];
    killed_after(&args, Duration::from_millis(1500));
    assert_kept(&dir.join("episode_001_rewards.png"));

    let dir = dir_with_precious("keep-live-plots", "episode_001_rewards.png");
    let args = [
        "run",
        "--episodes",
        "400",
        "--set",
        "task.max_time_steps=3",
        "--plot",
        dir.to_str().unwrap(),
    ];
    killed_after(&args, Duration::from_millis(1500));
    assert_kept(&dir.join("episode_001_rewards.png"));
}

#[test]
fn a_device_target_is_written_in_place_and_never_replaced() {
    use std::os::unix::fs::FileTypeExt;
    let out = hyq(&[
        "run",
        "--set",
        "task.max_time_steps=200",
        "--record",
        "/dev/full",
    ]);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    assert!(stderr(&out).contains("No space left"), "{}", stderr(&out));
    let kind = std::fs::metadata("/dev/full").unwrap().file_type();
    assert!(kind.is_char_device(), "/dev/full is still a device");
}

#[test]
fn a_model_survives_a_write_cut_short_and_a_finished_write_replaces_it() {
    // The shell's file-size limit (2 KiB, far below the 13 KB URDF; its signal ignored, so the
    // write fails as on a full disk) cuts the write short: `model` wrote in place, leaving the
    // first bytes of the new model where the old file was.
    let dir = dir_with_precious("keep-model", "model.urdf");
    let model = dir.join("model.urdf");
    let script = format!(
        "trap '' XFSZ; ulimit -f 2; exec '{}' model --format urdf --out '{}'",
        env!("CARGO_BIN_EXE_hyq"),
        model.display()
    );
    let out = Command::new("sh").args(["-c", &script]).output().unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.starts_with("hyq: error: cannot write") && err.lines().count() == 1,
        "{err}"
    );
    assert_kept(&model);
    assert_eq!(names(&dir), ["model.urdf"], "no temporary file is left");

    hyq_ok(&[
        "model",
        "--format",
        "urdf",
        "--out",
        model.to_str().unwrap(),
    ]);
    assert!(std::fs::read_to_string(&model).unwrap().contains("<robot"));
}

/// The effective user id of this process (from /proc, without unsafe code).
fn euid() -> u32 {
    let status = std::fs::read_to_string("/proc/self/status").unwrap();
    let uid = status.lines().find(|l| l.starts_with("Uid:")).unwrap();
    uid.split_whitespace().nth(2).unwrap().parse().unwrap()
}

#[test]
fn a_write_protected_record_is_refused_not_replaced() {
    use std::os::unix::fs::PermissionsExt;
    // The shell's `>` refuses a mode-444 file for its (non-root) owner; so must `--record`,
    // which used to replace it by a rename in the writable directory. Root may write any file,
    // so as root the command runs as `nobody` (uid 65534).
    let dir = dir_with_precious("keep-protected", "ro.jsonl");
    std::fs::set_permissions(&dir, std::fs::Permissions::from_mode(0o777)).unwrap();
    let record = dir.join("ro.jsonl");
    let run = [
        "run",
        "--set",
        "task.max_time_steps=3",
        "--record",
        record.to_str().unwrap(),
    ];
    let mut command = if euid() == 0 {
        // nobody must own the file (a user's own write-protected file) and reach the binary.
        std::process::Command::new("chown")
            .args(["65534", record.to_str().unwrap()])
            .status()
            .unwrap();
        let mut c = Command::new("setpriv");
        c.args(["--reuid=65534", "--regid=65534", "--clear-groups"])
            .arg(env!("CARGO_BIN_EXE_hyq"));
        c
    } else {
        Command::new(env!("CARGO_BIN_EXE_hyq"))
    };
    std::fs::set_permissions(&record, std::fs::Permissions::from_mode(0o444)).unwrap();
    let out = command.args(run).output().unwrap();
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(2), "{err}");
    assert!(
        err.contains("write-protected") && err.lines().count() == 1,
        "{err}"
    );
    assert_kept(&record);
}
