//! The field's robots derived from example-robot-data 6.0.0 (`assets/{a1,go1_urdf,anymal_b,
//! laikago}/`) load through their profiles as a user's URDF robot does, and their profiles'
//! numbers hold against their URDFs: the masses after lumping, the standing pose inside every
//! joint's range, the spawn height leaving the feet (and only the feet) 1 mm above the ground,
//! and a trot table naming a hip and a knee per leg.

use hyq_physics::RobotModel;
use hyq_physics::na::Isometry3;

/// (directory, total mass (kg) of every URDF link, feet-sphere bottoms below the trunk frame
/// at the standing pose (m), as each profile's comment states).
const ROBOTS: [(&str, f64, f64); 4] = [
    ("a1", 13.741, 0.265713),
    ("go1_urdf", 13.100529, 0.273826),
    ("anymal_b", 30.475390, 0.488097),
    ("laikago", 25.433, 0.333642),
];

fn load(dir: &str) -> RobotModel {
    let path = format!(
        "{}/../../assets/{dir}/profile.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    RobotModel::load(&path).unwrap_or_else(|e| panic!("{e}"))
}

#[test]
fn each_loads_with_its_mass_and_twelve_joints_and_four_feet() {
    for (dir, mass, _) in ROBOTS {
        let model = load(dir);
        assert_eq!(model.name(), dir);
        assert_eq!((model.num_joints(), model.num_feet()), (12, 4), "{dir}");
        assert!(
            (model.total_mass() - mass).abs() < 1e-5,
            "{dir}: {} kg",
            model.total_mass()
        );
    }
}

#[test]
fn standing_poses_are_inside_the_ranges() {
    for (dir, _, _) in ROBOTS {
        let model = load(dir);
        for (j, q) in model.joints().iter().zip(model.standing_pose()) {
            assert!(
                j.lower < *q && *q < j.upper,
                "{dir}: {} at {q} outside [{}, {}]",
                j.name,
                j.lower,
                j.upper
            );
        }
    }
}

#[test]
fn spawn_leaves_the_feet_and_only_the_feet_one_millimetre_up() {
    for (dir, _, depth) in ROBOTS {
        let model = load(dir);
        let mut poses = vec![Isometry3::identity(); model.num_links()];
        let spawn = model.spawn_state();
        model
            .link_poses(&spawn.trunk.pose, &spawn.q, &mut poses)
            .expect("sizes match");
        for f in 0..model.num_feet() {
            let gap = model.tracked_lowest_z(f, &poses);
            assert!((gap - 0.001).abs() < 1e-4, "{dir} foot {f}: {gap} m");
            assert!(
                (model.spawn_height() - gap - depth).abs() < 1e-6,
                "{dir}: feet {depth} m down"
            );
        }
        assert!(
            (model.lowest_z(&poses) - 0.001).abs() < 1e-4,
            "{dir}: only the feet lowest"
        );
    }
}

#[test]
fn each_carries_a_trot_with_a_hip_and_a_knee_per_leg() {
    for (dir, _, _) in ROBOTS {
        let model = load(dir);
        let gait = model
            .gait()
            .unwrap_or_else(|| panic!("{dir} has no [gait]"));
        assert_eq!(gait.legs.len(), 4, "{dir}");
        for leg in &gait.legs {
            assert!(model.joints()[leg.hip].name.ends_with("_hfe"), "{dir}");
            assert!(model.joints()[leg.knee].name.ends_with("_kfe"), "{dir}");
        }
    }
}
