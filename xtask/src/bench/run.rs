//! Running the measurements: the commands, and reading the figures from what they print.

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde_json::Value;

use super::args::BenchArgs;
use super::command::run;
use super::plan::{AnchorRun, HyqBackend, Measure, SEQUENCE, Series};
use super::plan::{anchor_modules, measurable_backends};
use super::report::{Host, python_versions};
use super::stats::Rep;
use super::venv::{PYTHON_ENV, read_pins, setup_venv};
use super::{ANCHORS_DIR, MODELS_DIR};
use crate::cli::strings;
use crate::workspace::run_cargo;

/// What the repetitions run: the anchors' Python and directory, the release `hyq`, the models,
/// the backends this machine measures and which anchor modules import.
pub(super) struct Setup {
    root: PathBuf,
    python: PathBuf,
    anchors: PathBuf,
    hyq: PathBuf,
    models: String,
    backends: Vec<&'static str>,
    modules: BTreeMap<&'static str, bool>,
}

impl Setup {
    /// Python first (a missing interpreter or pip fails before the long build), then the
    /// release build of `hyq` with every backend this machine can measure, the anchors' models
    /// written with it, and the anchors' modules; what was left out, and why, goes into
    /// `host`'s notes.
    pub(super) fn prepare(args: &BenchArgs, root: &Path, host: &mut Host) -> Result<Self, String> {
        let anchors = root.join(ANCHORS_DIR);
        let pins = read_pins(&anchors)?;
        let (python, venv_notes) = setup_venv(&args.venv, &pins)?;
        host.notes.extend(venv_notes);

        let (backends, features) = measurable_backends(args, root, &mut host.notes);
        let mut build = strings(&["build", "--release", "--locked", "-p", "hyq-cli"]);
        if !features.is_empty() {
            build.extend(strings(&["--features", &features.join(",")]));
        }
        let status = run_cargo(root, &build)?;
        if !status.success() {
            return Err(format!("the release build of hyq failed ({status})"));
        }
        let hyq = crate::workspace::target_dir(root)
            .join("release")
            .join("hyq");
        let models = crate::workspace::target_dir(root).join(MODELS_DIR);
        write_models(&hyq, root, &models)?;

        let modules = anchor_modules(&python, &anchors, args, &mut host.notes)?;
        host.anchors = python_versions(&python, &anchors, &pins);
        Ok(Setup {
            root: root.to_path_buf(),
            python,
            anchors,
            hyq,
            models: models.to_string_lossy().into_owned(),
            backends,
            modules,
        })
    }

    /// One repetition: every measurement of [`SEQUENCE`] in order, the raw output appended to
    /// `raw`.
    pub(super) fn repetition(&self, args: &BenchArgs, raw: &mut String) -> Result<Rep, String> {
        let mut r = Rep::new();
        for measure in SEQUENCE {
            match measure {
                Measure::Hyq(b) => self.hyq_backend(b, args, raw, &mut r)?,
                Measure::Anchor(a) => self.anchor(a, args, raw, &mut r)?,
                Measure::VecEnv => self.vec_env(args, raw, &mut r)?,
            }
        }
        Ok(r)
    }

    /// `hyq bench --json --backend <backend> <extra>`, its output appended to `raw`.
    fn hyq_bench(
        &self,
        backend: &str,
        extra: &[&str],
        raw: &mut String,
    ) -> Result<HyqFigures, String> {
        let mut a = strings(&["bench", "--json", "--backend", backend]);
        a.extend(strings(extra));
        let out = run(&self.hyq, &a, &self.root, &[])?;
        raw.push_str(&out);
        parse_hyq(&out)
    }

    /// A backend's single-env rate and spec share, unless it is not measured here.
    fn hyq_backend(
        &self,
        b: HyqBackend,
        args: &BenchArgs,
        raw: &mut String,
        r: &mut Rep,
    ) -> Result<(), String> {
        if !self.backends.contains(&b.name) {
            return Ok(());
        }
        let f = self.hyq_bench(b.name, &["--steps", &args.steps.to_string()], raw)?;
        r.insert(b.rate, f.cpu);
        if let Some(share) = f.spec_share {
            r.insert(b.spec_share, share);
        }
        Ok(())
    }

