//! A profile whose robot file is MJCF (`.xml`) is read by hyq-formats, which depends on this
//! crate; loaded here it is refused in one line saying where to load it, not fed to the URDF
//! parser.

#[test]
fn a_profile_naming_an_xml_file_is_refused_with_where_to_load_it() {
    let dir = std::env::temp_dir().join(format!("hyq-physics-mjcf-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let profile = hyq_physics::bundled::ANYMAL_C_PROFILE.replace("anymal_c.urdf", "robot.xml");
    std::fs::write(dir.join("profile.toml"), profile).expect("write");
    std::fs::write(dir.join("robot.xml"), "<mujoco/>").expect("write");
    let e = hyq_physics::RobotModel::load(dir.join("profile.toml")).expect_err("MJCF");
    let m = e.to_string();
    assert!(
        m.contains("robot.xml") && m.contains("hyq_formats::robots::load_profile"),
        "{m}"
    );
    assert!(!m.contains('\n'), "{m}");
    let _ = std::fs::remove_dir_all(&dir);
}
