//! `cargo xtask bench-vs-anchors`: the project's benchmark and the anchors' (the same workload
//! in MuJoCo and in DART, driven from Python by `bench/anchors/`), run side by side in one
//! run, with the ratios the speed targets are stated in.
//!
//! What it does, in order:
//! 1. sets up (or reuses) the anchors' Python virtual environment, `target/anchor-venv` unless
//!    `--venv DIR` (relative: to the workspace root) or `$HYQ_ANCHOR_VENV` says otherwise, with
//!    the versions pinned in `bench/anchors/requirements.txt`;
//! 2. builds `hyq` in release mode, with every backend of [`SEQUENCE`] whose engine is
//!    installed (DART when its headers are, MuJoCo when `cargo xtask setup mujoco` has put it
//!    in `target/mujoco` or `$MUJOCO_DIR`);
//! 3. writes the anchors' models afresh with that `hyq` (`hyq model`): `hyq.xml` (MJCF with
//!    position servos), `hyq.urdf` (capsules as cylinders, for DART's loader) and `hyq.json`
//!    (the facts the scripts read), into `target/anchor-models/`, so they are always the robot
//!    the environment simulates;
//! 4. repeats `--reps` times the measurements of [`SEQUENCE`], in its order, so that every
//!    repetition sees the same machine load: `hyq bench` on rapier; MuJoCo from Python (the
//!    env loop `env_random` and MuJoCo's own loop `c_loop`); `hyq bench` on MuJoCo; `hyq bench`
//!    on DART; DART from Python (Bullet detector, with `world.step()` timed alone in a second
//!    pass, and the ODE detector); the rapier vector env of 2 envs on 1 thread, then on 2
//!    threads;
//! 5. prints, and writes to `target/bench-vs-anchors.md`, a Markdown report: the CPU model, the
//!    load, the median, min and max of every figure, and each ratio against its target (the
//!    median of the per-repetition ratios, each taken within one repetition, and their min and
//!    max). The raw JSON lines go to `target/bench-vs-anchors.jsonl`.
//!
//! Single-env rates are CPU-time rates (env steps per CPU second of the process), the better
//! estimate of an idle core on a shared machine; the anchors report both kinds and the same
//! kind is compared. The vector env's scaling is a wall-clock ratio (that is what parallelism
//! buys), so it is only meaningful when two cores are free: the load average is printed with it.
//!
//! # Adding a backend
//! A new `hyq bench --backend X` row takes: two [`Series`] (its rate and its spec share) with
//! their labels in [`Series::label`] and places in [`Series::ALL`]; a [`HyqBackend`] in
//! [`SEQUENCE`] (with the cargo feature that builds it in); its availability in
//! [`backend_missing`]; and, if it has one, its target in [`TARGETS`].

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use crate::cli::{positive, strings, value};
use crate::stages::{
    PYTHON_INSTALL, PYTHON_MIN, run_cargo, venv_python, workspace_root,
};

/// The anchor harness, relative to the workspace root.
pub const ANCHORS_DIR: &str = "bench/anchors";

/// Where the anchors' models are written, relative to the workspace root.
pub const MODELS_DIR: &str = "target/anchor-models";

/// The anchors' default virtual environment, relative to the workspace root (git-ignored).
pub const DEFAULT_VENV: &str = "target/anchor-venv";

/// The command's settings.
#[derive(Clone, Debug, PartialEq)]
pub struct BenchArgs {
    /// Repetitions of the whole interleaved sequence.
    pub reps: usize,
    /// Env steps per `hyq bench` pass (one env).
    pub steps: u64,
    /// Vector steps per vector-env pass (each is 2 env steps).
    pub vec_steps: u64,
    /// Env steps per anchor run (MuJoCo and DART from Python).
    pub anchor_steps: u64,
    /// The anchors' virtual environment.
    pub venv: PathBuf,
    /// Measure the DART backend and DART from Python (when DART is installed).
    pub dart: bool,
    /// Measure the MuJoCo backend (when MuJoCo is set up); MuJoCo from Python runs either way,
    /// as the rapier targets' anchor.
    pub mujoco: bool,
}

impl BenchArgs {
    /// Whether `hyq bench --backend <name>` is wanted (`--no-dart`, `--no-mujoco` say no).
    pub fn wants(&self, backend: &str) -> bool {
        match backend {
            "dart" => self.dart,
            "mujoco" => self.mujoco,
            _ => true,
        }
    }
}

/// Parses the command's arguments; `root` is the workspace root (for the defaults and for
/// refusing a virtual environment among the repository's files); `env_venv` is
/// `$HYQ_ANCHOR_VENV`.
pub fn parse(args: &[String], root: &Path, env_venv: Option<PathBuf>) -> Result<BenchArgs, String> {
    const COMMAND: &str = "bench-vs-anchors";
    let mut out = BenchArgs {
        reps: 5,
        steps: 3000,
        vec_steps: 1500,
        anchor_steps: 3000,
        venv: env_venv.unwrap_or_else(|| root.join(DEFAULT_VENV)),
        dart: true,
        mujoco: true,
    };
    let mut it = args.iter();
    while let Some(arg) = it.next() {
        match arg.as_str() {
            "--reps" => out.reps = positive(&mut it, COMMAND, arg)? as usize,
            "--steps" => out.steps = positive(&mut it, COMMAND, arg)?,
            "--vec-steps" => out.vec_steps = positive(&mut it, COMMAND, arg)?,
            "--anchor-steps" => out.anchor_steps = positive(&mut it, COMMAND, arg)?,
            "--venv" => out.venv = PathBuf::from(value(&mut it, COMMAND, arg)?),
            "--no-dart" => out.dart = false,
            "--no-mujoco" => out.mujoco = false,
            other => {
                return Err(format!(
                    "`cargo xtask bench-vs-anchors`: unknown argument `{other}`"
                ));
            }
        }
    }
    if out.venv.is_relative() {
        out.venv = root.join(&out.venv);
    }
    if out.venv.starts_with(root) && !out.venv.starts_with(root.join("target")) {
        return Err(format!(
            "--venv {}: the anchors' virtual environment must be under the repository's \
             target/ or outside the repository ({}), not among its files",
            out.venv.display(),
            root.display()
        ));
    }
    Ok(out)
}

