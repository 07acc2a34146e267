//! The rapier backend passes the backend conformance suite of `hyq-physics` on every bundled
//! robot: the invariants every physics backend must hold (mass and kinematics from the URDF,
//! ballistic free fall, standing, collapse, joint limits, real contacts, determinism, resets,
//! input validation), on HyQ (the default) and on ANYmal C.

hyq_conformance::conformance_tests!(hyq_rapier::RapierBackend);

mod terrain {
    hyq_conformance::terrain_conformance_tests!(hyq_rapier::RapierBackend);
}

mod anymal_c {
    use hyq_conformance::fixtures::Robot;

    hyq_conformance::conformance_tests!(
        hyq_rapier::RapierBackend,
        hyq_rapier::RapierOptions::default(),
        Robot::bundled("anymal_c")
    );
}
