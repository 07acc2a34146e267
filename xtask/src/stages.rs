//! The stages of `cargo xtask test`: each is a command that either runs (and must pass, with at
//! least one test executed) or is skipped with the reason and the install line that would let it
//! run. A skipped stage that was required is a failure.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use hyq_engines::{ENGINES, Engine, Needs, Probe};

use crate::mujoco;
use crate::python::{PYTHON_INSTALL, PYTHON_MIN, pytest_passed_count, venv_command, venv_python};
use crate::workspace::{cargo, is_member, passed_count, workspace_members, workspace_root};

/// A part of the test run that needs something a fresh machine may lack.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
pub enum Part {
    /// An optional engine of hyq-engines' table: its backend crate's tests and every crate's
    /// tests with the feature of its name. Needs the engine's library.
    Engine(&'static Engine),
    /// The Python package: needs maturin, gymnasium and pytest.
    Python,
}

impl Part {
    fn name(self) -> &'static str {
        match self {
            Part::Engine(engine) => engine.name,
            Part::Python => "python",
        }
    }

    /// Every part, in the order the stages run: the optional engines, then Python.
    fn all() -> Vec<Part> {
        optional_engines()
            .map(Part::Engine)
            .chain([Part::Python])
            .collect()
    }
}

/// The engines a build may leave out (those with a cargo feature), in the table's order.
pub(crate) fn optional_engines() -> impl Iterator<Item = &'static Engine> {
    ENGINES.iter().filter(|e| e.feature.is_some())
}

/// The line that installs `engine`'s library, as xtask prints it (with `sudo` where it installs
/// system packages).
pub fn install_line(engine: &Engine) -> String {
    match engine.needs {
        Some(Needs {
            install,
            probe: Probe::File(_),
            ..
        }) => format!("sudo {install}"),
        Some(needs) => needs.install.to_owned(),
        None => String::new(),
    }
}

/// Why `engine`'s library is not usable on this machine (`None`: it is, or it needs none), in
/// one line; `root` is the workspace root.
pub fn engine_missing(engine: &Engine, root: &Path) -> Option<String> {
    let needs = engine.needs?;
    let why = match needs.probe {
        Probe::File(path) if !Path::new(path).exists() => format!("{path} is missing"),
        Probe::File(_) => return None,
        Probe::XtaskSetup => mujoco::check(&mujoco::mujoco_dir(root)).err()?,
    };
    Some(format!(
        "{} is not installed ({why}); to install it: {}",
        needs.what,
        install_line(engine)
    ))
}

/// What happened to one stage.
enum Outcome {
    Passed { tests: u64 },
    Skipped { why: String },
}

/// Parses `--require <part>|all` flags (a part: an optional engine's name, or `python`).
fn parse_required(args: &[String]) -> Result<Vec<Part>, String> {
    let names: Vec<&str> = Part::all().iter().map(|p| p.name()).collect();
    let expected = format!("{} or all", names.join(", "));
    let mut required = Vec::new();
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--require" => {
                let value = it
                    .next()
                    .ok_or_else(|| format!("`--require` needs a value: {expected}"))?;
                if value == "all" {
                    required.extend(Part::all());
                } else if let Some(part) = Part::all().into_iter().find(|p| p.name() == value) {
                    required.push(part);
                } else {
                    return Err(format!(
                        "`--require {value}`: unknown part (expected {expected})"
                    ));
                }
            }
            other => return Err(format!("`cargo xtask test`: unknown argument `{other}`")),
        }
    }
    Ok(required)
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

/// One stage of `cargo xtask test`: its name, what happened to it and how long it took.
struct Stage {
    name: &'static str,
    outcome: Outcome,
    /// Wall-clock time, from the stage's start to its end (what a CI log's reader budgets).
    wall: Duration,
}

/// Runs one stage and times it; an error (a test that failed, a tool that could not start) ends
/// the whole run.
fn timed(
    name: &'static str,
    run: impl FnOnce() -> Result<Outcome, String>,
) -> Result<Stage, String> {
    let start = Instant::now();
    let outcome = run()?;
    Ok(Stage {
        name,
        outcome,
        wall: start.elapsed(),
    })
}

