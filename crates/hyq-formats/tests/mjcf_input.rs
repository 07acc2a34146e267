//! The MJCF reader on small hand-written files: each orientation form, includes, joint
//! positions, motors; and bad input (deep nesting, repeated classes, include cycles,
//! non-finite and huge numbers, unknown elements and attributes), each refused in one line
//! naming what was wrong, none hanging.

use std::path::Path;

use hyq_formats::mjcf_read::{self, ActuatorKind};
use hyq_physics::na::{Isometry3, Vector3};
use hyq_physics::{Profile, RobotModel};

/// A two-body robot: a box trunk and one leg on a hinge, its geom and frame given by `leg`
/// (attributes of the leg body), `joint` (of its hinge) and `extra` (elements after the
/// worldbody).
fn robot(compiler: &str, leg: &str, joint: &str, extra: &str) -> String {
    format!(
        r#"<mujoco model="probe">
  <compiler {compiler}/>
  <default>
    <joint damping="0.1"/>
    <default class="legs">
      <geom type="capsule" size="0.02"/>
      <joint axis="0 1 0" range="-1 1"/>
    </default>
  </default>
  <worldbody>
    <geom name="floor" type="plane" size="0 0 1"/>
    <body name="base" pos="0 0 0.5">
      <freejoint/>
      <inertial pos="0 0 0" mass="5" diaginertia="0.1 0.1 0.1"/>
      <geom name="body" type="box" size="0.2 0.1 0.05"/>
      <body name="leg" {leg} childclass="legs">
        <joint name="hip" {joint}/>
        <inertial pos="0 0 -0.1" mass="1" diaginertia="0.01 0.01 0.001"/>
        <geom name="shin" fromto="0 0 0 0 0 -0.2"/>
        <geom name="foot" type="sphere" size="0.03" pos="0 0 -0.2"/>
      </body>
    </body>
  </worldbody>
  <actuator>
    <motor joint="hip" gear="2" ctrlrange="-10 10"/>
  </actuator>
  {extra}
</mujoco>"#
    )
}

const PROFILE: &str = r#"
name = "probe"
urdf = "probe.xml"
trunk = "base"
feet = [{ name = "f", link = "leg", collision = "foot" }]
joints = [{ name = "hip", urdf = "hip", standing = 0.0, velocity = 10.0 }]
[spawn]
height = 0.5
[gains]
kp = 10.0
kd = 1.0
"#;

fn model_of(text: &str) -> RobotModel {
    let profile = Profile::from_toml_str(PROFILE, "probe profile").expect("profile");
    mjcf_read::read_str(text, "probe.xml")
        .unwrap_or_else(|e| panic!("{e}"))
        .model(&profile)
        .unwrap_or_else(|e| panic!("{e}"))
}

fn error_of(text: &str) -> String {
    let e = mjcf_read::read_str(text, "probe.xml").expect_err("refused");
    let m = e.to_string();
    assert!(!m.contains('\n'), "one line: {m}");
    m
}

/// The leg joint's frame in the trunk frame, and its axis there.
fn leg_frame(model: &RobotModel) -> (Isometry3<f64>, Vector3<f64>) {
    let j = &model.joints()[0];
    (j.origin, j.origin.rotation * j.axis.into_inner())
}

#[test]
fn every_orientation_form_gives_the_same_robot() {
    // A quarter turn about z, then the leg 0.1 m out along x.
    let forms = [
        (
            "angle=\"radian\"",
            "quat=\"0.7071067811865476 0 0 0.7071067811865476\"",
        ),
        ("angle=\"degree\"", "axisangle=\"0 0 1 90\""),
        ("angle=\"radian\"", "axisangle=\"0 0 2 1.5707963267948966\""),
        ("angle=\"degree\"", "euler=\"0 0 90\""),
        (
            "angle=\"radian\" eulerseq=\"ZYX\"",
            "euler=\"1.5707963267948966 0 0\"",
        ),
        ("angle=\"radian\"", "xyaxes=\"0 1 0 -1 0 0\""),
        ("angle=\"radian\"", "xyaxes=\"0 2 0 -1 0.5 0\""),
    ];
    let mut frames = Vec::new();
    for (compiler, orient) in forms {
        let text = robot(compiler, &format!("pos=\"0.1 0 0\" {orient}"), "", "");
        frames.push((orient, leg_frame(&model_of(&text))));
    }
    let (_, (f0, a0)) = frames[0];
    assert!(
        (a0 - Vector3::new(-1.0, 0.0, 0.0)).norm() < 1e-12,
        "y turned a quarter about z"
    );
    for (orient, (f, a)) in &frames {
        assert!(
            (f.translation.vector - f0.translation.vector).norm() < 1e-12,
            "{orient}"
        );
        assert!(f.rotation.angle_to(&f0.rotation) < 1e-9, "{orient}");
        assert!((a - a0).norm() < 1e-9, "{orient}");
    }
    // zaxis: the frame whose z is the given axis.
    let m = model_of(&robot("angle=\"radian\"", "zaxis=\"1 0 0\"", "", ""));
    let (f, _) = leg_frame(&m);
    assert!((f.rotation * Vector3::z() - Vector3::x()).norm() < 1e-12);
}

