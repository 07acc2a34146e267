//! The DART backend passes the shared backend conformance suite of `hyq-physics`, unchanged:
//! every invariant the rapier backend is held to holds for DART too.

hyq_physics::conformance_tests!(hyq_dart::DartBackend);
