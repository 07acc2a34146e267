//! The bundled ANYmal C (`assets/anymal_c/`) is upstream's robot: its URDF's total mass (every
//! link, sensors included), twelve joints in the profile's leg-major order with HyQ's short
//! names, the URDF's HAA ranges and the profile's HFE/KFE ranges (the URDF says ±3π), four foot
//! spheres tracked without the shank tubes beside them, the SRDF standing pose within the
//! limits, and a spawn state that leaves the feet, and only the feet, about 1 mm above the
//! ground.

use hyq_physics::bundled::{self, ANYMAL_C_URDF, anymal_c};
use hyq_physics::na::Isometry3;
use hyq_physics::{RobotModel, Shape};

fn spawn_poses(model: &RobotModel) -> Vec<Isometry3<f64>> {
    let s = model.spawn_state();
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    model
        .link_poses(&s.trunk.pose, &s.q, &mut poses)
        .expect("forward kinematics");
    poses
}

#[test]
fn mass_is_every_urdf_link_including_the_sensors() {
    let urdf = urdf_rs::read_from_string(ANYMAL_C_URDF).expect("parses");
    let sum: f64 = urdf.links.iter().map(|l| l.inertial.mass.value).sum();
    let model = anymal_c();
    assert!((model.total_mass() - sum).abs() < 1e-9);
    assert!(
        (model.total_mass() - 52.13485).abs() < 1e-6,
        "{}",
        model.total_mass()
    );
    // One body per actuated joint plus the trunk; the 65 fixed links are lumped.
    assert_eq!(model.num_links(), 13);
    assert_eq!(urdf.links.len(), 78);
}

#[test]
fn joints_are_leg_major_with_upstream_and_profile_ranges() {
    let model = anymal_c();
    let names: Vec<&str> = model.joints().iter().map(|j| j.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "lf_haa", "lf_hfe", "lf_kfe", "lh_haa", "lh_hfe", "lh_kfe", "rf_haa", "rf_hfe",
            "rf_kfe", "rh_haa", "rh_hfe", "rh_kfe"
        ]
    );
    let half_pi = std::f64::consts::FRAC_PI_2;
    for j in model.joints() {
        assert_eq!(j.urdf_name, j.name.to_uppercase());
        assert_eq!(
            (j.effort, j.velocity, j.damping, j.friction),
            (80.0, 7.5, 0.0, 0.0)
        );
        let left = j.name.starts_with('l');
        let front = j.name.as_bytes()[1] == b'f';
        let range = (j.lower, j.upper);
        match &j.name[3..] {
            "haa" if left => assert_eq!(range, (-0.72, 0.49)),
            "haa" => assert_eq!(range, (-0.49, 0.72)),
            "hfe" => assert_eq!(range, (-half_pi, half_pi)),
            "kfe" if front => assert_eq!(range, (-2.6, 0.0)),
            "kfe" => assert_eq!(range, (0.0, 2.6)),
            other => panic!("unexpected joint kind {other}"),
        }
    }
    // The URDF itself says three turns either way for HFE and KFE.
    assert_eq!(ANYMAL_C_URDF.matches("lower=\"-9.42477796077\"").count(), 8);
}

#[test]
fn feet_are_the_four_spheres_and_not_the_shank_tubes() {
    let model = anymal_c();
    let names: Vec<&str> = model.tracked().iter().map(|t| t.name.as_str()).collect();
    assert_eq!(names, ["lf", "lh", "rf", "rh", "base"]);
    for foot in &model.tracked()[..model.num_feet()] {
        assert_eq!(foot.shapes.len(), 1);
        let c = &model.links()[foot.link].collisions[foot.shapes[0]];
        assert_eq!(
            c.name.as_deref(),
            Some(format!("{}_foot", foot.name).as_str())
        );
        assert_eq!(c.urdf_link, format!("{}_FOOT", foot.name.to_uppercase()));
        assert_eq!(c.shape, Shape::Sphere { radius: 0.03 });
    }
}

#[test]
fn standing_pose_is_the_srdf_one_within_the_limits() {
    let model = anymal_c();
    let expected = [
        -0.1, 0.7, -1.0, -0.1, -0.7, 1.0, 0.1, 0.7, -1.0, 0.1, -0.7, 1.0,
    ];
    assert_eq!(model.standing_pose(), expected);
    for (j, q) in model.joints().iter().zip(model.standing_pose()) {
        assert!((j.lower..=j.upper).contains(q), "{} = {q}", j.name);
    }
}

#[test]
fn spawn_leaves_the_feet_and_only_the_feet_one_millimetre_up() {
    let model = anymal_c();
    let poses = spawn_poses(&model);
    for t in 0..model.num_feet() {
        let clearance = model.tracked_lowest_z(t, &poses);
        assert!(
            (0.0009..0.0011).contains(&clearance),
            "foot {t} clearance {clearance} m"
        );
    }
    let feet_min = (0..model.num_feet())
        .map(|t| model.tracked_lowest_z(t, &poses))
        .fold(f64::INFINITY, f64::min);
    assert_eq!(
        model.lowest_z(&poses),
        feet_min,
        "nothing is lower than the feet"
    );
    assert!(model.standing_height() < model.spawn_height());
}

#[test]
fn profile_carries_a_gait_for_the_scripted_trot() {
    let model = anymal_c();
    let gait = model.gait().expect("[gait]");
    assert_eq!(gait.legs.len(), 4);
    for leg in &gait.legs {
        assert!(model.joints()[leg.hip].name.ends_with("_hfe"));
        assert!(model.joints()[leg.knee].name.ends_with("_kfe"));
    }
    assert!(bundled::by_name("anymal_c").is_some());
}
