//! Invariant: `hyq robot init`'s draft of each bundled robot's file agrees with the robot's
//! hand-made profile on the trunk, the feet, the joint order and names, the standing pose and
//! the spawn height; where it differs (gains by rule, ANYmal C's placeholder ranges, Go1's
//! velocity limits) the test says which and why. The written TOML parses back to the same
//! profile and loads. Bad robot files and SRDFs are one-line errors.

use std::path::{Path, PathBuf};

use hyq_formats::draft::{self, DEFAULT_VELOCITY, Draft};
use hyq_physics::Profile;

fn asset(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets")
        .join(path)
}

fn fixture(path: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("tests/fixtures")
        .join(path)
}

fn hand_made(robot: &str) -> Profile {
    let path = asset(&format!("{robot}/profile.toml"));
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
    Profile::from_toml_str(&text, robot).unwrap_or_else(|e| panic!("{e}"))
}

fn drafted(robot: &str, srdf: Option<&str>) -> Draft {
    let srdf = srdf.map(fixture);
    draft::draft_file(&asset(robot), srdf.as_deref(), "robot")
        .unwrap_or_else(|e| panic!("{robot}: {e}"))
}

/// The draft's trunk, feet, joint names, joint files' names, standing pose and spawn height
/// are the hand-made profile's; its TOML parses back to itself and loads.
fn agrees(draft: &Draft, hand: &Profile) {
    let p = draft.profile();
    assert_eq!(p.trunk, hand.trunk);
    assert_eq!(p.feet, hand.feet);
    let names = |p: &Profile| -> Vec<(String, String, f64)> {
        p.joints
            .iter()
            .map(|j| (j.name.clone(), j.urdf.clone(), j.standing))
            .collect()
    };
    assert_eq!(names(p), names(hand));
    assert_eq!(p.spawn.height, hand.spawn.height);
    let gait = p.gait.as_ref().expect("a named quadruped gets a trot");
    let hand_gait = hand.gait.as_ref().map(|g| &g.legs);
    if let Some(legs) = hand_gait {
        assert_eq!(&gait.legs, legs, "the same diagonal pairs");
    }
    let text = draft.to_toml();
    let back = Profile::from_toml_str(&text, "draft").unwrap_or_else(|e| panic!("{e}\n{text}"));
    assert_eq!(&back, p, "the written TOML is the draft");
    let model = draft.model().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.num_feet(), 4);
}

#[test]
fn go1_from_its_mjcf_is_its_profile_but_for_the_velocity_limits() {
    let draft = drafted("go1/go1.xml", None);
    let hand = hand_made("go1");
    agrees(&draft, &hand);
    let p = draft.profile();
    // The <position> servos' kp 35 and kv 0: the hand-made profile's gains.
    assert_eq!((p.gains.kp, p.gains.kd), (hand.gains.kp, hand.gains.kd));
    // MJCF has no velocity limit: the draft says DEFAULT_VELOCITY, the hand-made profile has
    // Unitree's URDF figures (30.1 and 20.06 rad/s).
    assert!(
        p.joints
            .iter()
            .all(|j| j.velocity == Some(DEFAULT_VELOCITY))
    );
    assert!(
        hand.joints
            .iter()
            .all(|j| j.velocity != Some(DEFAULT_VELOCITY))
    );
    let text = draft.to_toml();
    assert!(text.contains("`home` keyframe"), "{text}");
    assert!(text.contains("<position> actuator"), "{text}");
}

#[test]
fn hyq_from_its_urdf_and_standing_state_is_its_profile_but_for_the_rule_s_gains() {
    let draft = drafted("hyq/hyq.urdf", Some("hyq.srdf"));
    let hand = hand_made("hyq");
    agrees(&draft, &hand);
    // The rule (0.05 rad of sag under a quarter of the weight) gives kp 990 where the chosen
    // 1000 gives 0.045 rad; kd from the leg's inertia: 21 against the chosen 20.
    let g = &draft.profile().gains;
    assert!(
        (g.kp - hand.gains.kp).abs() <= 0.05 * hand.gains.kp,
        "kp {}",
        g.kp
    );
    assert!(
        (g.kd - hand.gains.kd).abs() <= 0.5 * hand.gains.kd,
        "kd {}",
        g.kd
    );
}

#[test]
fn anymal_c_from_its_urdf_and_standing_state_keeps_the_urdf_s_ranges() {
    let draft = drafted("anymal_c/anymal_c.urdf", Some("anymal_c.srdf"));
    let hand = hand_made("anymal_c");
    agrees(&draft, &hand);
    // The URDF's HFE and KFE ranges are ±3π placeholders: the draft writes them out, the
    // hand-made profile replaces them (its comment says with what and why).
    let p = draft.profile();
    let hfe = &p.joints[1];
    assert!(hfe.upper.is_some_and(|u| u > 9.0), "{hfe:?}");
    assert!(hand.joints[1].upper.is_some_and(|u| u < 2.0));
    // The rule gives kp 460 and kd 14 where 400 and 10 were chosen: same order, a little stiffer.
    assert!(
        (p.gains.kp - hand.gains.kp).abs() <= 0.2 * hand.gains.kp,
        "kp {}",
        p.gains.kp
    );
    assert!(
        (p.gains.kd - hand.gains.kd).abs() <= 0.5 * hand.gains.kd,
        "kd {}",
        p.gains.kd
    );
}

