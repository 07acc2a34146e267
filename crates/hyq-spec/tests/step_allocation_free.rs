//! Invariant: the per-step hot paths allocate nothing. `EpisodeRules::evaluate_step` and
//! `ObservationLayout::write` run every env step; this test counts the allocations made on its
//! own thread around 1000 of them (allocation-counter's global allocator counts per thread, so
//! the test harness's other threads cannot add to the count).

use hyq_spec::nalgebra::{Point3, UnitQuaternion, Vector3};
use hyq_spec::{
    Clipping, EpisodeRules, HeightPenalty, Observation, ObservationLayout, RobotDescription,
    StepSnapshot, TaskConfig,
};
#[test]
fn evaluating_a_step_and_writing_an_observation_allocate_nothing() {
    let robot = RobotDescription::hyq_spec();
    let layout = ObservationLayout::new(&robot);
    let start = Point3::new(0.0, 0.0, 0.62);
    let config = TaskConfig {
        base_rew_scaling: Some(1.0),
        norm_rew_scaling: Some(10.0),
        reach_bounds_penalty: 1.0,
        fall_penalty: 1.0,
        height_penalty: Some(HeightPenalty {
            nominal_height_m: 0.62,
            tolerance_m: 0.1,
            rate_per_m: 2.0,
        }),
        ..TaskConfig::default()
    };
    let rules = EpisodeRules::new(&config, start, Point3::new(5.0, 0.0, 0.62))
        .unwrap_or_else(|e| panic!("{e}"));
    let mut angles: Vec<f64> = robot.joint_ranges().iter().map(|r| r.lower()).collect();
    let speeds = vec![1.0; 12];
    let feet = [true, false, false, true];
    let mut out = [0.0f32; 39];

    let mut total = 0.0;
    let counted = allocation_counter::measure(|| {
        for t in 1..=1000u64 {
            angles[0] = -1.0 + 1e-3 * t as f64; // sometimes at a limit, sometimes not
            let position = Point3::new(0.005 * t as f64, 0.0, 0.62);
            let snapshot = StepSnapshot {
                step: t,
                previous_position: Point3::new(0.005 * (t - 1) as f64, 0.0, 0.62),
                position,
                orientation: UnitQuaternion::from_euler_angles(0.0, 0.01, 1e-4 * t as f64),
                joint_angles: &angles,
                joint_ranges: robot.joint_ranges(),
                trunk_contact: t % 7 == 0,
            };
            let outcome = rules
                .evaluate_step(&snapshot)
                .unwrap_or_else(|e| panic!("{e}"));
            total += outcome.reward.total;
            let obs = Observation {
                joint_angles: &angles,
                joint_speeds: &speeds,
                foot_contacts: &feet,
                trunk_contact: snapshot.trunk_contact,
                trunk_rotation: snapshot.orientation,
                trunk_acceleration: Vector3::new(0.0, 0.0, 0.1),
                trunk_position: position,
            };
            layout
                .write(&obs, Clipping::ToDeclaredBounds, &mut out)
                .unwrap_or_else(|e| panic!("{e}"));
        }
    });
    assert!(total.is_finite());
    assert_eq!(counted.count_total, 0, "{counted:?} in 1000 steps");
}
