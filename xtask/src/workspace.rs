//! The workspace as every xtask command sees it: where it is, its members, where it builds
//! (one answer for every command), and running cargo and other programs in it.

use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus};

/// The workspace's target directory: `$CARGO_TARGET_DIR` when it is set and not empty (relative
/// to the workspace root, as cargo reads it), else `target/` in the workspace. Every xtask path
/// under "target" (the release `hyq` a benchmark runs, the venvs, the vendored crate's check, the
/// reports) starts here, so setting the variable never leaves a command reading a stale copy.
pub(crate) fn target_dir(root: &Path) -> PathBuf {
    match std::env::var_os("CARGO_TARGET_DIR") {
        Some(dir) if !dir.is_empty() => root.join(dir),
        _ => root.join("target"),
    }
}

/// The workspace root (xtask lives one level below it).
pub fn workspace_root() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| manifest.to_path_buf())
}

/// Whether `name` is one of `members` (as [`workspace_members`] lists them).
pub fn is_member(members: &[String], name: &str) -> bool {
    members.iter().any(|m| m == name)
}

/// The package names listed as workspace members that exist on disk.
pub fn workspace_members(root: &Path) -> Result<Vec<String>, String> {
    let text = std::fs::read_to_string(root.join("Cargo.toml"))
        .map_err(|e| format!("cannot read the workspace Cargo.toml: {e}"))?;
    let manifest: toml::Table =
        toml::from_str(&text).map_err(|e| format!("the workspace Cargo.toml is invalid: {e}"))?;
    let members = manifest
        .get("workspace")
        .and_then(|w| w.get("members"))
        .and_then(|m| m.as_array())
        .ok_or("the workspace Cargo.toml has no [workspace] members list")?;
    let mut names = Vec::new();
    for member in members {
        let dir = member
            .as_str()
            .ok_or("a workspace member is not a string")?;
        let crate_toml = std::fs::read_to_string(root.join(dir).join("Cargo.toml"))
            .map_err(|e| format!("workspace member `{dir}` has no readable Cargo.toml: {e}"))?;
        let crate_manifest: toml::Table = toml::from_str(&crate_toml)
            .map_err(|e| format!("`{dir}/Cargo.toml` is invalid: {e}"))?;
        let name = crate_manifest
            .get("package")
            .and_then(|p| p.get("name"))
            .and_then(|n| n.as_str())
            .ok_or_else(|| format!("`{dir}/Cargo.toml` has no package name"))?;
        names.push(name.to_string());
    }
    Ok(names)
}

/// A `cargo` command (the one running xtask, `$CARGO`, else `cargo` from `PATH`) to be run in
/// the workspace root `root`.
pub fn cargo(root: &Path) -> Command {
    let cargo = std::env::var("CARGO").unwrap_or_else(|_| "cargo".to_string());
    let mut command = Command::new(cargo);
    command.current_dir(root);
    command
}

/// Prints `$ cargo args`, then runs it in the workspace root `root` with its output on the
/// terminal, and returns its exit status.
pub fn run_cargo(root: &Path, args: &[String]) -> Result<ExitStatus, String> {
    println!("$ cargo {}", args.join(" "));
    cargo(root)
        .args(args)
        .status()
        .map_err(|e| format!("cannot start cargo: {e}"))
}

/// The number of passed tests on a libtest summary line (`test result: ok. 12 passed; ...`).
pub fn passed_count(line: &str) -> u64 {
    let Some(rest) = line.trim().strip_prefix("test result:") else {
        return 0;
    };
    rest.split(';')
        .filter_map(|part| {
            part.trim()
                .trim_start_matches("ok.")
                .trim()
                .strip_suffix(" passed")
        })
        .filter_map(|n| n.trim().parse::<u64>().ok())
        .sum()
}

/// Runs `command`, echoing it; fails on a non-zero exit (the training stage uses it too).
pub(crate) fn run(command: &mut Command, what: &str) -> Result<(), String> {
    println!("\n$ {what}");
    let status = command
        .status()
        .map_err(|e| format!("cannot run {what}: {e}"))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!("`{what}` failed ({status})"))
    }
}
