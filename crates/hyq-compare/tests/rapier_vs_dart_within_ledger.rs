//! Invariant (with `--features dart`): rapier and DART, fed the same action scripts, stay within
//! the shipped ledger in every scenario at its default length, and agree on what happened: the
//! same termination reason (except `random`, which the ledger lets differ), standing heights
//! within 0.5 mm, and in `trot` both walk more than 3 m. A change to either engine's model,
//! contact handling or actuator that moves them apart fails here, naming the metric.

#![cfg(feature = "dart")]
#![allow(clippy::unwrap_used)]

mod common;

use hyq_compare::{ComparisonSpec, Ledger, Scenario};
use hyq_dart::DartBackend;
use hyq_env::Reason;
use hyq_rapier::RapierBackend;

#[test]
fn every_scenario_stays_within_the_ledger() {
    let ledger = Ledger::built_in().unwrap();
    for scenario in Scenario::ALL {
        let spec = ComparisonSpec {
            one_step_states: 25,
            ..ComparisonSpec::new(scenario)
        };
        let r = common::run::<RapierBackend, DartBackend>(&spec, "dart", &ledger);
        let outside: Vec<String> = r
            .flags()
            .map(|c| format!("{} = {} > {}", c.metric, c.value, c.tolerance))
            .collect();
        assert!(
            outside.is_empty(),
            "{scenario}: outside the ledger: {outside:?}"
        );
        let [a, b] = &r.sides;
        let expected = match scenario {
            Scenario::Stand | Scenario::Trot => Some(Reason::Timeout),
            Scenario::Fall => Some(Reason::Fell),
            Scenario::Limit => Some(Reason::JointLimit),
            Scenario::Reach => Some(Reason::Reached),
            Scenario::Random => None,
        };
        if let Some(reason) = expected {
            for side in [a, b] {
                assert_eq!(side.end_reasons, vec![reason], "{scenario}: {}", side.label);
            }
        }
        assert!((a.standing_height_m - b.standing_height_m).abs() < 5e-4);
        if scenario == Scenario::Trot {
            assert!(
                a.final_position[0] > 3.0 && b.final_position[0] > 3.0,
                "{a:?} {b:?}"
            );
        }
    }
}
