//! Shared strategies and builders for the contract tests (included with `mod common;`).
#![allow(dead_code)]

use hyq_spec::nalgebra::{Point3, UnitQuaternion, Vector3};
use hyq_spec::{EpisodeRules, JointRange, StepOutcome, StepSnapshot, TaskConfig};
use proptest::prelude::*;

/// A normalised distance aimed at the places where R_e changes shape: near 0, 1 and 9, plus
/// anywhere in [0, 12].
pub fn d_n_near_boundaries() -> impl Strategy<Value = f64> {
    prop_oneof![
        0.0f64..1e-6,
        (-1e-6f64..1e-6).prop_map(|e| 1.0 + e),
        (-1e-6f64..1e-6).prop_map(|e| 9.0 + e),
        Just(0.0),
        Just(1.0),
        Just(9.0),
        0.0f64..12.0,
    ]
}

/// A unit direction, from a non-degenerate random vector.
pub fn direction() -> impl Strategy<Value = Vector3<f64>> {
    (-1.0f64..1.0, -1.0f64..1.0, -1.0f64..1.0)
        .prop_filter("not too short to normalise", |(x, y, z)| {
            x * x + y * y + z * z > 1e-2
        })
        .prop_map(|(x, y, z)| Vector3::new(x, y, z).normalize())
}

/// An episode's start and goal, K = ‖G − C^0‖ between 0.1 m and 20 m.
pub fn start_and_goal() -> impl Strategy<Value = (Point3<f64>, Point3<f64>)> {
    (
        (-5.0f64..5.0, -5.0f64..5.0, 0.3f64..0.8),
        direction(),
        0.1f64..20.0,
    )
        .prop_map(|((x, y, z), dir, k)| {
            let start = Point3::new(x, y, z);
            (start, start + dir * k)
        })
}

/// HyQ's twelve joint ranges as the spec's §3 table prints them.
pub fn hyq_ranges() -> Vec<JointRange> {
    hyq_spec::RobotDescription::hyq_spec()
        .joint_ranges()
        .to_vec()
}

/// Mid-range angles for `ranges`.
pub fn mid_angles(ranges: &[JointRange]) -> Vec<f64> {
    ranges
        .iter()
        .map(|r| 0.5 * (r.lower() + r.upper()))
        .collect()
}

/// A level, contact-free snapshot moving from `previous` to `position` with all joints
/// mid-range.
pub fn level_snapshot<'a>(
    step: u64,
    previous: Point3<f64>,
    position: Point3<f64>,
    angles: &'a [f64],
    ranges: &'a [JointRange],
) -> StepSnapshot<'a> {
    StepSnapshot {
        step,
        previous_position: previous,
        position,
        orientation: UnitQuaternion::identity(),
        joint_angles: angles,
        joint_ranges: ranges,
        trunk_contact: false,
    }
}

/// The rules of an episode the test knows to be valid.
///
/// # Panics
/// If they are rejected.
pub fn rules(config: &TaskConfig, start: Point3<f64>, goal: Point3<f64>) -> EpisodeRules {
    match EpisodeRules::new(config, start, goal) {
        Ok(r) => r,
        Err(e) => panic!("valid episode rejected: {e}"),
    }
}

/// The outcome of a step the test knows to be valid.
///
/// # Panics
/// If the snapshot is rejected.
pub fn step(rules: &EpisodeRules, s: &StepSnapshot<'_>) -> StepOutcome {
    match rules.evaluate_step(s) {
        Ok(o) => o,
        Err(e) => panic!("valid snapshot rejected: {e}"),
    }
}
