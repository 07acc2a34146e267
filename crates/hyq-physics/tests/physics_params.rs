//! Physics parameters have the documented defaults, read from TOML with the field names of
//! the docs (unknown fields refused), and every invalid value is refused naming its field;
//! robot states are validated the same way.

use hyq_physics::bundled::hyq;
use hyq_physics::{PhysicsError, PhysicsParams};

#[test]
fn defaults() {
    let p = PhysicsParams::default();
    assert_eq!(p.dt, 0.001);
    assert_eq!(p.gravity, [0.0, 0.0, -9.81]);
    assert_eq!(p.ground_friction, 1.0);
    assert_eq!(p.contact_distance, 0.001);
    p.validate().expect("defaults are valid");
}

#[test]
fn reads_toml_and_fills_defaults() {
    let p: PhysicsParams = toml::from_str("dt = 0.002\nground_friction = 0.8").expect("parses");
    assert_eq!(p.dt, 0.002);
    assert_eq!(p.ground_friction, 0.8);
    assert_eq!(p.gravity, [0.0, 0.0, -9.81]);
}

#[test]
fn unknown_fields_are_refused() {
    let e = toml::from_str::<PhysicsParams>("timestep = 0.002").expect_err("refused");
    assert!(e.to_string().contains("timestep"), "{e}");
}

#[test]
fn invalid_values_name_their_field() {
    let cases = [
        (
            "dt",
            PhysicsParams {
                dt: -0.001,
                ..Default::default()
            },
        ),
        (
            "dt",
            PhysicsParams {
                dt: 0.5,
                ..Default::default()
            },
        ),
        (
            "gravity",
            PhysicsParams {
                gravity: [f64::NAN, 0.0, 0.0],
                ..Default::default()
            },
        ),
        (
            "ground_friction",
            PhysicsParams {
                ground_friction: f64::INFINITY,
                ..Default::default()
            },
        ),
        (
            "contact_distance",
            PhysicsParams {
                contact_distance: f64::NAN,
                ..Default::default()
            },
        ),
    ];
    for (field, p) in cases {
        match p.validate() {
            Err(PhysicsError::InvalidParam { field: f, .. }) => assert_eq!(f, field),
            other => panic!("{field}: expected InvalidParam, got {other:?}"),
        }
    }
}

#[test]
fn robot_states_are_validated() {
    let model = hyq();
    let good = model.spawn_state();
    good.validate(&model).expect("the spawn state is valid");
    let mut bad = good.clone();
    bad.qd.pop();
    assert!(matches!(
        bad.validate(&model),
        Err(PhysicsError::WrongLength {
            what: "joint speeds",
            expected: 12,
            got: 11
        })
    ));
    let mut bad = good.clone();
    bad.q[7] = f64::NAN;
    match bad.validate(&model) {
        Err(PhysicsError::NonFinite { what, .. }) => assert_eq!(what, "angle of joint rf_hfe"),
        other => panic!("expected NonFinite, got {other:?}"),
    }
    let mut bad = good;
    bad.trunk.linvel.x = f64::INFINITY;
    match bad.validate(&model) {
        Err(PhysicsError::NonFinite { what, .. }) => assert_eq!(what, "trunk linear velocity x"),
        other => panic!("expected NonFinite, got {other:?}"),
    }
}
