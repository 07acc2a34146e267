//! The shared backend conformance suite of hyq-physics, on MuJoCo.

hyq_physics::conformance_tests!(hyq_mujoco::MujocoBackend);
