//! Every bad `[randomize]` value is refused before anything runs, with one line naming the key
//! and the value: reversed or non-finite ranges, a scale that can make a mass or gain ≤ 0, a
//! delay longer than an env step, a negative noise deviation, an unknown key or preset, pushes
//! without a speed, and an added mass that can make the robot's trunk weightless.

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
        err.contains("randomize.trunk_added_mass_kg") && err.contains("positive"),
        "{err}"
    );
}
