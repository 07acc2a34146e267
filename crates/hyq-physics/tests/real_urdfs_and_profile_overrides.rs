//! The loader takes what upstream URDFs contain, or refuses it with a one-line error that names
//! the file, joint, link or profile key and the fix: joints without position limits (refused
//! unless the profile gives them), continuous joints (actuated with profile limits), profile
//! overrides of ranges, efforts and speeds (checked), optional trunk observation bounds and a
//! gait table (checked against the joints), and robot choices resolved by one function. No
//! input reaches a panic.

use std::path::{Path, PathBuf};

use hyq_physics::bundled::{self, ANYMAL_C_PROFILE, ANYMAL_C_URDF, HYQ_PROFILE, HYQ_URDF};
use hyq_physics::{ModelError, Profile, RobotModel, resolve_robot};

fn load(urdf: &str, profile: &str) -> Result<RobotModel, ModelError> {
    let profile = Profile::from_toml_str(profile, "test.toml")?;
    RobotModel::from_urdf_str(urdf, "test.urdf", &profile)
}

fn replaced(text: &str, from: &str, to: &str) -> String {
    assert!(
        text.contains(from),
        "test fixture: {from:?} not in the text"
    );
    text.replacen(from, to, 1)
}

/// A scratch directory for files a test writes, removed when dropped.
struct Scratch(PathBuf);

