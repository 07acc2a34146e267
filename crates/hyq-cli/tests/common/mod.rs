//! Helpers shared by the CLI tests: run the built `hyq` binary as a process, and scratch files.
#![allow(dead_code)]
// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The output of `hyq args…`, run as a process with no terminal (no progress bar).
pub fn hyq(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_hyq"))
        .args(args)
        .output()
        .unwrap_or_else(|e| panic!("cannot run hyq: {e}"))
}

/// stdout as text.
pub fn stdout(out: &Output) -> String {
    String::from_utf8(out.stdout.clone()).expect("stdout is UTF-8")
}

/// stderr as text.
pub fn stderr(out: &Output) -> String {
    String::from_utf8(out.stderr.clone()).expect("stderr is UTF-8")
}

/// `hyq args…`, which must succeed; returns stdout.
pub fn hyq_ok(args: &[&str]) -> String {
    let out = hyq(args);
    assert!(
        out.status.success(),
        "hyq {args:?} failed ({}): {}",
        out.status,
        stderr(&out)
    );
    stdout(&out)
}

/// `hyq args…` must fail as a usage error (status 2) with one line `hyq: error: …` on stderr
/// that contains every one of `words`.
pub fn usage_error_naming(args: &[&str], words: &[&str]) {
    let out = hyq(args);
    assert_eq!(out.status.code(), Some(2), "hyq {args:?}: {}", stderr(&out));
    let err = stderr(&out);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("hyq: error: "), "{err}");
    for w in words {
        assert!(err.contains(w), "the error does not name `{w}`: {err}");
    }
}

/// `out` must be exactly one line, a JSON object, which is returned.
pub fn one_json_line(out: &str) -> serde_json::Value {
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 1, "one object: {out}");
    serde_json::from_str(lines[0]).unwrap_or_else(|e| panic!("{e}: {}", lines[0]))
}

/// `r` must have every one of `keys`.
pub fn assert_has_keys(r: &serde_json::Value, keys: &[&str]) {
    for key in keys {
        assert!(r.get(key).is_some(), "no `{key}` in {r}");
    }
}

/// A fresh path in this test target's scratch directory (the file is removed if it exists).
pub fn scratch(name: &str) -> PathBuf {
    let path = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_file(&path);
    path
}

/// The path of the first `null` in `v` (`path` is `v`'s own), if any: the CLI's JSON outputs
/// hold numbers where numbers belong, never `null`.
pub fn first_null(v: &serde_json::Value, path: &str) -> Option<String> {
    match v {
        serde_json::Value::Null => Some(path.to_owned()),
        serde_json::Value::Array(items) => items
            .iter()
            .enumerate()
            .find_map(|(i, x)| first_null(x, &format!("{path}[{i}]"))),
        serde_json::Value::Object(map) => map
            .iter()
            .find_map(|(k, x)| first_null(x, &format!("{path}.{k}"))),
        _ => None,
    }
}

/// The committed trained policy file.
pub fn committed_policy() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/policies/hyq_walk.safetensors")
}

/// `mlp:PATH`.
pub fn policy_arg(path: &Path) -> String {
    format!("mlp:{}", path.display())
}

/// A copy of the committed policy with its JSON header changed by `edit` (the tensor bytes
/// kept), written to a scratch file.
pub fn edited_policy(
    name: &str,
    edit: impl FnOnce(&mut serde_json::Value, &mut Vec<u8>),
) -> PathBuf {
    let bytes = std::fs::read(committed_policy()).unwrap();
    let n = u64::from_le_bytes(bytes[..8].try_into().unwrap()) as usize;
    let mut header: serde_json::Value = serde_json::from_slice(&bytes[8..8 + n]).unwrap();
    let mut data = bytes[8 + n..].to_vec();
    edit(&mut header, &mut data);
    let mut text = serde_json::to_vec(&header).unwrap();
    while !text.len().is_multiple_of(8) {
        text.push(b' ');
    }
    let mut out = (text.len() as u64).to_le_bytes().to_vec();
    out.extend_from_slice(&text);
    out.extend_from_slice(&data);
    let path = scratch(name);
    std::fs::write(&path, out).unwrap();
    path
}
