//! The stages of `cargo xtask test`: each is a command that either runs (and must pass, with at
//! least one test executed) or is skipped with the reason and the install line that would let it
//! run. A skipped stage that was required is a failure.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};

use crate::mujoco;

/// A part of the test run that needs something a fresh machine may lack.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Part {
    /// The DART backend: needs Debian's libdart.
    Dart,
    /// The MuJoCo backend: needs MuJoCo's library (`cargo xtask setup mujoco`).
    Mujoco,
    /// The Python package: needs maturin, gymnasium and pytest.
    Python,
}

impl Part {
    fn name(self) -> &'static str {
        match self {
            Part::Dart => "dart",
            Part::Mujoco => "mujoco",
            Part::Python => "python",
        }
    }
}

/// The install line printed when DART is missing (the README gives the same line).
pub const DART_INSTALL: &str = "sudo apt-get install -y libdart-dev libdart-collision-bullet-dev";

/// The install line printed when Python 3 (with venv and pip) is missing.
pub const PYTHON_INSTALL: &str = "sudo apt-get install -y python3 python3-venv python3-pip";

/// The oldest CPython the pinned test requirements install on (numpy 2.4 needs 3.11).
pub const PYTHON_MIN: (u32, u32) = (3, 11);

/// What happened to one stage.
enum Outcome {
    Passed { tests: u64 },
    Skipped { why: String },
}

/// Parses `--require dart|mujoco|python|all` flags.
fn parse_required(args: &[String]) -> Result<Vec<Part>, String> {
    let mut required = Vec::new();
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--require" => {
                let value = it
                    .next()
                    .ok_or("`--require` needs a value: dart, mujoco, python or all")?;
                match value.as_str() {
                    "dart" => required.push(Part::Dart),
                    "mujoco" => required.push(Part::Mujoco),
                    "python" => required.push(Part::Python),
                    "all" => required.extend([Part::Dart, Part::Mujoco, Part::Python]),
                    other => {
                        return Err(format!(
                            "`--require {other}`: unknown part (expected dart, mujoco, python \
                             or all)"
                        ));
                    }
                }
            }
            other => return Err(format!("`cargo xtask test`: unknown argument `{other}`")),
        }
    }
    Ok(required)
}

/// The workspace root (xtask lives one level below it).
pub fn workspace_root() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest
        .parent()
        .map(Path::to_path_buf)
        .unwrap_or_else(|| manifest.to_path_buf())
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

/// The header of DART's Bullet collision detector, which the DART backend needs: every command
/// that builds the backend checks for it.
pub const DART_BULLET_HEADER: &str =
    "/usr/include/dart/collision/bullet/BulletCollisionDetector.hpp";

