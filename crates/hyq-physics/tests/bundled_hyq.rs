//! The bundled HyQ (`assets/hyq/`) is the robot the spec describes: joints in the spec's §3
//! order with the §3 limits and speed range, feet lf, lh, rf, rh, upstream's mass and standing
//! pose, and a spawn state that leaves the feet, and only the feet, about 1 mm above the ground.

use hyq_physics::bundled::{self, hyq};
use hyq_physics::na::Isometry3;
use hyq_physics::{RobotModel, Shape};

/// The spec's §3 table: joint name, min and max angle (rad); speeds are ±12 rad/s.
const SPEC_JOINTS: [(&str, f64, f64); 12] = [
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

fn spawn_poses(model: &RobotModel) -> Vec<Isometry3<f64>> {
    let s = model.spawn_state();
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    model
        .link_poses(&s.trunk.pose, &s.q, &mut poses)
        .expect("forward kinematics");
    poses
}

#[test]
fn joints_follow_the_spec_table() {
    let model = hyq();
    assert_eq!(model.num_joints(), SPEC_JOINTS.len());
    for (j, (name, lo, hi)) in model.joints().iter().zip(SPEC_JOINTS) {
        assert_eq!(j.name, name);
        assert_eq!(j.urdf_name, format!("{name}_joint"));
        // The spec prints 6 significant digits; the URDF has upstream's 12.
        assert!(
            (j.lower - lo).abs() < 1e-5,
            "{name} lower {} vs {lo}",
            j.lower
        );
        assert!(
            (j.upper - hi).abs() < 1e-5,
            "{name} upper {} vs {hi}",
            j.upper
        );
        assert_eq!(j.velocity, 12.0, "{name} velocity limit");
        assert_eq!(j.effort, 150.0, "{name} effort limit");
        assert_eq!(j.damping, 0.1, "{name} damping");
    }
}

#[test]
fn tracked_bodies_are_the_four_feet_then_the_trunk() {
    let model = hyq();
    let names: Vec<&str> = model.tracked().iter().map(|t| t.name.as_str()).collect();
    assert_eq!(names, ["lf", "lh", "rf", "rh", "trunk"]);
    assert_eq!(model.num_feet(), 4);
    assert_eq!(model.trunk_tracked_index(), 4);
    for foot in &model.tracked()[..4] {
        assert_eq!(foot.shapes.len(), 1, "a foot is one shape, not its shin");
        let link = &model.links()[foot.link];
        assert_eq!(link.name, format!("{}_lowerleg", foot.name));
        let c = &link.collisions[foot.shapes[0]];
        assert_eq!(
            c.name.as_deref(),
            Some(format!("{}_foot", foot.name).as_str())
        );
        assert_eq!(c.shape, Shape::Sphere { radius: 0.02175 });
        assert!(
            (c.origin.translation.vector - hyq_physics::na::Vector3::new(0.346, 0.0, 0.0)).norm()
                < 1e-12
        );
    }
}

#[test]
fn mass_is_upstreams() {
    let model = hyq();
    // 60.96 trunk + 4 × (2.93 + 2.638 + 0.881) legs + 0.018 IMU.
    assert!(
        (model.total_mass() - 86.774).abs() < 1e-9,
        "{}",
        model.total_mass()
    );
    let trunk = &model.links()[0];
    assert_eq!(trunk.lumped, ["trunk_imu"]);
    assert!((trunk.mass - 60.978).abs() < 1e-12);
}

#[test]
fn standing_pose_is_the_srdf_one() {
    let model = hyq();
    let expected = [
        -0.2, 0.75, -1.5, -0.2, -0.75, 1.5, -0.2, 0.75, -1.5, -0.2, -0.75, 1.5,
    ];
    assert_eq!(model.standing_pose(), expected);
    assert_eq!(model.kp(), [1000.0; 12]);
    assert_eq!(model.kd(), [20.0; 12]);
}

#[test]
fn spawn_leaves_the_feet_about_1_mm_above_the_ground() {
    let model = hyq();
    let poses = spawn_poses(&model);
    for t in 0..4 {
        let z = model.tracked_lowest_z(t, &poses);
        assert!((0.5e-3..=1.5e-3).contains(&z), "foot {t} clearance {z} m");
    }
    let lowest_foot = (0..4)
        .map(|t| model.tracked_lowest_z(t, &poses))
        .fold(f64::INFINITY, f64::min);
    assert_eq!(
        model.lowest_z(&poses),
        lowest_foot,
        "the feet are the lowest points"
    );
    let trunk = model.tracked_lowest_z(4, &poses);
    assert!(trunk > 0.4, "trunk clearance {trunk} m");
}

#[test]
fn standing_feet_are_under_the_hips() {
    // Upstream's SRDF root height 0.5775 puts the foot centres on the ground: forward
    // kinematics must put them 0.5775 m below the trunk frame, mirrored about both axes.
    let model = hyq();
    let poses = spawn_poses(&model);
    let spawn = model.spawn_height();
    for foot in &model.tracked()[..4] {
        let c = poses[foot.link] * model.links()[foot.link].collisions[foot.shapes[0]].origin;
        let p = c.translation.vector;
        assert!(
            (p.x.abs() - 0.37077).abs() < 1e-5,
            "{} x {}",
            foot.name,
            p.x
        );
        assert!(
            (p.y.abs() - 0.32407).abs() < 1e-5,
            "{} y {}",
            foot.name,
            p.y
        );
        assert!(
            (spawn - p.z - 0.577509).abs() < 1e-6,
            "{} z {}",
            foot.name,
            p.z
        );
        let front = foot.name.ends_with('f');
        let left = foot.name.starts_with('l');
        assert_eq!(p.x > 0.0, front, "{} in front?", foot.name);
        assert_eq!(p.y > 0.0, left, "{} on the left?", foot.name);
    }
}

#[test]
fn shared_instance_equals_a_fresh_load() {
    assert_eq!(*hyq(), bundled::load_hyq().expect("loads"));
}
