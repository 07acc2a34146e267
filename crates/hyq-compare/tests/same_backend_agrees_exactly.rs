//! Invariant: two runs of the same engine with the same seed and the same action script agree
//! exactly. Every divergence is 0.0 (not merely small), every contact flag agrees, both end on
//! the same step for the same reasons, and the one-step comparison from shared states finds no
//! difference at all: the comparator adds no noise of its own, so whatever it reports between two
//! engines comes from the engines. Checked on rapier, and on MuJoCo with `--features mujoco`.

#![allow(clippy::unwrap_used)]

mod common;

use hyq_compare::{Ledger, Scenario};
use hyq_rapier::RapierBackend;

#[test]
fn rapier_against_itself_agrees_bit_for_bit() {
    agrees_with_itself::<RapierBackend>("rapier (B)");
}

#[cfg(feature = "mujoco")]
#[test]
fn mujoco_against_itself_agrees_bit_for_bit() {
    agrees_with_itself::<hyq_mujoco::MujocoBackend>("mujoco (B)");
}

fn agrees_with_itself<B: hyq_physics::Backend>(label: &str) {
    let ledger = Ledger::built_in().unwrap();
    // random: the most varied inputs (contacts making and breaking, joints near limits);
    // fall: a start state other than the spawn state.
    for (scenario, seconds) in [(Scenario::Random, 1.5), (Scenario::Fall, 1.2)] {
        let spec = common::spec(scenario, seconds, 12, &[]);
        let r = common::run::<B, B>(&spec, label, &ledger);
        let t = &r.trajectory;
        assert!(t.samples > 50, "{scenario}: only {} samples", t.samples);
        for (what, d) in [
            ("position", &t.trunk_position),
            ("orientation", &t.trunk_orientation),
            ("joints", &t.joint_angles),
        ] {
            assert_eq!(
                (d.rms, d.max),
                (0.0, 0.0),
                "{scenario}: {what} diverged: {d:?}"
            );
        }
        assert!(t.joint_rms.iter().all(|v| *v == 0.0), "{:?}", t.joint_rms);
        assert!(
            t.contacts.iter().all(|c| c.agreement_pct == 100.0),
            "{:?}",
            t.contacts
        );
        let [a, b] = &r.sides;
        assert_eq!((a.end_step, &a.end_reasons), (b.end_step, &b.end_reasons));
        assert_eq!(a.sums, b.sums);
        assert_eq!(a.standing_height_m, b.standing_height_m);
        assert_eq!(r.one_step.states, 12);
        for s in &r.one_step.summary {
            assert_eq!(
                s.max, 0.0,
                "{scenario}: one-step {} differs: {s:?}",
                s.quantity
            );
        }
        assert_eq!(
            r.flagged,
            0,
            "{scenario}: flagged {:?}",
            common::flagged(&r)
        );
        assert!(r.checks.iter().all(|c| c.value == 0.0), "{:?}", r.checks);
    }
}
