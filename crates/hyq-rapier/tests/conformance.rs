//! The rapier backend passes the backend conformance suite of `hyq-physics`: the invariants
//! every physics backend must hold (mass and kinematics from the URDF, ballistic free fall,
//! standing, collapse, joint limits, real contacts, determinism, resets, input validation).

hyq_physics::conformance_tests!(hyq_rapier::RapierBackend);