impl Scratch {
    fn new(name: &str) -> Self {
        let dir = std::env::temp_dir().join(format!("hyq-physics-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).expect("temp dir");
        Self(dir)
    }

    fn write(&self, name: &str, text: &str) -> PathBuf {
        let path = self.0.join(name);
        std::fs::write(&path, text).expect("write");
        path
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        std::fs::remove_dir_all(&self.0).ok();
    }
}

const LF_KFE_LIMIT: &str =
    r#"<limit lower="-2.44346095279" upper="-0.349065850399" effort="150" velocity="12.0"/>"#;
const LF_KFE_ENTRY: &str = r#"{ name = "lf_kfe", urdf = "lf_kfe_joint", standing = -1.5 }"#;

#[test]
fn a_joint_without_limits_is_refused_with_the_profile_keys_that_fix_it() {
    let urdf = replaced(
        HYQ_URDF,
        LF_KFE_LIMIT,
        r#"<limit effort="150" velocity="12.0"/>"#,
    );
    match load(&urdf, HYQ_PROFILE) {
        Err(e @ ModelError::InvalidJoint { .. }) => {
            let m = e.to_string();
            assert!(m.contains("lf_kfe_joint"), "{m}");
            assert!(
                m.contains("joints[2].lower") && m.contains("joints[2].upper"),
                "{m}"
            );
        }
        other => panic!("expected InvalidJoint, got {other:?}"),
    }
    // The profile's range is the fix.
    let profile = replaced(
        HYQ_PROFILE,
        LF_KFE_ENTRY,
        r#"{ name = "lf_kfe", urdf = "lf_kfe_joint", standing = -1.5, lower = -2.4, upper = -0.4 }"#,
    );
    let model = load(&urdf, &profile).expect("limits from the profile");
    assert_eq!(
        (model.joints()[2].lower, model.joints()[2].upper),
        (-2.4, -0.4)
    );
}

#[test]
fn a_continuous_joint_is_actuated_within_the_profile_range() {
    let urdf = replaced(
        HYQ_URDF,
        r#"<joint name="lf_kfe_joint" type="revolute">"#,
        r#"<joint name="lf_kfe_joint" type="continuous">"#,
    );
    match load(&urdf, HYQ_PROFILE) {
        Err(ModelError::InvalidJoint { joint, reason }) => {
            assert_eq!(joint, "lf_kfe_joint");
            assert!(reason.contains("continuous"), "{reason}");
            assert!(reason.contains("joints[2].lower"), "{reason}");
        }
        other => panic!("expected InvalidJoint, got {other:?}"),
    }
    let profile = replaced(
        HYQ_PROFILE,
        LF_KFE_ENTRY,
        r#"{ name = "lf_kfe", urdf = "lf_kfe_joint", standing = -1.5, lower = -3.0, upper = 0.0 }"#,
    );
    let model = load(&urdf, &profile).expect("continuous joint with a profile range");
    assert_eq!(
        (model.joints()[2].lower, model.joints()[2].upper),
        (-3.0, 0.0)
    );
}

#[test]
fn profile_overrides_replace_the_urdf_limits() {
    let profile = replaced(
        HYQ_PROFILE,
        LF_KFE_ENTRY,
        r#"{ name = "lf_kfe", urdf = "lf_kfe_joint", standing = -1.5, lower = -2.0, upper = -1.0, effort = 90.0, velocity = 8.0 }"#,
    );
    let model = load(HYQ_URDF, &profile).expect("overrides");
    let j = &model.joints()[2];
    assert_eq!(
        (j.lower, j.upper, j.effort, j.velocity),
        (-2.0, -1.0, 90.0, 8.0)
    );
    // Only that joint changed.
    let plain = bundled::hyq();
    assert_eq!(model.joints()[3], plain.joints()[3]);
}

#[test]
fn bad_overrides_name_the_profile_key() {
    for (entry, key) in [
        (r#"lower = -1.0, upper = -2.0"#, "joints[2].lower"),
        (r#"effort = 0.0"#, "joints[2].effort"),
        (r#"velocity = -1.0"#, "joints[2].velocity"),
        (r#"upper = nan"#, "joints[2].upper"),
    ] {
        let profile = replaced(
            HYQ_PROFILE,
            LF_KFE_ENTRY,
            &format!(r#"{{ name = "lf_kfe", urdf = "lf_kfe_joint", standing = -1.5, {entry} }}"#),
        );
        let e = load(HYQ_URDF, &profile).expect_err(entry);
        let m = e.to_string();
        assert!(m.contains(key), "{entry}: {m}");
        assert!(!m.contains('\n'), "one line: {m}");
    }
}

#[test]
fn observation_bounds_are_checked_and_kept() {
    let with = |table: &str| format!("{HYQ_PROFILE}\n[observation]\n{table}\n");
    let model = load(
        HYQ_URDF,
        &with("trunk_position = [[-20.0, 20.0], [-20.0, 20.0], [0.0, 2.0]]"),
    )
    .expect("bounds");
    let bounds = model.observation_bounds().expect("kept");
    assert_eq!(
        bounds.trunk_position,
        Some([[-20.0, 20.0], [-20.0, 20.0], [0.0, 2.0]])
    );
    assert_eq!(bounds.trunk_acceleration, None);
    let e = load(
        HYQ_URDF,
        &with("trunk_position = [[-20.0, 20.0], [-20.0, 20.0], [2.0, 0.0]]"),
    )
    .expect_err("min > max");
    assert!(
        e.to_string().contains("observation.trunk_position[2]"),
        "{e}"
    );
    let e = load(HYQ_URDF, &with("trunk_speed = [[0.0, 1.0]]")).expect_err("unknown key");
    assert!(e.to_string().contains("trunk_speed"), "{e}");
}

#[test]
fn a_gait_naming_an_unknown_or_reused_joint_is_refused() {
    // HyQ's profile without its own [gait] table, then a new one.
    let without = HYQ_PROFILE.split("\n[gait]").next().expect("text");
    let gait = |legs: &str| {
        format!(
            "{without}\n[gait]\nfrequency_hz = 3.0\nhip_amplitude = 0.1\nknee_lift = 0.4\n\
             ramp_s = 1.0\nlegs = [{legs}]\n"
        )
    };
    let e = load(
        HYQ_URDF,
        &gait(r#"{ hip = "lf_hfe", knee = "lf_knee", phase = 0.0 }"#),
    )
    .expect_err("unknown joint");
    let m = e.to_string();
    assert!(
        m.contains("gait.legs[0].knee") && m.contains("lf_knee"),
        "{m}"
    );
    assert!(m.contains("lf_kfe"), "lists the joints: {m}");
    let e = load(
        HYQ_URDF,
        &gait(
            r#"{ hip = "lf_hfe", knee = "lf_kfe", phase = 0.0 }, { hip = "lf_hfe", knee = "rh_kfe", phase = 0.5 }"#,
        ),
    )
    .expect_err("joint used twice");
    assert!(e.to_string().contains("gait.legs[1].hip"), "{e}");
    let e = load(
        HYQ_URDF,
        &gait(r#"{ hip = "lf_hfe", knee = "lf_kfe", phase = 1.0 }"#),
    )
    .expect_err("phase out of [0, 1)");
    assert!(e.to_string().contains("gait.legs[0].phase"), "{e}");
}

#[test]
fn bundled_names_and_profile_paths_resolve_through_one_function() {
    for name in bundled::NAMES {
        let model = resolve_robot(name).expect("bundled");
        assert_eq!(model.name(), name);
        assert!(std::sync::Arc::ptr_eq(
            &model,
            &bundled::by_name(name).expect("bundled")
        ));
    }
    assert_eq!(bundled::DEFAULT, "hyq");
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    for name in bundled::NAMES {
        let path = assets.join(name).join("profile.toml");
        let model = resolve_robot(path.to_str().expect("utf-8 path")).expect("profile path");
        assert_eq!(*model, *bundled::by_name(name).expect("bundled"));
    }
}

#[test]
fn an_unknown_robot_choice_lists_the_bundled_robots() {
    let e = resolve_robot("anymal").expect_err("not bundled, not a path");
    let m = e.to_string();
    assert!(
        m.contains("\"anymal\"") && m.contains("hyq, anymal_c"),
        "{m}"
    );
    assert!(m.contains(".toml"), "says what a path is: {m}");
    let e = resolve_robot("no/such/profile.toml").expect_err("missing file");
    assert!(matches!(e, ModelError::Io { .. }), "{e:?}");
    assert!(e.to_string().contains("no/such/profile.toml"), "{e}");
}

#[test]
fn errors_from_a_profile_file_name_the_file() {
    let scratch = Scratch::new("errors-name-the-file");
    scratch.write("anymal_c.urdf", ANYMAL_C_URDF);
    let path = scratch.write(
        "profile.toml",
        &replaced(
            ANYMAL_C_PROFILE,
            r#"urdf = "RH_KFE""#,
            r#"urdf = "RH_KNEE""#,
        ),
    );
    let e = resolve_robot(path.to_str().expect("utf-8")).expect_err("missing joint");
    let m = e.to_string();
    assert!(
        m.contains(&path.display().to_string()),
        "names the file: {m}"
    );
    assert!(
        m.contains("RH_KNEE") && m.contains("joints[11].urdf"),
        "{m}"
    );
    assert!(!m.contains('\n'), "one line: {m}");
    assert!(
        matches!(e.innermost(), ModelError::MissingJoint { .. }),
        "{e:?}"
    );
}

#[test]
fn no_truncated_or_edited_profile_reaches_a_panic() {
    // Every profile made by dropping one line of a bundled profile, or by replacing every
    // number on one line by a hostile value, loads or fails with an error: never a panic.
    for (urdf, profile) in [(HYQ_URDF, HYQ_PROFILE), (ANYMAL_C_URDF, ANYMAL_C_PROFILE)] {
        let lines: Vec<&str> = profile.lines().collect();
        for skip in 0..lines.len() {
            let text: Vec<&str> = lines
                .iter()
                .enumerate()
                .filter(|&(i, _)| i != skip)
                .map(|(_, l)| *l)
                .collect();
            let _ = load(urdf, &text.join("\n"));
        }
        for (i, line) in lines.iter().enumerate() {
            for hostile in ["-1e308", "0.0", "nan", "inf", "1e-300"] {
                let edited = replace_numbers(line, hostile);
                if edited == *line {
                    continue;
                }
                let mut text = lines.clone();
                text[i] = &edited;
                if let Ok(model) = load(urdf, &text.join("\n")) {
                    // A model that loads is usable: finite limits, lower < upper.
                    for j in model.joints() {
                        assert!(j.lower < j.upper && j.effort > 0.0, "{edited}");
                    }
                }
            }
        }
    }
}

/// `line` with every number (a digit, or a minus sign before a digit, not inside a word)
/// replaced by `value`.
fn replace_numbers(line: &str, value: &str) -> String {
    let chars: Vec<char> = line.chars().collect();
    let mut out = String::new();
    let mut i = 0;
    while i < chars.len() {
        let in_word = i > 0 && (chars[i - 1].is_alphanumeric() || chars[i - 1] == '_');
        let digit_at = |k: usize| chars.get(k).is_some_and(char::is_ascii_digit);
        let starts = !in_word && (digit_at(i) || (chars[i] == '-' && digit_at(i + 1)));
        if !starts {
            out.push(chars[i]);
            i += 1;
            continue;
        }
        i += 1;
        while chars
            .get(i)
            .is_some_and(|c| c.is_ascii_digit() || matches!(c, '.' | 'e' | '-'))
        {
            i += 1;
        }
        out.push_str(value);
    }
    out
}
