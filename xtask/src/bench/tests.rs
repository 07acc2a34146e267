//! The command's tests: arguments, the plan, statistics, parsing and the report.

use std::path::{Path, PathBuf};

use super::ANCHORS_DIR;
use super::args::*;
use super::command::last_line;
use super::plan::*;
use super::report::*;
use super::run::*;
use super::stats::*;
use super::venv::*;
use crate::cli::strings;
use crate::workspace::workspace_root;

#[test]
fn defaults_and_arguments_parse_and_bad_ones_are_named() {
    let root = Path::new("/nonexistent/repo");
    let d = parse(&[], root, None).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(d.reps, 5);
    let target = crate::workspace::target_dir(root);
    assert_eq!(d.venv, target.join("anchor-venv"));
    assert!(d.dart && d.mujoco);
    let from_env =
        parse(&[], root, Some("/nonexistent/cache/venv".into())).unwrap_or_else(|e| panic!("{e}"));
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
    let no_mujoco = parse(&strings(&["--no-mujoco"]), root, None).unwrap_or_else(|e| panic!("{e}"));
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
    let text = std::fs::read_to_string(workspace_root().join(ANCHORS_DIR).join("requirements.txt"))
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
    // Without MuJoCo in the (missing) workspace, its row is skipped with the setup command
    // (unless MuJoCo is found outside the workspace: `$MUJOCO_DIR`, or `$CARGO_TARGET_DIR`'s).
    if std::env::var_os("MUJOCO_DIR").is_none() && std::env::var_os("CARGO_TARGET_DIR").is_none() {
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
        md.contains("| hyq, rapier backend, one env | env steps/s, CPU | 1500 | 1500 | 1500 | 1 |"),
        "{md}"
    );
    assert!(
        md.contains("| spec evaluation + observation, rapier | % of an env step | 0.21 % |"),
        "{md}"
    );
    assert!(md.contains("| rapier / MuJoCo from Python | ≥ 1× | 0.30× | 0.30× | 0.30× | not met: 30 % of the target, 3.33× short |"), "{md}");
    assert!(
        md.contains("| DART / DART from Python (Bullet) | ≥ 2× | | | | not measured |"),
        "{md}"
    );
    assert!(
        md.contains("| spec evaluation share, rapier | ≤ 1 % | 0.21 % | 0.21 % | 0.21 % | met |"),
        "{md}"
    );
    for series in Series::ALL {
        assert!(md.contains(series.label().0), "{:?} missing", series);
    }
}