    /// An anchor script's figures, unless its module does not import (or it is DART's and
    /// `--no-dart` was given).
    fn anchor(
        &self,
        a: AnchorRun,
        args: &BenchArgs,
        raw: &mut String,
        r: &mut Rep,
    ) -> Result<(), String> {
        if (a.dart && !args.dart) || self.modules.get(a.module) != Some(&true) {
            return Ok(());
        }
        let mut argv = strings(&[
            a.script,
            "--models",
            &self.models,
            "--env-steps",
            &args.anchor_steps.to_string(),
            "--runs",
            "1",
        ]);
        argv.extend(strings(a.args));
        let out = run(&self.python, &argv, &self.anchors, &PYTHON_ENV)?;
        raw.push_str(&out);
        for f in a.figures {
            r.insert(f.series, parse_anchor(&out, f.anchor, f.case, f.key)?);
        }
        Ok(())
    }

    /// The rapier vector env of 2 envs on 1 thread, then on 2: wall-clock and CPU rates.
    fn vec_env(&self, args: &BenchArgs, raw: &mut String, r: &mut Rep) -> Result<(), String> {
        let vec_steps = args.vec_steps.to_string();
        for (threads, series, cpu) in [
            ("1", Series::Vec1, Series::Vec1Cpu),
            ("2", Series::Vec2, Series::Vec2Cpu),
        ] {
            let extra = [
                "--num-envs",
                "2",
                "--threads",
                threads,
                "--steps",
                &vec_steps,
            ];
            let v = self.hyq_bench("rapier", &extra, raw)?;
            r.insert(series, v.wall);
            r.insert(cpu, v.cpu);
        }
        Ok(())
    }
}

/// The figures `hyq bench --json` reports that this command uses.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HyqFigures {
    /// `env_steps_per_s` (wall clock).
    pub wall: f64,
    /// `env_steps_per_s_cpu`.
    pub cpu: f64,
    /// `shares.spec + shares.observation` (single-env mode only).
    pub spec_share: Option<f64>,
}

fn number(v: &Value, path: &[&str]) -> Result<f64, String> {
    let mut at = v;
    for key in path {
        at = at
            .get(key)
            .ok_or_else(|| format!("no `{}` in {v}", path.join(".")))?;
    }
    at.as_f64()
        .ok_or_else(|| format!("`{}` is not a number: {at}", path.join(".")))
}

/// Reads the one JSON object `hyq bench --json` prints (schema version 1).
pub fn parse_hyq(stdout: &str) -> Result<HyqFigures, String> {
    let line = stdout
        .lines()
        .find(|l| l.trim_start().starts_with('{'))
        .ok_or_else(|| format!("`hyq bench --json` printed no JSON object: {stdout:?}"))?;
    let v: Value = serde_json::from_str(line)
        .map_err(|e| format!("`hyq bench --json` printed invalid JSON ({e}): {line}"))?;
    let schema = number(&v, &["schema_version"])?;
    if schema != 1.0 {
        return Err(format!(
            "`hyq bench --json` schema_version {schema}: this command reads version 1"
        ));
    }
    let spec_share = match v.get("shares") {
        Some(_) => Some(number(&v, &["shares", "spec"])? + number(&v, &["shares", "observation"])?),
        None => None,
    };
    Ok(HyqFigures {
        wall: number(&v, &["env_steps_per_s"])?,
        cpu: number(&v, &["env_steps_per_s_cpu"])?,
        spec_share,
    })
}

/// The number at `key` in the line of an anchor script's output (one JSON object a line;
/// other lines are ignored) whose `anchor` and `case` are the given ones.
pub fn parse_anchor(stdout: &str, anchor: &str, case: &str, key: &str) -> Result<f64, String> {
    for line in stdout.lines().filter(|l| l.trim_start().starts_with('{')) {
        let Ok(v) = serde_json::from_str::<Value>(line) else {
            continue;
        };
        if v.get("anchor").and_then(Value::as_str) == Some(anchor)
            && v.get("case").and_then(Value::as_str) == Some(case)
        {
            return number(&v, &[key]);
        }
    }
    Err(format!(
        "no result for anchor {anchor:?}, case {case:?} in: {}",
        stdout.trim()
    ))
}

/// Writes the anchors' models with the release `hyq` into `dir`: MJCF with position servos,
/// URDF with capsules as cylinders, and the facts.
pub(super) fn write_models(hyq: &Path, root: &Path, dir: &Path) -> Result<(), String> {
    std::fs::create_dir_all(dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    for (file, args) in [
        (
            "hyq.xml",
            &["--format", "mjcf", "--actuators", "position"][..],
        ),
        ("hyq.urdf", &["--format", "urdf", "--capsules", "cylinder"]),
        ("hyq.json", &["--format", "json"]),
    ] {
        let out = dir.join(file);
        let mut a = strings(&["model"]);
        a.extend(strings(args));
        a.extend(strings(&["--out", &out.to_string_lossy()]));
        run(hyq, &a, root, &[])?;
    }
    println!("wrote the anchors' models into {}", dir.display());
    Ok(())
}
