//! Invariant: the comparator catches a wrong engine. rapier against a rapier whose gravity is
//! 10 % too strong (−10.791 m/s²) must be flagged, both against the strict defaults (any engine
//! pair without known divergences) and against the shipped rapier-vs-DART tolerances: the ledger's
//! known divergences are not so loose that a 10 % gravity error hides inside them. On terrain
//! the entries measured on that ground judge it, not the flat ground's.

#![allow(clippy::unwrap_used)]

mod common;

use common::PERTURBED_GRAVITY;
use hyq_compare::{Ledger, Scenario};
use hyq_rapier::RapierBackend;

#[test]
fn ten_percent_more_gravity_is_flagged_by_the_strict_defaults() {
    let ledger = Ledger::built_in().unwrap();
    let spec = common::spec(
        Scenario::Stand,
        1.0,
        10,
        &[("physics.gravity", PERTURBED_GRAVITY)],
    );
    let r = common::run::<RapierBackend, RapierBackend>(&spec, "rapier (g +10 %)", &ledger);
    let flagged = common::flagged(&r);
    // One sub-step of 0.981 m/s² more gravity changes the trunk velocity by ~1e-3 m/s, ten
    // times the default tolerance; the heavier robot also stands about 1 mm lower.
    for metric in [
        "one_step_trunk_linvel_max_m_s",
        "one_step_qd_max_rad_s",
        "standing_height_diff_m",
    ] {
        assert!(
            flagged.contains(&metric),
            "{metric} not flagged: {flagged:?}"
        );
    }
    let [a, b] = &r.sides;
    let sag = a.standing_height_m - b.standing_height_m;
    assert!(
        sag > 5e-4 && sag < 3e-3,
        "heavier robot stands lower by {sag} m"
    );
    assert_eq!(
        b.overrides,
        vec![format!("physics.gravity={PERTURBED_GRAVITY}")]
    );
}

#[test]
fn ten_percent_more_gravity_is_flagged_even_by_the_rapier_dart_tolerances() {
    // The shipped ledger with its rapier-vs-DART entries relabelled as rapier-vs-rapier: the
    // same tolerances, now applying to this pair.
    let text = hyq_compare::ledger::BUILT_IN.replace(
        r#"backends = ["rapier", "dart"]"#,
        r#"backends = ["rapier", "rapier"]"#,
    );
    let ledger = Ledger::parse(&text, "relabelled").unwrap();
    assert!(ledger.known.len() > 20);
    let spec = common::spec(
        Scenario::Stand,
        1.0,
        5,
        &[("physics.gravity", PERTURBED_GRAVITY)],
    );
    let r = common::run::<RapierBackend, RapierBackend>(&spec, "rapier (g +10 %)", &ledger);
    let flagged = common::flagged(&r);
    // rapier and DART stand 0.15 mm apart (tolerance 0.5 mm); 10 % more gravity sinks rapier
    // by about 1 mm.
    assert!(flagged.contains(&"standing_height_diff_m"), "{flagged:?}");
}

#[test]
fn a_comparison_on_rough_ground_is_judged_by_the_rough_grounds_entries() {
    // The shipped ledger's defaults, with one metric given a strict flat-ground entry and a wide
    // rough-ground entry for this pair: on rough ground the second must judge it.
    let defaults = hyq_compare::ledger::BUILT_IN
        .split("[[known]]")
        .next()
        .unwrap();
    let entry = |terrain: &str, tolerance: f64| {
        format!(
            "\n[[known]]\nrobot = \"hyq\"\nbackends = [\"rapier\", \"rapier\"]\nscenario = \
             \"stand\"\nmetric = \"standing_height_diff_m\"\nterrain = \"{terrain}\"\ntolerance \
             = {tolerance}\nreason = \"measured on {terrain} ground\"\n"
        )
    };
    let text = format!("{defaults}{}{}", entry("flat", 0.0), entry("rough", 0.01));
    let ledger = Ledger::parse(&text, "per-ground").unwrap();
    let mut spec = common::spec(
        Scenario::Stand,
        0.2,
        2,
        &[("physics.gravity", PERTURBED_GRAVITY)],
    );
    spec.overrides = vec![("terrain.kind".into(), "\"rough\"".into())];
    let r = common::run::<RapierBackend, RapierBackend>(&spec, "rapier (g +10 %)", &ledger);
    let check = r
        .checks
        .iter()
        .find(|c| c.metric.name() == "standing_height_diff_m")
        .unwrap();
    // 10 % more gravity sinks the robot by about 1 mm: beyond the flat entry, within the
    // rough one, which is the one read.
    assert!(check.value > 5e-4, "{check:?}");
    assert_eq!(check.tolerance, 0.01, "{check:?}");
    assert!(check.within, "{check:?}");
    match &check.source {
        hyq_compare::ToleranceSource::Known { reason, .. } => {
            assert_eq!(reason, "measured on rough ground");
        }
        other => panic!("the tolerance came from {other:?}"),
    }
}
