//! Invariant: each deviation from the printed spec (spec §4.1, §4.3 and §6.2 of
//! `docs/spec.md`) has a reason that can be shown, and the ruled form removes it.
//!
//! - Printed eq. (2), r_b = |C^t − C^{t−1}|, pays for walking away from the goal; the ruled
//!   k_base · (D^{t−1} − D^t) charges for it.
//! - Printed eq. (4) jumps by +1/k at D_n = 1 and by +36 at D_n = 9, so a step away from the goal
//!   across D_n = 9 pays +36 (and one across D_n = 1 pays −1/k less than it should); the ruled
//!   R_e is continuous there.
//! - Printed §6.2, "not reached when θ_min < |θ − ε| < θ_max", holds for every angle of a front
//!   knee (range −2.44…−0.35 rad), ending every episode on its first step; the ruled test fires
//!   only within ε of a limit.

use hyq_spec::nalgebra::{Point3, Vector3};
use hyq_spec::printed;
use hyq_spec::reward::base::base_reward;
use hyq_spec::reward::exponential::{cumulative_exponential_reward, exponential_reward};
use hyq_spec::termination::joint_limit::joint_at_limit;
use hyq_spec::{JointRange, SPEC_TABLE};
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig { cases: 1024, ..ProptestConfig::default() })]

    /// Eq. (2) as printed pays for any motion, away from the goal included.
    #[test]
    fn printed_eq2_rewards_moving_away_from_the_goal(
        start in (-5.0f64..5.0, -5.0f64..5.0, 0.3f64..0.8),
        goal_offset in (0.5f64..10.0, -3.0f64..3.0),
        away in 0.001f64..0.5,
        k_base in 0.1f64..10.0,
    ) {
        let c_prev = Point3::new(start.0, start.1, start.2);
        let goal = c_prev + Vector3::new(goal_offset.0, goal_offset.1, 0.0);
        // One step straight away from the goal.
        let c = c_prev - (goal - c_prev).normalize() * away;
        let printed = printed::base_reward(&c_prev, &c);
        prop_assert!(printed > 0.0, "printed eq. (2) pays {printed} for walking away");
        let (d_prev, d) = ((goal - c_prev).norm(), (goal - c).norm());
        prop_assert!(d > d_prev);
        prop_assert!(base_reward(d_prev, d, k_base) < 0.0, "the ruled r_b charges for it");
    }

    /// Eq. (4) as printed pays about +36 for one step away from the goal across D_n = 9.
    #[test]
    fn printed_eq4_rewards_walking_away_across_nine(
        before in 8.9f64..9.0,
        after in 9.000_001f64..9.1,
        k in 0.1f64..10.0,
    ) {
        let printed_r_e = printed::cumulative_exponential_reward(after, k)
            - printed::cumulative_exponential_reward(before, k);
        prop_assert!(printed_r_e > 35.0, "printed r_e = {printed_r_e} for walking away");
        let ruled = exponential_reward(before, after, k);
        prop_assert!(ruled < 0.0 && ruled > -1.0, "ruled r_e = {ruled}");
    }

    /// Eq. (4) as printed jumps by 1/k at D_n = 1 and starts at 1/k, not 0.
    #[test]
    fn printed_eq4_jumps_at_one(k in 0.1f64..10.0) {
        let at_one = printed::cumulative_exponential_reward(1.0, k);
        prop_assert!((at_one - 1.0 / k).abs() < 1e-12, "printed R_e(1) = {at_one}, the text says 0");
        let just_past = printed::cumulative_exponential_reward(1.0f64.next_up(), k);
        prop_assert!(at_one - just_past > 0.99 / k, "printed R_e drops by {} at D_n = 1", at_one - just_past);
        prop_assert_eq!(cumulative_exponential_reward(1.0, k), 0.0);
        prop_assert!((cumulative_exponential_reward(1.0f64.next_up(), k)).abs() < 1e-12);
    }

    /// §6.2 as printed declares the limit reached for every front-knee angle.
    #[test]
    fn printed_joint_test_fires_for_every_front_knee_angle(t in 0.0f64..=1.0, eps in 0.0f64..0.05) {
        for row in [&SPEC_TABLE[2], &SPEC_TABLE[8]] {
            let (lower, upper) = (row.min, row.max);
            let theta = lower + t * (upper - lower);
            prop_assert!(printed::joint_limit_reached(theta, lower, upper, eps), "{}: θ = {theta}", row.name);
            let range = JointRange::new(lower, upper).map_err(|e| TestCaseError::fail(e.to_string()))?;
            let inside = theta > lower + eps && theta < upper - eps;
            prop_assert_eq!(joint_at_limit(theta, range, eps).is_some(), !inside);
        }
    }
}

#[test]
fn the_printed_joint_test_would_end_a_standing_episode_at_once() {
    // Every joint mid-range (a standing robot far from all limits): the printed test fires on
    // both front knees, and on no other joint; the ruled test fires on none.
    let eps = 0.01;
    let firing: Vec<_> = SPEC_TABLE[..12]
        .iter()
        .filter(|row| {
            printed::joint_limit_reached(0.5 * (row.min + row.max), row.min, row.max, eps)
        })
        .map(|row| row.name.as_ref())
        .collect();
    assert_eq!(firing, ["lf_kfe_angle", "rf_kfe_angle"]);
    for row in &SPEC_TABLE[..12] {
        let range = match JointRange::new(row.min, row.max) {
            Ok(r) => r,
            Err(e) => panic!("{e}"),
        };
        assert_eq!(
            joint_at_limit(0.5 * (row.min + row.max), range, eps),
            None,
            "{}",
            row.name
        );
    }
}
