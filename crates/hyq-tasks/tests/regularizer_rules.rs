//! The regularisers of `[regularizers]`: each gait term is the velocity task's own function of
//! numbers, `orientation` is the trunk's tilt, the goal terms measure the heading and the line to
//! the goal, their sum is Σ s·r·Δt over the terms that are on and nothing else, off is exactly
//! nothing, the preset is legged_gym's, bad keys are named, and a report writes the terms that
//! are on and reads them back.

use hyq_tasks::observation::projected_gravity;
use hyq_tasks::regularizers::{REGULARIZER_COUNT, RegularizerSnapshot, reward, values};
use hyq_tasks::step::AirTime;
use hyq_tasks::terms;
use hyq_tasks::{
    GoalGeometry, REGULARIZER_NAMES, RegularizerConfig, RegularizerPreset, RegularizerTerms,
    ReportedRegularizers,
};
use nalgebra::{UnitQuaternion, Vector3};
use proptest::prelude::*;

fn finite() -> impl Strategy<Value = f64> {
    -100.0..100.0f64
}

fn scales() -> impl Strategy<Value = [f64; REGULARIZER_COUNT]> {
    proptest::array::uniform11(prop_oneof![Just(0.0), -10.0..10.0f64])
}

proptest! {
    /// g_x² + g_y² of the trunk's gravity is 1 − cos² of its tilt (the angle between its z axis
    /// and the world's): 0 level, 1 on its side, in [0, 1], and blind to yaw.
    #[test]
    fn orientation_is_the_squared_sine_of_the_tilt(
        roll in -4.0..4.0f64, pitch in -4.0..4.0f64, yaw in -4.0..4.0f64, turn in -4.0..4.0f64,
    ) {
        let r = UnitQuaternion::from_euler_angles(roll, pitch, yaw);
        let v = terms::orientation(projected_gravity(&r));
        let up = (r * Vector3::z()).z;
        prop_assert!((-1e-12..=1.0 + 1e-12).contains(&v));
        prop_assert!((v - (1.0 - up * up)).abs() < 1e-12);
        let turned = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), turn) * r;
        prop_assert!((terms::orientation(projected_gravity(&turned)) - v).abs() < 1e-12);
        prop_assert_eq!(terms::orientation(projected_gravity(&UnitQuaternion::from_euler_angles(0.0, 0.0, yaw))), 0.0);
        let side = UnitQuaternion::from_euler_angles(std::f64::consts::FRAC_PI_2, 0.0, yaw);
        prop_assert!((terms::orientation(projected_gravity(&side)) - 1.0).abs() < 1e-12);
    }

    /// (h − h₀)² is 0 exactly at the target, positive elsewhere, symmetric about it.
    #[test]
    fn base_height_is_the_squared_distance_to_the_target(h in 0.0..2.0f64, target in 0.01..2.0f64) {
        let v = terms::base_height(h, target);
        prop_assert!(v >= 0.0 && v.is_finite());
        prop_assert_eq!(v == 0.0, h == target);
        let mirrored = terms::base_height(2.0 * target - h, target);
        prop_assert!((v - mirrored).abs() <= 1e-12 * (1.0 + v), "{v} vs {mirrored}");
        prop_assert_eq!(terms::base_height(target, target), 0.0);
    }

    /// The heading term is the angle the trunk must turn through to face the goal: 0 facing
    /// it, π facing away, the same either side, unchanged by how far the goal is along the
    /// bearing or how long the heading vector is.
    #[test]
    fn goal_heading_is_the_angle_to_the_bearing(
        trunk in proptest::array::uniform2(-100.0..100.0f64),
        bearing in -3.1..3.1f64,
        off in -3.1..3.1f64,
        distance in 0.01..100.0f64,
        length in 0.01..1.0f64,
    ) {
        let goal = [trunk[0] + distance * bearing.cos(), trunk[1] + distance * bearing.sin()];
        let facing = [length * bearing.cos(), length * bearing.sin()];
        let turned = [length * (bearing + off).cos(), length * (bearing + off).sin()];
        let mirrored = [length * (bearing - off).cos(), length * (bearing - off).sin()];
        let v = terms::goal_heading(trunk, turned, goal);
        prop_assert!((0.0..=std::f64::consts::PI).contains(&v));
        prop_assert!((v - off.abs()).abs() < 1e-9, "{v} vs {off}");
        prop_assert!((v - terms::goal_heading(trunk, mirrored, goal)).abs() < 1e-9);
        prop_assert!(terms::goal_heading(trunk, facing, goal) < 1e-9);
        let away = [-facing[0], -facing[1]];
        prop_assert!((terms::goal_heading(trunk, away, goal) - std::f64::consts::PI).abs() < 1e-9);
        // No direction to miss: a trunk on the goal, or a heading with no horizontal part.
        prop_assert_eq!(terms::goal_heading(trunk, turned, trunk), 0.0);
        prop_assert_eq!(terms::goal_heading(trunk, [0.0, 0.0], goal), 0.0);
    }

    /// The line term is the distance off the start–goal line: 0 on it (before the goal, past
    /// it or behind the start), the sideways offset for a line along x, the same on either side,
    /// and unchanged by sliding the trunk along the line.
    #[test]
    fn goal_line_is_the_distance_off_the_line(
        start in proptest::array::uniform2(-50.0..50.0f64),
        direction in -3.2..3.2f64,
        k in 0.1..50.0f64,
        along in -60.0..60.0f64,
        side in -5.0..5.0f64,
    ) {
        let (c, s) = (direction.cos(), direction.sin());
        let goal = [start[0] + k * c, start[1] + k * s];
        let at = |a: f64, d: f64| [start[0] + a * c - d * s, start[1] + a * s + d * c];
        let v = terms::goal_line(start, goal, at(along, side));
        prop_assert!((v - side.abs()).abs() < 1e-9, "{v} vs {side}");
        prop_assert!((terms::goal_line(start, goal, at(along, -side)) - v).abs() < 1e-9);
        prop_assert!((terms::goal_line(start, goal, at(along + 7.0, side)) - v).abs() < 1e-9);
        prop_assert!(terms::goal_line(start, goal, at(along, 0.0)) < 1e-9);
        let along_x = terms::goal_line([0.0, 0.0], [k, 0.0], [along, side]);
        prop_assert!((along_x - side.abs()).abs() <= 1e-12, "{along_x} vs {side}");
        // A goal straight above the start: the horizontal distance from the start.
        let p = at(along, side);
        prop_assert_eq!(terms::goal_line(start, start, p), (p[0] - start[0]).hypot(p[1] - start[1]));
    }

    /// The approach is the line distance's fall over the step: along any path from the start
    /// (on the line) its sum times Δt is minus the final distance, and it is positive exactly
    /// on the steps that close on the line.
    #[test]
    fn goal_line_approach_sums_to_the_final_distance(
        path in proptest::collection::vec(proptest::array::uniform2(-2.0..2.0f64), 1..50),
        dt in 0.001..0.1f64,
    ) {
        let (start, goal) = ([0.0, 0.0], [5.0, 0.0]);
        let mut previous = 0.0;
        let mut sum = 0.0;
        for p in &path {
            let now = terms::goal_line(start, goal, *p);
            let r = terms::goal_line_approach(previous, now, dt);
            prop_assert_eq!(r > 0.0, now < previous);
            sum += r * dt;
            previous = now;
        }
        prop_assert!((sum + previous).abs() < 1e-9, "{sum} vs {previous}");
    }

    /// The collision term counts the bodies in contact.
    #[test]
    fn collision_counts_the_bodies_in_contact(flags in proptest::collection::vec(any::<bool>(), 0..8)) {
        let n = flags.iter().filter(|f| **f).count();
        prop_assert_eq!(terms::collision(&flags), n as f64);
    }

    /// The sum is Σ s·r·Δt over the terms whose scale is not 0, whatever the others hold
    /// (not even a NaN of an off term reaches it).
    #[test]
    fn the_sum_is_the_scaled_terms_that_are_on(
        s in scales(),
        v in proptest::array::uniform11(finite()),
        dt in 0.001..0.1f64,
    ) {
        let scales = RegularizerTerms::from_array(s);
        let mut poisoned = v;
        for (k, scale) in s.iter().enumerate() {
            if *scale == 0.0 {
                poisoned[k] = f64::NAN;
            }
        }
        let got = reward(&scales, &RegularizerTerms::from_array(poisoned), dt);
        let mut want = -0.0; // the empty sum, which adds nothing to any number
        for k in 0..REGULARIZER_COUNT {
            if s[k] != 0.0 {
                want += s[k] * v[k] * dt;
            }
        }
        prop_assert!(got.is_finite());
        prop_assert_eq!(got.to_bits(), want.to_bits());
    }

    /// Every value is finite for finite inputs, and each is the velocity task's function of the
    /// same numbers.
    #[test]
    fn values_are_the_velocity_tasks_functions(
        a in proptest::array::uniform12(-1.0..1.0f64),
        a0 in proptest::array::uniform12(-1.0..1.0f64),
        tau in proptest::array::uniform12(-150.0..150.0f64),
        qd in proptest::array::uniform12(-50.0..50.0f64),
        qd0 in proptest::array::uniform12(-50.0..50.0f64),
        air in proptest::array::uniform4(prop_oneof![Just(0.0), 0.0..2.0f64]),
        vel in proptest::array::uniform4([-3.0..3.0f64, -3.0..3.0]),
        feet in proptest::array::uniform4(any::<bool>()),
        h in 0.0..1.5f64,
        trunk in any::<bool>(),
        xy in proptest::array::uniform4(-100.0..100.0f64),
        yaw in -4.0..4.0f64,
        previous_line in 0.0..100.0f64,
        tilt in proptest::array::uniform3(-4.0..4.0f64),
    ) {
        let gravity = projected_gravity(&UnitQuaternion::from_euler_angles(tilt[0], tilt[1], tilt[2]));
        let goal = GoalGeometry {
            trunk: [xy[0], xy[1]],
            heading: [yaw.cos(), yaw.sin()],
            start: [0.0, 0.0],
            goal: [xy[2], xy[3]],
        };
        let config = RegularizerConfig { preset: RegularizerPreset::LeggedGym, ..Default::default() };
        let scales = config.resolve(0.6);
        let dt = 0.01;
        let v = values(&scales, &RegularizerSnapshot {
            action: &a,
            previous_action: &a0,
            torques: &tau,
            joint_speeds: &qd,
            previous_joint_speeds: &qd0,
            air_at_touchdown: &air,
            foot_velocity_xy: &vel,
            foot_contacts: &feet,
            base_height: h,
            projected_gravity: gravity,
            penalised_contacts: &[trunk],
            goal,
            previous_goal_line: previous_line,
            env_dt: dt,
        });
        prop_assert!(v.to_array().iter().all(|x| x.is_finite()));
        prop_assert_eq!(v.action_rate, terms::action_rate(&a, &a0));
        prop_assert_eq!(v.torques, terms::torques(&tau));
        prop_assert_eq!(v.joint_acc, terms::joint_acc(&qd, &qd0, dt));
        prop_assert_eq!(v.feet_air_time, terms::feet_air_time(&air, 0.5, true));
        prop_assert_eq!(v.foot_slip, terms::foot_slip(&vel, &feet, true));
        prop_assert_eq!(v.base_height, terms::base_height(h, 0.6));
        prop_assert_eq!(v.collision, f64::from(u8::from(trunk)));
        prop_assert_eq!(v.goal_heading, terms::goal_heading(goal.trunk, goal.heading, goal.goal));
        prop_assert_eq!(v.goal_line, terms::goal_line(goal.start, goal.goal, goal.trunk));
        prop_assert_eq!(v.goal_line_approach, terms::goal_line_approach(previous_line, v.goal_line, dt));
        prop_assert_eq!(v.orientation, terms::orientation(gravity));
        prop_assert!(reward(&scales.terms, &v, dt).is_finite());
    }

    /// A report writes the terms that are on, in order, and reads back to itself.
    #[test]
    fn a_report_writes_the_terms_that_are_on(
        v in proptest::array::uniform11(finite()),
        on in proptest::array::uniform11(any::<bool>()),
    ) {
        let mut values = v;
        for k in 0..REGULARIZER_COUNT {
            if !on[k] {
                values[k] = 0.0;
            }
        }
        let report = ReportedRegularizers { values: RegularizerTerms::from_array(values), on };
        let json = serde_json_like(&report);
        let names: Vec<&str> = report.iter().map(|(n, _)| n).collect();
        let want: Vec<&str> = REGULARIZER_NAMES.iter().zip(on).filter(|(_, o)| *o).map(|(n, _)| *n).collect();
        prop_assert_eq!(&names, &want);
        let back: ReportedRegularizers = toml::from_str(&json).map_err(|e| TestCaseError::fail(e.to_string()))?;
        prop_assert_eq!(back, report);
    }
}

