//! Every number of a robot profile and its URDF is checked against one table of bounds
//! (`hyq_physics::bounds`), so a model that loads keeps everything derived from it finite (in
//! f64 and in f32): a number outside its row is refused with the field or element named and the
//! row's range, the bundled robots lie inside every row, and `docs/adding-a-robot.md` prints the
//! same table.

use hyq_physics::bounds::{self, TABLE};
use hyq_physics::bundled::{HYQ_PROFILE, HYQ_URDF};
use hyq_physics::{ModelError, Profile, RobotModel};

fn load(profile_text: &str, urdf: &str) -> Result<RobotModel, ModelError> {
    let profile = Profile::from_toml_str(profile_text, "P.toml")?;
    RobotModel::from_urdf_str(urdf, "P.urdf", &profile)
}

/// The bundled HyQ with one exact piece of its profile replaced.
fn with_profile(from: &str, to: &str) -> Result<RobotModel, ModelError> {
    assert!(HYQ_PROFILE.contains(from), "fixture: {from:?}");
    load(&HYQ_PROFILE.replacen(from, to, 1), HYQ_URDF)
}

/// The bundled HyQ with one exact piece of its URDF replaced.
fn with_urdf(from: &str, to: &str) -> Result<RobotModel, ModelError> {
    assert!(HYQ_URDF.contains(from), "fixture: {from:?}");
    load(HYQ_PROFILE, &HYQ_URDF.replacen(from, to, 1))
}

fn refused(result: Result<RobotModel, ModelError>, expect: &[&str]) -> String {
    let e = result.expect_err("refused").to_string();
    for part in expect {
        assert!(e.contains(part), "{part:?} not in {e}");
    }
    assert!(!e.contains('\n'), "one line: {e}");
    e
}

const LF_HAA: &str = "{ name = \"lf_haa\", urdf = \"lf_haa_joint\", standing = -0.2 }";

#[test]
fn joint_limits_whose_span_overflows_are_refused_by_name() {
    // Finite, lower < upper, but the span is infinite: the normalised map, the random policy and
    // the midpoint would all overflow.
    let e = refused(
        with_profile(
            LF_HAA,
            "{ name = \"lf_haa\", urdf = \"lf_haa_joint\", standing = -0.2, lower = -1.7e308, upper = 1.7e308 }",
        ),
        &["joints[0].lower", "[-1000, 1000] rad"],
    );
    assert!(e.contains("-1.7e308"), "short form: {e}");
    refused(
        with_urdf("<limit lower=\"-1.2217304764\"", "<limit lower=\"-1e39\""),
        &["lf_haa_joint", "lower position limit", "joints[0].lower"],
    );
    // A range too narrow for float32 spaces to keep low < high.
    refused(
        with_profile(
            LF_HAA,
            "{ name = \"lf_haa\", urdf = \"lf_haa_joint\", standing = -0.2, lower = -0.2, upper = -0.1999999 }",
        ),
        &["range", "[0.001, 2000] rad"],
    );
    for (key, value) in [("effort", "1e308"), ("velocity", "1e39"), ("effort", "0")] {
        refused(
            with_profile(
                LF_HAA,
                &format!(
                    "{{ name = \"lf_haa\", urdf = \"lf_haa_joint\", standing = -0.2, {key} = {value} }}"
                ),
            ),
            &[&format!("joints[0].{key}")],
        );
    }
    // At the table's ends the model loads.
    with_profile(
        LF_HAA,
        "{ name = \"lf_haa\", urdf = \"lf_haa_joint\", standing = -0.2, lower = -1000.0, upper = 1000.0, effort = 1e6, velocity = 1e4 }",
    )
    .expect("the table's ends load");
}

#[test]
fn masses_an_f32_engine_cannot_hold_are_refused() {
    let hip_mass = "<mass value=\"2.93\"/>";
    for (mass, expect) in [
        ("1e39", "[0, 1e6] kg"),
        ("1e300", "[0, 1e6] kg"),
        ("1e-30", "[1e-4, 1e6] kg"),
        ("1e-12", "[1e-4, 1e6] kg"),
        ("1e-46", "[1e-4, 1e6] kg"),
    ] {
        refused(
            with_urdf(hip_mass, &format!("<mass value=\"{mass}\"/>")),
            &["lf_hipassembly", expect],
        );
    }
    refused(
        with_urdf(
            "ixx=\"0.05071\" ixy=\"-4e-05\"",
            "ixx=\"1e300\" ixy=\"-4e-05\"",
        ),
        &["tensor entry", "[-1e6, 1e6] kg·m²"],
    );
    with_urdf(hip_mass, "<mass value=\"1e-3\"/>").expect("a gram is a mass");
}