/// One measured figure, sampled once per repetition.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Series {
    /// `hyq bench`, rapier: env steps per CPU second.
    Rapier,
    /// `hyq bench`, rapier: share of the step in spec evaluation and observation assembly.
    RapierSpecShare,
    /// MuJoCo from Python, `env_random`: env steps per CPU second.
    MujocoPy,
    /// MuJoCo's own loop of sub-steps, `c_loop`: env steps per CPU second.
    MujocoC,
    /// `hyq bench`, MuJoCo: env steps per CPU second.
    Mujoco,
    /// `hyq bench`, MuJoCo: share of the step in spec evaluation and observation assembly.
    MujocoSpecShare,
    /// `hyq bench`, DART: env steps per CPU second.
    Dart,
    /// `hyq bench`, DART: share of the step in spec evaluation and observation assembly.
    DartSpecShare,
    /// dartpy with the Bullet detector (the backend's detector), capsule legs.
    DartPyBullet,
    /// dartpy with the ODE detector, capsule legs.
    DartPyOde,
    /// dartpy with Bullet: the time inside `world.step()` alone, as env steps: the ceiling of
    /// any binding of that DART build, which can only remove the rest.
    DartPyStepOnly,
    /// The rapier vector env, 2 envs on 1 thread: env steps per wall second.
    Vec1,
    /// The same on 2 threads.
    Vec2,
    /// The rapier vector env, 2 envs on 1 thread: env steps per CPU second of the process.
    Vec1Cpu,
    /// The same on 2 threads (spinning idle workers count; a blocked caller does not).
    Vec2Cpu,
}

impl Series {
    /// Every series, in report order.
    pub const ALL: [Series; 15] = [
        Series::Rapier,
        Series::MujocoPy,
        Series::MujocoC,
        Series::Mujoco,
        Series::Dart,
        Series::DartPyBullet,
        Series::DartPyOde,
        Series::DartPyStepOnly,
        Series::Vec1,
        Series::Vec2,
        Series::Vec1Cpu,
        Series::Vec2Cpu,
        Series::RapierSpecShare,
        Series::DartSpecShare,
        Series::MujocoSpecShare,
    ];

    /// The row's label and unit.
    pub fn label(self) -> (&'static str, &'static str) {
        match self {
            Series::Rapier => ("hyq, rapier backend, one env", "env steps/s, CPU"),
            Series::MujocoPy => ("MuJoCo 4.0 from Python (`env_random`)", "env steps/s, CPU"),
            Series::MujocoC => (
                "MuJoCo 4.0, its own loop of sub-steps (`c_loop`)",
                "env steps/s, CPU",
            ),
            Series::Dart => ("hyq, DART backend, one env", "env steps/s, CPU"),
            Series::Mujoco => ("hyq, MuJoCo backend, one env", "env steps/s, CPU"),
            Series::DartPyBullet => (
                "DART from Python (dartpy 6.20, Bullet, capsules)",
                "env steps/s, CPU",
            ),
            Series::DartPyOde => (
                "DART from Python (dartpy 6.20, ODE, capsules)",
                "env steps/s, CPU",
            ),
            Series::DartPyStepOnly => (
                "DART 6.20 `world.step()` alone, timed from Python (Bullet)",
                "env steps/s, CPU",
            ),
            Series::Vec1 => (
                "hyq vector env, rapier, N = 2, 1 thread",
                "env steps/s, wall",
            ),
            Series::Vec2 => (
                "hyq vector env, rapier, N = 2, 2 threads",
                "env steps/s, wall",
            ),
            Series::Vec1Cpu => (
                "hyq vector env, rapier, N = 2, 1 thread",
                "env steps/s, CPU",
            ),
            Series::Vec2Cpu => (
                "hyq vector env, rapier, N = 2, 2 threads",
                "env steps/s, CPU",
            ),
            Series::RapierSpecShare => {
                ("spec evaluation + observation, rapier", "% of an env step")
            }
            Series::DartSpecShare => ("spec evaluation + observation, DART", "% of an env step"),
            Series::MujocoSpecShare => {
                ("spec evaluation + observation, MuJoCo", "% of an env step")
            }
        }
    }

    /// Whether the figure is a fraction printed as a percentage.
    fn is_share(self) -> bool {
        matches!(
            self,
            Series::RapierSpecShare | Series::DartSpecShare | Series::MujocoSpecShare
        )
    }
}

/// A `hyq bench` backend measured once per repetition (one env).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HyqBackend {
    /// The `--backend` value.
    pub name: &'static str,
    /// The hyq-cli cargo feature that builds it in (`None`: always built).
    pub feature: Option<&'static str>,
    /// Where its env steps per CPU second go.
    pub rate: Series,
    /// Where its spec-evaluation share goes.
    pub spec_share: Series,
}

/// One figure of an anchor script's output: the line with `anchor` and `case`, its number at
/// `key`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnchorFigure {
    /// The line's `anchor`.
    pub anchor: &'static str,
    /// The line's `case`.
    pub case: &'static str,
    /// The key of the number.
    pub key: &'static str,
    /// Where it goes.
    pub series: Series,
}

/// One run of an anchor script (`bench/anchors/<script>`) per repetition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AnchorRun {
    /// The script's file name.
    pub script: &'static str,
    /// Its arguments besides `--models`, `--env-steps` and `--runs`.
    pub args: &'static [&'static str],
    /// The Python module it needs (the run is skipped, with a note, when it does not import).
    pub module: &'static str,
    /// Whether it is a DART measurement (skipped with `--no-dart`).
    pub dart: bool,
    /// The figures it gives.
    pub figures: &'static [AnchorFigure],
}

/// One step of a repetition.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Measure {
    /// `hyq bench --backend <name>`, one env.
    Hyq(HyqBackend),
    /// An anchor script.
    Anchor(AnchorRun),
    /// The rapier vector env of 2 envs, on 1 thread then on 2.
    VecEnv,
}

