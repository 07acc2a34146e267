//! Every way a URDF or a robot profile can be unusable gives a specific error naming the file,
//! link, joint or field at fault, never a panic or a silently wrong model.

use std::path::PathBuf;

use hyq_physics::bundled::{HYQ_PROFILE, HYQ_URDF};
use hyq_physics::{ModelError, Profile, RobotModel};

fn profile() -> Profile {
    Profile::from_toml_str(HYQ_PROFILE, "test").expect("bundled profile parses")
}

fn load(urdf: &str, profile: &Profile) -> Result<RobotModel, ModelError> {
    RobotModel::from_urdf_str(urdf, "test.urdf", profile)
}

/// The bundled URDF with one exact piece of text replaced (which must be there).
fn urdf_with(from: &str, to: &str) -> String {
    assert!(
        HYQ_URDF.contains(from),
        "test fixture: {from:?} not in the URDF"
    );
    HYQ_URDF.replacen(from, to, 1)
}

fn profile_with(from: &str, to: &str) -> Result<Profile, ModelError> {
    assert!(
        HYQ_PROFILE.contains(from),
        "test fixture: {from:?} not in the profile"
    );
    Profile::from_toml_str(&HYQ_PROFILE.replacen(from, to, 1), "test.toml")
}

fn message(e: &ModelError) -> String {
    e.to_string()
}

#[test]
fn bundled_robot_loads() {
    let model = load(HYQ_URDF, &profile()).expect("bundled HyQ loads");
    assert_eq!(model.name(), "hyq");
}

#[test]
fn missing_profile_file_names_the_path() {
    let path = PathBuf::from("/nonexistent/dir/profile.toml");
    match RobotModel::load(&path) {
        Err(ModelError::Io { what, path: p, .. }) => {
            assert_eq!(what, "robot profile");
            assert_eq!(p, path);
        }
        other => panic!("expected Io, got {other:?}"),
    }
}

#[test]
fn missing_urdf_file_names_the_path() {
    let dir = std::env::temp_dir().join(format!("hyq-physics-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let profile_path = dir.join("profile.toml");
    std::fs::write(
        &profile_path,
        HYQ_PROFILE.replace("hyq.urdf", "absent.urdf"),
    )
    .expect("write profile");
    let result = RobotModel::load(&profile_path);
    std::fs::remove_dir_all(&dir).ok();
    match result {
        Err(e @ ModelError::Io { what: "URDF", .. }) => {
            assert!(message(&e).contains("absent.urdf"), "{e}");
        }
        other => panic!("expected Io for the URDF, got {other:?}"),
    }
}

#[test]
fn loads_from_a_profile_path() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../assets/hyq/profile.toml");
    let model = RobotModel::load(&path).expect("assets/hyq/profile.toml loads");
    assert_eq!(model, hyq_physics::bundled::load_hyq().expect("bundled"));
}

#[test]
fn malformed_xml_is_a_urdf_error() {
    let urdf = urdf_with("</robot>", "<link name=\"broken\"");
    match load(&urdf, &profile()) {
        Err(e @ ModelError::Urdf { .. }) => assert!(message(&e).contains("test.urdf"), "{e}"),
        other => panic!("expected Urdf, got {other:?}"),
    }
}

#[test]
fn malformed_toml_is_a_profile_error() {
    match profile_with("kp = 1000.0", "kp = = 1000.0") {
        Err(e @ ModelError::Profile { .. }) => assert!(message(&e).contains("test.toml"), "{e}"),
        other => panic!("expected Profile, got {other:?}"),
    }
}

#[test]
fn unknown_profile_field_is_refused() {
    match profile_with("kd = 20.0", "kd = 20.0\nki = 1.0") {
        Err(e @ ModelError::Profile { .. }) => {
            let m = message(&e);
            assert!(m.contains("ki") && m.contains("test.toml"), "{m}");
            assert!(
                m.contains("expected `kp` or `kd`"),
                "lists the known keys: {m}"
            );
            assert!(!m.contains('\n'), "one line: {m}");
        }
        other => panic!("expected Profile, got {other:?}"),
    }
}

#[test]
fn joint_entry_without_standing_angle_is_refused() {
    match profile_with(
        "{ name = \"lf_kfe\", urdf = \"lf_kfe_joint\", standing = -1.5 }",
        "{ name = \"lf_kfe\", urdf = \"lf_kfe_joint\" }",
    ) {
        Err(e @ ModelError::Profile { .. }) => assert!(message(&e).contains("standing"), "{e}"),
        other => panic!("expected Profile, got {other:?}"),
    }
}

#[test]
fn profile_joint_missing_from_urdf() {
    let p = profile_with("urdf = \"rh_kfe_joint\"", "urdf = \"rh_knee\"").expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::MissingJoint {
            joint,
            referenced_by,
            available,
        }) => {
            assert_eq!(joint, "rh_knee");
            assert_eq!(referenced_by, "joints[11].urdf");
            assert!(
                available.contains("rh_kfe_joint"),
                "lists the fix: {available}"
            );
        }
        other => panic!("expected MissingJoint, got {other:?}"),
    }
}