#[test]
fn gait_frequency_the_trot_cannot_use_is_refused() {
    refused(
        with_profile("frequency_hz = 3.0", "frequency_hz = 1e308"),
        &["gait.frequency_hz", "(0, 50] Hz"],
    );
    refused(
        with_profile("hip_amplitude = 0.1", "hip_amplitude = 1e308"),
        &["gait.hip_amplitude"],
    );
    let e = refused(
        with_profile("phase = 0.0", "phase = 1e308"),
        &["gait.legs[0].phase"],
    );
    assert!(e.len() < 200, "the number in short form: {e}");
    with_profile("frequency_hz = 3.0", "frequency_hz = 50.0").expect("50 Hz loads");
}

#[test]
fn profile_names_must_be_short_printable_ascii() {
    for bad in ["", "x\\u001b[31mRED\\nhyq: fake", "two words"] {
        refused(
            with_profile("name = \"hyq\"", &format!("name = \"{bad}\"")),
            &["robot profile field name"],
        );
    }
    refused(
        with_profile(
            "name = \"hyq\"",
            &format!("name = \"{}\"", "a".repeat(100_000)),
        ),
        &["100000 characters long"],
    );
    refused(
        with_profile("{ name = \"lf\",", "{ name = \"l\\nf\","),
        &["feet[0].name"],
    );
    refused(
        with_profile("name = \"lf_haa\"", "name = \"\""),
        &["joints[0].name"],
    );
}

#[test]
fn huge_or_tiny_collision_geometry_is_refused_at_load() {
    let trunk_box = "<box size=\"1.2898 0.5954 0.3737\"/>";
    assert!(HYQ_URDF.contains(trunk_box), "fixture");
    for size in ["1e6 1e6 1e6", "1e-300 0.5954 0.3737"] {
        refused(
            with_urdf(trunk_box, &format!("<box size=\"{size}\"/>")),
            &["trunk", "[1e-4, 100] m"],
        );
    }
    refused(
        with_urdf(
            "<origin xyz=\"0 0 0.08315\" rpy=\"0 0 0\"/>",
            "<origin xyz=\"1e30 0 0.08315\" rpy=\"0 0 0\"/>",
        ),
        &["<origin xyz", "[-100, 100] m"],
    );
}

#[test]
fn spawn_heights_outside_the_table_name_the_profile_key() {
    refused(
        with_profile("height = 0.6003", "height = 1e6"),
        &["spawn.height", "(0, 10] m"],
    );
    let e = refused(
        with_profile("standing_height = 0.5895", "standing_height = 1e308"),
        &["spawn.standing_height"],
    );
    assert!(!e.contains("goal") && e.len() < 200, "{e}");
}

#[test]
fn the_bundled_robots_lie_inside_every_row() {
    for name in hyq_physics::bundled::NAMES {
        let model = hyq_physics::bundled::load(name).expect("bundled loads");
        for j in model.joints() {
            for (b, v) in [
                (&bounds::JOINT_ANGLE, j.lower),
                (&bounds::JOINT_ANGLE, j.upper),
                (&bounds::JOINT_SPAN, j.upper - j.lower),
                (&bounds::JOINT_EFFORT, j.effort),
                (&bounds::JOINT_VELOCITY, j.velocity),
            ] {
                b.check(v)
                    .unwrap_or_else(|e| panic!("{name} {}: {e}", j.name));
            }
        }
        for l in model.links() {
            bounds::BODY_MASS
                .check(l.mass)
                .unwrap_or_else(|e| panic!("{name} {}: {e}", l.name));
        }
    }
}

#[test]
fn the_documentation_prints_the_table() {
    let doc = std::fs::read_to_string(
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/adding-a-robot.md"),
    )
    .expect("docs/adding-a-robot.md");
    for b in TABLE {
        let row = format!("| {} | {} |", b.quantity, b.range());
        assert!(
            doc.contains(&row),
            "docs/adding-a-robot.md lacks the row {row:?}"
        );
        assert!(
            doc.contains(b.why),
            "docs/adding-a-robot.md lacks {:?}",
            b.why
        );
    }
}
