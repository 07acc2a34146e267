//! Invariant: the §3 observation has one table. The layout built from HyQ's description (its
//! joint list with the spec's limits, its feet and its trunk) equals the spec's 39-row table row
//! by row; its named index ranges cover each block exactly once in the table's order; and
//! `write` puts each named field in its rows, unclipped unless asked, as f64 or f32, without
//! assuming HyQ's joint or foot count.

use hyq_spec::nalgebra::{Point3, UnitQuaternion, Vector3};
use hyq_spec::nomenclature::HyqJoint;
use hyq_spec::observation::trunk_acceleration;
use hyq_spec::{
    Clipping, JointDescription, JointRange, Observation, ObservationError, ObservationLayout,
    RobotDescription, SPEC_TABLE, TrunkDescription,
};
use proptest::prelude::*;

/// HyQ's joints with the §3 table's limits, typed in here from the spec (not read from the
/// table), in the spec order.
fn hyq_from_the_spec_text() -> RobotDescription {
    let limits: [(&str, f64, f64); 12] = [
        ("lf_haa", -1.22173, 0.436332),
        ("lf_hfe", -0.872665, 1.22173),
        ("lf_kfe", -2.44346, -0.349066),
        ("lh_haa", -1.22173, 0.436332),
        ("lh_hfe", -1.22173, 0.872665),
        ("lh_kfe", 0.349066, 2.44346),
        ("rf_haa", -1.22173, 0.436332),
        ("rf_hfe", -0.872665, 1.22173),
        ("rf_kfe", -2.44346, -0.349066),
        ("rh_haa", -1.22173, 0.436332),
        ("rh_hfe", -1.22173, 0.872665),
        ("rh_kfe", 0.349066, 2.44346),
    ];
    let joints = limits
        .iter()
        .zip(HyqJoint::ALL)
        .map(|(&(name, lower, upper), joint)| {
            assert_eq!(name, joint.name(), "spec order");
            let range = JointRange::new(lower, upper).unwrap_or_else(|e| panic!("{name}: {e}"));
            JointDescription {
                name: name.to_owned(),
                range,
                velocity_limit: 12.0,
            }
        })
        .collect();
    let feet = ["lf", "lh", "rf", "rh"].map(String::from).to_vec();
    RobotDescription::new(joints, feet, TrunkDescription::spec()).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn hyq_layout_equals_the_spec_table_row_by_row() {
    let layout = ObservationLayout::new(&hyq_from_the_spec_text());
    assert_eq!(layout.len(), 39);
    for (built, printed) in layout.rows().iter().zip(SPEC_TABLE.iter()) {
        assert_eq!(built, printed);
    }
    assert_eq!(layout.rows(), &SPEC_TABLE[..]);
    assert_eq!(
        ObservationLayout::new(&RobotDescription::hyq_spec()),
        layout
    );
}

#[test]
fn the_spec_table_is_indexed_and_flags_only_rows_33_to_38_as_estimates() {
    for (i, row) in SPEC_TABLE.iter().enumerate() {
        assert_eq!(row.index, i);
        assert_eq!(row.estimated, (33..=38).contains(&i), "{}", row.name);
        assert!(row.min < row.max, "{}", row.name);
    }
}

#[test]
fn named_ranges_partition_the_rows_in_table_order() {
    let layout = ObservationLayout::new(&RobotDescription::hyq_spec());
    assert_eq!(layout.joint_angles(), 0..12);
    assert_eq!(layout.joint_speeds(), 12..24);
    assert_eq!(layout.foot_contacts(), 24..28);
    assert_eq!(layout.trunk_contact(), 28);
    assert_eq!(layout.trunk_rotation(), 29..33);
    assert_eq!(layout.trunk_acceleration(), 33..36);
    assert_eq!(layout.trunk_position(), 36..39);
    let name = |i: usize| layout.rows()[i].name.to_string();
    assert!(layout.joint_angles().all(|i| name(i).ends_with("_angle")));
    assert!(layout.joint_speeds().all(|i| name(i).ends_with("_speed")));
    assert!(
        layout
            .foot_contacts()
            .all(|i| name(i).ends_with("_contact_flag"))
    );
    assert_eq!(name(layout.trunk_contact()), "trunk_contact_flag");
    assert_eq!(
        layout.trunk_rotation().map(name).collect::<Vec<_>>(),
        [
            "trunk_rotation_w",
            "trunk_rotation_x",
            "trunk_rotation_y",
            "trunk_rotation_z"
        ]
    );
}

/// A robot of `joints` joints and `feet` feet with made-up names and limits.
fn other_robot(joints: usize, feet: usize) -> RobotDescription {
    let joints = (0..joints)
        .map(|i| JointDescription {
            name: format!("j{i}"),
            range: JointRange::new(-1.0 - i as f64, 1.0 + i as f64)
                .unwrap_or_else(|e| panic!("{e}")),
            velocity_limit: 5.0 + i as f64,
        })
        .collect();
    let feet = (0..feet).map(|i| format!("foot{i}")).collect();
    RobotDescription::new(
        joints,
        feet,
        TrunkDescription {
            name: "base".into(),
            ..TrunkDescription::spec()
        },
    )
    .unwrap_or_else(|e| panic!("{e}"))
}

/// Writes an observation whose every value identifies its field and element, and checks each
/// named range holds exactly that field.
fn check_write_order(robot: &RobotDescription) {
    let layout = ObservationLayout::new(robot);
    let n = robot.joints().len();
    let angles: Vec<f64> = (0..n).map(|i| 0.01 * i as f64).collect();
    let speeds: Vec<f64> = (0..n).map(|i| 100.0 + i as f64).collect();
    let feet: Vec<bool> = (0..robot.feet().len()).map(|i| i % 2 == 0).collect();
    let q = UnitQuaternion::from_euler_angles(0.1, -0.2, 0.3);
    let obs = Observation {
        joint_angles: &angles,
        joint_speeds: &speeds,
        foot_contacts: &feet,
        trunk_contact: true,
        trunk_rotation: q,
        trunk_acceleration: Vector3::new(-60.0, 7.0, 8.0),
        trunk_position: Point3::new(11.0, -12.0, 1.5),
    };
    let mut out = vec![f64::NAN; layout.len()];
    assert_eq!(layout.write(&obs, Clipping::Off, &mut out), Ok(()));
    assert_eq!(&out[layout.joint_angles()], &angles[..]);
    assert_eq!(&out[layout.joint_speeds()], &speeds[..]);
    let flags: Vec<f64> = feet.iter().map(|f| if *f { 1.0 } else { 0.0 }).collect();
    assert_eq!(&out[layout.foot_contacts()], &flags[..]);
    assert_eq!(out[layout.trunk_contact()], 1.0);
    assert_eq!(&out[layout.trunk_rotation()], &[q.w, q.i, q.j, q.k]);
    assert_eq!(
        &out[layout.trunk_acceleration()],
        &[-60.0, 7.0, 8.0],
        "not clipped by default"
    );
    assert_eq!(
        &out[layout.trunk_position()],
        &[11.0, -12.0, 1.5],
        "not clipped by default"
    );

    // Clipped: every value within its row's bounds, and the out-of-bound ones at the bound.
    let mut clipped = vec![0.0f32; layout.len()];
    assert_eq!(
        layout.write(&obs, Clipping::ToDeclaredBounds, &mut clipped),
        Ok(())
    );
    for (value, row) in clipped.iter().zip(layout.rows()) {
        assert!(
            (row.min as f32..=row.max as f32).contains(value),
            "{} = {value}",
            row.name
        );
    }
    assert_eq!(clipped[layout.trunk_acceleration().start], -50.0);
    assert_eq!(clipped[layout.trunk_position().start], 10.0);
    assert_eq!(clipped[layout.trunk_position().end - 1], 1.0);
    assert_eq!(
        clipped[layout.joint_speeds().start],
        robot.joints()[0].velocity_limit as f32
    );

    // f32 is the f64 rounded to nearest.
    let mut single = vec![0.0f32; layout.len()];
    assert_eq!(layout.write(&obs, Clipping::Off, &mut single), Ok(()));
    for (s, d) in single.iter().zip(&out) {
        assert_eq!(*s, *d as f32);
    }
}

#[test]
fn write_puts_each_field_in_its_rows() {
    check_write_order(&RobotDescription::hyq_spec());
}

proptest! {
    #[test]
    fn layouts_follow_the_robot_not_hyq(joints in 1usize..20, feet in 0usize..8) {
        let robot = other_robot(joints, feet);
        let layout = ObservationLayout::new(&robot);
        prop_assert_eq!(layout.len(), 2 * joints + feet + 11);
        prop_assert_eq!(&layout.rows()[0].name, "j0_angle");
        prop_assert_eq!(&layout.rows()[layout.trunk_contact()].name, "base_contact_flag");
        prop_assert_eq!(layout.rows()[joints].max, 5.0);
        check_write_order(&robot);
    }
}

#[test]
fn mismatched_or_non_finite_observations_are_errors() {
    let robot = RobotDescription::hyq_spec();
    let layout = ObservationLayout::new(&robot);
    let angles = [0.0; 12];
    let obs = Observation {
        joint_angles: &angles,
        joint_speeds: &angles,
        foot_contacts: &[false; 4],
        trunk_contact: false,
        trunk_rotation: UnitQuaternion::identity(),
        trunk_acceleration: Vector3::zeros(),
        trunk_position: Point3::new(0.0, 0.0, f64::NAN),
    };
    let mut out = [0.0f32; 39];
    assert_eq!(
        layout
            .write(&obs, Clipping::Off, &mut out)
            .map_err(|e| e.to_string()),
        Err("observation row 38 (trunk_position_z) is NaN: observations must be finite".to_owned())
    );
    let short = Observation {
        foot_contacts: &[false; 3],
        ..obs
    };
    assert_eq!(
        layout.write(&short, Clipping::Off, &mut out),
        Err(ObservationError::Length {
            field: "foot_contacts",
            expected: 4,
            got: 3
        })
    );
    let mut small = [0.0f64; 38];
    let fine = Observation {
        trunk_position: Point3::origin(),
        ..obs
    };
    assert_eq!(
        layout.write(&fine, Clipping::Off, &mut small),
        Err(ObservationError::Length {
            field: "output buffer",
            expected: 39,
            got: 38
        })
    );
}

#[test]
fn acceleration_is_the_velocity_change_over_the_env_step() {
    let a = trunk_acceleration(
        &Vector3::new(1.0, 0.0, 0.0),
        &Vector3::new(1.1, 0.0, -0.2),
        0.01,
    );
    let a = a.unwrap_or_else(|e| panic!("{e}"));
    assert!((a - Vector3::new(10.0, 0.0, -20.0)).norm() < 1e-9);
    assert_eq!(
        trunk_acceleration(&Vector3::zeros(), &Vector3::zeros(), 0.01),
        Ok(Vector3::zeros())
    );
    for dt in [0.0, -0.01, f64::NAN] {
        assert!(matches!(
            trunk_acceleration(&Vector3::zeros(), &Vector3::zeros(), dt),
            Err(ObservationError::TimeStep { .. })
        ));
    }
}
