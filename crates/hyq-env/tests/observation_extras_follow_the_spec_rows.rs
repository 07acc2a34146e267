//! Invariant: `observation.extra` appends row groups after the spec's §3 rows, which stay the
//! spec's row for row; with none (the default) the observation is the spec's. The groups come in
//! one order whatever the order listed, named and bounded; the height scan is the ground's height
//! at points around the trunk in its heading frame minus the trunk's height, the goal vector
//! Rᵀ (G − C), the trunk velocity Rᵀ v and Rᵀ ω; records carry every row (docs/spec.md §7.11).

mod common;

use common::{config, rapier, reset, scripted, stand_action};
use hyq_env::{Env, StepRecord, observation_layout_for, observation_layout_of};
use hyq_physics::na::{UnitQuaternion, Vector3};
use hyq_rapier::RapierBackend;

const ALL: &str = r#"["trunk_velocity", "height_scan", "goal_vector"]"#;

#[test]
fn without_extras_the_layout_is_the_spec_table() {
    let model = hyq_physics::bundled::hyq();
    let spec = observation_layout_of(&model).unwrap_or_else(|e| panic!("{e}"));
    let default = observation_layout_for(&model, &config(&[])).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(default.rows(), spec.rows());
    assert!(default.groups().is_empty());
    assert_eq!(default.len(), 39);
    let mut env = scripted(&[]);
    reset(&mut env, 0);
    assert_eq!(env.observation().len(), 39);
}

#[test]
fn extras_come_after_the_spec_rows_in_a_fixed_order_named_and_bounded() {
    let model = hyq_physics::bundled::hyq();
    let spec = observation_layout_of(&model).unwrap_or_else(|e| panic!("{e}"));
    let listed = observation_layout_for(&model, &config(&[("observation.extra", ALL)]))
        .unwrap_or_else(|e| panic!("{e}"));
    let ordered = observation_layout_for(
        &model,
        &config(&[(
            "observation.extra",
            r#"["height_scan", "goal_vector", "trunk_velocity"]"#,
        )]),
    )
    .unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(listed.rows(), ordered.rows());
    assert_eq!(&listed.rows()[..39], spec.rows());
    assert_eq!(listed.spec_rows(), 0..39);
    let groups: Vec<(&str, &str, std::ops::Range<usize>)> = listed
        .groups()
        .iter()
        .map(|g| (g.name.as_ref(), g.unit, g.rows.clone()))
        .collect();
    // legged_gym's 17 x 11 points, then 3 and 6 rows.
    assert_eq!(
        groups,
        [
            ("height_scan", "m", 39..226),
            ("goal_vector", "m", 226..229),
            ("trunk_velocity", "m/s, rad/s", 229..235),
        ]
    );
    let names: Vec<&str> = listed.rows()[39..]
        .iter()
        .map(|r| r.name.as_ref())
        .collect();
    assert_eq!(names[0], "height_scan_00_00");
    assert_eq!(names[10], "height_scan_00_10");
    assert_eq!(names[186], "height_scan_16_10");
    assert_eq!(
        names[187..190],
        ["goal_vector_x", "goal_vector_y", "goal_vector_z"]
    );
    assert_eq!(names[190], "trunk_linvel_x");
    assert_eq!(names[195], "trunk_angvel_z");
    for (i, row) in listed.rows().iter().enumerate().skip(39) {
        assert_eq!(row.index, i);
        assert!(
            row.estimated && row.min < 0.0 && row.max == -row.min,
            "{row:?}"
        );
    }
    let mut env = scripted(&[("observation.extra", ALL)]);
    reset(&mut env, 0);
    assert_eq!(env.observation().len(), 235);
    // Flat ground: every scanned height is the trunk's depth below it.
    let z = env.state().trunk.pose.translation.z;
    assert!(env.observation()[39..226].iter().all(|h| *h == -z));
}

/// On rough ground, turned 30° and after some steps, each group is its definition, computed
/// here from the state, the goal and the ground.
#[test]
fn extras_are_the_height_scan_goal_vector_and_trunk_velocity_in_the_trunk_frame() {
    let mut env: Env<RapierBackend> = rapier(&[
        ("terrain.kind", "\"rough\""),
        ("terrain.amplitude_m", "0.05"),
        ("terrain.size_m", "[6.0, 6.0]"),
        ("reset.yaw_deg", "30"),
        ("goal.distance_m", "2.5"),
        ("observation.extra", ALL),
    ]);
    reset(&mut env, 4);
    let velocity = &env.observation()[229..235];
    assert!(velocity.iter().all(|v| *v == 0.0), "{velocity:?}");
    let action = stand_action(&env);
    for _ in 0..5 {
        env.step(&action).unwrap_or_else(|e| panic!("{e}"));
    }
    let obs = env.observation().to_vec();
    let trunk = env.state().trunk;
    let c = trunk.pose.translation.vector;
    let to_trunk = trunk.pose.rotation.inverse();
    // The heading frame is the trunk's yaw now (it settles within a degree of the 30° given).
    let (_, _, yaw) = trunk.pose.rotation.euler_angles();
    assert!((yaw - 30f64.to_radians()).abs() < 0.02, "yaw {yaw}");
    let heading = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw);
    let terrain = env.terrain().clone();
    let mut row = 39;
    for i in 0..17 {
        for j in 0..11 {
            let p = heading * Vector3::new(-0.8 + 0.1 * i as f64, -0.5 + 0.1 * j as f64, 0.0);
            let want = terrain.height_at(c.x + p.x, c.y + p.y) - c.z;
            assert!(
                (obs[row] - want).abs() < 1e-12,
                "scan {i} {j}: {} vs {want}",
                obs[row]
            );
            row += 1;
        }
    }
    let g = env.info().goal;
    let goal = to_trunk * (Vector3::new(g[0], g[1], g[2]) - c);
    let v = to_trunk * trunk.linvel;
    let w = to_trunk * trunk.angvel;
    let want: Vec<f64> = goal
        .iter()
        .chain(v.iter())
        .chain(w.iter())
        .copied()
        .collect();
    assert_eq!(obs[226..235], want[..]);
    assert!(v.norm() > 0.0, "the trunk did not move at all");
    // A record carries every row.
    let record = StepRecord::from_env(&env, &action);
    let json = serde_json::to_string(&record).unwrap_or_else(|e| panic!("{e}"));
    let back: StepRecord<'_> = serde_json::from_str(&json).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(back.obs.len(), 235);
}
