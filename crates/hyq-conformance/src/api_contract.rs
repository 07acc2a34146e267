//! The API contract: determinism and resets bit for bit, and every invalid input refused with an
//! error naming it, leaving the world as it was.

use std::sync::Arc;

use nalgebra::{UnitQuaternion, Vector3};

use super::fixtures::{
    Rng, Robot, build_default, first_difference, random_pd_trajectory, set, step_zero,
};
use hyq_physics::actuator::{Actuator, PdScratch, pd_substep};
use hyq_physics::error::PhysicsError;
use hyq_physics::{Backend, PhysicsParams, RobotState};

/// Two worlds built alike and driven alike produce bitwise-identical trajectories (joint
/// state, trunk state and contacts at every step).
pub fn same_inputs_give_bitwise_identical_trajectories<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let mut first: B = build_default(robot, options);
    let mut second: B = build_default(robot, options);
    let a = random_pd_trajectory(&mut first, 3, 400);
    let b = random_pd_trajectory(&mut second, 3, 400);
    assert_eq!(first_difference(&a, &b), None, "trajectories differ");
}

/// `set_state` forgets everything: after running on (contacts, warm starts, pending torques),
/// setting a state again and repeating the inputs repeats the trajectory bitwise, as does a
/// freshly built world; a world as built equals one set to the spawn state.
pub fn reset_restores_trajectory_bitwise<B: Backend>(robot: &Robot, options: &B::Options) {
    let model = Arc::clone(&robot.model);
    let mut rng = Rng::new(5);
    let mut moving = model.spawn_state();
    moving.trunk.linvel = Vector3::new(0.3, -0.1, 0.0);
    moving.trunk.angvel = Vector3::new(0.0, 0.2, 0.1);
    moving.qd = (0..model.num_joints())
        .map(|_| rng.range(-1.0, 1.0))
        .collect();
    for start in [model.spawn_state(), moving] {
        let mut b: B = build_default(robot, options);
        set(&mut b, &start);
        let first = random_pd_trajectory(&mut b, 9, 300);
        // Run on elsewhere, and leave a torque pending that the reset must discard.
        let _ = random_pd_trajectory(&mut b, 10, 200);
        b.set_joint_torques(&vec![50.0; model.num_joints()])
            .expect("torques");
        set(&mut b, &start);
        let again = random_pd_trajectory(&mut b, 9, 300);
        assert_eq!(
            first_difference(&first, &again),
            None,
            "trajectory after set_state differs"
        );
        let mut fresh: B = build_default(robot, options);
        set(&mut fresh, &start);
        let fresh_run = random_pd_trajectory(&mut fresh, 9, 300);
        assert_eq!(
            first_difference(&first, &fresh_run),
            None,
            "trajectory of a fresh world differs"
        );
    }
    let mut built: B = build_default(robot, options);
    let mut spawned: B = build_default(robot, options);
    set(&mut spawned, &model.spawn_state());
    assert_eq!(
        first_difference(
            &random_pd_trajectory(&mut built, 4, 200),
            &random_pd_trajectory(&mut spawned, 4, 200)
        ),
        None,
        "a world as built differs from one set to the spawn state"
    );
}

/// Invalid physics parameters are refused when the world is built, and the error names the
/// field.
pub fn invalid_params_are_rejected<B: Backend>(robot: &Robot, options: &B::Options) {
    let cases: [(&str, PhysicsParams); 5] = [
        (
            "dt",
            PhysicsParams {
                dt: 0.0,
                ..PhysicsParams::default()
            },
        ),
        (
            "dt",
            PhysicsParams {
                dt: f64::NAN,
                ..PhysicsParams::default()
            },
        ),
        (
            "gravity",
            PhysicsParams {
                gravity: [0.0, f64::INFINITY, -9.81],
                ..PhysicsParams::default()
            },
        ),
        (
            "ground_friction",
            PhysicsParams {
                ground_friction: -0.5,
                ..PhysicsParams::default()
            },
        ),
        (
            "contact_distance",
            PhysicsParams {
                contact_distance: -1e-3,
                ..PhysicsParams::default()
            },
        ),
    ];
    for (field, params) in cases {
        match B::build(Arc::clone(&robot.model), &params, options) {
            Err(PhysicsError::InvalidParam { field: f, .. }) => assert_eq!(f, field),
            Err(other) => panic!("{field}: expected InvalidParam, got {other}"),
            Ok(_) => panic!("{} accepted an invalid {field}", B::NAME),
        }
    }
}

/// Torques, targets and states of the wrong length are errors naming what was wrong, and
/// leave the world as it was.
pub fn wrong_length_inputs_are_errors<B: Backend>(robot: &Robot, options: &B::Options) {
    let mut b: B = build_default(robot, options);
    let model = Arc::clone(b.model());
    let n = model.num_joints();
    let before = b.state();
    for len in [0, n - 1, n + 1] {
        match b.set_joint_torques(&vec![0.0; len]) {
            Err(PhysicsError::WrongLength { expected, got, .. }) => {
                assert_eq!((expected, got), (n, len));
            }
            other => panic!("torques of length {len}: expected WrongLength, got {other:?}"),
        }
        let mut s = model.spawn_state();
        s.q = vec![0.0; len];
        assert!(
            matches!(b.set_state(&s), Err(PhysicsError::WrongLength { .. })),
            "joint angles of length {len} accepted"
        );
        let mut s = model.spawn_state();
        s.qd = vec![0.0; len];
        assert!(
            matches!(b.set_state(&s), Err(PhysicsError::WrongLength { .. })),
            "joint speeds of length {len} accepted"
        );
        let act = Actuator::new(&model);
        let mut scratch = PdScratch::new(n);
        assert!(
            matches!(
                pd_substep(&mut b, &act, &vec![0.0; len], &mut scratch),
                Err(PhysicsError::WrongLength { .. })
            ),
            "targets of length {len} accepted"
        );
    }
    assert_eq!(b.state(), before, "a rejected input changed the world");
}

