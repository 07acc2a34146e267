//! The DART backend passes the shared backend conformance suite of `hyq-physics`, unchanged,
//! on every bundled robot: every invariant the rapier backend is held to holds for DART too,
//! on HyQ (the default) and on ANYmal C.

hyq_conformance::conformance_tests!(hyq_dart::DartBackend);

mod terrain {
    hyq_conformance::terrain_conformance_tests!(hyq_dart::DartBackend);
}

mod anymal_c {
    use hyq_conformance::fixtures::Robot;

    hyq_conformance::conformance_tests!(
        hyq_dart::DartBackend,
        hyq_dart::DartOptions::default(),
        Robot::bundled("anymal_c")
    );
}
