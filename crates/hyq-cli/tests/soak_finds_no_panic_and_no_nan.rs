//! Invariant (the CI-sized soak; `cargo xtask soak` runs 10⁶ steps): 5·10³ env steps of
//! uniformly random actions on the default backend, resetting at every episode end, neither
//! panic nor emit a non-finite number anywhere (every observation row, the reward and its
//! terms, every info field: `hyq soak` checks each and fails naming the first bad one), and the
//! summary accounts for every row and every episode. Five episodes at least: enough to cross
//! resets and falls; longer runs find nothing more here (the 10⁶-step soak found nothing) and
//! would cost CI time.

// In tests a failed unwrap is a failed test, with its location.
#![allow(clippy::unwrap_used)]

mod common;

use common::hyq_ok;
use serde_json::Value;

#[test]
fn five_thousand_random_steps_emit_only_finite_numbers() {
    let out = hyq_ok(&["soak", "--steps", "5000", "--seed", "1", "--json"]);
    let r: Value = serde_json::from_str(out.trim()).unwrap_or_else(|e| panic!("{e}: {out}"));
    assert_eq!(r["steps"], 5000);
    assert_eq!(r["non_finite"], 0);
    let episodes = r["episodes"].as_u64().unwrap();
    assert!(
        episodes >= 5,
        "t_max = 1000 ends at least 5 episodes, got {episodes}"
    );
    let rows = r["rows"].as_array().unwrap();
    assert_eq!(rows.len(), 39);
    for row in rows {
        let (min, max) = (row["min"].as_f64().unwrap(), row["max"].as_f64().unwrap());
        assert!(min.is_finite() && max.is_finite() && min <= max, "{row}");
    }
    // Flailing moves every joint, and the quaternion stays a unit quaternion's components.
    for row in &rows[0..12] {
        assert!(
            row["max"].as_f64().unwrap() > row["min"].as_f64().unwrap(),
            "{row}"
        );
    }
    for row in &rows[29..33] {
        assert!(row["max_abs"].as_f64().unwrap() <= 1.0 + 1e-12, "{row}");
    }
}
