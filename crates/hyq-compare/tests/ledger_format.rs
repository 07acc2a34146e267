//! Invariant: the ledger is checked when it is read. The shipped ledger parses, gives every
//! metric a default, and every known divergence has a reason; a malformed ledger is an error that
//! names the entry and the offending key or value; the most specific entry wins, an engine
//! pair matches in either order, and an entry holds only for the robot and the ground it names.

#![allow(clippy::unwrap_used)]

use hyq_compare::{Ledger, Metric, Scenario, ToleranceSource};

const DEFAULTS: &str = "[default]
termination_reason_mismatch = 0
termination_step_diff = 0
trunk_position_rms_m = 1e-3
trunk_position_max_m = 1e-3
trunk_orientation_rms_rad = 1e-3
trunk_orientation_max_rad = 1e-3
joint_angle_rms_rad = 1e-3
joint_angle_max_rad = 1e-3
contact_disagreement_max_pct = 0
return_diff = 1e-3
standing_height_diff_m = 1e-4
one_step_q_max_rad = 1e-6
one_step_qd_max_rad_s = 1e-4
one_step_trunk_position_max_m = 1e-6
one_step_trunk_orientation_max_rad = 1e-6
one_step_trunk_linvel_max_m_s = 1e-4
one_step_trunk_angvel_max_rad_s = 1e-4
";

fn known(scenario: &str, metric: &str, tolerance: &str, reason: &str) -> String {
    format!(
        "\n[[known]]\nrobot = \"hyq\"\nbackends = [\"rapier\", \"dart\"]\nscenario = \"{scenario}\"\nmetric = \"{metric}\"\ntolerance = {tolerance}\nreason = \"{reason}\"\n"
    )
}

fn error(text: &str) -> String {
    Ledger::parse(text, "test.toml").unwrap_err().to_string()
}

#[test]
fn the_shipped_ledger_is_complete_and_every_entry_has_a_reason() {
    let ledger = Ledger::built_in().unwrap();
    assert_eq!(ledger.default.len(), Metric::ALL.len());
    assert!(ledger.known.len() >= 60, "{} entries", ledger.known.len());
    for k in &ledger.known {
        assert!(k.reason.len() > 40, "{:?}: reason too short", k);
        assert!(k.reason.contains("measured"), "{:?}: no measured value", k);
        assert!(
            k.tolerance > ledger.default[&k.metric],
            "{k:?} does not widen the default"
        );
    }
    // Every scenario has its one-step tolerances for rapier vs DART.
    for s in Scenario::ALL {
        let (_, source) = ledger.tolerance("hyq", ["rapier", "dart"], s, Metric::OneStepQd);
        assert!(matches!(source, ToleranceSource::Known { .. }), "{s}");
    }
    // Every ground but flat has its measured entries for every pair in every scenario: the
    // one-step velocities differ on every ground (contacts at every state sampled).
    for terrain in ["rough", "slope", "stairs", "heightfield"] {
        for pair in [["rapier", "dart"], ["rapier", "mujoco"], ["dart", "mujoco"]] {
            for s in Scenario::ALL {
                let (tolerance, source) =
                    ledger.tolerance_on("hyq", pair, s, terrain, Metric::OneStepQd);
                assert!(
                    matches!(source, ToleranceSource::Known { .. })
                        && tolerance > ledger.default[&Metric::OneStepQd],
                    "{terrain} {pair:?} {s}: {source:?}"
                );
            }
        }
    }
}

#[test]
fn lookup_prefers_the_scenario_entry_and_ignores_pair_order() {
    let text = format!(
        "{DEFAULTS}{}{}",
        known("all", "return_diff", "0.5", "a reason for all scenarios"),
        known("trot", "return_diff", "0.7", "a reason for the trot")
    );
    let ledger = Ledger::parse(&text, "test.toml").unwrap();
    let (t, source) = ledger.tolerance(
        "hyq",
        ["dart", "rapier"],
        Scenario::Trot,
        Metric::ReturnDiff,
    );
    assert_eq!(t, 0.7);
    assert!(matches!(source, ToleranceSource::Known { ref scenario, .. } if scenario == "trot"));
    let (t, _) = ledger.tolerance(
        "hyq",
        ["rapier", "dart"],
        Scenario::Stand,
        Metric::ReturnDiff,
    );
    assert_eq!(t, 0.5);
    // Measured on HyQ: another robot gets the default.
    let (t, source) = ledger.tolerance(
        "anymal_c",
        ["rapier", "dart"],
        Scenario::Trot,
        Metric::ReturnDiff,
    );
    assert_eq!((t, source), (1e-3, ToleranceSource::Default));
    let (t, source) = ledger.tolerance(
        "hyq",
        ["rapier", "rapier"],
        Scenario::Trot,
        Metric::ReturnDiff,
    );
    assert_eq!((t, source), (1e-3, ToleranceSource::Default));
}