/// `cargo xtask test`.
pub fn test(args: &[String]) -> Result<(), String> {
    let start = Instant::now();
    let (with, args) = crate::rllib::split_with(args)?;
    let required = parse_required(&args)?;
    let root = workspace_root();
    let members = workspace_members(&root)?;
    let has = |name: &str| is_member(&members, name);
    let mut stages = Vec::new();

    // Stage 1: every Rust crate that needs nothing but a Rust toolchain (rapier is the backend).
    stages.push(timed("rust workspace (rapier backend)", || {
        let mut args = vec!["test".to_string(), "--locked".to_string()];
        args.extend(workspace_selection(&members));
        let tests = cargo_test(&root, &args.iter().map(String::as_str).collect::<Vec<_>>())?;
        Ok(Outcome::Passed { tests })
    })?);

    // The patched rapier3d: its tree is the published crate plus vendor/patches, and its
    // multibody tests pass.
    stages.push(timed("vendor/rapier3d (check, tests)", || {
        let tests = crate::vendor::stage(&root)?;
        Ok(Outcome::Passed { tests })
    })?);

    // Then one stage per optional engine: its backend and everything that runs on it.
    let mut engines_run = Vec::new();
    for engine in optional_engines() {
        let stage = timed(engine.name, || engine_stage(engine, &members, &root))?;
        if matches!(stage.outcome, Outcome::Passed { .. }) {
            engines_run.push(engine);
        }
        stages.push(stage);
    }

    // The Python package.
    stages.push(timed(Part::Python.name(), || {
        if !has("hyq-py") {
            return Ok(Outcome::Skipped {
                why: "the hyq-py crate is not in the workspace yet".into(),
            });
        }
        Ok(match python_tools(&root) {
            Err(why) => Outcome::Skipped { why },
            Ok(venv) => Outcome::Passed {
                tests: python_stage(&root, &venv, &engines_run)?,
            },
        })
    })?);

    // Optional stages, run only when asked for (`--with rllib`, `--with train`).
    if with.iter().any(|w| w == "rllib") {
        stages.push(timed("rllib (--with rllib)", || {
            let tests = crate::rllib::stage(&root)?;
            Ok(Outcome::Passed { tests })
        })?);
    }
    if with.iter().any(|w| w == "train") {
        let features = python_features(&engines_run);
        stages.push(timed("train (--with train)", || {
            let tests = crate::train::stage(&root, &features)?;
            Ok(Outcome::Passed { tests })
        })?);
    }

    summarize(&stages, &required, start.elapsed())
}

/// The first stage's packages: the workspace without the optional engines' crates and the
/// Python package (those that need more than a Rust toolchain).
pub(crate) fn workspace_selection(members: &[String]) -> Vec<String> {
    let mut args = vec!["--workspace".to_string()];
    let optional = optional_engines().map(|e| e.crate_name).chain(["hyq-py"]);
    for optional in optional.filter(|name| is_member(members, name)) {
        args.extend(["--exclude".to_string(), optional.to_string()]);
    }
    args
}

/// An optional engine's stage: its backend and everything that runs on it, or why it cannot run
/// here (its crate is not a member, or its library is not installed, with the line that installs
/// it).
fn engine_stage(engine: &Engine, members: &[String], root: &Path) -> Result<Outcome, String> {
    if !is_member(members, engine.crate_name) {
        return Ok(Outcome::Skipped {
            why: format!(
                "the {} crate is not in the workspace yet",
                engine.crate_name
            ),
        });
    }
    if let Some(why) = engine_missing(engine, root) {
        return Ok(Outcome::Skipped {
            why: format!("{why}; then these tests run"),
        });
    }
    let args = engine_stage_args(engine, members, root)?;
    let tests = cargo_test(root, &args.iter().map(String::as_str).collect::<Vec<_>>())?;
    Ok(Outcome::Passed { tests })
}