#[test]
fn degrees_apply_to_ranges_and_a_joint_pos_moves_the_link_frame() {
    let m = model_of(&robot(
        "angle=\"degree\"",
        "pos=\"0.1 0 0\"",
        "pos=\"0 0 -0.05\" range=\"-90 45\"",
        "",
    ));
    let j = &m.joints()[0];
    assert!((j.lower + std::f64::consts::FRAC_PI_2).abs() < 1e-12);
    assert!((j.upper - std::f64::consts::FRAC_PI_4).abs() < 1e-12);
    assert!((j.origin.translation.vector - Vector3::new(0.1, 0.0, -0.05)).norm() < 1e-12);
    // The link frame is the joint's, so the foot sphere sits 0.05 m higher in it.
    let leg = &m.links()[j.child];
    let foot = leg
        .collisions
        .iter()
        .find(|c| c.name.as_deref() == Some("foot"));
    let z = foot.expect("foot").origin.translation.vector.z;
    assert!((z + 0.15).abs() < 1e-12, "{z}");
    assert!((leg.com.z + 0.05).abs() < 1e-12, "{}", leg.com.z);
    assert_eq!(j.damping, 0.1, "the main class's joint default");
}

#[test]
fn a_motor_sets_the_effort_limit_and_the_floor_is_noted() {
    let mjcf = mjcf_read::read_str(&robot("", "", "", ""), "probe.xml").expect("reads");
    assert_eq!(mjcf.actuators[0].kind, ActuatorKind::Motor { gear: 2.0 });
    assert!(
        mjcf.notes.iter().any(|n| n.contains("world geom")),
        "{:?}",
        mjcf.notes
    );
    let profile = Profile::from_toml_str(PROFILE, "probe").expect("profile");
    let m = mjcf.model(&profile).expect("builds");
    assert_eq!(m.joints()[0].effort, 20.0, "gear 2 × ctrlrange 10");
    assert_eq!(m.kp(), &[10.0], "a motor has no gains: the profile's");
}

#[test]
fn includes_are_read_relative_to_the_including_file_and_cycles_refused() {
    let dir = std::env::temp_dir().join(format!("hyq-mjcf-include-{}", std::process::id()));
    std::fs::create_dir_all(dir.join("sub")).expect("temp dir");
    let text = robot("", "", "", "<include file=\"sub/keys.xml\"/>");
    std::fs::write(dir.join("probe.xml"), &text).expect("write");
    std::fs::write(
        dir.join("sub/keys.xml"),
        "<mujoco><keyframe><key name=\"k\" qpos=\"0 0 1 1 0 0 0 0.5\"/></keyframe></mujoco>",
    )
    .expect("write");
    let mjcf = mjcf_read::read_file(dir.join("probe.xml")).expect("reads");
    assert_eq!(mjcf.keyframes[0].qpos.len(), 8);
    // A file that includes itself, through another.
    std::fs::write(
        dir.join("a.xml"),
        "<mujoco><include file=\"b.xml\"/></mujoco>",
    )
    .expect("w");
    std::fs::write(
        dir.join("b.xml"),
        "<mujoco><include file=\"a.xml\"/></mujoco>",
    )
    .expect("w");
    let e = mjcf_read::read_file(dir.join("a.xml")).expect_err("a cycle");
    assert!(e.to_string().contains("<include> cycle"), "{e}");
    let e = mjcf_read::read_file(dir.join("missing.xml")).expect_err("no file");
    assert!(e.to_string().contains("cannot read MJCF file"), "{e}");
    let _ = std::fs::remove_dir_all(&dir);
    let e = error_of(&robot("", "", "", "<include file=\"x.xml\"/>"));
    assert!(e.contains("no directory"), "{e}");
}

#[test]
fn ten_thousand_nested_bodies_are_refused_before_parsing() {
    let n = 10_000;
    let mut text = String::from("<mujoco><worldbody>");
    for i in 0..n {
        text.push_str(&format!("<body name=\"b{i}\">"));
    }
    text.push_str(&"</body>".repeat(n));
    text.push_str("</worldbody></mujoco>");
    let e = error_of(&text);
    assert!(e.contains("deep"), "{e}");
}

