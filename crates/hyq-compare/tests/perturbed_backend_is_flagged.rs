//! Invariant: the comparator catches a wrong engine. rapier against a rapier whose gravity is
//! 10 % too strong (−10.791 m/s²) must be flagged, both against the strict defaults (any engine
//! pair without known divergences) and against the shipped rapier-vs-DART tolerances: the ledger's
//! known divergences are not so loose that a 10 % gravity error hides inside them.

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
