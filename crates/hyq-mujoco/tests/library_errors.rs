//! Invariant: a missing MuJoCo library, or a library of another version than the headers the
//! shim was compiled against, is a one-line error when the first world is built, naming the
//! path, the version found and the version wanted, and saying how to get the right one; the
//! process is not aborted. Each case runs `hyq-mujoco-check` in its own process, since a process
//! opens the library once.

use std::process::Command;

fn check(mujoco_dir: &str) -> (bool, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_hyq-mujoco-check"))
        .env("MUJOCO_DIR", mujoco_dir)
        .output()
        .unwrap_or_else(|e| panic!("cannot run hyq-mujoco-check: {e}"));
    let text = String::from_utf8_lossy(if out.status.success() {
        &out.stdout
    } else {
        &out.stderr
    })
    .into_owned();
    (out.status.success(), text)
}

fn one_line(text: &str) -> &str {
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 1, "one line expected: {text:?}");
    lines[0]
}

#[test]
fn a_missing_library_says_how_to_get_it() {
    let dir = std::env::temp_dir().join("hyq-mujoco-nowhere");
    let (ok, text) = check(dir.to_str().unwrap_or_default());
    assert!(!ok, "no library, yet: {text}");
    let line = one_line(&text);
    for part in [
        "cannot load MuJoCo 4.0.0",
        "libmujoco.so.4.0.0",
        "cargo xtask setup mujoco",
        "hyq-mujoco-nowhere",
    ] {
        assert!(line.contains(part), "{part:?} not in {line:?}");
    }
}

#[test]
fn another_version_names_the_version_found_and_wanted() {
    let (ok, text) = check(env!("HYQ_MUJOCO_OTHER_VERSION_DIR"));
    assert!(!ok, "a 3.3.7 library was accepted: {text}");
    let line = one_line(&text);
    for part in [
        "MuJoCo 3.3.7",
        "built against MuJoCo 4.0.0",
        "cargo xtask setup mujoco",
    ] {
        assert!(line.contains(part), "{part:?} not in {line:?}");
    }
}

#[test]
fn the_library_the_crate_was_built_against_works() {
    let (ok, text) = check("");
    assert!(ok, "{text}");
    assert!(one_line(&text).starts_with("MuJoCo 4.0.0 at "), "{text}");
}