/// The report as TOML text (the crate's dev-dependencies have no JSON writer; the map is the
/// same either way).
fn serde_json_like(report: &ReportedRegularizers) -> String {
    toml::to_string(report).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn off_by_default_and_the_preset_is_legged_gyms() {
    let off = RegularizerConfig::default();
    assert!(off.is_off() && off.is_default());
    assert_eq!(off.scales(), RegularizerTerms::default());
    let lg = RegularizerConfig {
        preset: RegularizerPreset::LeggedGym,
        ..Default::default()
    };
    assert!(!lg.is_off());
    // legged_gym's LeggedRobotCfg.rewards.scales.
    let s = lg.scales();
    assert_eq!(
        [
            s.action_rate,
            s.torques,
            s.joint_acc,
            s.feet_air_time,
            s.collision
        ],
        [-0.01, -1.0e-5, -2.5e-7, 1.0, -1.0]
    );
    assert_eq!([s.foot_slip, s.base_height], [0.0, 0.0]);
    // A key over the preset; 0 turns a term off; every term 0 is off.
    let over = RegularizerConfig {
        preset: RegularizerPreset::LeggedGym,
        torques: Some(0.0),
        foot_slip: Some(-0.1),
        ..Default::default()
    };
    assert_eq!(over.scales().torques, 0.0);
    assert_eq!(over.scales().foot_slip, -0.1);
    let zeros = RegularizerConfig {
        action_rate: Some(0.0),
        ..Default::default()
    };
    assert!(zeros.is_off() && !zeros.is_default());
    // The settings' defaults: legged_gym's threshold, the robot's standing height.
    let r = off.resolve(0.5895);
    assert_eq!(
        (r.feet_air_time_threshold_s, r.base_height_target_m),
        (0.5, 0.5895)
    );
}

#[test]
fn bad_keys_are_named() {
    let cases: [(&str, RegularizerConfig); 5] = [
        (
            "regularizers.torques",
            RegularizerConfig {
                torques: Some(f64::NAN),
                ..Default::default()
            },
        ),
        (
            "regularizers.action_rate",
            RegularizerConfig {
                action_rate: Some(-2.0e4),
                ..Default::default()
            },
        ),
        (
            "regularizers.collision",
            RegularizerConfig {
                collision: Some(f64::INFINITY),
                ..Default::default()
            },
        ),
        (
            "regularizers.feet_air_time_threshold_s",
            RegularizerConfig {
                feet_air_time_threshold_s: Some(-0.1),
                ..Default::default()
            },
        ),
        (
            "regularizers.base_height_target_m",
            RegularizerConfig {
                base_height_target_m: Some(0.0),
                ..Default::default()
            },
        ),
    ];
    for (key, config) in cases {
        let e = config
            .validate()
            .err()
            .unwrap_or_else(|| panic!("{key} accepted"));
        assert_eq!(e.key, key);
        assert!(!e.to_string().contains('\n'), "{e}");
    }
    let unknown = toml::from_str::<RegularizerConfig>("dof_acc = -2.5e-7");
    assert!(unknown.is_err(), "an unknown key is refused");
    let unknown_term = toml::from_str::<ReportedRegularizers>("stumble = 1.0");
    assert!(unknown_term.is_err(), "an unknown term is refused");
}

#[test]
fn feet_air_time_counts_a_touchdown_after_time_in_the_air() {
    // One foot lifted for 0.6 s then put down, at Δt 0.01: its touchdown pays 0.6 − 0.5.
    let mut air = AirTime::new(1);
    let mut paid = Vec::new();
    for step in 0..70 {
        let contact = !(1..=59).contains(&step);
        let at = air.update(&[contact], 0.01)[0];
        paid.push(terms::feet_air_time(&[at], 0.5, true));
    }
    let total: f64 = paid.iter().sum();
    assert!((total - 0.1).abs() < 1e-9, "{total}");
    assert_eq!(paid.iter().filter(|p| **p != 0.0).count(), 1);
}

#[test]
fn foot_velocity_is_the_displacement_over_the_step() {
    let mut feet = hyq_tasks::FootVelocity::new(2);
    feet.reset([[1.0, 2.0], [0.0, 0.0]]);
    assert_eq!(feet.velocity(), &[[0.0, 0.0], [0.0, 0.0]]);
    let v = feet.update([[1.5, 1.0], [0.0, 0.0]], 0.5).to_vec();
    assert_eq!(v, [[1.0, -2.0], [0.0, 0.0]]);
    let v = feet.update([[1.5, 1.0], [0.25, 0.0]], 0.5).to_vec();
    assert_eq!(v, [[0.0, 0.0], [0.5, 0.0]]);
}
