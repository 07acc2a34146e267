//! Every loader of a user's file reads only a regular file, through the one rule of the capped
//! reader (`input::open`): a FIFO with no writer is refused at once, where opening it used to
//! block the process forever (and Python's Ctrl-C could not end it), and a device such as
//! `/dev/zero` is refused rather than read up to the cap. Each case runs on a thread of its own
//! with a deadline, so a loader that waits again fails the test instead of hanging it.
#![cfg(unix)]

use std::path::{Path, PathBuf};
use std::sync::mpsc;
use std::time::Duration;

use hyq_physics::RobotModel;
use hyq_physics::bundled::HYQ_PROFILE;
use hyq_physics::input::{self, NOT_A_FILE};
use hyq_physics::terrain::file::{Placement, read};

/// A FIFO at `path` (no writer ever opens it), made by `mkfifo(1)`: the crate has no `unsafe`.
fn mkfifo(path: &Path) {
    let status = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs");
    assert!(status.success(), "mkfifo {}", path.display());
}

/// What `load` says, or a failure if it has not returned within five seconds.
fn within_deadline(what: &str, load: impl FnOnce() -> String + Send + 'static) -> String {
    let (tx, rx) = mpsc::channel();
    std::thread::spawn(move || tx.send(load()).ok());
    rx.recv_timeout(Duration::from_secs(5))
        .unwrap_or_else(|_| panic!("{what}: the loader is still waiting after 5 s"))
}

fn scratch(tag: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hyq-fifo-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    dir
}

#[test]
fn every_kind_of_user_file_refuses_a_fifo_at_once() {
    let dir = scratch("kinds");
    let fifo = dir.join("input.fifo");
    mkfifo(&fifo);
    for kind in input::KINDS {
        let path = fifo.clone();
        let text = within_deadline(kind.what, move || {
            input::read_bytes(&path, kind)
                .map(|b| format!("read {} bytes", b.len()))
                .unwrap_or_else(|e| e.to_string())
        });
        assert_eq!(text, NOT_A_FILE, "{}", kind.what);
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_fifo_profile_or_urdf_is_refused_naming_the_file() {
    let dir = scratch("robot");
    let profile = dir.join("profile.toml");
    mkfifo(&profile);
    let p = profile.clone();
    let text = within_deadline("profile", move || {
        RobotModel::load(&p).map_or_else(|e| e.to_string(), |_| "loaded".into())
    });
    assert!(
        text.contains("profile.toml") && text.contains("is not a regular file"),
        "{text}"
    );
    std::fs::remove_file(&profile).ok();

    let urdf_dir = scratch("urdf");
    std::fs::write(urdf_dir.join("profile.toml"), HYQ_PROFILE).expect("profile");
    mkfifo(&urdf_dir.join("hyq.urdf"));
    let p = urdf_dir.join("profile.toml");
    let text = within_deadline("URDF", move || {
        RobotModel::load(&p).map_or_else(|e| e.to_string(), |_| "loaded".into())
    });
    assert!(
        text.contains("hyq.urdf") && text.contains("is not a regular file"),
        "{text}"
    );
    std::fs::remove_dir_all(&dir).ok();
    std::fs::remove_dir_all(&urdf_dir).ok();
}

#[test]
fn devices_and_directories_are_refused_like_fifos() {
    for path in ["/dev/zero", "/dev/null"] {
        let text = within_deadline(path, move || {
            RobotModel::load(path).map_or_else(|e| e.to_string(), |_| "loaded".into())
        });
        assert!(
            text.contains(path) && text.contains("is not a regular file"),
            "{text}"
        );
    }
    let dir = scratch("dir");
    let e = input::read_bytes(&dir, &input::CONFIG).expect_err("a directory");
    assert_eq!(e.to_string(), NOT_A_FILE);
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn the_height_file_reader_follows_the_same_rule() {
    let dir = scratch("heights");
    let fifo = dir.join("heights.npy");
    mkfifo(&fifo);
    let path = fifo.clone();
    let text = within_deadline("height file", move || {
        let placement = Placement {
            center: [0.0, 0.0],
            size: [4.0, 4.0],
            vertical_scale: 1.0,
        };
        read(&path, &placement).map_or_else(|e| e.to_string(), |_| "loaded".into())
    });
    assert!(text.contains("is not a regular file"), "{text}");
    std::fs::remove_dir_all(&dir).ok();
}
