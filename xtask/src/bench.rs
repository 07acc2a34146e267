//! `cargo xtask bench-vs-anchors`: the project's benchmark and the anchor harness's, run side
//! by side in one run, with the ratios the speed targets are stated in.
//!
//! What it does, in order:
//! 1. builds `hyq` in release mode, with the DART backend when DART is installed and the MuJoCo
//!    backend when MuJoCo is set up (`cargo xtask setup mujoco`);
//! 2. sets up (or reuses) the anchors' Python virtual environment outside the repository, with
//!    the versions the anchor harness pins (`run_anchors.sh`): numpy, mujoco, dartpy;
//! 3. repeats `--reps` times, in this order so that every repetition sees the same machine
//!    load: `hyq bench` on rapier; MuJoCo from Python (`bench_mujoco.py`, cases `env_random` and
//!    its C loop `phys_c_random`); `hyq bench` on MuJoCo; `hyq bench` on DART; DART from Python (`bench_dart.py`,
//!    Bullet and ODE detectors, capsule legs); the rapier vector env of 2 envs on 1 thread,
//!    then on 2 threads;
//! 4. prints, and writes to `target/bench-vs-anchors.md`, a Markdown report: the CPU model, the
//!    load, the median, min and max of every figure, and each ratio against its target (the
//!    median of the per-repetition ratios, each taken within one repetition, and their min and
//!    max). The raw JSON lines go to `target/bench-vs-anchors.jsonl`.
//!
//! Single-env rates are CPU-time rates (env steps per CPU second of the process), the better
//! estimate of an idle core on a shared machine; the anchors report both kinds and the same
//! kind is compared. The vector env's scaling is a wall-clock ratio (that is what parallelism
//! buys), so it is only meaningful when two cores are free: the load average is printed with it.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use crate::cli::{positive, strings, value};
use crate::mujoco;
use crate::stages::{DART_BULLET_HEADER, run_cargo, venv_python, workspace_root};

/// The anchor harness's pinned versions (`run_anchors.sh`).
const PINS: [(&str, &str); 3] = [
    ("numpy", "2.4.6"),
    ("mujoco", "4.0.0"),
    ("dartpy", "6.20.0"),
];

/// Physics sub-steps per env step in the anchors (and in the project's default configuration).
const SUBSTEPS: f64 = 10.0;

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
    /// The anchor harness's directory (default `../shared/bench/anchors` beside the repository).
    pub anchors: PathBuf,
    /// The anchors' virtual environment (default `$ANCHOR_VENV` or `/tmp/anchor-venv`).
    pub venv: PathBuf,
    /// Measure the DART backend (when DART is installed).
    pub dart: bool,
    /// Measure the MuJoCo backend (when MuJoCo is set up).
    pub mujoco: bool,
}