#[test]
fn profile_trunk_missing_from_urdf() {
    let p = profile_with("trunk = \"trunk\"", "trunk = \"body\"").expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::MissingLink {
            link,
            referenced_by,
        }) => {
            assert_eq!(link, "body");
            assert_eq!(referenced_by, "trunk");
        }
        other => panic!("expected MissingLink, got {other:?}"),
    }
}

#[test]
fn profile_foot_link_missing_from_urdf() {
    let p = profile_with("link = \"rf_lowerleg\"", "link = \"rf_shank\"").expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::MissingLink {
            link,
            referenced_by,
        }) => {
            assert_eq!(link, "rf_shank");
            assert_eq!(referenced_by, "feet[2].link");
        }
        other => panic!("expected MissingLink, got {other:?}"),
    }
}

#[test]
fn profile_foot_collision_missing_from_urdf() {
    let p = profile_with("collision = \"lh_foot\"", "collision = \"lh_toe\"").expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::MissingCollision {
            link,
            collision,
            referenced_by,
            available,
        }) => {
            assert_eq!(available, "lh_shin, lh_foot", "lists the fix");
            assert_eq!(
                (link.as_str(), collision.as_str()),
                ("lh_lowerleg", "lh_toe")
            );
            assert_eq!(referenced_by, "feet[1].collision");
        }
        other => panic!("expected MissingCollision, got {other:?}"),
    }
}

#[test]
fn negative_mass_is_an_invalid_inertia() {
    let urdf = urdf_with("<mass value=\"2.638\"/>", "<mass value=\"-2.638\"/>");
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidInertia { link, reason }) => {
            assert_eq!(link, "lf_upperleg");
            assert!(reason.contains("-2.638"), "{reason}");
        }
        other => panic!("expected InvalidInertia, got {other:?}"),
    }
}

#[test]
fn indefinite_tensor_is_an_invalid_inertia() {
    let urdf = urdf_with("ixx=\"0.00047\"", "ixx=\"-0.00047\"");
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidInertia { link, reason }) => {
            assert_eq!(link, "lf_lowerleg");
            assert!(reason.contains("positive semi-definite"), "{reason}");
        }
        other => panic!("expected InvalidInertia, got {other:?}"),
    }
}

/// Upstream's foot placeholder (every entry 1e-6: principal moments 3e-6, 0, 0) on a link
/// fixed to the lower leg.
const PLACEHOLDER_FOOT: &str = r#"<joint name="lf_foot_joint" type="fixed">
    <origin xyz="0.346 0 0" rpy="0 0 0"/>
    <parent link="lf_lowerleg"/>
    <child link="lf_foot"/>
  </joint>
  <link name="lf_foot">
    <inertial>
      <mass value="MASS"/>
      <inertia ixx="1e-6" ixy="1e-6" ixz="1e-6" iyy="1e-6" iyz="1e-6" izz="IZZ"/>
    </inertial>
  </link>
</robot>"#;

#[test]
fn invalid_tensor_of_a_fixed_link_is_checked_as_part_of_its_body() {
    // The placeholder violates the triangle inequality on its own, but the lower leg it is
    // fixed to stays a valid rigid body: accepted, its mass counted.
    let urdf = urdf_with(
        "</robot>",
        &PLACEHOLDER_FOOT
            .replace("MASS", "1e-6")
            .replace("IZZ", "1e-6"),
    );
    let model = load(&urdf, &profile()).expect("a valid body with a placeholder part loads");
    let body = &model.links()[model.link_index("lf_lowerleg").expect("body")];
    assert_eq!(body.lumped, ["lf_foot"]);
    assert!((body.mass - 0.881001).abs() < 1e-12, "{}", body.mass);
}

#[test]
fn invalid_tensor_of_a_lumped_body_names_the_body_and_its_links() {
    // A heavy part with a flat tensor makes the whole lower leg invalid.
    let urdf = urdf_with(
        "</robot>",
        &PLACEHOLDER_FOOT
            .replace("MASS", "1.0")
            .replace("IZZ", "10.0"),
    );
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidInertia { link, reason }) => {
            assert_eq!(link, "lf_lowerleg");
            assert!(reason.contains("lf_foot"), "{reason}");
            assert!(reason.contains("triangle"), "{reason}");
        }
        other => panic!("expected InvalidInertia, got {other:?}"),
    }
}

