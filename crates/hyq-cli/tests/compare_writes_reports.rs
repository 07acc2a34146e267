//! Invariant: `hyq compare` writes report.md, report.json and trunk_x_z.png into `--out` for the
//! two backends it was given, with the documented JSON keys; a self-comparison agrees exactly;
//! and `--strict` turns a divergence outside the ledger into exit status 1 with one error line,
//! after the reports are written (so the evidence is always on disk); with `[randomize]` on, the
//! report says whether both sides drew the same values.

#![allow(clippy::unwrap_used)]

mod common;

use std::path::Path;

use common::{hyq, hyq_ok, scratch, stderr};

fn fresh_dir(name: &str) -> std::path::PathBuf {
    let dir = scratch(name);
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

fn read_json(dir: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(dir.join("report.json")).unwrap()).unwrap()
}

#[test]
fn a_self_comparison_writes_three_files_and_agrees_exactly() {
    let dir = fresh_dir("compare_self");
    let out = hyq_ok(&[
        "compare",
        "--backends",
        "rapier,rapier",
        "--scenario",
        "trot",
        "--seconds",
        "0.5",
        "--one-step-states",
        "5",
        "--strict",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.contains("every metric within the ledger"), "{out}");

    let json = read_json(&dir);
    for key in [
        "scenario",
        "seed",
        "seconds",
        "script_fingerprint",
        "engines",
        "ledger",
        "sides",
        "trajectory",
        "one_step",
        "checks",
        "flagged",
        "series",
    ] {
        assert!(json.get(key).is_some(), "report.json has no {key}");
    }
    assert_eq!(json["scenario"], "trot");
    assert_eq!(json["flagged"], 0);
    assert_eq!(json["script_steps"], 50);
    assert_eq!(json["one_step"]["states"], 5);
    let sides = json["sides"].as_array().unwrap();
    assert_eq!(sides[0]["label"], "rapier");
    assert_eq!(sides[1]["label"], "rapier (B)");
    for side in sides {
        for key in [
            "end_reasons",
            "end_step",
            "sums",
            "standing_height_m",
            "final_position",
        ] {
            assert!(side.get(key).is_some(), "side has no {key}");
        }
        assert_eq!(side["end_reasons"][0], "timeout");
    }
    assert_eq!(json["trajectory"]["trunk_position"]["max"], 0.0);
    assert_eq!(json["trajectory"]["contacts"].as_array().unwrap().len(), 5);
    let checks = json["checks"].as_array().unwrap();
    assert_eq!(checks.len(), 17);
    assert!(
        checks
            .iter()
            .all(|c| c["within"] == true && c["value"] == 0.0)
    );

    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    for section in [
        "## Per backend",
        "## Divergence over time",
        "## One step from a shared state",
        "## Checks against the ledger",
        "trunk_x_z.png",
        "hyq compare --backends rapier,rapier",
    ] {
        assert!(md.contains(section), "report.md lacks {section:?}");
    }
    assert!(!md.contains("Randomised"), "off, not mentioned");
    assert!(json["sides"][0].get("randomize").is_none());
    let png = std::fs::read(dir.join("trunk_x_z.png")).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n");
    assert!(png.len() < 200_000, "plot is {} bytes", png.len());
}

#[test]
fn strict_fails_on_a_perturbed_backend_after_writing_the_reports() {
    let dir = fresh_dir("compare_strict");
    let args = [
        "compare",
        "--backends",
        "rapier,rapier",
        "--scenario",
        "stand",
        "--seconds",
        "0.5",
        "--one-step-states",
        "5",
        "--set-b",
        "physics.gravity=[0,0,-10.791]",
        "--out",
        dir.to_str().unwrap(),
    ];
    // Without --strict the divergence is reported, not an error.
    let out = hyq_ok(&args);
    assert!(
        out.contains("outside the ledger: one_step_trunk_linvel_max_m_s"),
        "{out}"
    );

    std::fs::remove_dir_all(&dir).unwrap();
    let mut strict = args.to_vec();
    strict.push("--strict");
    let out = hyq(&strict);
    assert_eq!(out.status.code(), Some(1), "{}", stderr(&out));
    let err = stderr(&out);
    assert_eq!(err.lines().count(), 1, "{err}");
    assert!(err.starts_with("hyq: error: --strict:"), "{err}");
    assert!(err.contains("one_step_trunk_linvel_max_m_s"), "{err}");
    assert!(err.contains("report.md"), "{err}");
    for file in ["report.md", "report.json", "trunk_x_z.png"] {
        assert!(dir.join(file).is_file(), "{file} not written");
    }
    let json = read_json(&dir);
    assert!(json["flagged"].as_u64().unwrap() > 0);
    assert_eq!(json["overrides_b"][0], "physics.gravity=[0,0,-10.791]");
}

#[test]
fn a_randomised_scenario_says_whether_both_sides_drew_alike() {
    let dir = fresh_dir("compare_randomized");
    let mut args = vec![
        "compare",
        "--backends",
        "rapier,rapier",
        "--scenario",
        "stand",
        "--seconds",
        "0.2",
        "--one-step-states",
        "2",
        "--set",
        "randomize.ground_friction=[0.5, 1.0]",
        "--set",
        "randomize.kp_scale=[0.9, 1.1]",
        "--out",
        dir.to_str().unwrap(),
    ];
    hyq_ok(&args);
    let json = read_json(&dir);
    let (a, b) = (
        &json["sides"][0]["randomize"],
        &json["sides"][1]["randomize"],
    );
    assert!(a["kp_scale"].is_array(), "{a}");
    assert_eq!(a, b);
    // Drawn alike, the same engine runs alike.
    assert_eq!(json["trajectory"]["trunk_position"]["max"], 0.0);
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(md.contains("both sides drew the same values"), "{md}");

    // Randomised on one side only, they differ, and the report says so.
    args.extend(["--set-b", "randomize.ground_friction=[0.3, 0.4]"]);
    hyq_ok(&args);
    let json = read_json(&dir);
    assert_ne!(json["sides"][0]["randomize"], json["sides"][1]["randomize"]);
    let md = std::fs::read_to_string(dir.join("report.md")).unwrap();
    assert!(
        md.contains("both sides did not draw the same values"),
        "{md}"
    );
}

/// With DART built in, the real comparison runs and stays within the ledger.
#[cfg(feature = "dart")]
#[test]
fn rapier_against_dart_within_the_ledger() {
    let dir = fresh_dir("compare_dart");
    let out = hyq_ok(&[
        "compare",
        "--backends",
        "rapier,dart",
        "--scenario",
        "limit",
        "--one-step-states",
        "5",
        "--strict",
        "--out",
        dir.to_str().unwrap(),
    ]);
    assert!(out.contains("rapier ended joint_limit"), "{out}");
    assert!(out.contains("dart ended joint_limit"), "{out}");
    let json = read_json(&dir);
    assert_eq!(json["engines"][1], "dart");
}
