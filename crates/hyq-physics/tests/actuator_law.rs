//! The shared actuator computes τ = kp (q* − q) − kd q̇, never pushes a joint already faster
//! than its velocity limit further in its direction of motion (braking stays allowed), and
//! never exceeds the effort limit; bad inputs are errors.

use hyq_physics::bundled::hyq;
use hyq_physics::{Actuator, PhysicsError};

#[test]
fn pd_law_within_limits() {
    let model = hyq();
    let act = Actuator::new(&model);
    // kp 1000, kd 20: 1000 × 0.05 − 20 × 0.5 = 40.
    assert_eq!(act.torque(0, 0.05, 0.0, 0.5), 40.0);
    assert_eq!(act.torque(3, -0.1, 0.0, -1.0), -80.0);
}

#[test]
fn effort_limit_clamps() {
    let model = hyq();
    let act = Actuator::new(&model);
    assert_eq!(act.torque(0, 1.0, 0.0, 0.0), 150.0);
    assert_eq!(act.torque(0, -1.0, 0.0, 0.0), -150.0);
}

#[test]
fn velocity_limit_cuts_accelerating_torque_only() {
    let model = hyq();
    let act = Actuator::new(&model);
    // Faster than +12 rad/s: a torque pushing further becomes 0 ...
    assert_eq!(act.torque(0, 1.0, 0.0, 12.5), 0.0);
    // ... braking is kept.
    assert_eq!(act.torque(0, -1.0, 0.0, 12.5), -150.0);
    // Same below -12 rad/s.
    assert_eq!(act.torque(0, -1.0, 0.0, -12.5), 0.0);
    assert_eq!(act.torque(0, 1.0, 0.0, -12.5), 150.0);
    // At exactly the limit the motor may still push (Gazebo's strict comparison).
    assert_eq!(act.torque(0, 1.0, 0.0, 12.0), 150.0);
}

#[test]
fn velocity_limit_rule_can_be_switched_off() {
    let model = hyq();
    let mut act = Actuator::new(&model);
    assert!(act.velocity_limit());
    act.set_velocity_limit(false);
    assert_eq!(act.torque(0, 1.0, 0.0, 12.5), 150.0);
}

#[test]
fn torques_of_all_joints() {
    let model = hyq();
    let act = Actuator::with_gains(&model, &[2.0; 12], &[1.0; 12]).expect("gains");
    let targets = [1.0; 12];
    let q = [0.5; 12];
    let qd = [0.25; 12];
    let mut out = [0.0; 12];
    act.torques(&targets, &q, &qd, &mut out).expect("torques");
    assert_eq!(out, [0.75; 12]);
}

#[test]
fn wrong_lengths_are_errors() {
    let model = hyq();
    let act = Actuator::new(&model);
    let mut out = [0.0; 12];
    match act.torques(&[0.0; 11], &[0.0; 12], &[0.0; 12], &mut out) {
        Err(PhysicsError::WrongLength {
            what,
            expected,
            got,
        }) => {
            assert_eq!((what, expected, got), ("joint targets", 12, 11));
        }
        other => panic!("expected WrongLength, got {other:?}"),
    }
    assert!(matches!(
        Actuator::with_gains(&model, &[1.0; 13], &[1.0; 12]),
        Err(PhysicsError::WrongLength {
            what: "kp gains",
            ..
        })
    ));
}

#[test]
fn negative_or_non_finite_gains_are_errors() {
    let model = hyq();
    let mut kp = [1.0; 12];
    kp[4] = -1.0;
    match Actuator::with_gains(&model, &kp, &[1.0; 12]) {
        Err(PhysicsError::InvalidState { what, .. }) => assert!(what.contains("lh_hfe"), "{what}"),
        other => panic!("expected InvalidState, got {other:?}"),
    }
    let mut kd = [1.0; 12];
    kd[0] = f64::NAN;
    assert!(matches!(
        Actuator::with_gains(&model, &[1.0; 12], &kd),
        Err(PhysicsError::NonFinite { .. })
    ));
}