#[test]
fn triangle_inequality_violation_of_a_body_is_an_invalid_inertia() {
    let urdf = urdf_with("izz=\"0.01233\"", "izz=\"0.05\"");
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidInertia { link, reason }) => {
            assert!(link.ends_with("_lowerleg"), "{link}");
            assert!(reason.contains("triangle"), "{reason}");
        }
        other => panic!("expected InvalidInertia, got {other:?}"),
    }
}

#[test]
fn massless_moving_body_is_an_invalid_inertia() {
    let urdf = urdf_with("<mass value=\"2.93\"/>", "<mass value=\"0\"/>");
    let urdf = urdf.replacen(
        "ixx=\"0.05071\" ixy=\"-4e-05\" ixz=\"-0.00159\" iyy=\"0.05486\" iyz=\"-5e-05\" izz=\"0.00571\"",
        "ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"",
        1,
    );
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidInertia { link, reason }) => {
            assert_eq!(link, "lf_hipassembly");
            assert!(reason.contains("must be positive"), "{reason}");
            assert!(
                reason.contains("give the link"),
                "says what to do: {reason}"
            );
        }
        other => panic!("expected InvalidInertia, got {other:?}"),
    }
}

#[test]
fn singular_moving_body_is_an_invalid_inertia() {
    // A point mass: positive mass, zero tensor. It cannot turn about its joint.
    let urdf = urdf_with(
        "ixx=\"0.05071\" ixy=\"-4e-05\" ixz=\"-0.00159\" iyy=\"0.05486\" iyz=\"-5e-05\" izz=\"0.00571\"",
        "ixx=\"0\" ixy=\"0\" ixz=\"0\" iyy=\"0\" iyz=\"0\" izz=\"0\"",
    );
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidInertia { link, reason }) => {
            assert_eq!(link, "lf_hipassembly");
            assert!(reason.contains("positive definite"), "{reason}");
        }
        other => panic!("expected InvalidInertia, got {other:?}"),
    }
}

#[test]
fn standing_pose_outside_limits() {
    let p = profile_with(
        "{ name = \"lh_kfe\", urdf = \"lh_kfe_joint\", standing = 1.5 }",
        "{ name = \"lh_kfe\", urdf = \"lh_kfe_joint\", standing = -1.5 }",
    )
    .expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::InvalidProfile { field, reason }) => {
            assert_eq!(field, "joints[5].standing");
            assert!(reason.contains("-1.5"), "{reason}");
        }
        other => panic!("expected InvalidProfile, got {other:?}"),
    }
}

#[test]
fn joint_listed_twice() {
    let p = profile_with("urdf = \"lh_haa_joint\"", "urdf = \"lf_haa_joint\"").expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::InvalidProfile { field, reason }) => {
            assert_eq!(field, "joints[3].urdf");
            assert!(reason.contains("twice"), "{reason}");
        }
        other => panic!("expected InvalidProfile, got {other:?}"),
    }
}

#[test]
fn movable_joint_missing_from_profile() {
    let p = profile_with(
        "    { name = \"rh_kfe\", urdf = \"rh_kfe_joint\", standing = 1.5 },\n",
        "",
    )
    .expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::InvalidJoint { joint, reason }) => {
            assert_eq!(joint, "rh_kfe_joint");
            assert!(reason.contains("not listed"), "{reason}");
        }
        other => panic!("expected InvalidJoint, got {other:?}"),
    }
}

#[test]
fn trunk_that_is_not_the_root() {
    let p = profile_with("trunk = \"trunk\"", "trunk = \"lf_upperleg\"").expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::Structure { reason }) => {
            assert!(reason.contains("lf_hfe_joint"), "{reason}");
        }
        other => panic!("expected Structure, got {other:?}"),
    }
}

#[test]
fn disconnected_link() {
    let urdf = urdf_with("</robot>", "<link name=\"stray\"/>\n</robot>");
    match load(&urdf, &profile()) {
        Err(ModelError::Structure { reason }) => assert!(reason.contains("stray"), "{reason}"),
        other => panic!("expected Structure, got {other:?}"),
    }
}

#[test]
fn unsupported_joint_type() {
    let urdf = urdf_with(
        "<joint name=\"lf_kfe_joint\" type=\"revolute\">",
        "<joint name=\"lf_kfe_joint\" type=\"prismatic\">",
    );
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidJoint { joint, reason }) => {
            assert_eq!(joint, "lf_kfe_joint");
            assert!(reason.contains("Prismatic"), "{reason}");
            assert!(
                reason.contains("make it fixed"),
                "says what to do: {reason}"
            );
        }
        other => panic!("expected InvalidJoint, got {other:?}"),
    }
}

