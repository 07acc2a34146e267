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

/// Coulomb joint friction (URDF `<dynamics friction>`) opposes the joint's motion with its full
/// value above `FRICTION_SMOOTHING`, proportionally below, on top of the clamped motor torque;
/// a frictionless joint's torque is bit for bit the motor's.
#[test]
fn joint_friction_opposes_motion_outside_the_motor_limit() {
    use hyq_physics::actuator::FRICTION_SMOOTHING;
    let urdf = hyq_physics::bundled::HYQ_URDF.replacen(
        "<dynamics damping=\"0.1\" friction=\"0\"/>",
        "<dynamics damping=\"0.1\" friction=\"2.5\"/>",
        1,
    );
    let profile = hyq_physics::Profile::from_toml_str(hyq_physics::bundled::HYQ_PROFILE, "test")
        .expect("profile");
    let model = hyq_physics::RobotModel::from_urdf_str(&urdf, "test", &profile).expect("loads");
    let act = Actuator::new(&model);
    // Moving forward at 1 rad/s: kp 1000 × 0.05 − kd 20 × 1 − 2.5 = 27.5.
    assert_eq!(act.torque(0, 0.05, 0.0, 1.0), 27.5);
    assert_eq!(act.torque(0, 0.05, 0.0, -1.0), 70.0 + 2.5);
    // Saturated motor, friction on top: the joint feels more than the effort limit.
    assert_eq!(act.torque(0, 1.0, 0.0, 1.0), 150.0 - 2.5);
    // Half the smoothing speed: half the friction.
    let slow = 0.5 * FRICTION_SMOOTHING;
    assert_eq!(
        act.torque(0, 0.0, 0.0, slow),
        -20.0 * slow - 1.25,
        "linear below the smoothing speed"
    );
    assert_eq!(act.torque(0, 0.0, 0.0, 0.0), 0.0, "no friction at rest");
    // Joint 1 has none: the plain law, bit for bit.
    let plain = Actuator::new(&hyq());
    for (t, q, qd) in [(0.3, 0.1, -0.7), (-1.0, 0.5, 13.0), (0.0, 0.0, -0.0)] {
        assert_eq!(
            act.torque(1, t, q, qd).to_bits(),
            plain.torque(1, t, q, qd).to_bits()
        );
    }
}
