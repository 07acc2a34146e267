//! A robot's files are read through the size-capped reader and checked before the XML parser
//! runs: a file past its cap is refused from its size, a URDF nested thousands deep (which
//! would overflow the parser's stack, an abort no caller can catch) is refused by its depth, and
//! one with tens of thousands of links or shapes is refused by count, each with one line naming
//! the file and what was too big.

use std::path::{Path, PathBuf};

use hyq_physics::bundled::{HYQ_PROFILE, HYQ_URDF};
use hyq_physics::{ModelError, RobotModel};

/// A directory holding the HyQ profile and `urdf` as its URDF (and the profile's text changed
/// by `profile_edit`).
fn robot_dir(tag: &str, urdf: &str, profile_edit: (&str, &str)) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("hyq-caps-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    std::fs::write(dir.join("hyq.urdf"), urdf).expect("urdf");
    let profile = HYQ_PROFILE.replacen(profile_edit.0, profile_edit.1, 1);
    std::fs::write(dir.join("profile.toml"), profile).expect("profile");
    dir
}

fn load_from(dir: &Path) -> Result<RobotModel, ModelError> {
    let result = RobotModel::load(dir.join("profile.toml"));
    std::fs::remove_dir_all(dir).ok();
    result
}

fn one_line(e: &ModelError) -> String {
    let text = e.to_string();
    assert!(!text.contains('\n'), "one line: {text}");
    text
}

#[test]
fn deeply_nested_urdf_is_refused_before_parsing() {
    // 20 000 nested elements (120 KB): enough to overflow the parser's stack, which aborted the
    // CLI and killed Python with a segmentation fault.
    let deep = HYQ_URDF.replacen(
        "</robot>",
        &format!("{}{}</robot>", "<a>".repeat(20_000), "</a>".repeat(20_000)),
        1,
    );
    let e = load_from(&robot_dir("deep", &deep, ("", ""))).expect_err("too deep");
    let text = one_line(&e);
    assert!(
        text.contains("hyq.urdf") && text.contains("nested more than 64 deep"),
        "{text}"
    );
    // Foreign elements a few levels deep (vendor extensions) still load.
    let nested = HYQ_URDF.replacen(
        "</robot>",
        "<gazebo><plugin><a><b><c/></b></a></plugin></gazebo></robot>",
        1,
    );
    load_from(&robot_dir("nested", &nested, ("", ""))).expect("a few levels load");
}

#[test]
fn oversized_profile_and_urdf_files_are_refused_at_their_cap() {
    // Sparse files past the caps: refused from their size, before a byte is read.
    let dir = std::env::temp_dir().join(format!("hyq-caps-big-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let big = |name: &str, bytes: u64| {
        let path = dir.join(name);
        std::fs::File::create(&path)
            .and_then(|f| f.set_len(bytes))
            .expect("a sparse file");
        path
    };
    let profile = big("big_profile.toml", (1 << 20) + 1);
    let text = one_line(&RobotModel::load(&profile).expect_err("a 1 MiB + 1 profile"));
    assert!(
        text.contains("big_profile.toml")
            && text.contains("larger than 1 MiB, which no robot profile is"),
        "{text}"
    );
    let urdf = big("big.urdf", (8 << 20) + 1);
    let profile = HYQ_PROFILE.replacen(
        "urdf = \"hyq.urdf\"",
        &format!("urdf = {:?}", urdf.display().to_string()),
        1,
    );
    std::fs::write(dir.join("profile.toml"), profile).expect("profile");
    let text = one_line(&load_from(&dir).expect_err("an 8 MiB + 1 URDF"));
    assert!(
        text.contains("big.urdf: larger than 8 MiB, which no URDF is"),
        "{text}"
    );
}

/// The bundled URDF with `count` extra fixed links on the trunk, each carrying `shapes` spheres.
fn with_extra_links(count: usize, shapes: usize) -> String {
    let mut extra = String::new();
    for i in 0..count {
        extra.push_str(&format!("<link name=\"x{i}\">"));
        for _ in 0..shapes {
            extra.push_str("<collision><geometry><sphere radius=\"0.01\"/></geometry></collision>");
        }
        extra.push_str(&format!(
            "</link><joint name=\"xj{i}\" type=\"fixed\"><parent link=\"trunk\"/>\
             <child link=\"x{i}\"/></joint>\n"
        ));
    }
    HYQ_URDF.replacen("</robot>", &format!("{extra}</robot>"), 1)
}

#[test]
fn urdf_with_too_many_links_joints_or_shapes_is_refused_by_name() {
    let links = load_from(&robot_dir("links", &with_extra_links(1001, 1), ("", "")))
        .expect_err("1015 links");
    let text = one_line(&links);
    assert!(
        text.contains("the URDF's links: 1015 is more than the 1000 allowed"),
        "{text}"
    );
    let shapes = load_from(&robot_dir("shapes", &with_extra_links(100, 10), ("", "")))
        .expect_err("1000 extra shapes");
    let text = one_line(&shapes);
    assert!(text.contains("the URDF's collision shapes:"), "{text}");
    load_from(&robot_dir("fine", &with_extra_links(200, 1), ("", ""))).expect("200 links load");
}