/// The measurements of one repetition, in order (interleaved so that load changes within a
/// repetition touch both sides of a ratio alike).
pub const SEQUENCE: [Measure; 7] = [
    Measure::Hyq(HyqBackend {
        name: "rapier",
        feature: None,
        rate: Series::Rapier,
        spec_share: Series::RapierSpecShare,
    }),
    Measure::Anchor(AnchorRun {
        script: "mujoco_anchor.py",
        args: &["--cases", "env_random,c_loop"],
        module: "mujoco",
        dart: false,
        figures: &[
            AnchorFigure {
                anchor: "mujoco",
                case: "env_random",
                key: "env_steps_per_s_cpu",
                series: Series::MujocoPy,
            },
            AnchorFigure {
                anchor: "mujoco",
                case: "c_loop",
                key: "env_steps_per_s_cpu",
                series: Series::MujocoC,
            },
        ],
    }),
    Measure::Hyq(HyqBackend {
        name: "mujoco",
        feature: Some("mujoco"),
        rate: Series::Mujoco,
        spec_share: Series::MujocoSpecShare,
    }),
    Measure::Hyq(HyqBackend {
        name: "dart",
        feature: Some("dart"),
        rate: Series::Dart,
        spec_share: Series::DartSpecShare,
    }),
    Measure::Anchor(AnchorRun {
        script: "dart_anchor.py",
        args: &["--detector", "bullet", "--step-only"],
        module: "dartpy",
        dart: true,
        figures: &[
            AnchorFigure {
                anchor: "dart-bullet-capsule",
                case: "env_random",
                key: "env_steps_per_s_cpu",
                series: Series::DartPyBullet,
            },
            AnchorFigure {
                anchor: "dart-bullet-capsule",
                case: "env_random",
                key: "step_only_env_steps_per_s_cpu",
                series: Series::DartPyStepOnly,
            },
        ],
    }),
    Measure::Anchor(AnchorRun {
        script: "dart_anchor.py",
        args: &["--detector", "ode"],
        module: "dartpy",
        dart: true,
        figures: &[AnchorFigure {
            anchor: "dart-ode-capsule",
            case: "env_random",
            key: "env_steps_per_s_cpu",
            series: Series::DartPyOde,
        }],
    }),
    Measure::VecEnv,
];

/// Why backend `name` cannot be measured on this machine (`None`: it can); `root` is the
/// workspace root (MuJoCo is looked for in `$MUJOCO_DIR`, else its `target/mujoco`).
pub fn backend_missing(name: &str, root: &Path) -> Option<String> {
    let engine = hyq_engines::find(name)?;
    crate::stages::engine_missing(engine, root)
        .map(|why| format!("{why}, so the {} backend was not measured", engine.title))
}

/// The figures of one repetition (a series is absent when its run was skipped or failed).
pub type Rep = BTreeMap<Series, f64>;

/// The pinned `name==version` lines of a requirements file (comments and blank lines skipped);
/// any other line is an error naming it.
pub fn parse_requirements(text: &str) -> Result<Vec<(String, String)>, String> {
    let mut pins = Vec::new();
    for (i, line) in text.lines().enumerate() {
        let line = line.split('#').next().unwrap_or("").trim();
        if line.is_empty() {
            continue;
        }
        match line.split_once("==") {
            Some((name, version)) if !name.trim().is_empty() && !version.trim().is_empty() => {
                pins.push((name.trim().to_string(), version.trim().to_string()));
            }
            _ => {
                return Err(format!(
                    "{ANCHORS_DIR}/requirements.txt line {}: `{line}` is not a `name==version` pin",
                    i + 1
                ));
            }
        }
    }
    Ok(pins)
}

/// The median, min and max of `values` (`None` when empty).
pub fn summary(values: &[f64]) -> Option<(f64, f64, f64)> {
    if values.is_empty() {
        return None;
    }
    let mut v = values.to_vec();
    v.sort_by(f64::total_cmp);
    let n = v.len();
    let median = if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    };
    Some((median, v[0], v[n - 1]))
}

/// The samples of `series` over the repetitions.
pub fn samples(reps: &[Rep], series: Series) -> Vec<f64> {
    reps.iter()
        .filter_map(|r| r.get(&series).copied())
        .collect()
}

/// The per-repetition ratios num / den, taken only within a repetition that has both.
pub fn ratios(reps: &[Rep], num: Series, den: Series) -> Vec<f64> {
    reps.iter()
        .filter_map(|r| Some(r.get(&num)? / r.get(&den)?))
        .collect()
}

/// What a target asks of a figure.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Goal {
    /// The ratio num / den must be at least `target`.
    RatioAtLeast {
        /// Numerator.
        num: Series,
        /// Denominator.
        den: Series,
        /// The bound.
        target: f64,
    },
    /// The series must be at most `target`.
    AtMost {
        /// The figure.
        series: Series,
        /// The bound.
        target: f64,
    },
}

/// One target of issue 7, with its label.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Target {
    /// What is compared.
    pub label: &'static str,
    /// The bound.
    pub goal: Goal,
}

/// The targets, in report order.
pub const TARGETS: [Target; 11] = [
    Target {
        label: "rapier / MuJoCo from Python",
        goal: Goal::RatioAtLeast {
            num: Series::Rapier,
            den: Series::MujocoPy,
            target: 1.0,
        },
    },
    Target {
        label: "rapier / MuJoCo C loop (stretch)",
        goal: Goal::RatioAtLeast {
            num: Series::Rapier,
            den: Series::MujocoC,
            target: 1.0,
        },
    },
    Target {
        label: "DART / DART from Python (Bullet)",
        goal: Goal::RatioAtLeast {
            num: Series::Dart,
            den: Series::DartPyBullet,
            target: 1.5,
        },
    },
    Target {
        label: "DART / DART from Python (ODE)",
        goal: Goal::RatioAtLeast {
            num: Series::Dart,
            den: Series::DartPyOde,
            target: 1.5,
        },
    },
    Target {
        label: "vector env N = 2: 2 threads / 1 thread",
        goal: Goal::RatioAtLeast {
            num: Series::Vec2,
            den: Series::Vec1,
            target: 1.9,
        },
    },
    Target {
        label: "vector env N = 2: CPU efficiency, 2 threads / 1 thread (load-independent proxy)",
        goal: Goal::RatioAtLeast {
            num: Series::Vec2Cpu,
            den: Series::Vec1Cpu,
            target: 0.95,
        },
    },
    Target {
        label: "spec evaluation share, rapier",
        goal: Goal::AtMost {
            series: Series::RapierSpecShare,
            target: 0.01,
        },
    },
    Target {
        label: "spec evaluation share, DART",
        goal: Goal::AtMost {
            series: Series::DartSpecShare,
            target: 0.01,
        },
    },
    Target {
        label: "MuJoCo backend / MuJoCo from Python",
        goal: Goal::RatioAtLeast {
            num: Series::Mujoco,
            den: Series::MujocoPy,
            target: 1.3,
        },
    },
    Target {
        label: "MuJoCo backend / MuJoCo from Python (stretch)",
        goal: Goal::RatioAtLeast {
            num: Series::Mujoco,
            den: Series::MujocoPy,
            target: 1.5,
        },
    },
    Target {
        label: "spec evaluation share, MuJoCo",
        goal: Goal::AtMost {
            series: Series::MujocoSpecShare,
            target: 0.01,
        },
    },
];

