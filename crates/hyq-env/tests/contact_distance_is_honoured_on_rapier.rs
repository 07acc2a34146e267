//! Invariant: `physics.contact_distance` means the same on every engine, "a tracked shape
//! within this distance of the ground counts as touching it", whatever rapier's own
//! `prediction_distance` (the distance within which it creates contacts at all): a contact
//! distance above it still sees the trunk near the ground.

mod common;

use common::{rapier, reset, stand_action};
use hyq_env::Reason;

#[test]
fn a_contact_distance_beyond_rapiers_prediction_distance_still_counts() {
    // The standing trunk's box is about 0.5 m above the ground: within 1 m, it touches. With
    // rapier's default prediction distance (0.02 m) this used to report no contact at all.
    let mut env = rapier(&[("physics.contact_distance", "1.0")]);
    reset(&mut env, 0);
    let a = stand_action(&env);
    let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
    assert!(
        s.info.reasons.contains(Reason::Fell),
        "{:?}",
        s.info.reasons
    );

    // The default contact distance (1 mm): standing is no fall.
    let mut env = rapier(&[]);
    reset(&mut env, 0);
    let a = stand_action(&env);
    let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
    assert!(s.info.reasons.is_empty(), "{:?}", s.info.reasons);
}
