//! Every bad `[randomize]` value is refused before anything runs, with one line naming the key
//! and the value: reversed or non-finite ranges, a scale that can make a mass or gain ≤ 0, a
//! delay longer than an env step, a negative noise deviation, an unknown key or preset, pushes
//! without a speed, an added mass that can make the robot's trunk weightless, and masses that
//! pass as positive but that no engine holds (DART aborted the process on them).

use hyq_env::{Env, EnvConfig};
use hyq_rapier::RapierBackend;

fn refused(pairs: &[(&str, &str)]) -> String {
    let err = EnvConfig::load::<&str, &str>(None, pairs)
        .expect_err("a bad [randomize] value")
        .to_string();
    assert!(!err.contains('\n'), "one line: {err:?}");
    err
}

#[test]
fn each_bad_value_names_its_key_and_value() {
    let cases: &[(&str, &str, &str)] = &[
        ("randomize.ground_friction", "[1.0, 0.5]", "lo <= hi"),
        ("randomize.ground_friction", "[-0.1, 0.5]", "lo >= 0"),
        ("randomize.ground_friction", "[0.5, inf]", "finite"),
        ("randomize.ground_friction", "[nan, 0.5]", "finite"),
        ("randomize.kp_scale", "[0.0, 1.0]", "lo > 0"),
        ("randomize.kd_scale", "[-0.5, 1.0]", "lo > 0"),
        ("randomize.effort_scale", "[0.5, 1000.0]", "hi <= 100"),
        (
            "randomize.link_mass_scale",
            "[0.0, 1.1]",
            "mass, gain or effort",
        ),
        ("randomize.joint_damping_scale", "[2.0, 1.0]", "lo <= hi"),
        ("randomize.trunk_added_mass_kg", "[1.0, -1.0]", "lo <= hi"),
        (
            "randomize.trunk_com_offset_m",
            "[[0.0, 0.0], [0.0, 0.0], [0.0, 0.6]]",
            "0.5",
        ),
        (
            "randomize.actuator_delay_substeps",
            "[0, 11]",
            "longer than an env step",
        ),
        ("randomize.actuator_delay_substeps", "[3, 2]", "lo <= hi"),
        (
            "randomize.contact_stiffness_scale",
            "[0.001, 1.0]",
            "lo >= 0.01",
        ),
        (
            "randomize.contact_damping_scale",
            "[1.0, 200.0]",
            "hi <= 100",
        ),
        ("randomize.restitution", "[0.5, 1.5]", "hi <= 1"),
        ("randomize.restitution", "[-0.1, 0.5]", "lo >= 0"),
        ("randomize.obs_noise.joint_angle", "-0.01", "deviation"),
        ("randomize.obs_noise.quaternion", "nan", "deviation"),
        ("randomize.obs_noise.contact_flip", "1.5", "probability"),
        ("randomize.push_interval_s", "[0.0, 2.0]", "lo > 0"),
        ("randomize.push_interval_s", "[2.0, 4.0]", "need a speed"),
        ("randomize.push_velocity_xy_mps", "[-0.5, 0.5]", "lo >= 0"),
    ];
    for (key, value, says) in cases {
        let err = refused(&[(key, value)]);
        assert!(
            err.contains(key) && err.contains(says),
            "{key} = {value}: {err:?} should name the key and say {says:?}"
        );
    }
    for (key, value) in [
        ("randomize.bogus", "1.0"),
        ("randomize.preset", "\"gym_legged\""),
        ("randomize.obs_noise.distribution", "\"laplace\""),
    ] {
        let err = refused(&[(key, value)]);
        let name = key.rsplit('.').next().unwrap_or(key);
        assert!(
            err.contains(name) || err.contains(value.trim_matches('"')),
            "{key} = {value}: {err:?}"
        );
    }
    // A delay of exactly one env step is allowed; with fewer sub-steps per step it is not.
    EnvConfig::load::<&str, &str>(None, &[("randomize.actuator_delay_substeps", "[0, 10]")])
        .unwrap_or_else(|e| panic!("{e}"));
    let err = refused(&[
        ("randomize.actuator_delay_substeps", "[0, 10]"),
        ("control.sim_steps_per_env_step", "5"),
    ]);
    assert!(err.contains("sim_steps_per_env_step = 5"), "{err}");
}

