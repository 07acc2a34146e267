//! Helpers shared by the comparison tests.
#![allow(dead_code)]

use hyq_compare::{ComparisonSpec, Ledger, Report, Scenario, compare};
use hyq_physics::Backend;

/// Gravity 10 % stronger than the default −9.81 m/s²: the perturbation the comparator must flag.
pub const PERTURBED_GRAVITY: &str = "[0, 0, -10.791]";

/// `scenario` for `seconds` with `shared` one-step states, second side overridden by
/// `overrides_b`.
pub fn spec(
    scenario: Scenario,
    seconds: f64,
    states: usize,
    overrides_b: &[(&str, &str)],
) -> ComparisonSpec {
    ComparisonSpec {
        seconds: Some(seconds),
        one_step_states: states,
        overrides_b: overrides_b
            .iter()
            .map(|(k, v)| ((*k).to_owned(), (*v).to_owned()))
            .collect(),
        ..ComparisonSpec::new(scenario)
    }
}

/// Compares `A` (labelled by its name) with `B` (its name, or `label_b`).
pub fn run<A: Backend, B: Backend>(
    spec: &ComparisonSpec,
    label_b: &str,
    ledger: &Ledger,
) -> Report {
    compare::<A, B>(
        hyq_physics::bundled::hyq(),
        spec,
        [A::NAME, label_b],
        ledger,
    )
    .unwrap_or_else(|e| panic!("{:?} comparison failed: {e}", spec.scenario))
}

/// The names of the flagged metrics.
pub fn flagged(report: &Report) -> Vec<&'static str> {
    report.flags().map(|c| c.metric.name()).collect()
}
