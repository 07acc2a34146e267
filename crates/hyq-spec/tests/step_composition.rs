//! Invariant: one env step's reward is the composition of its reported terms, to the bit,
//!
//! total = (r_b + r_n + r_e + r_reach) · m_yaw · m_pitch · m_height − joint_penalty − fall_penalty
//!
//! (spec §4 eq. (1) and §5), each term is the rule applied to the snapshot, the
//! reach bonus is scaled by the multipliers, the fixed penalties are not, every penalty whose
//! condition holds is subtracted, and an episode whose goal is at its start is rejected (naming
//! the goal) instead of dividing by K = 0.

mod common;

use common::{direction, hyq_ranges, level_snapshot, mid_angles, rules, start_and_goal, step};
use hyq_spec::nalgebra::{Point3, UnitQuaternion, Vector3};
use hyq_spec::penalty::orientation::orientation_multiplier;
use hyq_spec::reward::exponential::cumulative_exponential_reward;
use hyq_spec::{
    EpisodeError, EpisodeRules, HeightPenalty, JointRange, RewardBreakdown, StepError, StepOutcome,
    StepSnapshot, TaskConfig, Termination,
};
use proptest::prelude::*;

/// The reported total is the composition of the reported terms, in the documented order, to the
/// bit; written out here rather than calling `compose`.
fn check_total_is_composition(r: &RewardBreakdown) {
    let by_hand = (r.r_b + r.r_n + r.r_e + r.r_reach) * r.m_yaw * r.m_pitch * r.m_height
        - r.joint_penalty
        - r.fall_penalty;
    assert_eq!(r.total.to_bits(), by_hand.to_bits(), "{r:?}");
    assert_eq!(r.total.to_bits(), r.compose().to_bits());
}

/// Each term is its rule applied to the snapshot.
fn check_terms(rules: &EpisodeRules, s: &StepSnapshot<'_>, o: &StepOutcome) {
    let c = rules.config();
    let g = rules.goal();
    let k = (g - rules.initial()).norm();
    let (d_prev, d) = ((g - s.previous_position).norm(), (g - s.position).norm());
    let r = &o.reward;
    assert_eq!(o.distance, d);
    assert_eq!(
        r.r_b,
        c.base_rew_scaling.map_or(0.0, |kb| kb * (d_prev - d))
    );
    assert_eq!(
        r.r_n,
        c.norm_rew_scaling.map_or(0.0, |kn| kn * (d_prev - d) / k)
    );
    let r_e = c.exp_rew_scaling.map_or(0.0, |ke| {
        cumulative_exponential_reward(d / k, ke) - cumulative_exponential_reward(d_prev / k, ke)
    });
    assert_eq!(r.r_e, r_e);
    let reached = (s.position - g)
        .iter()
        .all(|o| o.abs() <= c.accepted_error / 2.0);
    assert_eq!(
        r.r_reach,
        if reached {
            c.reach_target_bonus_reward
        } else {
            0.0
        }
    );
    assert_eq!(o.terminations.contains(Termination::Reached), reached);
    assert_eq!(
        r.m_yaw,
        orientation_multiplier(o.attitude.yaw, c.yaw_limit_deg.to_radians())
    );
    assert_eq!(
        r.m_pitch,
        orientation_multiplier(o.attitude.pitch, c.pitch_limit_deg.to_radians())
    );
    assert_eq!(
        r.joint_penalty,
        if o.joint_at_limit.is_some() {
            c.reach_bounds_penalty
        } else {
            0.0
        }
    );
    assert_eq!(
        r.fall_penalty,
        if s.trunk_contact { c.fall_penalty } else { 0.0 }
    );
    for m in [r.m_yaw, r.m_pitch, r.m_height] {
        assert!((0.0..=1.0).contains(&m));
    }
}

