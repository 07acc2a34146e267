//! Running a program of the benchmark (an anchor script, the release `hyq`, a shell probe of the
//! host) and reading what it printed; a file of its own so that every step of the benchmark can
//! run programs without importing the step that runs the whole sequence.

use std::path::Path;
use std::process::Command;

/// The last non-empty line of a program's error output (a Python traceback ends with the
/// error itself), for one-line messages.
pub(super) fn last_line(text: &str) -> &str {
    text.lines()
        .map(str::trim)
        .rfind(|l| !l.is_empty())
        .unwrap_or("")
}

/// Runs `program args` in `dir` with `env`, returning its stdout; a failure is one line naming
/// the command and the last line of its error output.
pub(super) fn run(
    program: &Path,
    args: &[String],
    dir: &Path,
    env: &[(&str, &str)],
) -> Result<String, String> {
    let shown = format!("{} {}", program.display(), args.join(" "));
    let out = Command::new(program)
        .args(args)
        .current_dir(dir)
        .envs(env.iter().copied())
        .output()
        .map_err(|e| format!("cannot start `{shown}`: {e}"))?;
    if !out.status.success() {
        return Err(format!(
            "`{shown}` failed ({}): {}",
            out.status,
            last_line(&String::from_utf8_lossy(&out.stderr))
        ));
    }
    Ok(String::from_utf8_lossy(&out.stdout).into_owned())
}

/// The trimmed stdout of the shell command `line` (`""` when it cannot run).
pub(super) fn shell(line: &str) -> String {
    Command::new("sh")
        .args(["-c", line])
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default()
}