#[test]
fn an_added_mass_that_empties_the_trunk_is_refused_for_the_robot() {
    let model = hyq_physics::bundled::hyq();
    let trunk = model.links()[0].mass;
    let config = |lo: f64| {
        EnvConfig::load::<&str, String>(
            None,
            &[
                ("randomize.trunk_added_mass_kg", format!("[{lo}, 0.0]")),
                ("randomize.link_mass_scale", "[0.5, 1.0]".to_owned()),
            ],
        )
        .unwrap_or_else(|e| panic!("{e}"))
    };
    Env::<RapierBackend>::new(model.clone(), config(-0.49 * trunk))
        .unwrap_or_else(|e| panic!("{e}"));
    let err = Env::<RapierBackend>::new(model.clone(), config(-0.5 * trunk))
        .err()
        .expect("a weightless trunk")
        .to_string();
    assert!(
        err.contains("randomize.trunk_added_mass_kg") && err.contains("[1e-4, 1e6] kg"),
        "{err}"
    );
}

#[test]
fn masses_no_engine_holds_are_refused_before_anything_runs() {
    // Finite and ordered, but 1e308 kg is far past the bounds table's 1e6 kg: refused when the
    // configuration is read (DART aborted on it, rapier silently lost the mass).
    for value in [
        "[1e308, 1e308]",
        "[1e20, 1e20]",
        "[0.0, 1000001.0]",
        "[-1e7, 0.0]",
    ] {
        let err = refused(&[("randomize.trunk_added_mass_kg", value)]);
        assert!(
            err.contains("randomize.trunk_added_mass_kg") && err.contains("1000000"),
            "{value}: {err}"
        );
    }
    // Positive factors whose bodies fall below what an engine resolves: refused when the
    // environment is built, naming the key and a body (they failed at the first reset with a
    // message naming no key, or aborted DART).
    let model = hyq_physics::bundled::hyq();
    for (key, value) in [
        ("randomize.link_mass_scale", "[1e-30, 1e-30]"),
        ("randomize.link_mass_scale", "[5e-324, 1.0]"),
        ("randomize.trunk_added_mass_kg", "[999000.0, 999999.0]"),
    ] {
        let config = EnvConfig::load::<&str, &str>(None, &[(key, value)])
            .unwrap_or_else(|e| panic!("{key} = {value} passes the robot-free checks: {e}"));
        let err = Env::<RapierBackend>::new(model.clone(), config)
            .err()
            .unwrap_or_else(|| panic!("{key} = {value} is refused for the robot"))
            .to_string();
        assert!(
            err.contains(key) && err.contains("mass properties of body") && !err.contains('\n'),
            "{key} = {value}: {err}"
        );
    }
}

#[test]
fn a_push_interval_shorter_than_an_env_step_is_refused_and_push_messages_quote_the_range() {
    // Pushes come at most once per env step: 1e-9 s used to push at every step.
    for interval in ["[1e-9, 1e-9]", "[5e-324, 5e-324]", "[0.005, 1.0]"] {
        let err = refused(&[
            ("randomize.push_interval_s", interval),
            ("randomize.push_velocity_xy_mps", "[1.0, 1.0]"),
        ]);
        assert!(
            err.contains("randomize.push_interval_s") && err.contains("one env step"),
            "{interval}: {err}"
        );
    }
    // With 20 sub-steps of 1 ms a step is 20 ms, and so is the shortest interval.
    let err = refused(&[
        ("randomize.push_interval_s", "[0.01, 1.0]"),
        ("randomize.push_velocity_xy_mps", "[1.0, 1.0]"),
        ("control.sim_steps_per_env_step", "20"),
    ]);
    assert!(err.contains("lo >= 0.02 s"), "{err}");
    EnvConfig::load::<&str, &str>(
        None,
        &[
            ("randomize.push_interval_s", "[0.01, 0.01]"),
            ("randomize.push_velocity_xy_mps", "[1.0, 1.0]"),
        ],
    )
    .unwrap_or_else(|e| panic!("one env step is allowed: {e}"));
    // A speed without an interval quotes the range, not Rust's `Some(…)`.
    for key in [
        "randomize.push_velocity_xy_mps",
        "randomize.push_velocity_z_mps",
    ] {
        let err = refused(&[(key, "[1.0, 1.0]")]);
        assert!(
            err.contains(&format!("{key} = [1.0, 1.0]")) && !err.contains("Some("),
            "{err}"
        );
    }
}