fn config_strategy() -> impl Strategy<Value = TaskConfig> {
    (
        (
            prop::option::of(0.1f64..100.0),
            prop::option::of(0.1f64..10.0),
            prop::option::of(0.1f64..100.0),
        ),
        (
            0.0f64..100.0,
            prop_oneof![Just(0.001), 1e-3f64..0.5],
            0.0f64..0.05,
        ),
        (0.0f64..100.0, 0.0f64..100.0, 1u64..50),
        (
            prop_oneof![Just(2.5), 0.0f64..=180.0],
            prop_oneof![Just(2.5), 0.0f64..=180.0],
        ),
        prop::option::of((0.3f64..0.8, 0.0f64..0.2, 0.1f64..5.0)),
    )
        .prop_map(|(scalings, a, b, limits, height)| TaskConfig {
            base_rew_scaling: scalings.0,
            exp_rew_scaling: scalings.1,
            norm_rew_scaling: scalings.2,
            reach_target_bonus_reward: a.0,
            accepted_error: a.1,
            accepted_dist_to_bounds: a.2,
            reach_bounds_penalty: b.0,
            fall_penalty: b.1,
            max_time_steps: b.2,
            yaw_limit_deg: limits.0,
            pitch_limit_deg: limits.1,
            height_penalty: height.map(|(z, t, r)| HeightPenalty {
                nominal_height_m: z,
                tolerance_m: t,
                rate_per_m: r,
            }),
        })
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1024, ..ProptestConfig::default() })]

    #[test]
    fn total_is_the_composition_of_the_breakdown(
        config in config_strategy(),
        (start, goal) in start_and_goal(),
        moves in (direction(), 0.0f64..0.2, direction(), prop_oneof![Just(0.0), 0.0f64..0.3, 0.0f64..0.002]),
        at_goal: bool,
        attitude in ((-0.2f64..0.2), prop_oneof![(-0.1f64..0.1), -1.5f64..1.5], prop_oneof![(-0.1f64..0.1), -3.1f64..3.1]),
        joint_pick in (0usize..13, 0.0f64..1.0),
        t in 1u64..60,
        trunk_contact: bool,
    ) {
        let rules = rules(&config, start, goal);
        let previous = start + moves.0 * moves.1;
        // Either somewhere near the goal (on the reach cube's scale) or anywhere on the way.
        let position = if at_goal { goal + moves.2 * moves.3 } else { previous + moves.2 * 0.05 };
        let ranges = hyq_ranges();
        let mut angles = mid_angles(&ranges);
        if let Some(r) = ranges.get(joint_pick.0) {
            angles[joint_pick.0] = r.lower() + joint_pick.1 * (r.upper() - r.lower());
        }
        let (roll, pitch, yaw) = attitude;
        let s = StepSnapshot {
            step: t,
            previous_position: previous,
            position,
            orientation: UnitQuaternion::from_euler_angles(roll, pitch, yaw),
            joint_angles: &angles,
            joint_ranges: &ranges,
            trunk_contact,
        };
        let o = step(&rules, &s);
        check_total_is_composition(&o.reward);
        check_terms(&rules, &s, &o);
        prop_assert_eq!(o.terminations.contains(Termination::Fell), trunk_contact);
        prop_assert_eq!(o.terminations.contains(Termination::Timeout), t >= config.max_time_steps);
    }
}

#[test]
fn reaching_pays_the_bonus_times_the_multipliers() {
    // Reached while yawed 30° and pitched 10°: the bonus is scaled by cos 30° · cos 10°.
    let start = Point3::new(0.0, 0.0, 0.6);
    let goal = Point3::new(1.0, 0.0, 0.6);
    let config = TaskConfig {
        reach_target_bonus_reward: 100.0,
        exp_rew_scaling: None,
        ..TaskConfig::default()
    };
    let rules = rules(&config, start, goal);
    let ranges = hyq_ranges();
    let angles = mid_angles(&ranges);
    let mut s = level_snapshot(
        7,
        Point3::new(0.999, 0.0, 0.6),
        goal + Vector3::new(0.0004, -0.0005, 0.0),
        &angles,
        &ranges,
    );
    let (yaw, pitch) = (30f64.to_radians(), 10f64.to_radians());
    s.orientation = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw)
        * UnitQuaternion::from_axis_angle(&Vector3::y_axis(), pitch);
    let o = step(&rules, &s);
    assert!(o.terminated() && !o.truncated());
    assert_eq!(
        o.terminations.iter().collect::<Vec<_>>(),
        [Termination::Reached]
    );
    assert_eq!(o.reward.r_reach, 100.0);
    assert!(
        (o.reward.total - 100.0 * yaw.cos() * pitch.cos()).abs() < 1e-9,
        "{:?}",
        o.reward
    );
    check_total_is_composition(&o.reward);
}

#[test]
fn joint_limit_and_fall_on_the_same_step_both_subtract() {
    let start = Point3::new(0.0, 0.0, 0.6);
    let config = TaskConfig {
        reach_bounds_penalty: 3.0,
        fall_penalty: 7.0,
        ..TaskConfig::default()
    };
    let rules = rules(&config, start, Point3::new(5.0, 0.0, 0.6));
    let ranges = hyq_ranges();
    let mut angles = mid_angles(&ranges);
    angles[5] = ranges[5].lower(); // lh_kfe at its (positive) lower limit
    let mut s = level_snapshot(3, start, start, &angles, &ranges);
    s.trunk_contact = true;
    // Tilted past 90° as after a fall: the multipliers are 0, the fixed penalties still apply.
    s.orientation = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), 2.0);
    let o = step(&rules, &s);
    assert_eq!(o.reward.joint_penalty, 3.0);
    assert_eq!(o.reward.fall_penalty, 7.0);
    assert_eq!(o.reward.m_yaw, 0.0);
    assert_eq!(o.reward.total, -10.0);
    assert_eq!(
        o.terminations.iter().collect::<Vec<_>>(),
        [Termination::JointLimit, Termination::Fell]
    );
    assert_eq!(o.joint_at_limit.map(|h| h.joint), Some(5));
    check_total_is_composition(&o.reward);
}