/// One evaluated target: its values (ratios or the series), their summary and the verdict.
#[derive(Clone, Debug, PartialEq)]
pub struct Verdict {
    /// Median, min and max of the compared values (`None`: not measured).
    pub summary: Option<(f64, f64, f64)>,
    /// Whether the median meets the bound.
    pub met: Option<bool>,
    /// "met", "not met: …" or "not measured".
    pub text: String,
}

/// Evaluates `goal` on the repetitions (the verdict is taken on the median).
pub fn evaluate(reps: &[Rep], goal: Goal) -> Verdict {
    let values = match goal {
        Goal::RatioAtLeast { num, den, .. } => ratios(reps, num, den),
        Goal::AtMost { series, .. } => samples(reps, series),
    };
    let Some(s) = summary(&values) else {
        return Verdict {
            summary: None,
            met: None,
            text: "not measured".into(),
        };
    };
    let median = s.0;
    let (met, text) = match goal {
        Goal::RatioAtLeast { target, .. } => {
            if median >= target {
                (true, "met".to_string())
            } else {
                (
                    false,
                    format!(
                        "not met: {:.0} % of the target, {:.2}× short",
                        100.0 * median / target,
                        target / median
                    ),
                )
            }
        }
        Goal::AtMost { target, .. } => {
            if median <= target {
                (true, "met".to_string())
            } else {
                (
                    false,
                    format!(
                        "not met: {:.2} % against {:.2} %",
                        100.0 * median,
                        100.0 * target
                    ),
                )
            }
        }
    };
    Verdict {
        summary: Some(s),
        met: Some(met),
        text,
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

fn fmt_value(series: Series, x: f64) -> String {
    if series.is_share() {
        format!("{:.2} %", 100.0 * x)
    } else {
        format!("{x:.0}")
    }
}

/// Where and when the run happened.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Host {
    /// The exact command.
    pub command: String,
    /// UTC date and time.
    pub date: String,
    /// `model name` from /proc/cpuinfo.
    pub cpu: String,
    /// Online CPUs.
    pub cores: String,
    /// Load averages (1, 5, 15 min) at the start and at the end.
    pub load_start: String,
    /// The same at the end.
    pub load_end: String,
    /// The anchors' Python and package versions.
    pub anchors: String,
    /// The git commit (and `-dirty` with uncommitted changes).
    pub commit: String,
    /// `rustc --version`.
    pub rustc: String,
    /// Notes (skipped parts and why).
    pub notes: Vec<String>,
}

/// The Markdown report.
pub fn markdown(host: &Host, reps: &[Rep]) -> String {
    let mut s = String::new();
    // Writing to a String cannot fail.
    let _ = writeln!(s, "Command: `{}`  ", host.command);
    let _ = writeln!(s, "Date: {}  ", host.date);
    let _ = writeln!(s, "CPU: {} ({} cores online)  ", host.cpu, host.cores);
    let _ = writeln!(
        s,
        "Load average (1/5/15 min): {} at the start, {} at the end  ",
        host.load_start, host.load_end
    );
    let _ = writeln!(
        s,
        "Build: release (thin LTO), commit {}, {}  ",
        host.commit, host.rustc
    );
    if !host.anchors.is_empty() {
        let _ = writeln!(s, "Anchors: {}  ", host.anchors);
    }
    let _ = writeln!(
        s,
        "Repetitions: {}, each running every row below once, in turn\n",
        reps.len()
    );
    let _ = writeln!(s, "| figure | unit | median | min | max | runs |");
    let _ = writeln!(s, "|---|---|---:|---:|---:|---:|");
    for series in Series::ALL {
        let (label, unit) = series.label();
        let v = samples(reps, series);
        match summary(&v) {
            Some((med, lo, hi)) => {
                let _ = writeln!(
                    s,
                    "| {label} | {unit} | {} | {} | {} | {} |",
                    fmt_value(series, med),
                    fmt_value(series, lo),
                    fmt_value(series, hi),
                    v.len()
                );
            }
            None => {
                let _ = writeln!(s, "| {label} | {unit} | not measured | | | 0 |");
            }
        }
    }
    let _ = writeln!(
        s,
        "\n| target | bound | median | min | max | verdict |\n|---|---|---:|---:|---:|---|"
    );
    for t in TARGETS {
        let v = evaluate(reps, t.goal);
        let (bound, series) = match t.goal {
            Goal::RatioAtLeast { target, num, .. } => (format!("≥ {target}×"), num),
            Goal::AtMost { target, series } => (format!("≤ {:.0} %", 100.0 * target), series),
        };
        let f = |x: f64| {
            if series.is_share() {
                fmt_value(series, x)
            } else {
                format!("{x:.2}×")
            }
        };
        match v.summary {
            Some((med, lo, hi)) => {
                let _ = writeln!(
                    s,
                    "| {} | {bound} | {} | {} | {} | {} |",
                    t.label,
                    f(med),
                    f(lo),
                    f(hi),
                    v.text
                );
            }
            None => {
                let _ = writeln!(s, "| {} | {bound} | | | | {} |", t.label, v.text);
            }
        }
    }
    let _ = writeln!(
        s,
        "\nRatios are taken within each repetition (same minutes, same load), then summarised. \
         Single-env rates are per CPU second of the process; the vector env's scaling is in \
         wall-clock time and needs both cores free to reach 2×."
    );
    for note in &host.notes {
        let _ = writeln!(s, "\nNote: {note}");
    }
    s
}

/// The last non-empty line of a program's error output (a Python traceback ends with the
/// error itself), for one-line messages.
fn last_line(text: &str) -> &str {
    text.lines()
        .map(str::trim)
        .rfind(|l| !l.is_empty())
        .unwrap_or("")
}

/// Runs `program args` in `dir` with `env`, returning its stdout; a failure is one line naming
/// the command and the last line of its error output.
fn run(
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

fn shell(line: &str) -> String {
    Command::new("sh")
        .args(["-c", line])
        .output()
        .ok()
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_default()
}

/// The Python that creates the anchors' venv: `$HYQ_PYTHON`, else `python3`.
fn system_python() -> String {
    std::env::var("HYQ_PYTHON").unwrap_or_else(|_| "python3".to_string())
}

/// Creates the anchors' virtual environment if needed and installs the pins that are missing
/// or at another version; returns its Python and notes on what could not be installed (only
/// dartpy may be missing: its rows are then left out).
fn setup_venv(venv: &Path, pins: &[(String, String)]) -> Result<(PathBuf, Vec<String>), String> {
    let python = venv_python(venv);
    if !python.exists() {
        let system = system_python();
        let check = format!(
            "import sys, venv, ensurepip; sys.exit(0 if sys.version_info >= {PYTHON_MIN:?} else 3)"
        );
        match Command::new(&system).args(["-c", &check]).status() {
            Err(e) => {
                return Err(format!(
                    "`{system}` cannot be run ({e}): the anchors need Python {}.{}+ with venv \
                     and pip ({PYTHON_INSTALL}; or set HYQ_PYTHON)",
                    PYTHON_MIN.0, PYTHON_MIN.1
                ));
            }
            Ok(s) if s.code() == Some(3) => {
                return Err(format!(
                    "`{system}` is older than Python {}.{}, which the pinned numpy needs; set \
                     HYQ_PYTHON to a newer interpreter",
                    PYTHON_MIN.0, PYTHON_MIN.1
                ));
            }
            Ok(s) if !s.success() => {
                return Err(format!(
                    "`{system}` lacks the venv or ensurepip module, which the anchors' virtual \
                     environment needs: {PYTHON_INSTALL}"
                ));
            }
            Ok(_) => {}
        }
        println!(
            "creating the anchors' virtual environment at {}",
            venv.display()
        );
        run(
            Path::new(&system),
            &strings(&["-m", "venv", &venv.to_string_lossy()]),
            Path::new("/"),
            &[],
        )
        .map_err(|e| format!("cannot create the anchors' virtual environment: {e}"))?;
    }
    if run(
        &python,
        &strings(&["-m", "pip", "--version"]),
        Path::new("/"),
        &[],
    )
    .is_err()
    {
        return Err(format!(
            "the anchors' virtual environment {} has no pip (remove it to have it created \
             again, or: {PYTHON_INSTALL})",
            venv.display()
        ));
    }
    let mut notes = Vec::new();
    for (package, version) in pins {
        let check = format!(
            "import importlib.metadata as m, sys; sys.exit(0 if m.version('{package}') == '{version}' else 1)"
        );
        if run(&python, &strings(&["-c", &check]), Path::new("/"), &[]).is_ok() {
            continue;
        }
        println!("installing {package}=={version} into {}", venv.display());
        let pin = format!("{package}=={version}");
        let env = [("PIP_DISABLE_PIP_VERSION_CHECK", "1")];
        if let Err(e) = run(
            &python,
            &strings(&["-m", "pip", "install", "-q", &pin]),
            Path::new("/"),
            &env,
        ) {
            if package == "dartpy" {
                notes.push(format!(
                    "dartpy {version} could not be installed, so DART from Python was not \
                     measured: {e}"
                ));
            } else {
                return Err(format!("pip could not install {pin}: {e}"));
            }
        }
    }
    Ok((python, notes))
}

/// Writes the anchors' models with the release `hyq` into `dir`: MJCF with position servos,
/// URDF with capsules as cylinders, and the facts.
fn write_models(hyq: &Path, root: &Path, dir: &Path) -> Result<(), String> {
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

impl Host {
    /// The machine, the load, the commit and the toolchain now, and the command being run.
    fn now() -> Self {
        let command = std::iter::once("cargo xtask bench-vs-anchors".to_string())
            .chain(std::env::args().skip(2))
            .collect::<Vec<_>>()
            .join(" ");
        Host {
            command,
            date: shell("date -u '+%Y-%m-%d %H:%M UTC'"),
            cpu: shell("grep -m1 'model name' /proc/cpuinfo | cut -d: -f2"),
            cores: shell("getconf _NPROCESSORS_ONLN"),
            load_start: shell("cut -d' ' -f1-3 /proc/loadavg"),
            commit: shell("git rev-parse --short HEAD; git diff --quiet HEAD || echo -dirty")
                .replace('\n', ""),
            rustc: shell("rustc --version"),
            ..Host::default()
        }
    }
}

/// The backends this machine can measure, and the features that build them in; why any other
/// was left out goes into `notes`.
fn measurable_backends(
    args: &BenchArgs,
    root: &Path,
    notes: &mut Vec<String>,
) -> (Vec<&'static str>, Vec<&'static str>) {
    let mut features = Vec::new();
    let mut backends = Vec::new();
    for measure in SEQUENCE {
        let Measure::Hyq(b) = measure else { continue };
        if !args.wants(b.name) {
            if b.name == "mujoco" {
                notes.push("--no-mujoco: the MuJoCo backend was not measured".into());
            }
            continue;
        }
        match backend_missing(b.name, root) {
            Some(why) => notes.push(why),
            None => {
                backends.push(b.name);
                features.extend(b.feature);
            }
        }
    }
    (backends, features)
}

/// Which of the anchors' Python modules import in their virtual environment (`python`); a
/// missing one is an error unless it is DART's, which is noted in `notes` instead.
fn anchor_modules(
    python: &Path,
    anchors: &Path,
    args: &BenchArgs,
    notes: &mut Vec<String>,
) -> Result<BTreeMap<&'static str, bool>, String> {
    let importable = |module: &str| {
        run(
            python,
            &strings(&["-c", &format!("import {module}")]),
            anchors,
            &[],
        )
        .is_ok()
    };
    let mut modules = BTreeMap::new();
    for measure in SEQUENCE {
        if let Measure::Anchor(a) = measure {
            let ok = *modules
                .entry(a.module)
                .or_insert_with(|| importable(a.module));
            if !ok && !a.dart {
                return Err(format!(
                    "`import {}` fails in the anchors' virtual environment {}",
                    a.module,
                    args.venv.display()
                ));
            }
        }
    }
    if !args.dart {
        notes.push("--no-dart: the DART backend and DART from Python were not measured".into());
    } else if modules.get("dartpy") == Some(&false) && !notes.iter().any(|n| n.contains("dartpy")) {
        notes.push(
            "dartpy does not import in the anchors' venv: DART from Python was not measured".into(),
        );
    }
    Ok(modules)
}

/// Writes the report and the raw measurements into `target/`.
fn write_reports(root: &Path, report: &str, raw: &str) -> Result<(), String> {
    let target = root.join("target");
    std::fs::create_dir_all(&target)
        .map_err(|e| format!("cannot create {}: {e}", target.display()))?;
    for (name, text) in [
        ("bench-vs-anchors.md", report),
        ("bench-vs-anchors.jsonl", raw),
    ] {
        let path = target.join(name);
        std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// The anchors' Python and the versions of the pinned packages `pins` installed for `python`.
fn python_versions(python: &Path, anchors: &Path, pins: &[(String, String)]) -> String {
    let versions = format!(
        "import sys, importlib.metadata as m\nout = ['Python ' + sys.version.split()[0]]\n\
         for p in {:?}:\n    try: out.append(p + ' ' + m.version(p))\n    \
         except m.PackageNotFoundError: pass\nprint(', '.join(out))",
        pins.iter().map(|(p, _)| p.as_str()).collect::<Vec<_>>()
    );
    run(python, &strings(&["-c", &versions]), anchors, &[])
        .map(|s| s.trim().to_string())
        .unwrap_or_default()
}

/// The anchors' environment: one thread for every numerical library; no bytecode written into
/// the repository.
const PYTHON_ENV: [(&str, &str); 5] = [
    ("OMP_NUM_THREADS", "1"),
    ("OPENBLAS_NUM_THREADS", "1"),
    ("MKL_NUM_THREADS", "1"),
    ("NUMEXPR_NUM_THREADS", "1"),
    ("PYTHONDONTWRITEBYTECODE", "1"),
];

/// The anchors' pinned packages (`requirements.txt` in `anchors`).
fn read_pins(anchors: &Path) -> Result<Vec<(String, String)>, String> {
    let requirements = anchors.join("requirements.txt");
    parse_requirements(
        &std::fs::read_to_string(&requirements)
            .map_err(|e| format!("cannot read {}: {e}", requirements.display()))?,
    )
}

/// `cargo xtask bench-vs-anchors`.
pub fn bench_vs_anchors(args: &[String]) -> Result<(), String> {
    let root = workspace_root();
    let args = parse(
        args,
        &root,
        std::env::var_os("HYQ_ANCHOR_VENV").map(PathBuf::from),
    )?;
    let mut host = Host::now();
    let anchors = root.join(ANCHORS_DIR);
    let pins = read_pins(&anchors)?;

    // Python first: a missing interpreter or pip fails before the long build.
    let (python, venv_notes) = setup_venv(&args.venv, &pins)?;
    host.notes.extend(venv_notes);

    let (backends, features) = measurable_backends(&args, &root, &mut host.notes);
    let mut build = strings(&["build", "--release", "--locked", "-p", "hyq-cli"]);
    if !features.is_empty() {
        build.extend(strings(&["--features", &features.join(",")]));
    }
    let status = run_cargo(&root, &build)?;
    if !status.success() {
        return Err(format!("the release build of hyq failed ({status})"));
    }
    let hyq = root.join("target").join("release").join("hyq");
    let models = root.join(MODELS_DIR);
    write_models(&hyq, &root, &models)?;

    let modules = anchor_modules(&python, &anchors, &args, &mut host.notes)?;
    host.anchors = python_versions(&python, &anchors, &pins);

    let mut raw = String::new();
    let mut reps: Vec<Rep> = Vec::new();
    let (steps, vec_steps, anchor_steps) = (
        args.steps.to_string(),
        args.vec_steps.to_string(),
        args.anchor_steps.to_string(),
    );
    let models_arg = models.to_string_lossy().into_owned();
    for rep in 1..=args.reps {
        println!("repetition {rep}/{}", args.reps);
        let mut r = Rep::new();
        let hyq_bench = |backend: &str, extra: &[&str], raw: &mut String| {
            let mut a = strings(&["bench", "--json", "--backend", backend]);
            a.extend(strings(extra));
            let out = run(&hyq, &a, &root, &[])?;
            raw.push_str(&out);
            parse_hyq(&out)
        };
        for measure in SEQUENCE {
            match measure {
                Measure::Hyq(b) => {
                    if !backends.contains(&b.name) {
                        continue;
                    }
                    let f = hyq_bench(b.name, &["--steps", &steps], &mut raw)?;
                    r.insert(b.rate, f.cpu);
                    if let Some(share) = f.spec_share {
                        r.insert(b.spec_share, share);
                    }
                }
                Measure::Anchor(a) => {
                    if (a.dart && !args.dart) || modules.get(a.module) != Some(&true) {
                        continue;
                    }
                    let mut argv = strings(&[
                        a.script,
                        "--models",
                        &models_arg,
                        "--env-steps",
                        &anchor_steps,
                        "--runs",
                        "1",
                    ]);
                    argv.extend(strings(a.args));
                    let out = run(&python, &argv, &anchors, &PYTHON_ENV)?;
                    raw.push_str(&out);
                    for f in a.figures {
                        r.insert(f.series, parse_anchor(&out, f.anchor, f.case, f.key)?);
                    }
                }
                Measure::VecEnv => {
                    for (threads, series, cpu) in [
                        ("1", Series::Vec1, Series::Vec1Cpu),
                        ("2", Series::Vec2, Series::Vec2Cpu),
                    ] {
                        let v = hyq_bench(
                            "rapier",
                            &[
                                "--num-envs",
                                "2",
                                "--threads",
                                threads,
                                "--steps",
                                &vec_steps,
                            ],
                            &mut raw,
                        )?;
                        r.insert(series, v.wall);
                        r.insert(cpu, v.cpu);
                    }
                }
            }
        }
        let line: Vec<String> = r
            .iter()
            .map(|(s, x)| format!("{s:?} {}", fmt_value(*s, *x)))
            .collect();
        println!("  {}", line.join(", "));
        reps.push(r);
    }
    host.load_end = shell("cut -d' ' -f1-3 /proc/loadavg");

    let report = markdown(&host, &reps);
    println!("\n{report}");
    write_reports(&root, &report, &raw)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_and_arguments_parse_and_bad_ones_are_named() {
        let root = Path::new("/nonexistent/repo");
        let d = parse(&[], root, None).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(d.reps, 5);
        assert_eq!(
            d.venv,
            PathBuf::from("/nonexistent/repo/target/anchor-venv")
        );
        assert!(d.dart && d.mujoco);
        let from_env = parse(&[], root, Some("/nonexistent/cache/venv".into()))
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(from_env.venv, PathBuf::from("/nonexistent/cache/venv"));
        let p = parse(
            &strings(&[
                "--reps",
                "3",
                "--steps",
                "100",
                "--vec-steps",
                "50",
                "--anchor-steps",
                "70",
                "--venv",
                "/nonexistent/venv",
                "--no-dart",
                "--no-mujoco",
            ]),
            root,
            Some("/nonexistent/overridden".into()),
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            (p.reps, p.steps, p.vec_steps, p.anchor_steps),
            (3, 100, 50, 70)
        );
        assert_eq!(
            (&p.venv, p.dart, p.mujoco),
            (&PathBuf::from("/nonexistent/venv"), false, false)
        );
        // Each switch turns off its backend alone.
        assert!(!p.wants("dart") && !p.wants("mujoco") && p.wants("rapier"));
        assert!(d.wants("dart") && d.wants("mujoco") && d.wants("rapier"));
        let no_mujoco =
            parse(&strings(&["--no-mujoco"]), root, None).unwrap_or_else(|e| panic!("{e}"));
        assert!(no_mujoco.wants("dart") && !no_mujoco.wants("mujoco"));
        // A relative --venv is taken from the workspace root; under target/ is allowed.
        let rel =
            parse(&strings(&["--venv", "target/v"]), root, None).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(rel.venv, PathBuf::from("/nonexistent/repo/target/v"));
        for (bad, named) in [
            (&["--reps", "0"][..], "--reps 0"),
            (&["--steps", "x"], "--steps x"),
            (&["--venv"], "--venv"),
            (&["--fast"], "--fast"),
            // The anchor harness is part of the repository now: no option points elsewhere.
            (&["--anchors", "/nonexistent/anchors"], "--anchors"),
            (
                &["--venv", "/nonexistent/repo/.venv"],
                "not among its files",
            ),
            (&["--venv", "bench/venv"], "not among its files"),
        ] {
            let err = parse(&strings(bad), root, None).err().unwrap_or_default();
            assert!(err.contains(named), "{bad:?}: {err}");
        }
    }

    #[test]
    fn the_pinned_requirements_are_read_and_bad_lines_named() {
        let pins = parse_requirements("# pins\nnumpy==2.4.6\n\nmujoco == 4.0.0  # MuJoCo\n")
            .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            pins,
            vec![
                ("numpy".to_string(), "2.4.6".to_string()),
                ("mujoco".to_string(), "4.0.0".to_string())
            ]
        );
        for bad in ["numpy>=2", "==1.0", "mujoco"] {
            let err = parse_requirements(bad).err().unwrap_or_default();
            assert!(err.contains("line 1") && err.contains(bad), "{err}");
        }
        // The repository's own file pins exactly what the report's labels name.
        let text =
            std::fs::read_to_string(workspace_root().join(ANCHORS_DIR).join("requirements.txt"))
                .unwrap_or_else(|e| panic!("{e}"));
        let pins = parse_requirements(&text).unwrap_or_else(|e| panic!("{e}"));
        let version = |name: &str| {
            pins.iter()
                .find(|(p, _)| p == name)
                .map(|(_, v)| v.as_str())
                .unwrap_or_default()
        };
        assert_eq!(version("mujoco"), "4.0.0");
        assert_eq!(version("dartpy"), "6.20.0");
        assert!(!version("numpy").is_empty());
        assert!(Series::MujocoPy.label().0.contains("MuJoCo 4.0"));
        assert!(Series::DartPyBullet.label().0.contains("dartpy 6.20"));
    }

    #[test]
    fn every_series_is_measured_by_the_sequence_and_every_script_exists() {
        let mut produced = Vec::new();
        for measure in SEQUENCE {
            match measure {
                Measure::Hyq(b) => produced.extend([b.rate, b.spec_share]),
                Measure::Anchor(a) => {
                    let script = workspace_root().join(ANCHORS_DIR).join(a.script);
                    assert!(script.is_file(), "{} is missing", script.display());
                    produced.extend(a.figures.iter().map(|f| f.series));
                }
                Measure::VecEnv => {
                    produced.extend([Series::Vec1, Series::Vec2, Series::Vec1Cpu, Series::Vec2Cpu])
                }
            }
        }
        for series in Series::ALL {
            assert_eq!(
                produced.iter().filter(|s| **s == series).count(),
                1,
                "{series:?} must come from exactly one measurement"
            );
        }
        assert_eq!(produced.len(), Series::ALL.len());
        let root = Path::new("/nonexistent/repo");
        assert_eq!(backend_missing("rapier", root), None);
        // Without MuJoCo in the (missing) workspace, its row is skipped with the setup command.
        if std::env::var_os("MUJOCO_DIR").is_none() {
            let why = backend_missing("mujoco", root).unwrap_or_default();
            assert!(why.contains("cargo xtask setup mujoco"), "{why}");
        }
    }

    #[test]
    fn failures_are_reported_by_their_last_line() {
        let traceback = "Traceback (most recent call last):\n  File \"x.py\", line 1\nSystemExit: no robot facts\n\n";
        assert_eq!(last_line(traceback), "SystemExit: no robot facts");
        assert_eq!(last_line(""), "");
    }

    #[test]
    fn summary_is_median_min_max() {
        assert_eq!(summary(&[]), None);
        assert_eq!(summary(&[3.0, 1.0, 2.0]), Some((2.0, 1.0, 3.0)));
        assert_eq!(summary(&[4.0, 1.0, 2.0, 10.0]), Some((3.0, 1.0, 10.0)));
    }

    #[test]
    fn hyq_bench_json_is_read_and_other_schemas_refused() {
        let single = r#"{"schema_version":1,"workload":"env_random","env_steps_per_s":1500.5,"env_steps_per_s_cpu":1600.0,"shares":{"physics":0.99,"actuator":0.002,"observation":0.0015,"spec":0.0005,"other":0.006}}"#;
        let f = parse_hyq(single).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((f.wall, f.cpu), (1500.5, 1600.0));
        let share = f.spec_share.unwrap_or(f64::NAN);
        assert!((share - 0.002).abs() < 1e-12, "{share}");
        let vec = "noise\n{\"schema_version\":1,\"workload\":\"env_random_vec\",\"env_steps_per_s\":3000,\"env_steps_per_s_cpu\":1700}\n";
        let v = parse_hyq(vec).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!((v.wall, v.cpu, v.spec_share), (3000.0, 1700.0, None));
        let err = parse_hyq(r#"{"schema_version":2}"#)
            .err()
            .unwrap_or_default();
        assert!(err.contains("schema_version 2"), "{err}");
        let err = parse_hyq(r#"{"schema_version":1,"env_steps_per_s":1}"#)
            .err()
            .unwrap_or_default();
        assert!(err.contains("env_steps_per_s_cpu"), "{err}");
        assert!(parse_hyq("no json").is_err());
    }

    #[test]
    fn anchor_lines_are_found_by_anchor_and_case() {
        let out = concat!(
            "{\"anchor\": \"mujoco\", \"case\": \"env_random\", \"env_steps_per_s_cpu\": 4500.5}\n",
            "warning: not json\n",
            "{\"anchor\": \"mujoco\", \"case\": \"c_loop\", \"env_steps_per_s_cpu\": 6000}\n",
            "{\"anchor\": \"dart-bullet-capsule\", \"case\": \"env_random\", \"step_only_env_steps_per_s_cpu\": 3100}\n",
        );
        let cpu = "env_steps_per_s_cpu";
        assert_eq!(parse_anchor(out, "mujoco", "env_random", cpu), Ok(4500.5));
        assert_eq!(parse_anchor(out, "mujoco", "c_loop", cpu), Ok(6000.0));
        assert_eq!(
            parse_anchor(
                out,
                "dart-bullet-capsule",
                "env_random",
                "step_only_env_steps_per_s_cpu"
            ),
            Ok(3100.0)
        );
        let err = parse_anchor(out, "dart-ode-capsule", "env_random", cpu)
            .err()
            .unwrap_or_default();
        assert!(err.contains("dart-ode-capsule"), "{err}");
        let err = parse_anchor(out, "dart-bullet-capsule", "env_random", cpu)
            .err()
            .unwrap_or_default();
        assert!(err.contains(cpu), "{err}");
    }

    fn rep(pairs: &[(Series, f64)]) -> Rep {
        pairs.iter().copied().collect()
    }

    #[test]
    fn ratios_pair_figures_within_a_repetition_and_verdicts_follow_the_median() {
        let reps = vec![
            rep(&[(Series::Rapier, 1000.0), (Series::MujocoPy, 4000.0)]),
            rep(&[(Series::Rapier, 3000.0), (Series::MujocoPy, 6000.0)]),
            // No anchor this time: no ratio from this repetition.
            rep(&[(Series::Rapier, 9000.0)]),
            rep(&[(Series::Rapier, 1200.0), (Series::MujocoPy, 4000.0)]),
        ];
        assert_eq!(
            ratios(&reps, Series::Rapier, Series::MujocoPy),
            vec![0.25, 0.5, 0.3]
        );
        let v = evaluate(&reps, TARGETS[0].goal);
        assert_eq!(v.summary, Some((0.3, 0.25, 0.5)));
        assert_eq!(v.met, Some(false));
        assert!(v.text.contains("30 % of the target"), "{}", v.text);
        let fast = vec![rep(&[(Series::Vec1, 1000.0), (Series::Vec2, 1950.0)])];
        let v = evaluate(&fast, TARGETS[4].goal);
        assert_eq!((v.met, v.text.as_str()), (Some(true), "met"));
        let shares = vec![
            rep(&[(Series::RapierSpecShare, 0.004)]),
            rep(&[(Series::RapierSpecShare, 0.02)]),
            rep(&[(Series::RapierSpecShare, 0.003)]),
        ];
        assert_eq!(evaluate(&shares, TARGETS[6].goal).met, Some(true));
        let none = evaluate(&shares, TARGETS[2].goal);
        assert_eq!((none.met, none.text.as_str()), (None, "not measured"));
        // The MuJoCo backend against MuJoCo from Python: 1.3× is the target, 1.5× the stretch.
        let target = |label: &str| {
            TARGETS
                .iter()
                .find(|t| t.label == label)
                .map(|t| t.goal)
                .unwrap_or_else(|| panic!("no target {label:?}"))
        };
        let mujoco = vec![rep(&[(Series::Mujoco, 1400.0), (Series::MujocoPy, 1000.0)])];
        let v = evaluate(&mujoco, target("MuJoCo backend / MuJoCo from Python"));
        assert_eq!((v.summary, v.met), (Some((1.4, 1.4, 1.4)), Some(true)));
        let v = evaluate(
            &mujoco,
            target("MuJoCo backend / MuJoCo from Python (stretch)"),
        );
        assert_eq!(v.met, Some(false), "{}", v.text);
    }

    #[test]
    fn the_report_has_every_row_and_target() {
        let reps = vec![rep(&[
            (Series::Rapier, 1500.0),
            (Series::MujocoPy, 5000.0),
            (Series::RapierSpecShare, 0.0021),
        ])];
        let host = Host {
            command: "cargo xtask bench-vs-anchors".into(),
            cpu: "AMD EPYC".into(),
            ..Host::default()
        };
        let md = markdown(&host, &reps);
        assert!(
            md.contains("Command: `cargo xtask bench-vs-anchors`"),
            "{md}"
        );
        assert!(md.contains("CPU: AMD EPYC"), "{md}");
        assert!(
            md.contains(
                "| hyq, rapier backend, one env | env steps/s, CPU | 1500 | 1500 | 1500 | 1 |"
            ),
            "{md}"
        );
        assert!(
            md.contains("| spec evaluation + observation, rapier | % of an env step | 0.21 % |"),
            "{md}"
        );
        assert!(md.contains("| rapier / MuJoCo from Python | ≥ 1× | 0.30× | 0.30× | 0.30× | not met: 30 % of the target, 3.33× short |"), "{md}");
        assert!(
            md.contains("| DART / DART from Python (Bullet) | ≥ 1.5× | | | | not measured |"),
            "{md}"
        );
        assert!(
            md.contains(
                "| spec evaluation share, rapier | ≤ 1 % | 0.21 % | 0.21 % | 0.21 % | met |"
            ),
            "{md}"
        );
        for series in Series::ALL {
            assert!(md.contains(series.label().0), "{:?} missing", series);
        }
    }
}
