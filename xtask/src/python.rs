//! Python as the stages use it: the version wanted, the install line, and running programs
//! inside a virtual environment.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The install line printed when Python 3 (with venv and pip) is missing.
pub const PYTHON_INSTALL: &str = "sudo apt-get install -y python3 python3-venv python3-pip";

/// The oldest CPython the pinned test requirements install on (numpy 2.4 needs 3.11).
pub const PYTHON_MIN: (u32, u32) = (3, 11);

/// The Python interpreter of the virtual environment at `venv`.
pub fn venv_python(venv: &Path) -> PathBuf {
    venv.join("bin").join("python")
}

/// A command run in `dir` as if the venv were activated (maturin finds the venv through
/// `VIRTUAL_ENV`).
pub(crate) fn venv_command(venv: &Path, dir: &Path, program: &Path) -> Command {
    let mut command = Command::new(program);
    let path = std::env::var_os("PATH").unwrap_or_default();
    let mut paths = vec![venv.join("bin")];
    paths.extend(std::env::split_paths(&path));
    command
        .current_dir(dir)
        .env("VIRTUAL_ENV", venv)
        .env("PATH", std::env::join_paths(paths).unwrap_or(path))
        .env("PIP_DISABLE_PIP_VERSION_CHECK", "1");
    command
}

/// The number of passed tests on pytest's closing summary line, or `None` if `line` is not one.
/// The line is `49 passed in 3.70s` with `-q`, `==== 1 failed, 48 passed, 2 warnings in 3.70s
/// ====` otherwise, and `no tests ran in 0.01s` when nothing ran (0 passed).
pub(crate) fn pytest_passed_count(line: &str) -> Option<u64> {
    let body = line.trim().trim_matches('=').trim();
    let (counts, time) = body.rsplit_once(" in ")?;
    if !time.starts_with(|c: char| c.is_ascii_digit()) || !time.contains('s') {
        return None;
    }
    if counts == "no tests ran" {
        return Some(0);
    }
    let mut passed = 0;
    for part in counts.split(", ") {
        let (n, word) = part.split_once(' ')?;
        let n: u64 = n.parse().ok()?;
        if !word.chars().all(|c| c.is_ascii_lowercase()) {
            return None;
        }
        if word == "passed" {
            passed = n;
        }
    }
    Some(passed)
}