#[test]
fn a_goal_at_the_start_is_rejected_naming_the_goal() {
    let start = Point3::new(1.5, -2.0, 0.6);
    for config in [
        TaskConfig::default(),
        TaskConfig {
            exp_rew_scaling: None,
            norm_rew_scaling: Some(10.0),
            ..TaskConfig::default()
        },
    ] {
        for goal in [start, start + Vector3::new(0.0, 0.0, 1e-7)] {
            let e = EpisodeRules::new(&config, start, goal);
            assert!(matches!(e, Err(EpisodeError::GoalAtStart { .. })), "{e:?}");
            let message = e.err().map(|e| e.to_string()).unwrap_or_default();
            assert!(
                message.starts_with(&format!("goal ({}, {}, {}", goal.x, goal.y, goal.z)),
                "{message}"
            );
        }
    }
    // With r_n and r_e off nothing divides by K: allowed, and D_n is reported as unknown.
    let config = TaskConfig {
        exp_rew_scaling: None,
        base_rew_scaling: Some(1.0),
        ..TaskConfig::default()
    };
    let rules = rules(&config, start, start);
    let ranges = hyq_ranges();
    let angles = mid_angles(&ranges);
    let o = step(
        &rules,
        &level_snapshot(
            1,
            start,
            start + Vector3::new(0.1, 0.0, 0.0),
            &angles,
            &ranges,
        ),
    );
    assert_eq!(o.normalised_distance, None);
    assert!((o.reward.r_b + 0.1).abs() < 1e-12);
    assert!(o.reward.total.is_finite());
}

#[test]
fn invalid_inputs_are_errors_not_numbers() {
    let start = Point3::new(0.0, 0.0, 0.6);
    let bad_config = TaskConfig {
        accepted_error: 0.0,
        ..TaskConfig::default()
    };
    let e = EpisodeRules::new(&bad_config, start, Point3::new(1.0, 0.0, 0.6))
        .err()
        .map(|e| e.to_string());
    assert!(
        e.as_deref().is_some_and(|m| m.contains("accepted_error")),
        "{e:?}"
    );
    let e = EpisodeRules::new(
        &TaskConfig::default(),
        start,
        Point3::new(f64::NAN, 0.0, 0.6),
    )
    .err()
    .map(|e| e.to_string());
    assert!(
        e.as_deref().is_some_and(|m| m.starts_with("goal (NaN")),
        "{e:?}"
    );

    let rules = rules(&TaskConfig::default(), start, Point3::new(1.0, 0.0, 0.6));
    let ranges = hyq_ranges();
    let angles = mid_angles(&ranges);
    let ok = level_snapshot(1, start, start, &angles, &ranges);
    assert_eq!(
        rules.evaluate_step(&StepSnapshot { step: 0, ..ok }).err(),
        Some(StepError::StepZero)
    );
    let e = rules
        .evaluate_step(&StepSnapshot {
            joint_angles: &angles[..11],
            ..ok
        })
        .err()
        .map(|e| e.to_string());
    assert_eq!(
        e.as_deref(),
        Some("11 joint angles given for 12 joint ranges: they must pair one to one")
    );
    let mut nan_angles = angles.clone();
    nan_angles[4] = f64::NAN;
    let e = rules
        .evaluate_step(&StepSnapshot {
            joint_angles: &nan_angles,
            ..ok
        })
        .err();
    assert!(
        matches!(
            e,
            Some(StepError::NonFinite {
                what: "joint angle",
                index: 4,
                ..
            })
        ),
        "{e:?}"
    );
    let e = rules
        .evaluate_step(&StepSnapshot {
            position: Point3::new(0.0, f64::INFINITY, 0.0),
            ..ok
        })
        .err();
    assert!(
        matches!(
            e,
            Some(StepError::NonFinite {
                what: "position",
                ..
            })
        ),
        "{e:?}"
    );
}

#[test]
fn the_breakdown_serialises_with_the_spec_keys() {
    let start = Point3::new(0.0, 0.0, 0.6);
    let rules = rules(&TaskConfig::default(), start, Point3::new(1.0, 0.0, 0.6));
    let ranges: Vec<JointRange> = hyq_ranges();
    let angles = mid_angles(&ranges);
    let o = step(
        &rules,
        &level_snapshot(1, start, Point3::new(0.5, 0.0, 0.6), &angles, &ranges),
    );
    let json = serde_json::to_value(o.reward).unwrap_or_default();
    let keys: Vec<_> = json
        .as_object()
        .map(|m| m.keys().cloned().collect())
        .unwrap_or_default();
    let mut expected = [
        "r_b",
        "r_n",
        "r_e",
        "r_reach",
        "m_yaw",
        "m_pitch",
        "m_height",
        "joint_penalty",
        "fall_penalty",
        "total",
    ];
    expected.sort_unstable();
    let mut keys = keys;
    keys.sort_unstable();
    assert_eq!(keys, expected);
    assert_eq!(json["r_e"].as_f64(), Some(o.reward.r_e));
    let back: RewardBreakdown = serde_json::from_value(json).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back, o.reward);
    let outcome = serde_json::to_value(o).unwrap_or_default();
    assert_eq!(outcome["terminations"], serde_json::json!([]));
}
