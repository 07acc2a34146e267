//! A randomised episode's actuator is the base actuator with each joint's kp, kd, effort limit
//! and Coulomb friction multiplied by its own factor, the velocity limits untouched; invalid
//! factors are refused and leave the actuator as it was.

use hyq_physics::bundled::hyq;
use hyq_physics::{Actuator, ActuatorScales};

/// HyQ with 2.5 N·m of Coulomb friction on its first joint.
fn with_friction() -> hyq_physics::RobotModel {
    let urdf = hyq_physics::bundled::HYQ_URDF.replacen(
        "<dynamics damping=\"0.1\" friction=\"0\"/>",
        "<dynamics damping=\"0.1\" friction=\"2.5\"/>",
        1,
    );
    let profile = hyq_physics::Profile::from_toml_str(hyq_physics::bundled::HYQ_PROFILE, "test")
        .expect("profile");
    hyq_physics::RobotModel::from_urdf_str(&urdf, "test", &profile).expect("loads")
}

#[test]
fn every_factor_scales_its_own_joint() {
    let model = with_friction();
    let base = Actuator::new(&model);
    let n = base.num_joints();
    let mut scales = ActuatorScales::nominal(n);
    scales.kp[0] = 0.5;
    scales.kd[0] = 2.0;
    scales.effort[0] = 0.1;
    scales.friction[0] = 0.4;
    scales.kp[5] = 1.5;
    let mut act = base.clone();
    act.scale_from(&base, &scales).expect("valid scales");
    assert_eq!(act.kp()[0], 0.5 * base.kp()[0]);
    assert_eq!(act.kd()[0], 2.0 * base.kd()[0]);
    assert_eq!(act.effort()[0], 0.1 * base.effort()[0]);
    assert_eq!(act.friction()[0], 0.4 * 2.5);
    assert_eq!(act.kp()[5], 1.5 * base.kp()[5]);
    assert_eq!(act.kp()[1], base.kp()[1], "a factor of 1 changes nothing");
    // The law with the scaled values: kp 500 × 0.01 − kd 40 × 0.1 − friction 1.0 = 0.
    assert_eq!(act.torque(0, 0.01, 0.0, 0.1), 5.0 - 4.0 - 1.0);
    // The effort limit (150 N·m) scaled to 15 N·m caps the motor; friction acts on top.
    assert_eq!(act.torque(0, 1.0, 0.0, 1.0), 15.0 - 1.0);
    // Scaling from the base again, not from the scaled actuator: factors do not compound.
    act.scale_from(&base, &scales).expect("valid scales");
    assert_eq!(act.kp()[0], 0.5 * base.kp()[0]);
    act.scale_from(&base, &ActuatorScales::nominal(n))
        .expect("valid scales");
    assert_eq!(act, base, "nominal factors give the base back");
}

#[test]
fn invalid_factors_are_refused_and_change_nothing() {
    let model = hyq();
    let base = Actuator::new(&model);
    let n = base.num_joints();
    let mut act = base.clone();
    let mut scales = ActuatorScales::nominal(n);
    scales.kp[2] = 0.7;
    scales.kd[3] = 0.0;
    let err = act
        .scale_from(&base, &scales)
        .expect_err("a zero kd factor")
        .to_string();
    assert!(
        err.contains("kd scales[3]") && err.contains("positive"),
        "{err}"
    );
    assert_eq!(act, base, "the refused call left the actuator as it was");
    let err = act
        .scale_from(&base, &ActuatorScales::nominal(n - 1))
        .expect_err("one factor too few")
        .to_string();
    assert!(err.contains("kp scales"), "{err}");
}
