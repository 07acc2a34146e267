//! The shared backend conformance suite of hyq-physics, on MuJoCo, on every bundled robot
//! (HyQ, the default, and ANYmal C).

hyq_conformance::conformance_tests!(hyq_mujoco::MujocoBackend);

mod terrain {
    hyq_conformance::terrain_conformance_tests!(hyq_mujoco::MujocoBackend);
}

mod anymal_c {
    use hyq_conformance::fixtures::Robot;

    hyq_conformance::conformance_tests!(
        hyq_mujoco::MujocoBackend,
        <hyq_mujoco::MujocoBackend as hyq_physics::Backend>::Options::default(),
        Robot::bundled("anymal_c")
    );
}