#[test]
fn bad_input_is_refused_by_name_and_line() {
    let cases: Vec<(String, &str)> = vec![
        (
            robot("", "", "damping=\"NaN\"", ""),
            "`damping`: NaN is not a finite number",
        ),
        (
            robot("", "", "damping=\"1e300\"", ""),
            "`damping`: 1e300 is not a finite",
        ),
        (robot("", "pos=\"0 0 inf\"", "", ""), "`pos`: inf"),
        (
            robot("", "", "", "<tendon><fixed/></tendon>"),
            "<tendon>: cannot be represented",
        ),
        (
            robot("", "", "", "<gizmo/>"),
            "<gizmo>: is not an MJCF element",
        ),
        (
            robot("", "", "stiffness=\"5\"", ""),
            "`stiffness` cannot be represented",
        ),
        (
            robot("", "", "type=\"slide\"", ""),
            "joint type \"slide\" cannot be represented",
        ),
        (
            robot("", "", "spin=\"1\"", ""),
            "attribute `spin` is not understood",
        ),
        (
            robot("", "quat=\"1 0 0 0\" euler=\"0 0 1\"", "", ""),
            "more than one orientation",
        ),
        (robot("", "quat=\"0 0 0 0\"", "", ""), "zero quaternion"),
        (
            robot("", "", "class=\"nope\"", ""),
            "no default class named \"nope\"",
        ),
        (
            robot("", "", "", "<default><default class=\"legs\"/></default>"),
            "defined twice",
        ),
        (
            robot("", "", "", "<actuator><muscle joint=\"hip\"/></actuator>"),
            "<muscle>: this actuator cannot be represented",
        ),
        (
            robot("", "", "", "<actuator><motor joint=\"knee\"/></actuator>"),
            "no hinge joint named \"knee\"",
        ),
        (
            robot(
                "",
                "",
                "",
                "<contact><pair geom1=\"a\" geom2=\"b\"/></contact>",
            ),
            "<pair>: cannot be represented",
        ),
        (
            robot("", "", "", "<keyframe><key qpos=\"1 2\"/></keyframe>"),
            "`qpos`: 2 numbers, expected 8",
        ),
        ("<robot name=\"x\"/>".to_owned(), "not <mujoco>"),
        ("<mujoco><worldbody>".to_owned(), "probe.xml"),
        ("<mujoco/>".to_owned(), "no robot"),
    ];
    for (text, expected) in cases {
        let e = error_of(&text);
        assert!(e.contains(expected), "expected {expected:?} in: {e}");
    }
    // The element's line is named: the leg's hinge is on line 17 of `robot`.
    let e = error_of(&robot("", "", "damping=\"NaN\"", ""));
    assert!(e.starts_with("probe.xml:17: <joint>"), "{e}");
}

#[test]
fn a_colliding_mesh_is_refused_and_a_visual_one_skipped() {
    let visual = "<geom type=\"mesh\" mesh=\"m\" contype=\"0\" conaffinity=\"0\"/>";
    let text = robot("", "", "", "").replace("<freejoint/>", &format!("<freejoint/>{visual}"));
    let mjcf = mjcf_read::read_str(&text, "probe.xml").expect("a visual mesh is skipped");
    assert!(mjcf.notes.iter().any(|n| n.contains("1 visual-only geoms")));
    let text = robot("", "", "", "").replace("<freejoint/>", "<freejoint/><geom type=\"mesh\"/>");
    assert!(error_of(&text).contains("colliding mesh geom cannot be represented"));
}

#[test]
fn a_profile_naming_an_mjcf_file_loads_through_resolve() {
    let dir = std::env::temp_dir().join(format!("hyq-mjcf-profile-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("probe.xml"), robot("", "", "", "")).expect("write");
    std::fs::write(dir.join("probe.toml"), PROFILE).expect("write");
    let path = dir.join("probe.toml");
    let model = hyq_formats::robots::resolve(path.to_str().expect("utf-8")).expect("loads");
    assert_eq!(model.num_joints(), 1);
    let e = hyq_formats::robots::resolve(dir.join("probe.xml").to_str().expect("utf-8"))
        .expect_err("an MJCF file alone");
    assert!(e.to_string().contains("through a robot profile"), "{e}");
    let e = hyq_formats::robots::resolve("nothing").expect_err("unknown");
    assert!(e.to_string().contains("hyq, anymal_c, go1"), "{e}");
    let _ = std::fs::remove_dir_all(Path::new(&dir));
}
