//! Go1 from Unitree's URDF (`assets/go1_urdf/`) against Go1 from Playground's MJCF
//! (`assets/go1/`), both at the MJCF profile's pose, spawn and gains (the profile pointed at the
//! URDF: `urdf`, `trunk` and the feet renamed). As given the two files differ (foot spheres r
//! 0.020 against 0.023 m; joint damping 0.01 against 0.5 N m s/rad and Coulomb friction 0.2
//! against 0.3 / 0.3 / 1.0 N m; the URDF's trunk carries the four hip rotors, 0.357 kg, that
//! the MJCF leaves out: `crates/hyq-formats/tests/go1_mjcf_and_urdf.rs`), so they stand apart by
//! each engine's stated gaps; given the MJCF's feet and joint dynamics the URDF stands within
//! 2 mm of the MJCF on every engine (the rotors' 2.8 % of the weight, at kp 35, sags it about
//! 1 mm). Each engine's test file calls [`go1_mjcf_and_urdf_tests!`](crate::go1_mjcf_and_urdf_tests)
//! with its figures.

use std::path::Path;

use hyq_physics::Backend;

use crate::fixtures::Robot;
use crate::standing_heights;

/// The URDF Go1 under the MJCF Go1's profile; with `mjcf_feet_and_dynamics`, its foot spheres
/// and joint damping and friction set to the MJCF's.
pub fn urdf_go1(mjcf_feet_and_dynamics: bool) -> Robot {
    let assets = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../assets");
    let mut urdf = std::fs::read_to_string(assets.join("go1_urdf/go1.urdf")).expect("reads");
    let mut profile = hyq_formats::robots::GO1_PROFILE.to_owned();
    let mut edits = vec![
        (
            "urdf = \"go1.xml\"".to_owned(),
            "urdf = \"go1.urdf\"".to_owned(),
        ),
        (
            "trunk = \"trunk\"".to_owned(),
            "trunk = \"base\"".to_owned(),
        ),
    ];
    for (short, leg) in [("lf", "FL"), ("lh", "RL"), ("rf", "FR"), ("rh", "RR")] {
        edits.push((
            format!("link = \"{leg}_calf\", collision = \"{leg}\""),
            format!("link = \"{leg}_foot\", collision = \"{short}_foot\""),
        ));
    }
    if mjcf_feet_and_dynamics {
        urdf = with_mjcf_feet_and_dynamics(&urdf);
    } else {
        // 3 mm smaller feet: the same 1 mm clearance 3 mm lower.
        edits.push(("height = 0.2955".to_owned(), "height = 0.2925".to_owned()));
    }
    for (from, to) in edits {
        assert!(profile.contains(&from), "the Go1 profile has no {from}");
        profile = profile.replace(&from, &to);
    }
    Robot::from_text(&urdf, &profile, "go1_urdf under the MJCF Go1's profile")
}

/// The URDF with the MJCF's foot radius, joint damping and per-joint Coulomb friction.
fn with_mjcf_feet_and_dynamics(urdf: &str) -> String {
    let urdf = urdf.replace("<sphere radius=\"0.02\"/>", "<sphere radius=\"0.023\"/>");
    let mut out = String::new();
    let mut calf = false;
    for line in urdf.lines() {
        if line.contains("<joint name=") {
            calf = line.contains("_calf_joint");
        }
        let friction = if calf { "1.0" } else { "0.3" };
        out.push_str(&line.replace(
            "damping=\"0.01\" friction=\"0.2\"",
            &format!("damping=\"0.5\" friction=\"{friction}\""),
        ));
        out.push('\n');
    }
    out
}

/// The bundled Go1, from Playground's MJCF.
pub fn mjcf_go1() -> Robot {
    Robot {
        model: hyq_formats::robots::by_name("go1").expect("bundled"),
        urdf: hyq_formats::robots::go1_urdf().expect("writes"),
        profile: hyq_formats::robots::go1_profile().expect("parses"),
    }
}

/// The standing-height gaps URDF − MJCF (mm) 1 s and 10 s after spawn on engine `B`.
pub fn standing_gaps_mm<B: Backend>(urdf: &Robot) -> (f64, f64) {
    let (m1, m10) = standing_heights::<B>(&mjcf_go1(), &Default::default());
    let (u1, u10) = standing_heights::<B>(urdf, &Default::default());
    println!("MJCF {m1:.5} / {m10:.5} m, URDF {u1:.5} / {u10:.5} m at 1 s / 10 s");
    (1e3 * (u1 - m1), 1e3 * (u10 - m10))
}

/// The two Go1 tests for one engine: as given, the URDF Go1 stands `as_given_mm` (1 s, 10 s;
/// within 0.5 mm) from the MJCF Go1; with the MJCF's feet and joint dynamics, within 2 mm.
#[macro_export]
macro_rules! go1_mjcf_and_urdf_tests {
    (engine: $engine:ty, as_given_mm: ($at_1s:expr, $at_10s:expr) $(,)?) => {
        #[test]
        fn as_given_they_stand_apart_by_the_stated_gaps() {
            let urdf = $crate::go1_pair::urdf_go1(false);
            let (at_1s, at_10s) = $crate::go1_pair::standing_gaps_mm::<$engine>(&urdf);
            assert!((at_1s - $at_1s).abs() < 0.5, "{at_1s} mm at 1 s");
            assert!((at_10s - $at_10s).abs() < 0.5, "{at_10s} mm at 10 s");
        }

        #[test]
        fn with_the_mjcf_feet_and_joint_dynamics_they_stand_within_2_mm() {
            let urdf = $crate::go1_pair::urdf_go1(true);
            let (at_1s, at_10s) = $crate::go1_pair::standing_gaps_mm::<$engine>(&urdf);
            assert!(
                at_1s.abs() < 2.0 && at_10s.abs() < 2.0,
                "{at_1s} mm, {at_10s} mm"
            );
        }
    };
}
