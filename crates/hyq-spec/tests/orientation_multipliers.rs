//! Invariant: the §5.1 multipliers, m(angle) = 1 if |angle| ≤ limit else
//! max(0, cos angle), are in [0, 1], even in the angle, exactly 1 at ±limit, exactly cos angle
//! just beyond it and 0 past 90°; and the composed step applies m_yaw and m_pitch to the
//! trunk's actual yaw and pitch.

mod common;

use common::{hyq_ranges, level_snapshot, mid_angles};
use hyq_spec::nalgebra::{Point3, UnitQuaternion, Vector3};
use hyq_spec::penalty::orientation::orientation_multiplier as m;
use hyq_spec::{EpisodeRules, TaskConfig};
use proptest::prelude::*;
use std::f64::consts::{FRAC_PI_2, PI};

/// A limit in radians: the default 2.5°, or any of [0°, 180°].
fn limit() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(2.5f64.to_radians()),
        (0.0f64..=180.0).prop_map(f64::to_radians)
    ]
}

/// An angle near ±2.5°, near ±90°, or anywhere in [−π, π].
fn angle() -> impl Strategy<Value = f64> {
    let near = |centre: f64| (-1e-3f64..1e-3).prop_map(move |e| centre + e);
    prop_oneof![
        near(2.5f64.to_radians()),
        near(-(2.5f64.to_radians())),
        near(FRAC_PI_2),
        near(-FRAC_PI_2),
        -PI..PI,
    ]
}

/// m(angle) against its definition, and the properties that follow.
fn check_multiplier(angle: f64, limit: f64) {
    let value = m(angle, limit);
    assert!(
        (0.0..=1.0).contains(&value),
        "m({angle}, {limit}) = {value}"
    );
    assert_eq!(value, m(-angle, limit), "m is not even at {angle}");
    if angle.abs() <= limit {
        assert_eq!(value, 1.0);
    } else if angle.abs() < FRAC_PI_2 {
        assert_eq!(value, angle.cos());
    } else {
        assert!(value <= 1e-15, "m({angle}) = {value} past 90°");
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2048, ..ProptestConfig::default() })]

    #[test]
    fn follows_its_definition(angle in angle(), limit in limit()) {
        check_multiplier(angle, limit);
    }

    #[test]
    fn one_at_the_limit_and_cosine_just_beyond(limit in limit().prop_filter("below 90°", |l| *l < FRAC_PI_2)) {
        prop_assert_eq!(m(limit, limit), 1.0);
        prop_assert_eq!(m(-limit, limit), 1.0);
        let beyond = limit.next_up();
        prop_assert_eq!(m(beyond, limit), beyond.cos());
        prop_assert_eq!(m(-beyond, limit), beyond.cos());
    }

    #[test]
    fn zero_past_ninety_degrees(excess in 1e-9f64..(PI / 2.0), limit in limit().prop_filter("below 90°", |l| *l < FRAC_PI_2)) {
        prop_assert_eq!(m(FRAC_PI_2 + excess, limit), 0.0);
        prop_assert_eq!(m(-FRAC_PI_2 - excess, limit), 0.0);
    }

    #[test]
    fn the_step_applies_them_to_the_trunk_yaw_and_pitch(
        yaw in prop_oneof![(-5.0f64..5.0).prop_map(f64::to_radians), -PI..PI],
        pitch in prop_oneof![(-5.0f64..5.0).prop_map(f64::to_radians), -1.5f64..1.5],
    ) {
        let start = Point3::new(0.0, 0.0, 0.6);
        let rules = EpisodeRules::new(&TaskConfig::default(), start, Point3::new(5.0, 0.0, 0.6))
            .map_err(|e| TestCaseError::fail(e.to_string()))?;
        let ranges = hyq_ranges();
        let angles = mid_angles(&ranges);
        let mut s = level_snapshot(1, start, Point3::new(1.0, 0.0, 0.6), &angles, &ranges);
        s.orientation = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw)
            * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), pitch);
        let o = rules.evaluate_step(&s).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let limit = 2.5f64.to_radians();
        prop_assert_eq!(o.reward.m_yaw, m(o.attitude.yaw, limit));
        prop_assert_eq!(o.reward.m_pitch, m(o.attitude.pitch, limit));
        prop_assert!((o.attitude.yaw - yaw).abs() < 1e-9 && (o.attitude.pitch - pitch).abs() < 1e-9);
    }
}

#[test]
fn a_limit_of_180_degrees_turns_the_penalty_off() {
    let off = 180f64.to_radians();
    for angle in [-PI, -2.0, 0.0, 1.0, PI] {
        assert_eq!(m(angle, off), 1.0);
    }
}
