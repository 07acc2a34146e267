//! Invariant: each §6 termination test fires exactly at its boundary.
//!
//! - §6.1 reached ⇔ |C_i − G_i| ≤ ε/2 on every axis: true on the cube's faces and corners, false
//!   just beyond (1 nm, or one float where that is exact), symmetric per axis.
//! - §6.2 joint limit ⇔ θ ≤ θ_min + ε or θ ≥ θ_max − ε: true at and beyond those points, false one
//!   float inside, for negative (front knee), positive (hind knee) and mixed (hip) ranges.
//! - §6.4 timeout ⇔ t ≥ t_max: first at t = t_max (after the first step when t_max = 1).
//! - All four are independent: every combination is reported as it holds.

mod common;

use common::{hyq_ranges, level_snapshot, mid_angles, rules, step};
use hyq_spec::nalgebra::{Point3, Vector3};
use hyq_spec::termination::joint_limit::{first_joint_at_limit, joint_at_limit};
use hyq_spec::termination::reach::goal_reached;
use hyq_spec::termination::timeout::timed_out;
use hyq_spec::{EpisodeRules, JointRange, LimitSide, TaskConfig, Termination};
use proptest::prelude::*;

/// A dyadic goal coordinate (k/1024 m), so that G ± ε/2 is exact in binary floating point.
fn dyadic_coordinate() -> impl Strategy<Value = f64> {
    (-10240i32..10240).prop_map(|k| k as f64 / 1024.0)
}

/// A dyadic ε_reach (k/1024 m, from 1/1024 to 1 m).
fn dyadic_epsilon() -> impl Strategy<Value = f64> {
    (1i32..=1024).prop_map(|k| k as f64 / 1024.0)
}

/// reached ⇔ every |C_i − G_i| ≤ ε/2, checked against offsets chosen exactly on, inside or just
/// outside the faces.
fn check_reach(goal: Point3<f64>, offset: Vector3<f64>, eps: f64) {
    let expected = offset.iter().all(|o| o.abs() <= eps / 2.0);
    assert_eq!(
        goal_reached(&(goal + offset), &goal, eps),
        expected,
        "goal {goal:?}, offset {offset:?}, ε {eps}"
    );
}

/// The smallest step outside a face used here: 2⁻³⁰ m (≈ 1 nm), exact next to the dyadic goal
/// coordinates (|G_i| < 16 m needs 34 bits of mantissa for G_i + ε/2 + 2⁻³⁰).
const JUST_OUTSIDE: f64 = 1.0 / (1u64 << 30) as f64;

/// One offset per axis: exactly on a face (±ε/2), just outside it, inside, or 0.
fn face_offset(eps: f64, kind: u8, negative: bool) -> f64 {
    let half = eps / 2.0;
    let o = match kind {
        0 => half,
        1 => half + JUST_OUTSIDE,
        2 => half * 0.5,
        _ => 0.0,
    };
    if negative { -o } else { o }
}

/// The §6.2 test at and around its two edges θ_min + ε and θ_max − ε, and at `theta` (any angle).
fn check_joint_limit(range: JointRange, eps: f64, theta: f64) {
    let (low_edge, high_edge) = (range.lower() + eps, range.upper() - eps);
    // At the edges and beyond: reached.
    assert_eq!(joint_at_limit(low_edge, range, eps), Some(LimitSide::Lower));
    assert_eq!(
        joint_at_limit(low_edge - 1e-3, range, eps),
        Some(LimitSide::Lower)
    );
    assert_eq!(
        joint_at_limit(high_edge, range, eps),
        Some(LimitSide::Upper)
    );
    assert_eq!(
        joint_at_limit(high_edge + 1e-3, range, eps),
        Some(LimitSide::Upper)
    );
    // One float inside either edge: not reached.
    assert_eq!(joint_at_limit(low_edge.next_up(), range, eps), None);
    assert_eq!(joint_at_limit(high_edge.next_down(), range, eps), None);
    // Anywhere: reached exactly outside the open interval between the edges.
    let expected = if theta <= low_edge {
        Some(LimitSide::Lower)
    } else if theta >= high_edge {
        Some(LimitSide::Upper)
    } else {
        None
    };
    assert_eq!(
        joint_at_limit(theta, range, eps),
        expected,
        "θ = {theta}, range {range:?}, ε = {eps}"
    );
}