/// Parses the command's arguments; `root` is the workspace root (for the defaults and for
/// refusing a virtual environment inside the repository).
pub fn parse(args: &[String], root: &Path) -> Result<BenchArgs, String> {
    const COMMAND: &str = "bench-vs-anchors";
    let mut out = BenchArgs {
        reps: 5,
        steps: 3000,
        vec_steps: 1500,
        anchor_steps: 3000,
        anchors: root
            .parent()
            .unwrap_or(root)
            .join("shared")
            .join("bench")
            .join("anchors"),
        venv: std::env::var_os("ANCHOR_VENV")
            .map_or_else(|| PathBuf::from("/tmp/anchor-venv"), PathBuf::from),
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
            "--anchors" => out.anchors = PathBuf::from(value(&mut it, COMMAND, arg)?),
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
    if out.venv.starts_with(root) {
        return Err(format!(
            "--venv {}: the anchors' virtual environment must be outside the repository ({})",
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
    /// MuJoCo's C loop, `phys_c_random`: env steps per CPU second.
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
    /// dartpy with the ODE detector, capsule legs (the harness's default DART row).
    DartPyOde,
    /// dartpy with Bullet: the time inside `world.step()` alone, as env steps (10 sub-steps):
    /// the ceiling of any binding of that DART build, which can only remove the rest.
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
            Series::MujocoC => ("MuJoCo 4.0, C loop (`phys_c_random`)", "env steps/s, CPU"),
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
                "DART 6.20 `world.step()` alone, timed from Python (Bullet), ÷ 10 sub-steps",
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

/// The figures of one repetition (a series is absent when its run was skipped or failed).
pub type Rep = BTreeMap<Series, f64>;

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

/// The median CPU-time rate of the anchor line with `sim` and `case` in an anchor script's
/// output (one JSON object a line; other lines are ignored).
pub fn parse_anchor(stdout: &str, sim: &str, case: &str) -> Result<f64, String> {
    parse_anchor_key(stdout, sim, case, &["cpu", "median"])
}

/// The number at `key` (a path of object keys) in the anchor line with `sim` and `case`.
pub fn parse_anchor_key(stdout: &str, sim: &str, case: &str, key: &[&str]) -> Result<f64, String> {
    for line in stdout.lines().filter(|l| l.trim_start().starts_with('{')) {
        let Ok(v) = serde_json::from_str::<Value>(line) else {
            continue;
        };
        if v.get("sim").and_then(Value::as_str) == Some(sim)
            && v.get("case").and_then(Value::as_str) == Some(case)
        {
            return number(&v, key);
        }
    }
    Err(format!(
        "no result for sim {sim:?}, case {case:?} in: {stdout}"
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

/// Runs `program args` in `dir` with `env`, returning its stdout; a failure names the command.
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
            String::from_utf8_lossy(&out.stderr).trim()
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

/// Creates the anchors' virtual environment if needed and installs the pinned versions that
/// are missing; returns its Python and the notes on what could not be installed.
fn setup_venv(venv: &Path) -> Result<(PathBuf, Vec<String>), String> {
    let python = venv_python(venv);
    if !python.exists() {
        println!(
            "creating the anchors' virtual environment at {}",
            venv.display()
        );
        run(
            Path::new("python3"),
            &strings(&["-m", "venv", &venv.to_string_lossy()]),
            Path::new("/"),
            &[],
        )?;
    }
    let mut notes = Vec::new();
    for (package, version) in PINS {
        let check = format!(
            "import importlib.metadata as m, sys; sys.exit(0 if m.version('{package}') == '{version}' else 1)"
        );
        if run(&python, &strings(&["-c", &check]), Path::new("/"), &[]).is_ok() {
            continue;
        }
        println!("installing {package}=={version} into {}", venv.display());
        let pin = format!("{package}=={version}");
        if let Err(e) = run(
            &python,
            &strings(&["-m", "pip", "install", "-q", &pin]),
            Path::new("/"),
            &[],
        ) {
            if package == "dartpy" {
                notes.push(format!("dartpy {version} could not be installed, so DART from Python was not measured: {e}"));
            } else {
                return Err(e);
            }
        }
    }
    Ok((python, notes))
}

/// `cargo xtask bench-vs-anchors`.
pub fn bench_vs_anchors(args: &[String]) -> Result<(), String> {
    let root = workspace_root();
    let args = parse(args, &root)?;
    let command = std::iter::once("cargo xtask bench-vs-anchors".to_string())
        .chain(std::env::args().skip(2))
        .collect::<Vec<_>>()
        .join(" ");
    let mut host = Host {
        command,
        date: shell("date -u '+%Y-%m-%d %H:%M UTC'"),
        cpu: shell("grep -m1 'model name' /proc/cpuinfo | cut -d: -f2"),
        cores: shell("getconf _NPROCESSORS_ONLN"),
        load_start: shell("cut -d' ' -f1-3 /proc/loadavg"),
        commit: shell("git rev-parse --short HEAD; git diff --quiet HEAD || echo -dirty")
            .replace('\n', ""),
        rustc: shell("rustc --version"),
        ..Host::default()
    };
    if !args.anchors.join("bench_mujoco.py").exists() {
        return Err(format!(
            "no anchor harness at {} (bench_mujoco.py); pass --anchors DIR",
            args.anchors.display()
        ));
    }
    let dart = args.dart && Path::new(DART_BULLET_HEADER).exists();
    if args.dart && !dart {
        host.notes.push(format!(
            "DART is not installed ({DART_BULLET_HEADER} missing), so the DART backend was not measured"
        ));
    }

    let mujoco = args.mujoco && mujoco::check(&mujoco::mujoco_dir(&root)).is_ok();
    if args.mujoco && !mujoco {
        host.notes.push(format!(
            "MuJoCo is not set up (`{}`), so the MuJoCo backend was not measured",
            mujoco::SETUP_COMMAND
        ));
    }

    let mut build = strings(&["build", "--release", "--locked", "-p", "hyq-cli"]);
    let features: Vec<&str> = [(dart, "dart"), (mujoco, "mujoco")]
        .iter()
        .filter(|(on, _)| *on)
        .map(|(_, f)| *f)
        .collect();
    if !features.is_empty() {
        build.extend(strings(&["--features", &features.join(",")]));
    }
    let status = run_cargo(&root, &build)?;
    if !status.success() {
        return Err(format!("the release build of hyq failed ({status})"));
    }
    let hyq = root.join("target").join("release").join("hyq");

    let (python, venv_notes) = setup_venv(&args.venv)?;
    host.notes.extend(venv_notes);
    let dartpy = run(
        &python,
        &strings(&["-c", "import dartpy"]),
        &args.anchors,
        &[],
    )
    .is_ok();
    let single = [
        ("OMP_NUM_THREADS", "1"),
        ("OPENBLAS_NUM_THREADS", "1"),
        ("MKL_NUM_THREADS", "1"),
        ("NUMEXPR_NUM_THREADS", "1"),
    ];

    let mut raw = String::new();
    let mut reps: Vec<Rep> = Vec::new();
    let (steps, vec_steps, anchor_steps) = (
        args.steps.to_string(),
        args.vec_steps.to_string(),
        args.anchor_steps.to_string(),
    );
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
        let rapier = hyq_bench("rapier", &["--steps", &steps], &mut raw)?;
        r.insert(Series::Rapier, rapier.cpu);
        if let Some(share) = rapier.spec_share {
            r.insert(Series::RapierSpecShare, share);
        }
        let a = strings(&[
            "bench_mujoco.py",
            "--runs",
            "1",
            "--cases",
            "env_random,phys_c_random",
            "--env-steps",
            &anchor_steps,
        ]);
        let out = run(&python, &a, &args.anchors, &single)?;
        raw.push_str(&out);
        r.insert(
            Series::MujocoPy,
            parse_anchor(&out, "mujoco", "env_random")?,
        );
        r.insert(
            Series::MujocoC,
            parse_anchor(&out, "mujoco", "phys_c_random")?,
        );
        if mujoco {
            let m = hyq_bench("mujoco", &["--steps", &steps], &mut raw)?;
            r.insert(Series::Mujoco, m.cpu);
            if let Some(share) = m.spec_share {
                r.insert(Series::MujocoSpecShare, share);
            }
        }
        if dart {
            let d = hyq_bench("dart", &["--steps", &steps], &mut raw)?;
            r.insert(Series::Dart, d.cpu);
            if let Some(share) = d.spec_share {
                r.insert(Series::DartSpecShare, share);
            }
        }
        if dartpy {
            for (detector, series) in [("bullet", Series::DartPyBullet), ("ode", Series::DartPyOde)]
            {
                let a = strings(&[
                    "bench_dart.py",
                    "--runs",
                    "1",
                    "--cases",
                    "env_random",
                    "--detector",
                    detector,
                    "--shape",
                    "capsule",
                    "--env-steps",
                    &anchor_steps,
                ]);
                let out = run(&python, &a, &args.anchors, &single)?;
                raw.push_str(&out);
                let sim = format!("dart-{detector}-capsule");
                r.insert(series, parse_anchor(&out, &sim, "env_random")?);
                if series == Series::DartPyBullet {
                    let key = ["world_step_only_physics_steps_per_s_cpu_median"];
                    let physics = parse_anchor_key(&out, &sim, "env_random", &key)?;
                    r.insert(Series::DartPyStepOnly, physics / SUBSTEPS);
                }
            }
        }
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
        let line: Vec<String> = r
            .iter()
            .map(|(s, x)| format!("{s:?} {}", fmt_value(*s, *x)))
            .collect();
        println!("  {}", line.join(", "));
        reps.push(r);
    }
    host.load_end = shell("cut -d' ' -f1-3 /proc/loadavg");
    if !dartpy {
        host.notes.push(
            "dartpy does not import in the anchors' venv: DART from Python was not measured".into(),
        );
    }

    let report = markdown(&host, &reps);
    println!("\n{report}");
    let target = root.join("target");
    std::fs::create_dir_all(&target)
        .map_err(|e| format!("cannot create {}: {e}", target.display()))?;
    for (name, text) in [
        ("bench-vs-anchors.md", &report),
        ("bench-vs-anchors.jsonl", &raw),
    ] {
        let path = target.join(name);
        std::fs::write(&path, text).map_err(|e| format!("cannot write {}: {e}", path.display()))?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn defaults_and_arguments_parse_and_bad_ones_are_named() {
        let root = Path::new("/nonexistent/repo");
        let d = parse(&[], root).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(d.reps, 5);
        assert_eq!(
            d.anchors,
            PathBuf::from("/nonexistent/shared/bench/anchors")
        );
        assert!(d.dart && d.mujoco);
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
                "--anchors",
                "/nonexistent/anchors",
                "--no-dart",
                "--no-mujoco",
            ]),
            root,
        )
        .unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(
            (p.reps, p.steps, p.vec_steps, p.anchor_steps),
            (3, 100, 50, 70)
        );
        assert_eq!(
            (p.venv, p.anchors, p.dart, p.mujoco),
            (
                "/nonexistent/venv".into(),
                "/nonexistent/anchors".into(),
                false,
                false
            )
        );
        for (bad, named) in [
            (&["--reps", "0"][..], "--reps 0"),
            (&["--steps", "x"], "--steps x"),
            (&["--venv"], "--venv"),
            (&["--fast"], "--fast"),
            (
                &["--venv", "/nonexistent/repo/.venv"],
                "outside the repository",
            ),
        ] {
            let err = parse(&strings(bad), root).err().unwrap_or_default();
            assert!(err.contains(named), "{bad:?}: {err}");
        }
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
    fn anchor_lines_are_found_by_sim_and_case() {
        let out = concat!(
            "{\"sim\": \"mujoco\", \"case\": \"env_random\", \"cpu\": {\"min\": 1, \"median\": 4500.5, \"max\": 9}}\n",
            "warning: not json\n",
            "{\"sim\": \"mujoco\", \"case\": \"phys_c_random\", \"cpu\": {\"median\": 6000}}\n",
        );
        assert_eq!(parse_anchor(out, "mujoco", "env_random"), Ok(4500.5));
        assert_eq!(parse_anchor(out, "mujoco", "phys_c_random"), Ok(6000.0));
        assert_eq!(
            parse_anchor_key(out, "mujoco", "env_random", &["cpu", "min"]),
            Ok(1.0)
        );
        let err = parse_anchor(out, "dart-bullet-capsule", "env_random")
            .err()
            .unwrap_or_default();
        assert!(err.contains("dart-bullet-capsule"), "{err}");
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
