//! What one repetition measures, in order ([`SEQUENCE`]), the figures it gives ([`Series`]),
//! and which of them this machine can measure.

use std::collections::BTreeMap;
use std::path::Path;

use super::args::BenchArgs;
use super::command::run;
use crate::cli::strings;

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
    pub(super) fn is_share(self) -> bool {
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

/// The backends this machine can measure, and the features that build them in; why any other
/// was left out goes into `notes`.
pub(super) fn measurable_backends(
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
pub(super) fn anchor_modules(
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
