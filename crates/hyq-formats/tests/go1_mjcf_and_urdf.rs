//! Go1 from MuJoCo Playground's MJCF (`assets/go1/`, bundled) and Go1 from Unitree's URDF as
//! packaged by example-robot-data (`assets/go1_urdf/`) are the same robot where it matters to
//! a rigid-body simulation, and differ where the files do, by the stated amounts:
//!
//! - the same: every leg body's mass (1e-6 kg), centre of mass (1e-6 m) and inertia tensor
//!   (1e-8 kg m², the MJCF's `diaginertia` + `quat` against the URDF's full tensor, each written
//!   to 6 or 7 digits), every joint's frame (1e-9 m), axis, position range and effort and
//!   velocity limits (exactly). The URDF's rotor links (fixed to the hip, the thigh and the
//!   trunk) and foot links are lumped into the bodies the MJCF has, which is how their masses
//!   agree: an MJCF hip body (0.680 kg) is the URDF's hip (0.591) and thigh rotor (0.089).
//! - different: the URDF's trunk carries the four hip rotors (0.089 kg each), the IMU
//!   (0.001 kg), eight sensor boxes (1e-5 kg each) and its root link's 1e-6 kg placeholder,
//!   0.357081 kg in all, which the MJCF
//!   leaves out (13.1005 kg against 12.7434 kg in all); the foot spheres (r 0.020 against
//!   0.023 m); the joint dynamics (damping 0.01 against 0.5 N m s/rad, Coulomb friction 0.2
//!   against 0.3 / 0.3 / 1.0 N m, armature 0 against 0.005 kg m²). The engines' tests
//!   (`tests/field_robots.rs`, module `go1_mjcf_and_urdf`) show what these do to the standing
//!   height.

use std::path::Path;
use std::sync::Arc;

use hyq_formats::robots;
use hyq_physics::RobotModel;

fn urdf_go1() -> RobotModel {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/go1_urdf/profile.toml");
    robots::load_profile(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn mjcf_go1() -> Arc<RobotModel> {
    robots::by_name("go1").expect("bundled")
}

#[test]
fn the_legs_are_the_same_bodies_and_joints() {
    let (u, m) = (urdf_go1(), mjcf_go1());
    assert_eq!((u.links().len(), u.joints().len()), (13, 12));
    assert_eq!((m.links().len(), m.joints().len()), (13, 12));
    let mut compared = 0;
    for ul in &u.links()[1..] {
        let ml = m
            .links()
            .iter()
            .find(|l| l.name == ul.name)
            .unwrap_or_else(|| panic!("the MJCF has no body {}", ul.name));
        assert!(
            (ul.mass - ml.mass).abs() < 1e-6,
            "{}: mass {} against {}",
            ul.name,
            ul.mass,
            ml.mass
        );
        assert!(
            (ul.com - ml.com).norm() < 1e-6,
            "{}: centre of mass {:?} against {:?}",
            ul.name,
            ul.com,
            ml.com
        );
        let d = (ul.inertia - ml.inertia).abs().max();
        assert!(d < 1e-8, "{}: inertia differs by {d:e} kg m²", ul.name);
        compared += 1;
    }
    assert_eq!(compared, 12);
    for uj in u.joints() {
        let mj = m
            .joints()
            .iter()
            .find(|j| j.urdf_name == uj.urdf_name)
            .unwrap_or_else(|| panic!("the MJCF has no joint {}", uj.urdf_name));
        let where_ = (uj.origin.translation.vector - mj.origin.translation.vector).norm();
        assert!(
            where_ < 1e-9,
            "{}: joint frame {where_} m apart",
            uj.urdf_name
        );
        assert!(
            uj.origin.rotation.angle_to(&mj.origin.rotation) < 1e-9,
            "{}",
            uj.urdf_name
        );
        assert_eq!(uj.axis, mj.axis, "{}", uj.urdf_name);
        assert_eq!(
            (uj.lower, uj.upper),
            (mj.lower, mj.upper),
            "{}",
            uj.urdf_name
        );
        assert_eq!(
            (uj.effort, uj.velocity),
            (mj.effort, mj.velocity),
            "{}",
            uj.urdf_name
        );
    }
}

#[test]
fn the_urdf_trunk_carries_the_hip_rotors_and_sensors_the_mjcf_leaves_out() {
    let (u, m) = (urdf_go1(), mjcf_go1());
    let (ut, mt) = (&u.links()[0], &m.links()[0]);
    assert_eq!((ut.name.as_str(), mt.name.as_str()), ("base", "trunk"));
    // What the URDF's trunk body holds besides the trunk link, by the URDF's masses: the root
    // link `base` (a 1e-6 kg placeholder) and the links fixed to the trunk.
    let urdf = urdf_rs::read_file(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets/go1_urdf/go1.urdf"),
    )
    .expect("parses");
    let extra: f64 = urdf
        .links
        .iter()
        .filter(|l| (l.name == "base" || ut.lumped.contains(&l.name)) && l.name != "trunk")
        .map(|l| l.inertial.mass.value)
        .sum();
    assert!((extra - 0.357081).abs() < 1e-9, "{extra} kg");
    let trunk_link = urdf
        .links
        .iter()
        .find(|l| l.name == "trunk")
        .expect("trunk");
    assert_eq!(
        trunk_link.inertial.mass.value, mt.mass,
        "the trunk links are the same 5.204 kg"
    );
    assert!((ut.mass - mt.mass - extra).abs() < 1e-9);
    assert!((u.total_mass() - m.total_mass() - extra).abs() < 1e-6);
    for rotor in [
        "FL_hip_rotor",
        "FR_hip_rotor",
        "RL_hip_rotor",
        "RR_hip_rotor",
    ] {
        assert!(
            ut.lumped.iter().any(|l| l == rotor),
            "{rotor} lumped into the trunk"
        );
    }
}

#[test]
fn the_feet_and_joint_dynamics_differ_as_stated() {
    let (u, m) = (urdf_go1(), mjcf_go1());
    let radius = |model: &RobotModel, foot: usize| {
        let t = &model.tracked()[foot];
        match model.links()[t.link].collisions[t.shapes[0]].shape {
            hyq_physics::Shape::Sphere { radius } => radius,
            ref other => panic!("foot {} is a {other:?}", t.name),
        }
    };
    for f in 0..4 {
        assert_eq!((radius(&u, f), radius(&m, f)), (0.02, 0.023));
    }
    for uj in u.joints() {
        let mj = m
            .joints()
            .iter()
            .find(|j| j.urdf_name == uj.urdf_name)
            .expect("same joints");
        let calf = uj.urdf_name.ends_with("calf_joint");
        assert_eq!((uj.damping, uj.friction, uj.armature), (0.01, 0.2, 0.0));
        assert_eq!(
            (mj.damping, mj.friction, mj.armature),
            (0.5, if calf { 1.0 } else { 0.3 }, 0.005)
        );
    }
}
