//! Every loader of a user's file survives a fixed, seeded run of mutated inputs and every input
//! kept in its corpus: no panic, no abort, no hang; each input is refused with one good line or
//! accepted as a model, configuration, policy, plot or ledger whose derived quantities are all
//! finite and which runs (see the crate docs for the checks). The runs here are short and
//! reproducible (seed and case count fixed); `cargo xtask fuzz` runs them for longer.

use hyq_fuzz::{Plan, Target, corpus, run, run_case};

/// The seed of the runs in this test.
const SEED: u64 = 26;

/// Runs `cases` inputs of `target` (its seed files, then mutations) and fails on a finding.
fn survives(target: Target, cases: u64) {
    let scratch = tempfile::tempdir().expect("scratch directory");
    let plan = Plan {
        seed: SEED,
        cases,
        time: None,
    };
    match run(target, &plan, scratch.path()) {
        Ok(tally) => {
            assert_eq!(tally.cases, cases);
            // Some inputs must get through, or the checks of accepted ones never ran.
            assert!(
                tally.accepted > 0,
                "{}: nothing was accepted",
                target.name()
            );
        }
        Err(finding) => panic!("{finding}: {}", String::from_utf8_lossy(&finding.input)),
    }
}

#[test]
fn configuration_files_and_overrides() {
    survives(Target::Config, 300);
}

#[test]
fn robot_profiles() {
    survives(Target::Profile, 120);
}

#[test]
fn urdfs() {
    survives(Target::Urdf, 120);
}

#[test]
fn mjcf_files() {
    survives(Target::Mjcf, 120);
}

#[test]
fn robot_files_drafted_into_profiles() {
    survives(Target::Draft, 120);
}

#[test]
fn policy_files() {
    survives(Target::Policy, 200);
}

#[test]
fn step_records_for_hyq_plot() {
    survives(Target::Records, 12);
}

#[test]
fn comparison_ledgers() {
    survives(Target::Ledger, 200);
}

#[test]
fn terrain_height_files() {
    survives(Target::Heights, 150);
}

#[test]
fn every_kept_input_is_refused_well_or_accepted_sound() {
    let scratch = tempfile::tempdir().expect("scratch directory");
    let mut replayed = 0;
    for target in Target::ALL {
        for (name, input) in corpus(target).expect("the corpus reads") {
            if let Err(finding) = run_case(target, &input, scratch.path()) {
                panic!("corpus/{}/{name}: {finding}", target.name());
            }
            replayed += 1;
        }
    }
    assert!(replayed > 0, "the corpus holds inputs");
}