/// Non-finite states and torques, and orientations that are not unit quaternions, are
/// rejected with an error naming the value, and leave the world as it was.
pub fn non_finite_inputs_are_rejected<B: Backend>(robot: &Robot, options: &B::Options) {
    let mut b: B = build_default(robot, options);
    let model = Arc::clone(b.model());
    let before = b.state();
    let spawn = model.spawn_state();
    let mut cases: Vec<(&str, RobotState)> = Vec::new();
    let mut s = spawn.clone();
    // Joints 1 and 2 where the robot has them: not only the first joint is checked.
    let (second, third) = (1.min(model.num_joints() - 1), 2.min(model.num_joints() - 1));
    s.q[second] = f64::NAN;
    cases.push(("angle of joint", s));
    let mut s = spawn.clone();
    s.qd[0] = f64::INFINITY;
    cases.push(("speed of joint", s));
    let mut s = spawn.clone();
    s.trunk.pose.translation.z = f64::NAN;
    cases.push(("trunk position z", s));
    let mut s = spawn.clone();
    s.trunk.angvel.y = f64::NEG_INFINITY;
    cases.push(("trunk angular velocity y", s));
    for (what, state) in cases {
        match b.set_state(&state) {
            Err(PhysicsError::NonFinite { what: w, .. }) => {
                assert!(w.contains(what), "error names {w:?}, expected {what:?}");
            }
            other => panic!("{what}: expected NonFinite, got {other:?}"),
        }
    }
    let mut s = spawn.clone();
    s.trunk.pose.rotation =
        UnitQuaternion::new_unchecked(nalgebra::Quaternion::new(2.0, 0.0, 0.0, 0.0));
    assert!(
        matches!(b.set_state(&s), Err(PhysicsError::InvalidState { .. })),
        "a non-unit quaternion was accepted"
    );
    let mut torques = vec![0.0; model.num_joints()];
    torques[third] = f64::NAN;
    match b.set_joint_torques(&torques) {
        Err(PhysicsError::NonFinite { what, .. }) => {
            assert!(
                what.contains(&model.joints()[third].name),
                "error names {what:?}"
            );
        }
        other => panic!("NaN torque: expected NonFinite, got {other:?}"),
    }
    let mut targets = model.standing_pose().to_vec();
    targets[0] = f64::NAN;
    let act = Actuator::new(&model);
    let mut scratch = PdScratch::new(model.num_joints());
    assert!(
        matches!(
            pd_substep(&mut b, &act, &targets, &mut scratch),
            Err(PhysicsError::NonFinite { .. })
        ),
        "a NaN target was accepted"
    );
    assert_eq!(b.state(), before, "a rejected input changed the world");
}

/// A step never returns `Ok` with a non-finite state: driven with absurd (finite) torques,
/// every `Ok` step leaves every read finite, a diverged step says so, and `set_state` brings
/// the world back.
pub fn divergence_is_reported_and_recoverable<B: Backend>(robot: &Robot, options: &B::Options) {
    let mut b: B = build_default(robot, options);
    let model = Arc::clone(b.model());
    let huge = vec![1e300; model.num_joints()];
    let mut diverged = false;
    for _ in 0..20 {
        b.set_joint_torques(&huge)
            .expect("finite torques are valid input");
        match b.step() {
            Ok(()) => {
                let s = b.state();
                assert_eq!(
                    s.first_non_finite(&model),
                    None,
                    "step returned Ok with a non-finite state"
                );
                assert!(
                    s.trunk.pose.rotation.quaternion().norm().is_finite(),
                    "non-finite orientation after Ok"
                );
            }
            Err(PhysicsError::Diverged { .. }) => {
                diverged = true;
                break;
            }
            Err(other) => panic!("expected Diverged, got {other}"),
        }
    }
    set(&mut b, &model.spawn_state());
    step_zero(&mut b);
    let s = b.state();
    assert_eq!(
        s.first_non_finite(&model),
        None,
        "not recovered after set_state"
    );
    let z = s.trunk.pose.translation.z;
    assert!(
        (z - model.spawn_height()).abs() < 0.01,
        "after set_state (diverged before: {diverged}) the trunk is at {z} m"
    );
    // The world behaves as a fresh one again.
    let mut fresh: B = build_default(robot, options);
    set(&mut b, &model.spawn_state());
    let again = random_pd_trajectory(&mut b, 13, 100);
    let reference = random_pd_trajectory(&mut fresh, 13, 100);
    assert_eq!(
        first_difference(&again, &reference),
        None,
        "a world reset after divergence differs from a fresh one"
    );
}