/// timeout ⇔ t ≥ t_max.
fn check_timeout(t: u64, t_max: u64) {
    assert_eq!(timed_out(t, t_max), t >= t_max, "t = {t}, t_max = {t_max}");
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 2048, ..ProptestConfig::default() })]

    #[test]
    fn reach_is_the_closed_cube(
        goal in (dyadic_coordinate(), dyadic_coordinate(), dyadic_coordinate()),
        eps in dyadic_epsilon(),
        kinds in (0u8..4, 0u8..4, 0u8..4),
        signs: (bool, bool, bool),
    ) {
        let goal = Point3::new(goal.0, goal.1, goal.2);
        let offset = Vector3::new(
            face_offset(eps, kinds.0, signs.0),
            face_offset(eps, kinds.1, signs.1),
            face_offset(eps, kinds.2, signs.2),
        );
        // The offsets are exact, so the position is on, inside or outside the face as intended.
        prop_assert_eq!((goal + offset) - goal, offset);
        check_reach(goal, offset, eps);
        // Symmetric per axis: flipping any one offset's sign changes nothing.
        for axis in 0..3 {
            let mut flipped = offset;
            flipped[axis] = -flipped[axis];
            prop_assert_eq!(goal_reached(&(goal + flipped), &goal, eps), goal_reached(&(goal + offset), &goal, eps));
        }
    }

    #[test]
    fn joint_limit_fires_exactly_within_epsilon_of_either_end(
        range in prop_oneof![
            Just((-2.44346, -0.349066)), // front knee: negative
            Just((0.349066, 2.44346)),   // hind knee: positive
            Just((-1.22173, 0.436332)),  // hip abduction: mixed
            (-3.0f64..3.0, 0.05f64..3.0).prop_map(|(lo, width)| (lo, lo + width)),
        ],
        eps in prop_oneof![Just(0.01), Just(0.0), 0.0f64..0.02],
        fraction in prop_oneof![0.0f64..=1.0, -0.1f64..1.1],
    ) {
        let (lower, upper) = range;
        let range = JointRange::new(lower, upper).map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assume!(lower + eps < upper - eps);
        check_joint_limit(range, eps, lower + fraction * (upper - lower));
    }

    #[test]
    fn any_joint_at_a_limit_is_found_and_named(joint in 0usize..12, upper: bool, eps in 0.0f64..0.02) {
        let ranges = hyq_ranges();
        let mut angles = mid_angles(&ranges);
        let r = ranges[joint];
        angles[joint] = if upper { r.upper() - eps } else { r.lower() + eps };
        let hit = first_joint_at_limit(&angles, &ranges, eps).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let hit = hit.ok_or_else(|| TestCaseError::fail("limit not found"))?;
        prop_assert_eq!(hit.joint, joint);
        prop_assert_eq!(hit.side, if upper { LimitSide::Upper } else { LimitSide::Lower });
        prop_assert_eq!(hit.angle, angles[joint]);
    }

    #[test]
    fn timeout_is_t_at_least_t_max(t_max in 1u64..10_000, offset in -3i64..=3, t in 0u64..20_000) {
        check_timeout(t_max.saturating_add_signed(offset), t_max);
        check_timeout(t, t_max);
        prop_assert!(timed_out(t_max, t_max) && !timed_out(t_max - 1, t_max));
    }

    #[test]
    fn the_four_conditions_are_independent(reached: bool, at_limit: bool, fell: bool, timeout: bool) {
        let start = Point3::new(0.0, 0.0, 0.5);
        let goal = Point3::new(2.0, 0.0, 0.5);
        let config = TaskConfig { max_time_steps: 10, ..TaskConfig::default() };
        let rules = EpisodeRules::new(&config, start, goal).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let ranges = hyq_ranges();
        let mut angles = mid_angles(&ranges);
        if at_limit {
            angles[2] = ranges[2].upper(); // lf_kfe at its (negative) upper limit
        }
        let position = if reached { goal } else { Point3::new(1.0, 0.0, 0.5) };
        let mut s = level_snapshot(if timeout { 10 } else { 9 }, start, position, &angles, &ranges);
        s.trunk_contact = fell;
        let o = rules.evaluate_step(&s).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let t = o.terminations;
        prop_assert_eq!(t.contains(Termination::Reached), reached);
        prop_assert_eq!(t.contains(Termination::JointLimit), at_limit);
        prop_assert_eq!(t.contains(Termination::Fell), fell);
        prop_assert_eq!(t.contains(Termination::Timeout), timeout);
        prop_assert_eq!(o.terminated(), reached || at_limit || fell);
        prop_assert_eq!(o.truncated(), timeout && !(reached || at_limit || fell));
        prop_assert_eq!(o.joint_at_limit.map(|h| h.joint), at_limit.then_some(2));
    }
}

#[test]
fn t_max_of_one_ends_the_episode_after_the_first_step() {
    let start = Point3::new(0.0, 0.0, 0.5);
    let config = TaskConfig {
        max_time_steps: 1,
        ..TaskConfig::default()
    };
    let rules = rules(&config, start, Point3::new(2.0, 0.0, 0.5));
    let ranges = hyq_ranges();
    let angles = mid_angles(&ranges);
    let o = step(
        &rules,
        &level_snapshot(1, start, Point3::new(0.1, 0.0, 0.5), &angles, &ranges),
    );
    assert!(o.truncated() && !o.terminated());
    assert_eq!(
        o.terminations.iter().collect::<Vec<_>>(),
        [Termination::Timeout]
    );
}

#[test]
fn the_reach_cube_includes_its_corners() {
    // At the origin C − G = C exactly, so one float beyond the face is outside.
    assert!(goal_reached(
        &Point3::new(0.25, 0.25, 0.25),
        &Point3::new(0.0, 0.0, 0.0),
        0.5
    ));
    assert!(!goal_reached(
        &Point3::new(0.25, 0.25, 0.25f64.next_up()),
        &Point3::new(0.0, 0.0, 0.0),
        0.5
    ));
}