/// The venv the Python stage builds the package into and runs pytest from: `$HYQ_VENV`, else
/// `target/py-venv` in the workspace (inside the checkout but git-ignored, and kept between
/// runs so a warm run only rebuilds what changed).
fn python_venv(root: &Path) -> PathBuf {
    std::env::var_os("HYQ_VENV")
        .map(PathBuf::from)
        .unwrap_or_else(|| crate::workspace::target_dir(root).join("py-venv"))
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

/// The cargo features the Python package is built with, comma-separated: those of `engines`
/// (the engines whose stage ran) that have `python_tests` (`""` for none).
pub fn python_features(engines: &[&Engine]) -> String {
    let features: Vec<&str> = engines
        .iter()
        .filter(|e| e.python_tests)
        .filter_map(|e| e.feature)
        .collect();
    features.join(",")
}

/// Stage 3: installs the pinned requirements into the venv (and Stable-Baselines3 without its
/// dependencies), builds the extension with the dev
/// profile and installs the package (`maturin develop`: fast to build; users get release
/// builds from `maturin build --release` or `pip install`), then runs pytest with the `hyq`
/// command the first stage built (for the CLI parity tests) and returns how many tests passed. The package is built
/// with the feature of each of `engines` (those whose stage ran) that has `python_tests`, so its
/// tests run on them too.
fn python_stage(root: &Path, venv: &Path, engines: &[&Engine]) -> Result<u64, String> {
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
    let features = python_features(engines);
    let mut develop = vec!["-m", "maturin", "develop", "--locked"];
    if !features.is_empty() {
        develop.extend(["--features", &features]);
    }
    run_in_venv(venv, &crate_dir, &python, &develop)?;
    // The `hyq` command the CLI parity tests run is the one the first stage built for hyq-cli's
    // integration tests (an engine stage after it rebuilds it with that engine built in, which
    // these tests, on the default engine, do not see). `cargo build -p hyq-cli` here would
    // unify the crates' features in yet another way (no dev-dependencies) and compile the
    // physics crates and everything above them once more.
    let cli = crate::workspace::target_dir(root).join("debug").join("hyq");
    if !cli.is_file() {
        return Err(format!(
            "{} is missing: the first stage's `cargo test` builds it for hyq-cli's tests",
            cli.display()
        ));
    }

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

/// The crates whose feature of an engine's name runs some of their tests on that engine too (the
/// spec section by section, the env, the command line, the comparison runs).
const ENGINE_FEATURE_CRATES: [&str; 4] = ["spec-tests", "hyq-env", "hyq-cli", "hyq-compare"];

/// What marks a test file as one an engine's stage runs: it names the engine's feature in a
/// positive `cfg` (`feature = "<feature>"`, not inside `not(...)`), or it runs its bodies on
/// every built engine through one of these (hyq-engines' macros and its list of built engines).
const EVERY_ENGINE_MARKERS: [&str; 4] = [
    "for_each_backend!",
    "for_each_engine!",
    "with_engine!",
    "hyq_engines::built",
];

/// Whether a test's source `text` exercises the engine whose cargo feature is `feature`: see
/// [`EVERY_ENGINE_MARKERS`]. A file that names the feature only as `not(feature = ...)` holds
/// tests of the build without the engine, which the rapier stage runs.
fn exercises_engine(text: &str, feature: &str) -> bool {
    if EVERY_ENGINE_MARKERS.iter().any(|m| text.contains(m)) {
        return true;
    }
    let needle = format!("feature = \"{feature}\"");
    text.match_indices(&needle)
        .any(|(at, _)| !text[..at].trim_end().ends_with("not("))
}

/// One integration-test target of a crate: its name (`tests/<name>.rs`, or `tests/<name>/`
/// with a `main.rs`) and the text of its sources (every `.rs` file of the directory).
struct TestTarget {
    name: String,
    text: String,
}

/// The integration-test targets of the crate in `dir` (cargo's automatic discovery, which every
/// crate of the workspace uses), by name, with the helper modules (`tests/<dir>/` without a
/// `main.rs`, such as `common/`) as a second list.
fn test_targets(dir: &Path) -> Result<(Vec<TestTarget>, Vec<TestTarget>), String> {
    let tests = dir.join("tests");
    let mut targets = Vec::new();
    let mut helpers = Vec::new();
    let entries = match std::fs::read_dir(&tests) {
        Ok(entries) => entries,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok((targets, helpers)),
        Err(e) => return Err(format!("cannot list {}: {e}", tests.display())),
    };
    for entry in entries {
        let path = entry
            .map_err(|e| format!("cannot list {}: {e}", tests.display()))?
            .path();
        let Some(name) = path.file_stem().and_then(|n| n.to_str()).map(str::to_owned) else {
            continue;
        };
        if path.is_dir() {
            let target = TestTarget {
                name,
                text: rust_sources(&path)?,
            };
            if path.join("main.rs").is_file() {
                targets.push(target);
            } else {
                helpers.push(target);
            }
        } else if path.extension().is_some_and(|e| e == "rs") {
            let text = std::fs::read_to_string(&path)
                .map_err(|e| format!("cannot read {}: {e}", path.display()))?;
            targets.push(TestTarget { name, text });
        }
    }
    targets.sort_by(|a, b| a.name.cmp(&b.name));
    Ok((targets, helpers))
}

/// Every `.rs` file under `dir`, concatenated (in name order, so the result is stable).
fn rust_sources(dir: &Path) -> Result<String, String> {
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .map_err(|e| format!("cannot list {}: {e}", dir.display()))?
        .filter_map(|entry| entry.ok().map(|e| e.path()))
        .collect();
    paths.sort();
    let mut text = String::new();
    for path in paths {
        if path.is_dir() {
            text.push_str(&rust_sources(&path)?);
        } else if path.extension().is_some_and(|e| e == "rs") {
            text.push_str(
                &std::fs::read_to_string(&path)
                    .map_err(|e| format!("cannot read {}: {e}", path.display()))?,
            );
            text.push('\n');
        }
    }
    Ok(text)
}

/// The names of the crate in `dir`'s integration tests that exercise the engine of `feature`
/// ([`exercises_engine`]), counting a helper module's marker for every target that declares it
/// (`mod common;`).
fn engine_tests(dir: &Path, feature: &str) -> Result<Vec<String>, String> {
    let (targets, helpers) = test_targets(dir)?;
    let marked_helpers: Vec<String> = helpers
        .iter()
        .filter(|h| exercises_engine(&h.text, feature))
        .map(|h| format!("mod {};", h.name))
        .collect();
    Ok(targets
        .into_iter()
        .filter(|t| {
            exercises_engine(&t.text, feature)
                || marked_helpers.iter().any(|m| t.text.contains(m.as_str()))
        })
        .map(|t| t.name)
        .collect())
}

/// The directory of workspace member `name` (`crates/<name>`, or `<name>` at the root).
fn member_dir(root: &Path, name: &str) -> PathBuf {
    let nested = root.join("crates").join(name);
    if nested.is_dir() {
        nested
    } else {
        root.join(name)
    }
}

/// An engine stage's `cargo test` command, one command so that cargo unifies the features of
/// every crate it builds once, as the first stage did: the backend crate's unit tests and every
/// integration test of it, and, of each crate of [`ENGINE_FEATURE_CRATES`] that is a workspace
/// member, the integration tests that exercise the engine ([`engine_tests`]), built with the
/// feature of the engine's name. The rest of those crates' tests (bad input, documents, rapier
/// alone, the build without the engine) would run exactly as in the first stage, which ran them,
/// so they are not rebuilt and run again. `--lib` also runs those crates' unit tests, which cargo
/// cannot leave out of one command.
fn engine_stage_args(
    engine: &Engine,
    members: &[String],
    root: &Path,
) -> Result<Vec<String>, String> {
    let feature = engine.feature.unwrap_or(engine.name);
    let mut tests: Vec<String> = test_targets(&member_dir(root, engine.crate_name))?
        .0
        .into_iter()
        .map(|t| t.name)
        .collect();
    for name in engine_feature_crates(members) {
        for test in engine_tests(&member_dir(root, name), feature)? {
            if !tests.contains(&test) {
                tests.push(test);
            }
        }
    }
    let mut args: Vec<String> = ["test", "--locked"].map(String::from).to_vec();
    args.extend(engine_selection(engine, members));
    args.push("--lib".to_string());
    for test in tests {
        args.extend(["--test".to_string(), test]);
    }
    Ok(args)
}

/// The members of ENGINE_FEATURE_CRATES that are in the workspace.
fn engine_feature_crates(members: &[String]) -> impl Iterator<Item = &'static str> {
    ENGINE_FEATURE_CRATES
        .into_iter()
        .filter(|name| is_member(members, name))
}

/// An engine stage's packages and features: the engine's backend crate, and each crate of
/// ENGINE_FEATURE_CRATES with its feature of the engine's name.
pub(crate) fn engine_selection(engine: &Engine, members: &[String]) -> Vec<String> {
    let feature = engine.feature.unwrap_or(engine.name);
    let mut args = vec!["-p".to_string(), engine.crate_name.to_string()];
    let mut features = Vec::new();
    for name in engine_feature_crates(members) {
        args.extend(["-p".to_string(), name.to_string()]);
        features.push(format!("{name}/{feature}"));
    }
    if !features.is_empty() {
        args.extend(["--features".to_string(), features.join(",")]);
    }
    args
}

/// Prints the summary table, one line per stage with its wall time and a last line with the
/// total, and turns a required-but-skipped part or an empty stage into an error.
fn summarize(stages: &[Stage], required: &[Part], total: Duration) -> Result<(), String> {
    println!("\n==== cargo xtask test: summary ====");
    let mut problems = Vec::new();
    for Stage {
        name,
        outcome,
        wall,
    } in stages
    {
        let wall = seconds(*wall);
        match outcome {
            Outcome::Passed { tests } => {
                println!("  {name:<34} {wall:>7}  passed  ({tests} tests)");
                if *tests == 0 {
                    problems.push(format!("stage `{name}` ran no test"));
                }
            }
            Outcome::Skipped { why } => {
                println!("  {name:<34} {wall:>7}  NOT RUN: {why}");
                if required.iter().any(|p| p.name() == *name) {
                    problems.push(format!(
                        "stage `{name}` was required but did not run: {why}"
                    ));
                }
            }
        }
    }
    println!("  {:<34} {:>7}  wall clock", "total", seconds(total));
    if problems.is_empty() {
        Ok(())
    } else {
        Err(problems.join("; "))
    }
}

/// A wall time as the summary prints it: whole seconds (`"812 s"`).
fn seconds(wall: Duration) -> String {
    format!("{} s", wall.as_secs_f64().round())
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
        let engine = |name| Part::Engine(hyq_engines::find(name).expect("an engine"));
        assert_eq!(
            parse_required(&strings(&["--require", "all"])),
            Ok(vec![engine("dart"), engine("mujoco"), Part::Python])
        );
        assert_eq!(
            parse_required(&strings(&["--require", "mujoco", "--require", "python"])),
            Ok(vec![engine("mujoco"), Part::Python])
        );
        assert!(parse_required(&strings(&["--require", "rapier"])).is_err());
        let err = parse_required(&strings(&["--require", "matlab"]))
            .expect_err("an unknown part must be refused");
        assert!(err.contains("matlab"), "{err}");
        assert!(parse_required(&strings(&["--require"])).is_err());
    }

    #[test]
    fn a_test_file_exercises_an_engine_by_its_feature_or_by_running_on_every_engine() {
        assert!(exercises_engine("#![cfg(feature = \"dart\")]", "dart"));
        assert!(exercises_engine(
            "#[cfg(feature = \"mujoco\")]\nfn t() {}",
            "mujoco"
        ));
        assert!(exercises_engine(
            "#[cfg(any(feature = \"dart\", feature = \"mujoco\"))]",
            "mujoco"
        ));
        assert!(exercises_engine(
            "spec_tests::for_each_backend! { }",
            "dart"
        ));
        assert!(exercises_engine(
            "for e in hyq_engines::built() {}",
            "mujoco"
        ));
        assert!(!exercises_engine("#[cfg(feature = \"dart\")]", "mujoco"));
        assert!(!exercises_engine("#[cfg(not(feature = \"dart\"))]", "dart"));
        assert!(!exercises_engine("//! with `--features dart`", "dart"));
        assert!(!exercises_engine("run(&[\"--backend\", \"dart\"])", "dart"));
    }

    /// The `--test` names of an engine stage's command, and the command without them.
    fn stage_of(engine: &str) -> (String, Vec<String>) {
        let members = workspace_members(&workspace_root()).unwrap_or_else(|e| panic!("{e}"));
        let engine = hyq_engines::find(engine).expect("an engine");
        let args = engine_stage_args(engine, &members, &workspace_root())
            .unwrap_or_else(|e| panic!("{e}"));
        let mut tests = Vec::new();
        let mut rest = Vec::new();
        let mut it = args.into_iter();
        while let Some(arg) = it.next() {
            if arg == "--test" {
                tests.push(it.next().expect("a test name follows --test"));
            } else {
                rest.push(arg);
            }
        }
        (rest.join(" "), tests)
    }

    #[test]
    fn the_dart_stage_runs_the_backend_and_the_tests_that_exercise_dart_in_one_command() {
        let (command, tests) = stage_of("dart");
        assert_eq!(
            command,
            "test --locked -p hyq-dart -p spec-tests -p hyq-env -p hyq-cli -p hyq-compare \
             --features spec-tests/dart,hyq-env/dart,hyq-cli/dart,hyq-compare/dart --lib"
        );
        for test in [
            "conformance",
            "determinism",
            "threads",
            "spec",
            "dart_backend",
            "other_robots_through_env",
            "compare_writes_reports",
            "run_summary_output",
            "rapier_vs_dart_within_ledger",
        ] {
            assert!(
                tests.iter().any(|t| t == test),
                "{test} missing from {tests:?}"
            );
        }
        for test in [
            "mujoco_backend",
            "bad_input_cases",
            "cli_errors_are_one_line",
        ] {
            assert!(!tests.iter().any(|t| t == test), "{test} in {tests:?}");
        }
    }

    #[test]
    fn the_mujoco_stage_runs_the_backend_and_the_tests_that_exercise_mujoco_in_one_command() {
        let (command, tests) = stage_of("mujoco");
        assert!(
            command.starts_with("test --locked -p hyq-mujoco -p spec-tests"),
            "{command}"
        );
        for test in [
            "library_errors",
            "spec",
            "mujoco_backend",
            "env_step_allocates_nothing_on_its_thread",
            "same_backend_agrees_exactly",
        ] {
            assert!(
                tests.iter().any(|t| t == test),
                "{test} missing from {tests:?}"
            );
        }
        assert!(!tests.iter().any(|t| t == "dart_backend"), "{tests:?}");
    }

    /// The engine stages select the backend crates' unit tests with `--lib` alone: a test in one
    /// of their binaries would not run, so there must be none.
    #[test]
    fn the_backend_crates_binaries_hold_no_unit_tests() {
        for engine in optional_engines() {
            let dir = member_dir(&workspace_root(), engine.crate_name);
            let bins = dir.join("src").join("bin");
            let mut files: Vec<PathBuf> = vec![dir.join("src").join("main.rs")];
            if let Ok(entries) = std::fs::read_dir(&bins) {
                files.extend(entries.filter_map(|e| e.ok().map(|e| e.path())));
            }
            for file in files {
                let text = if file.is_dir() {
                    rust_sources(&file).unwrap_or_else(|e| panic!("{e}"))
                } else {
                    std::fs::read_to_string(&file).unwrap_or_default()
                };
                assert!(!text.contains("#[test]"), "{} holds a test", file.display());
            }
        }
    }

    #[test]
    fn a_required_part_that_did_not_run_fails_the_run() {
        let results = [stage(
            "dart",
            Outcome::Skipped {
                why: "not installed".into(),
            },
        )];
        assert!(summarize(&results, &[], Duration::ZERO).is_ok());
        let dart = hyq_engines::find("dart").expect("an engine");
        let err = summarize(&results, &[Part::Engine(dart)], Duration::ZERO)
            .expect_err("a required part that did not run must fail");
        assert!(err.contains("dart"), "{err}");
    }

    #[test]
    fn a_stage_that_ran_no_test_fails_the_run() {
        let results = [stage("rust", Outcome::Passed { tests: 0 })];
        assert!(summarize(&results, &[], Duration::ZERO).is_err());
    }

    /// A stage that took no time, for the summary's tests.
    fn stage(name: &'static str, outcome: Outcome) -> Stage {
        Stage {
            name,
            outcome,
            wall: Duration::ZERO,
        }
    }

    #[test]
    fn wall_times_are_whole_seconds() {
        assert_eq!(seconds(Duration::from_millis(812_400)), "812 s");
        assert_eq!(seconds(Duration::from_millis(1_600)), "2 s");
        assert_eq!(seconds(Duration::ZERO), "0 s");
    }
}