#[test]
fn malformed_ledgers_are_errors_naming_what_is_wrong() {
    let missing = DEFAULTS.replace("return_diff = 1e-3\n", "");
    assert!(
        error(&missing).contains("return_diff"),
        "{}",
        error(&missing)
    );

    let unknown = format!("{DEFAULTS}bogus_metric_m = 1\n");
    assert!(error(&unknown).contains("bogus_metric_m"));

    let negative = DEFAULTS.replace("return_diff = 1e-3", "return_diff = -1");
    let e = error(&negative);
    assert!(e.contains("return_diff") && e.contains("-1"), "{e}");

    let cases = [
        (known("trot", "nope_metric", "1", "r"), "nope_metric"),
        (known("moonwalk", "return_diff", "1", "r"), "moonwalk"),
        (known("trot", "return_diff", "nan", "r"), "NaN"),
        (known("trot", "return_diff", "1", "  "), "reason is empty"),
        (
            known("trot", "return_diff", "1", "r").replace("robot = \"hyq\"", "robot = \" \""),
            "robot name is empty",
        ),
    ];
    for (entry, named) in cases {
        let e = error(&format!("{DEFAULTS}{entry}"));
        assert!(e.contains(named) && e.contains("test.toml"), "{e}");
        assert!(!e.contains('\n'), "one line: {e}");
    }
    let twice = format!(
        "{DEFAULTS}{}{}",
        known("trot", "return_diff", "1", "first"),
        known("trot", "return_diff", "2", "second")
    );
    assert!(error(&twice).contains("duplicates"), "{}", error(&twice));

    let extra = format!("{DEFAULTS}{}", known("trot", "return_diff", "1", "r"))
        .replace("reason =", "colour = \"red\"\nreason =");
    assert!(error(&extra).contains("colour"), "{}", error(&extra));

    let missing_file = Ledger::from_file("/nonexistent/ledger.toml")
        .unwrap_err()
        .to_string();
    assert!(
        missing_file.contains("/nonexistent/ledger.toml"),
        "{missing_file}"
    );
}

/// An entry holds on the ground it was measured on: one without `terrain` on flat ground only,
/// one with `terrain = "rough"` on rough ground only; the same metric may have both; an unknown
/// ground is an error naming the entry.
#[test]
fn an_entry_holds_on_the_ground_it_names() {
    let rough = known(
        "trot",
        "return_diff",
        "0.9",
        "measured on rough ground, a reason",
    )
    .replace("tolerance", "terrain = \"rough\"\ntolerance");
    let text = format!(
        "{DEFAULTS}{}{rough}",
        known(
            "trot",
            "return_diff",
            "0.7",
            "measured on flat ground, a reason"
        )
    );
    let ledger = Ledger::parse(&text, "test.toml").unwrap();
    let engines = ["rapier", "dart"];
    let on = |terrain: &str| {
        ledger
            .tolerance_on("hyq", engines, Scenario::Trot, terrain, Metric::ReturnDiff)
            .0
    };
    assert_eq!((on("flat"), on("rough"), on("slope")), (0.7, 0.9, 1e-3));
    let (flat, _) = ledger.tolerance("hyq", engines, Scenario::Trot, Metric::ReturnDiff);
    assert_eq!(flat, 0.7);
    let lava = format!("{DEFAULTS}{}", rough.replace("\"rough\"", "\"lava\""));
    assert!(
        error(&lava).contains("unknown terrain \"lava\""),
        "{}",
        error(&lava)
    );
    assert!(error(&format!("{DEFAULTS}{rough}{rough}")).contains("duplicates"));
}
