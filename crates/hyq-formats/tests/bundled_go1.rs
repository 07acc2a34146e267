//! The bundled Go1, read from MuJoCo Playground's MJCF: what the reader makes of it, checked
//! against figures read off `assets/go1/go1.xml` by hand (so a reader that skipped the default
//! classes, as one importer once did, would fail here rather than load a different robot).

use hyq_formats::mjcf_read::ActuatorKind;
use hyq_formats::robots;
use hyq_physics::Shape;
use hyq_physics::na::{Isometry3, Translation3, UnitQuaternion, Vector3};

#[test]
fn go1_masses_joints_and_gains_are_the_files() {
    let model = robots::load_go1().expect("the bundled Go1 builds");
    // 5.204 (trunk) + 4 × (0.68 + 1.009 + 0.195862).
    assert!((model.total_mass() - 12.743448).abs() < 1e-9);
    assert_eq!(model.num_links(), 13, "the trunk and three bodies per leg");
    assert_eq!(model.num_joints(), 12);
    for (i, j) in model.joints().iter().enumerate() {
        // Profile order per leg: haa (class abduction), hfe (hip), kfe (knee).
        let (axis, range, effort, friction) = match i % 3 {
            0 => (Vector3::x(), [-0.863, 0.863], 23.7, 0.3),
            1 => (Vector3::y(), [-0.686, 4.501], 23.7, 0.3),
            _ => (Vector3::y(), [-2.818, -0.888], 35.55, 1.0),
        };
        assert_eq!(j.axis.into_inner(), axis, "{}", j.name);
        assert_eq!([j.lower, j.upper], range, "{}", j.name);
        assert_eq!(
            j.effort, effort,
            "{}: the class's <position forcerange>",
            j.name
        );
        assert_eq!(j.friction, friction, "{}: frictionloss", j.name);
        assert_eq!(j.damping, 0.5, "{}", j.name);
        assert_eq!(j.armature, 0.005, "{}", j.name);
    }
    assert_eq!(model.kp(), &[35.0; 12], "the <position> actuators' kp");
}

#[test]
fn go1_shapes_come_from_their_classes() {
    let model = robots::load_go1().expect("the bundled Go1 builds");
    let thigh = &model.links()[model.link_index("FL_thigh").expect("a body")];
    let t1 = thigh
        .collisions
        .iter()
        .find(|c| c.name.as_deref() == Some("fl_thigh1"))
        .expect("class thigh1");
    // fromto="-0.02 0 0 -0.02 0 -0.16", size 0.015: a capsule down z, centred half way.
    assert_eq!(
        t1.shape,
        Shape::Capsule {
            radius: 0.015,
            half_length: 0.08
        }
    );
    assert!((t1.origin.translation.vector - Vector3::new(-0.02, 0.0, -0.08)).norm() < 1e-12);
    let hip = &model.links()[model.link_index("FL_hip").expect("a body")];
    let h = &hip.collisions[0];
    // hip_left1: cylinder, size "0.046 0.02", pos "0 0.045 0", quat "1 1 0 0" (axis along -y).
    assert_eq!(
        h.shape,
        Shape::Cylinder {
            radius: 0.046,
            half_length: 0.02
        }
    );
    assert!((h.origin.rotation * Vector3::z() + Vector3::y()).norm() < 1e-12);
    let calf = &model.links()[model.link_index("FL_calf").expect("a body")];
    let foot = calf
        .collisions
        .iter()
        .find(|c| c.name.as_deref() == Some("FL"))
        .expect("the foot");
    assert_eq!(foot.shape, Shape::Sphere { radius: 0.023 });
    assert!((foot.origin.translation.vector - Vector3::new(0.0, 0.0, -0.213)).norm() < 1e-12);
    let trunk = &model.links()[0];
    assert_eq!(
        trunk.collisions.len(),
        2,
        "the two trunk cylinders; the mesh is visual"
    );
}

#[test]
fn go1_spawns_with_its_feet_one_millimetre_up() {
    let model = robots::load_go1().expect("the bundled Go1 builds");
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    let trunk = Isometry3::from_parts(
        Translation3::new(0.0, 0.0, model.spawn_height()),
        UnitQuaternion::identity(),
    );
    model
        .link_poses(&trunk, model.standing_pose(), &mut poses)
        .expect("sizes match");
    for f in 0..model.num_feet() {
        let gap = model.tracked_lowest_z(f, &poses);
        assert!((gap - 0.001).abs() < 1e-4, "foot {f}: {gap} m");
    }
    assert!(
        (model.lowest_z(&poses) - 0.001).abs() < 1e-4,
        "only the feet touch first"
    );
}

#[test]
fn go1_keeps_its_keyframe_and_notes_what_it_skipped() {
    let mjcf = robots::go1_mjcf().expect("the bundled MJCF reads");
    let home = &mjcf.keyframes[0];
    assert_eq!(home.name, "home");
    assert_eq!(home.qpos.len(), 19);
    assert_eq!(home.ctrl.len(), 12);
    assert_eq!(mjcf.actuators.len(), 12);
    for a in &mjcf.actuators {
        assert!(matches!(a.kind, ActuatorKind::Position { kp, kv } if kp == 35.0 && kv == 0.0));
        // inheritrange="1": the control range is the joint's range.
        let j = mjcf
            .robot
            .joints
            .iter()
            .find(|j| j.name == a.joint)
            .expect("joint");
        let [lo, hi] = a.ctrl_range.expect("inherited");
        assert!((lo - j.limit.lower).abs() < 1e-12 && (hi - j.limit.upper).abs() < 1e-12);
    }
    let notes = mjcf.notes.join("\n");
    assert!(notes.contains("13 visual-only geoms"), "{notes}");
    assert!(notes.contains("<sensor>: skipped"), "{notes}");
}

#[test]
fn go1_resolves_by_name_and_is_shared() {
    let a = robots::resolve("go1").expect("bundled");
    let b = robots::by_name("go1").expect("bundled");
    assert!(std::sync::Arc::ptr_eq(&a, &b));
    assert_eq!(a.name(), "go1");
    assert_eq!(*a, robots::load_go1().expect("builds"));
    for name in robots::NAMES {
        assert!(robots::resolve(name).is_ok(), "{name}");
    }
}