#[test]
fn a_urdf_without_srdf_stands_at_zero_or_the_nearest_limit_and_says_so() {
    let draft = drafted("hyq/hyq.urdf", None);
    let p = draft.profile();
    // HyQ's knees cannot be at 0: the front ones stand at their upper limit, the hind ones at
    // their lower.
    let kfe = |name: &str| {
        p.joints
            .iter()
            .find(|j| j.name == name)
            .map(|j| (j.standing, j.lower, j.upper))
    };
    let (s, _, upper) = kfe("lf_kfe").expect("lf_kfe");
    assert_eq!(Some(s), upper);
    let (s, lower, _) = kfe("lh_kfe").expect("lh_kfe");
    assert_eq!(Some(s), lower);
    assert_eq!(
        p.joints
            .iter()
            .find(|j| j.name == "lf_hfe")
            .map(|j| j.standing),
        Some(0.0)
    );
    assert!(draft.to_toml().contains("EDIT THEM"));
    draft.model().unwrap_or_else(|e| panic!("{e}"));
}

#[test]
fn a_settled_height_is_written_with_how_it_was_measured() {
    let mut draft = drafted("go1/go1.xml", None);
    assert!(draft.to_toml().contains("# standing_height ="));
    draft.set_standing_height(0.263_447, "Measured on rapier 1 s after spawn.");
    let text = draft.to_toml();
    assert!(text.contains("standing_height = 0.2634\n"), "{text}");
    assert!(text.contains("Measured on rapier"));
}