/// True when Debian's DART development files are installed, with the Bullet collision detector
/// the backend uses.
fn dart_installed() -> bool {
    Path::new("/usr/include/dart/config.hpp").exists() && Path::new(DART_BULLET_HEADER).exists()
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

/// Runs `cargo` with `args` in the workspace root, streaming its output, and returns how many
/// tests passed (summed over every `test result:` line). A failing command is an error.
fn cargo_test(root: &Path, args: &[&str]) -> Result<u64, String> {
    println!("\n$ cargo {}", args.join(" "));
    let mut passed = 0u64;
    let status = stream_stdout(cargo(root).args(args), "cargo", |line| {
        passed += passed_count(line);
    })?;
    if !status.success() {
        return Err(format!("`cargo {}` failed ({status})", args.join(" ")));
    }
    Ok(passed)
}

/// Runs `command` (named `name` in errors), echoing each line of its stdout and handing it to
/// `each`, and returns its exit status.
fn stream_stdout(
    command: &mut Command,
    name: &str,
    mut each: impl FnMut(&str),
) -> Result<ExitStatus, String> {
    let mut child = command
        .stdout(Stdio::piped())
        .spawn()
        .map_err(|e| format!("cannot start {name}: {e}"))?;
    if let Some(stdout) = child.stdout.take() {
        for line in BufReader::new(stdout).lines() {
            let line = line.map_err(|e| format!("reading {name}'s output: {e}"))?;
            println!("{line}");
            each(&line);
        }
    }
    child.wait().map_err(|e| format!("waiting for {name}: {e}"))
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

/// `cargo xtask test`.
pub fn test(args: &[String]) -> Result<(), String> {
    let (with, args) = crate::rllib::split_with(args)?;
    let required = parse_required(&args)?;
    let root = workspace_root();
    let members = workspace_members(&root)?;
    let has = |name: &str| members.iter().any(|m| m == name);
    let mut results: Vec<(&str, Outcome)> = Vec::new();

    // Stage 1: every Rust crate that needs nothing but a Rust toolchain (rapier is the backend).
    let mut args: Vec<&str> = vec!["test", "--workspace", "--locked"];
    for optional in ["hyq-dart", "hyq-mujoco", "hyq-py"] {
        if has(optional) {
            args.extend(["--exclude", optional]);
        }
    }
    let tests = cargo_test(&root, &args)?;
    results.push(("rust workspace (rapier backend)", Outcome::Passed { tests }));

    // The patched rapier3d: its tree is the published crate plus vendor/patches, and its
    // multibody tests pass.
    let tests = crate::vendor::stage(&root)?;
    results.push(("vendor/rapier3d (check, tests)", Outcome::Passed { tests }));

    // Stage 2: the DART backend and everything that runs on it.
    let dart = if !has("hyq-dart") {
        Outcome::Skipped {
            why: "the hyq-dart crate is not in the workspace yet".into(),
        }
    } else if !dart_installed() {
        Outcome::Skipped {
            why: format!("DART is not installed; to run these tests: {DART_INSTALL}"),
        }
    } else {
        let tests = cargo_test(
            &root,
            &dart_stage_args(&members)
                .iter()
                .map(String::as_str)
                .collect::<Vec<_>>(),
        )?;
        Outcome::Passed { tests }
    };
    results.push((Part::Dart.name(), dart));

    // Stage 3: the MuJoCo backend and everything that runs on it.
    let mujoco = if !has("hyq-mujoco") {
        Outcome::Skipped {
            why: "the hyq-mujoco crate is not in the workspace yet".into(),
        }
    } else if let Err(why) = mujoco::check(&mujoco::mujoco_dir(&root)) {
        Outcome::Skipped {
            why: format!(
                "MuJoCo {} is not set up ({why}); to run these tests: {}",
                mujoco::VERSION,
                mujoco::SETUP_COMMAND
            ),
        }
    } else {
        let mut tests = 0;
        for args in mujoco_stage_args(&members) {
            tests += cargo_test(&root, &args.iter().map(String::as_str).collect::<Vec<_>>())?;
        }
        Outcome::Passed { tests }
    };
    results.push((Part::Mujoco.name(), mujoco));

    // Stage 4: the Python package. With MuJoCo set up, the package is built with it, so that
    // its tests run `backend="mujoco"` too (and the training stage's recipes can train there).
    let with_mujoco = has("hyq-mujoco") && mujoco::check(&mujoco::mujoco_dir(&root)).is_ok();
    let python = if !has("hyq-py") {
        Outcome::Skipped {
            why: "the hyq-py crate is not in the workspace yet".into(),
        }
    } else {
        match python_tools(&root) {
            Err(why) => Outcome::Skipped { why },
            Ok(venv) => Outcome::Passed {
                tests: python_stage(&root, &venv, with_mujoco)?,
            },
        }
    };
    results.push((Part::Python.name(), python));

    // Optional stages, run only when asked for (`--with rllib`, `--with train`).
    if with.iter().any(|w| w == "rllib") {
        let tests = crate::rllib::stage(&root)?;
        results.push(("rllib (--with rllib)", Outcome::Passed { tests }));
    }
    if with.iter().any(|w| w == "train") {
        let tests = crate::train::stage(&root, with_mujoco)?;
        results.push(("train (--with train)", Outcome::Passed { tests }));
    }

    summarize(&results, &required)
}

/// The venv the Python stage builds the package into and runs pytest from: `$HYQ_VENV`, else
/// `target/py-venv` in the workspace (inside the checkout but git-ignored, and kept between
/// runs so a warm run only rebuilds what changed).
fn python_venv(root: &Path) -> PathBuf {
    std::env::var_os("HYQ_VENV")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target").join("py-venv"))
}

/// The Python stage's venv, created if missing, or why the stage cannot run (with the install
/// line). Needs a `python3` (or `$HYQ_PYTHON`) of at least [`PYTHON_MIN`] that can create a
/// venv with pip.
fn python_tools(root: &Path) -> Result<PathBuf, String> {
    let venv = python_venv(root);
    if venv_python(&venv).is_file() {
        return Ok(venv);
    }
    let python = std::env::var("HYQ_PYTHON").unwrap_or_else(|_| "python3".to_string());
    let check = format!(
        "import sys, venv, ensurepip; sys.exit(0 if sys.version_info >= {PYTHON_MIN:?} else 3)"
    );
    let status = Command::new(&python).args(["-c", &check]).status();
    match status {
        Err(e) => {
            return Err(format!(
                "`{python}` cannot be run ({e}); to run these tests: {PYTHON_INSTALL}"
            ));
        }
        Ok(s) if s.code() == Some(3) => {
            return Err(format!(
                "`{python}` is older than CPython {}.{}, which the pinned numpy needs; set \
                 HYQ_PYTHON to a newer interpreter",
                PYTHON_MIN.0, PYTHON_MIN.1
            ));
        }
        Ok(s) if !s.success() => {
            return Err(format!(
                "`{python}` lacks the venv or ensurepip module; to run these tests: \
                 {PYTHON_INSTALL}"
            ));
        }
        Ok(_) => {}
    }
    println!("\n$ {python} -m venv {}", venv.display());
    let created = Command::new(&python)
        .args(["-m", "venv"])
        .arg(&venv)
        .status()
        .map_err(|e| format!("cannot run `{python} -m venv`: {e}"))?;
    if !created.success() {
        return Err(format!(
            "`{python} -m venv {}` failed; to run these tests: {PYTHON_INSTALL}",
            venv.display()
        ));
    }
    Ok(venv)
}

/// The Python interpreter of the virtual environment at `venv`.
pub fn venv_python(venv: &Path) -> PathBuf {
    venv.join("bin").join("python")
}

/// Runs `program args` in `dir` with the venv activated, failing on a non-zero exit.
fn run_in_venv(venv: &Path, dir: &Path, program: &Path, args: &[&str]) -> Result<(), String> {
    println!("\n$ {} {}", program.display(), args.join(" "));
    let status = venv_command(venv, dir, program)
        .args(args)
        .status()
        .map_err(|e| format!("cannot run {}: {e}", program.display()))?;
    if status.success() {
        Ok(())
    } else {
        Err(format!(
            "`{} {}` failed ({status})",
            program.display(),
            args.join(" ")
        ))
    }
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

/// Stage 3: installs the pinned requirements into the venv (and Stable-Baselines3 without its
/// dependencies), builds the extension with the dev
/// profile and installs the package (`maturin develop`: fast to build; users get release
/// builds from `maturin build --release` or `pip install`), builds the `hyq` command the CLI
/// parity test runs, then runs pytest and returns how many tests passed. `with_mujoco` builds
/// the package with its `mujoco` feature.
fn python_stage(root: &Path, venv: &Path, with_mujoco: bool) -> Result<u64, String> {
    let crate_dir = root.join("crates").join("hyq-py");
    let python = venv_python(venv);
    run_in_venv(
        venv,
        &crate_dir,
        &python,
        &["-m", "pip", "install", "-q", "-r", "requirements-test.txt"],
    )?;
    // Stable-Baselines3 alone, without PyTorch (see the file's header).
    run_in_venv(
        venv,
        &crate_dir,
        &python,
        &[
            "-m",
            "pip",
            "install",
            "-q",
            "--no-deps",
            "-r",
            "requirements-test-nodeps.txt",
        ],
    )?;
    let mut develop = vec!["-m", "maturin", "develop", "--locked"];
    if with_mujoco {
        develop.extend(["--features", "mujoco"]);
    }
    run_in_venv(venv, &crate_dir, &python, &develop)?;
    cargo_test(root, &["build", "--locked", "-p", "hyq-cli"])?;
    let target = std::env::var_os("CARGO_TARGET_DIR")
        .map(PathBuf::from)
        .unwrap_or_else(|| root.join("target"));
    let cli = target.join("debug").join("hyq");

    let args = ["-m", "pytest", "-p", "no:cacheprovider"];
    println!("\n$ {} {}", python.display(), args.join(" "));
    let mut passed = None;
    let status = stream_stdout(
        venv_command(venv, &crate_dir, &python)
            .args(args)
            .env("HYQ_CLI", &cli),
        "pytest",
        |line| {
            if let Some(n) = pytest_passed_count(line) {
                passed = Some(n);
            }
        },
    )?;
    if !status.success() {
        return Err(format!("pytest failed ({status})"));
    }
    passed.ok_or_else(|| "pytest printed no summary line".to_string())
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

/// The crates whose `dart` feature runs their tests on the DART backend too (the spec section by
/// section, the env, the command line, the comparison runs).
const DART_FEATURE_CRATES: [&str; 4] = ["spec-tests", "hyq-env", "hyq-cli", "hyq-compare"];

/// The crates whose `mujoco` feature runs their tests on the MuJoCo backend too (the command
/// line's MuJoCo tests run on their own, see [`mujoco_stage_args`]).
const MUJOCO_FEATURE_CRATES: [&str; 3] = ["spec-tests", "hyq-env", "hyq-compare"];

/// The MuJoCo stage's `cargo test` commands: the backend's own tests and every crate of
/// [`MUJOCO_FEATURE_CRATES`] with its `mujoco` feature; then, to keep the stage short, only the
/// command line's MuJoCo test file (`hyq-cli/tests/mujoco_backend.rs`) rather than all of its
/// tests again, which the first stage ran on rapier.
fn mujoco_stage_args(members: &[String]) -> Vec<Vec<String>> {
    let mut commands = vec![feature_stage_args(
        "hyq-mujoco",
        "mujoco",
        &MUJOCO_FEATURE_CRATES,
        members,
    )];
    if members.iter().any(|m| m == "hyq-cli") {
        commands.push(
            [
                "test",
                "--locked",
                "-p",
                "hyq-cli",
                "--features",
                "hyq-cli/mujoco",
                "--test",
                "mujoco_backend",
            ]
            .map(String::from)
            .to_vec(),
        );
    }
    commands
}

/// The DART stage's `cargo test` arguments: the backend's own tests plus every member crate that
/// has a `dart` feature, built with it (members not in the workspace yet are left out).
fn dart_stage_args(members: &[String]) -> Vec<String> {
    feature_stage_args("hyq-dart", "dart", &DART_FEATURE_CRATES, members)
}

/// A backend stage's `cargo test` arguments: the backend crate's own tests plus each of
/// `crates` that is a workspace member, built with its `feature`.
fn feature_stage_args(
    backend: &str,
    feature: &str,
    crates: &[&str],
    members: &[String],
) -> Vec<String> {
    let mut args: Vec<String> = ["test", "--locked", "-p", backend]
        .map(String::from)
        .to_vec();
    let mut features = Vec::new();
    for &name in crates {
        if members.iter().any(|m| m == name) {
            args.extend(["-p".to_string(), name.to_string()]);
            features.push(format!("{name}/{feature}"));
        }
    }
    if !features.is_empty() {
        args.extend(["--features".to_string(), features.join(",")]);
    }
    args
}

/// Prints the summary table and turns a required-but-skipped part or an empty stage into an error.
fn summarize(results: &[(&str, Outcome)], required: &[Part]) -> Result<(), String> {
    println!("\n==== cargo xtask test: summary ====");
    let mut problems = Vec::new();
    for (stage, outcome) in results {
        match outcome {
            Outcome::Passed { tests } => {
                println!("  {stage:<34} passed  ({tests} tests)");
                if *tests == 0 {
                    problems.push(format!("stage `{stage}` ran no test"));
                }
            }
            Outcome::Skipped { why } => {
                println!("  {stage:<34} NOT RUN: {why}");
                if required.iter().any(|p| p.name() == *stage) {
                    problems.push(format!(
                        "stage `{stage}` was required but did not run: {why}"
                    ));
                }
            }
        }
    }
    if problems.is_empty() {
        Ok(())
    } else {
        Err(problems.join("; "))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cli::strings;

    #[test]
    fn counts_passed_tests_on_libtest_summary_lines() {
        assert_eq!(
            passed_count("test result: ok. 12 passed; 0 failed; 0 ignored; 0 measured"),
            12
        );
        assert_eq!(passed_count("running 3 tests"), 0);
        assert_eq!(passed_count("test foo ... ok"), 0);
    }

    #[test]
    fn streamed_output_reaches_the_caller_line_by_line_with_the_exit_status() {
        let mut lines = Vec::new();
        let status = stream_stdout(
            Command::new("sh").args(["-c", "echo 'test result: ok. 2 passed; 0 failed'; exit 3"]),
            "sh",
            |line| lines.push(line.to_string()),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(lines, ["test result: ok. 2 passed; 0 failed"]);
        assert_eq!(status.code(), Some(3));
        let err = stream_stdout(&mut Command::new("/nonexistent/xtask-tool"), "tool", |_| {})
            .expect_err("a missing program cannot start");
        assert!(err.starts_with("cannot start tool:"), "{err}");
    }

    #[test]
    fn counts_passed_tests_on_pytest_summary_lines() {
        assert_eq!(pytest_passed_count("49 passed in 3.73s"), Some(49));
        assert_eq!(
            pytest_passed_count("==== 1 failed, 48 passed, 2 warnings in 3.70s ===="),
            Some(48)
        );
        assert_eq!(
            pytest_passed_count("===== 3 passed, 1 skipped in 123.45s (0:02:03) ====="),
            Some(3)
        );
        assert_eq!(pytest_passed_count("2 failed in 0.50s"), Some(0));
        assert_eq!(pytest_passed_count("no tests ran in 0.01s"), Some(0));
        assert_eq!(
            pytest_passed_count("tests/test_x.py ....                [100%]"),
            None
        );
        assert_eq!(pytest_passed_count("the robot walked 3 m in 5 s"), None);
        assert_eq!(
            pytest_passed_count("FAILED tests/test_x.py::test_y - in 3s"),
            None
        );
    }

    #[test]
    fn require_flags_parse_and_reject_unknown_parts() {
        assert_eq!(
            parse_required(&strings(&["--require", "all"])),
            Ok(vec![Part::Dart, Part::Mujoco, Part::Python])
        );
        let err = parse_required(&strings(&["--require", "matlab"]))
            .expect_err("an unknown part must be refused");
        assert!(err.contains("matlab"), "{err}");
        assert!(parse_required(&strings(&["--require"])).is_err());
    }

    #[test]
    fn the_dart_stage_runs_every_dart_feature_crate_with_its_feature() {
        let members: Vec<String> = ["hyq-spec", "hyq-dart", "spec-tests", "hyq-env"]
            .map(String::from)
            .to_vec();
        assert_eq!(
            dart_stage_args(&members).join(" "),
            "test --locked -p hyq-dart -p spec-tests -p hyq-env --features spec-tests/dart,hyq-env/dart"
        );
    }

    #[test]
    fn the_mujoco_stage_runs_every_mujoco_feature_crate_and_the_clis_mujoco_tests() {
        let members: Vec<String> = ["hyq-mujoco", "spec-tests", "hyq-env", "hyq-cli", "xtask"]
            .map(String::from)
            .to_vec();
        let commands: Vec<String> = mujoco_stage_args(&members)
            .iter()
            .map(|c| c.join(" "))
            .collect();
        assert_eq!(
            commands,
            [
                "test --locked -p hyq-mujoco -p spec-tests -p hyq-env --features \
                 spec-tests/mujoco,hyq-env/mujoco",
                "test --locked -p hyq-cli --features hyq-cli/mujoco --test mujoco_backend",
            ]
        );
    }

    #[test]
    fn a_required_part_that_did_not_run_fails_the_run() {
        let results = [(
            "dart",
            Outcome::Skipped {
                why: "not installed".into(),
            },
        )];
        assert!(summarize(&results, &[]).is_ok());
        let err = summarize(&results, &[Part::Dart])
            .expect_err("a required part that did not run must fail");
        assert!(err.contains("dart"), "{err}");
    }

    #[test]
    fn a_stage_that_ran_no_test_fails_the_run() {
        let results = [("rust", Outcome::Passed { tests: 0 })];
        assert!(summarize(&results, &[]).is_err());
    }
}
