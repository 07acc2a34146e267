//! rapier options have the documented defaults, read from TOML (unknown fields refused), and
//! invalid values are refused when the world is built, naming the option.

use hyq_physics::{Backend, PhysicsError, PhysicsParams, bundled};
use hyq_rapier::{RapierBackend, RapierOptions};

#[test]
fn defaults() {
    let o = RapierOptions::default();
    assert_eq!(o.solver_iterations, 2);
    assert_eq!(o.ground_contact_frequency, 240.0);
    assert_eq!(o.ground_contact_damping_ratio, 10.0);
    assert_eq!(o.prediction_distance, 0.02);
    assert!(
        !o.mass_matrix_once_per_step,
        "off: the default keeps rapier's integrator"
    );
    o.validate().expect("defaults are valid");
}

#[test]
fn reads_toml() {
    let o: RapierOptions = toml::from_str("solver_iterations = 4").expect("parses");
    assert_eq!(o.solver_iterations, 4);
    assert_eq!(o.ground_contact_frequency, 240.0);
    let o: RapierOptions = toml::from_str("mass_matrix_once_per_step = true").expect("parses");
    assert!(o.mass_matrix_once_per_step);
    assert_eq!(o.solver_iterations, 2);
    let e = toml::from_str::<RapierOptions>("iterations = 4").expect_err("unknown field");
    assert!(e.to_string().contains("iterations"), "{e}");
}

#[test]
fn invalid_options_are_refused_by_build() {
    let cases = [
        (
            "rapier.solver_iterations",
            RapierOptions {
                solver_iterations: 0,
                ..Default::default()
            },
        ),
        (
            "rapier.ground_contact_frequency",
            RapierOptions {
                ground_contact_frequency: -1.0,
                ..Default::default()
            },
        ),
        (
            "rapier.ground_contact_damping_ratio",
            RapierOptions {
                ground_contact_damping_ratio: f64::NAN,
                ..Default::default()
            },
        ),
        (
            "rapier.prediction_distance",
            RapierOptions {
                prediction_distance: -0.1,
                ..Default::default()
            },
        ),
    ];
    for (field, options) in cases {
        match RapierBackend::build(bundled::hyq(), &PhysicsParams::default(), &options) {
            Err(PhysicsError::InvalidParam { field: f, .. }) => assert_eq!(f, field),
            Err(other) => panic!("{field}: expected InvalidParam, got {other}"),
            Ok(_) => panic!("{field}: invalid option accepted"),
        }
    }
}