/// The draft of `robot` (text written to a temporary file named `name`) fails with one line
/// containing `what`.
fn refused(name: &str, robot: &str, srdf: Option<&str>, what: &str) {
    let dir = std::env::temp_dir().join(format!("hyq-draft-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join(name);
    std::fs::write(&path, robot).unwrap_or_else(|e| panic!("{e}"));
    let srdf_path = srdf.map(|s| {
        let p = dir.join("robot.srdf");
        std::fs::write(&p, s).unwrap_or_else(|e| panic!("{e}"));
        p
    });
    let result = draft::draft_file(&path, srdf_path.as_deref(), "robot");
    let _ = std::fs::remove_dir_all(&dir);
    let e = result.expect_err(name).to_string();
    assert!(!e.contains('\n'), "one line: {e}");
    assert!(e.contains(what), "{name}: {e:?} should say {what:?}");
}

const ONE_LINK: &str = r#"<robot name="r"><link name="base"><collision><geometry><box size="1 1 1"/></geometry></collision><inertial><mass value="1"/><inertia ixx="1" iyy="1" izz="1" ixy="0" ixz="0" iyz="0"/></inertial></link></robot>"#;

#[test]
fn bad_robot_files_are_one_line_errors() {
    let missing = draft::draft_file(Path::new("/nonexistent/robot.urdf"), None, "r");
    assert!(missing.is_err_and(|e| e.to_string().contains("/nonexistent/robot.urdf")));
    refused("not-xml.urdf", "this is not XML", None, "not a URDF");
    refused("not-xml.xml", "{ \"json\": 1 }", None, "not-xml.xml");
    refused("no-legs.urdf", ONE_LINK, None, "no legs");
    let world = ONE_LINK.replace(
        "</robot>",
        r#"<link name="world"/><joint name="fix" type="fixed"><parent link="world"/><child link="base"/></joint></robot>"#,
    );
    refused("world.urdf", &world, None, "no free root");
    let deep = format!(
        "<robot name=\"r\">{}{}</robot>",
        "<a>".repeat(10_000),
        "</a>".repeat(10_000)
    );
    refused("deep.urdf", &deep, None, "deep");
    let mjcf_no_free =
        r#"<mujoco><worldbody><body name="b"><geom size="0.1"/></body></worldbody></mujoco>"#;
    refused("no-free.xml", mjcf_no_free, None, "free");
}

#[test]
fn bad_srdfs_are_one_line_errors() {
    let urdf = std::fs::read_to_string(asset("hyq/hyq.urdf")).unwrap_or_else(|e| panic!("{e}"));
    let unknown = r#"<robot name="hyq"><group_state name="standing" group="all"><joint name="lf_elbow" value="1"/></group_state></robot>"#;
    refused("hyq.urdf", &urdf, Some(unknown), "lf_elbow");
    let no_state = r#"<robot name="hyq"><group_state name="sitting" group="all"/></robot>"#;
    refused("hyq.urdf", &urdf, Some(no_state), "sitting");
    let nan = r#"<robot name="hyq"><group_state name="standing" group="all"><joint name="lf_haa_joint" value="nan"/></group_state></robot>"#;
    refused("hyq.urdf", &urdf, Some(nan), "finite");
    refused("hyq.urdf", &urdf, Some("<robot"), "not XML");
    let outside = r#"<robot name="hyq"><group_state name="standing" group="all"><joint name="lf_kfe_joint" value="1"/></group_state></robot>"#;
    refused("hyq.urdf", &urdf, Some(outside), "outside");
}

#[test]
fn an_mjcf_file_alone_resolves_to_its_draft_unless_it_lacks_a_pose_or_gains() {
    use hyq_formats::robots::{resolve, resolve_with};
    let path = asset("go1/go1.xml");
    let choice = path.to_str().expect("a UTF-8 path");
    let model = resolve(choice).unwrap_or_else(|e| panic!("{e}"));
    let bundled = hyq_formats::robots::load_go1().unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(model.name(), "go1");
    assert_eq!(model.standing_pose(), bundled.standing_pose());
    assert_eq!(model.kp(), bundled.kp());
    assert_eq!(model.spawn_height(), bundled.spawn_height());
    // No settle run: the spawn height stands for the standing height; with one, its figure.
    assert_eq!(model.standing_height(), model.spawn_height());
    let settle = |_| Ok(0.26);
    let settled = resolve_with(choice, Some(&settle)).unwrap_or_else(|e| panic!("{e}"));
    assert_eq!(settled.standing_height(), 0.26);
    let falls = |_| Err("it fell".to_owned());
    let e = resolve_with(choice, Some(&falls))
        .expect_err("a robot that falls")
        .to_string();
    assert!(e.contains("it fell") && e.contains("hyq robot init"), "{e}");

    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{e}"));
    let dir = std::env::temp_dir().join(format!("hyq-alone-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let cut = |from: &str, to: &str| {
        let start = text.find(from).expect("the element");
        let end = text[start..].find(to).expect("its end") + start + to.len();
        format!("{}{}", &text[..start], &text[end..])
    };
    for (name, edited, why) in [
        (
            "no-key.xml",
            cut("<keyframe>", "</keyframe>"),
            "no keyframe",
        ),
        (
            "no-servo.xml",
            // The keyframe's controls go with the actuators.
            without_ctrl(&cut("<actuator>", "</actuator>")),
            "no <position> actuator",
        ),
    ] {
        let file = dir.join(name);
        std::fs::write(&file, edited).unwrap_or_else(|e| panic!("{e}"));
        let e = resolve(file.to_str().expect("UTF-8"))
            .expect_err(name)
            .to_string();
        assert!(
            e.contains(why) && e.contains("hyq robot init"),
            "{name}: {e}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `text` without its first ` ctrl="…"` attribute.
fn without_ctrl(text: &str) -> String {
    let start = text.find(" ctrl=\"").expect("a ctrl attribute");
    let value = start + " ctrl=\"".len();
    let end = text[value..].find('"').expect("its closing quote") + value + 1;
    format!("{}{}", &text[..start], &text[end..])
}

#[test]
fn legs_that_are_not_four_of_three_joints_keep_the_file_s_order_and_names() {
    // ANYmal C with its hip abduction joints fixed: four legs of two joints.
    let mut urdf =
        std::fs::read_to_string(asset("anymal_c/anymal_c.urdf")).unwrap_or_else(|e| panic!("{e}"));
    for leg in ["LF", "LH", "RF", "RH"] {
        let revolute = format!("<joint name=\"{leg}_HAA\" type=\"revolute\">");
        assert!(urdf.contains(&revolute));
        urdf = urdf.replace(
            &revolute,
            &format!("<joint name=\"{leg}_HAA\" type=\"fixed\">"),
        );
    }
    let dir = std::env::temp_dir().join(format!("hyq-eight-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap_or_else(|e| panic!("{e}"));
    let path = dir.join("anymal_8.urdf");
    std::fs::write(&path, &urdf).unwrap_or_else(|e| panic!("{e}"));
    let draft = draft::draft_file(&path, None, "anymal_8.urdf").unwrap_or_else(|e| panic!("{e}"));
    let _ = std::fs::remove_dir_all(&dir);
    let p = draft.profile();
    let names: Vec<&str> = p.joints.iter().map(|j| j.name.as_str()).collect();
    assert_eq!(names.len(), 8);
    assert_eq!(names, file_order(&urdf), "the file's order");
    assert!(
        p.joints.iter().all(|j| j.name == j.urdf),
        "the file's names"
    );
    assert_eq!(p.feet.len(), 4);
    assert!(p.gait.is_none(), "no trot without the project's leg names");
    let text = draft.to_toml();
    assert!(text.contains("not four of three joints"), "{text}");
    draft.model().unwrap_or_else(|e| panic!("{e}"));
}

/// The revolute joints' names in the order the URDF text lists them.
fn file_order(urdf: &str) -> Vec<&str> {
    urdf.split("<joint name=\"")
        .skip(1)
        .filter(|rest| {
            rest.contains("type=\"revolute\"") && rest.find("type=\"revolute\"") < rest.find('>')
        })
        .filter_map(|rest| rest.split('"').next())
        .collect()
}