#[test]
fn inverted_position_limits() {
    let urdf = urdf_with(
        "lower=\"-2.44346095279\" upper=\"-0.349065850399\"",
        "lower=\"-0.349065850399\" upper=\"-2.44346095279\"",
    );
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidJoint { joint, reason }) => {
            assert_eq!(joint, "lf_kfe_joint");
            assert!(reason.contains("lower < upper"), "{reason}");
        }
        other => panic!("expected InvalidJoint, got {other:?}"),
    }
}

#[test]
fn joint_friction_is_read_into_the_model() {
    let urdf = urdf_with(
        "<dynamics damping=\"0.1\" friction=\"0\"/>",
        "<dynamics damping=\"0.1\" friction=\"2.5\"/>",
    );
    let model = load(&urdf, &profile()).expect("joint friction is supported");
    assert_eq!(model.joints()[0].friction, 2.5);
    assert!(model.joints()[1..].iter().all(|j| j.friction == 0.0));
}

#[test]
fn negative_joint_friction_is_refused() {
    let urdf = urdf_with(
        "<dynamics damping=\"0.1\" friction=\"0\"/>",
        "<dynamics damping=\"0.1\" friction=\"-2.5\"/>",
    );
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidJoint { joint, reason }) => {
            assert_eq!(joint, "lf_haa_joint");
            assert!(reason.contains("-2.5"), "{reason}");
        }
        other => panic!("expected InvalidJoint, got {other:?}"),
    }
}

#[test]
fn mesh_collision_is_unsupported() {
    let urdf = urdf_with(
        "<box size=\"1.2898 0.5954 0.3737\"/>",
        "<mesh filename=\"trunk.dae\"/>",
    );
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidGeometry {
            link,
            collision,
            reason,
        }) => {
            assert_eq!((link.as_str(), collision.as_str()), ("trunk", "trunk"));
            assert!(reason.contains("trunk.dae"), "{reason}");
            assert!(
                reason.contains("rapier and DART"),
                "says what engines take: {reason}"
            );
            assert!(reason.contains("replace it"), "says what to do: {reason}");
        }
        other => panic!("expected InvalidGeometry, got {other:?}"),
    }
}

#[test]
fn non_positive_radius_is_invalid_geometry() {
    let urdf = urdf_with("<sphere radius=\"0.02175\"/>", "<sphere radius=\"0\"/>");
    match load(&urdf, &profile()) {
        Err(ModelError::InvalidGeometry {
            link, collision, ..
        }) => {
            assert_eq!(
                (link.as_str(), collision.as_str()),
                ("lf_lowerleg", "lf_foot")
            );
        }
        other => panic!("expected InvalidGeometry, got {other:?}"),
    }
}

#[test]
fn non_positive_spawn_height() {
    let p = profile_with("height = 0.6003", "height = -1.0").expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::InvalidProfile { field, .. }) => assert_eq!(field, "spawn.height"),
        other => panic!("expected InvalidProfile, got {other:?}"),
    }
}

#[test]
fn negative_gain() {
    let p = profile_with("kd = 20.0", "kd = -20.0").expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::InvalidProfile { field, .. }) => assert_eq!(field, "gains.kd"),
        other => panic!("expected InvalidProfile, got {other:?}"),
    }
}

#[test]
fn profile_without_joints() {
    let mut p = profile();
    p.joints.clear();
    match load(HYQ_URDF, &p) {
        Err(ModelError::InvalidProfile { field, .. }) => assert_eq!(field, "joints"),
        other => panic!("expected InvalidProfile, got {other:?}"),
    }
}

#[test]
fn duplicate_foot_names() {
    let p = profile_with("{ name = \"rh\",", "{ name = \"lf\",").expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::InvalidProfile { field, .. }) => assert_eq!(field, "feet[3].name"),
        other => panic!("expected InvalidProfile, got {other:?}"),
    }
}

#[test]
fn standing_height_must_be_positive_and_defaults_to_the_spawn_height() {
    let p = profile_with("standing_height = 0.5895", "standing_height = -0.1").expect("parses");
    match load(HYQ_URDF, &p) {
        Err(ModelError::InvalidProfile { field, reason }) => {
            assert_eq!(field, "spawn.standing_height");
            assert!(reason.contains("-0.1"), "{reason}");
        }
        other => panic!("expected InvalidProfile, got {other:?}"),
    }
    let p = profile_with("standing_height = 0.5895", "").expect("parses");
    let model = load(HYQ_URDF, &p).expect("loads without standing_height");
    assert_eq!(model.standing_height(), model.spawn_height());
    let model = load(HYQ_URDF, &profile()).expect("bundled HyQ loads");
    assert_eq!(model.standing_height(), 0.5895);
}
