//! The rapier backend passes the backend conformance suite of `hyq-physics` at 1 and at 4
//! solver iterations too, not only at its default of 2 (`tests/conformance.rs`): the option
//! changes rapier's internal substeps, so every invariant must hold at each documented setting.

mod one_iteration {
    use hyq_conformance::fixtures::Robot;

    hyq_conformance::conformance_tests!(
        hyq_rapier::RapierBackend,
        hyq_rapier::RapierOptions {
            solver_iterations: 1,
            ..Default::default()
        },
        Robot::bundled(hyq_physics::bundled::DEFAULT)
    );
}

mod four_iterations {
    use hyq_conformance::fixtures::Robot;

    hyq_conformance::conformance_tests!(
        hyq_rapier::RapierBackend,
        hyq_rapier::RapierOptions {
            solver_iterations: 4,
            ..Default::default()
        },
        Robot::bundled(hyq_physics::bundled::DEFAULT)
    );
}

/// `mass_matrix_once_per_step` reuses the first internal substep's mass matrices at the later
/// ones, so it changes nothing at 1 iteration; at 2 (the default) and 4 the suite must hold with
/// it for the option to be offered.
mod mass_matrix_once_per_step_two_iterations {
    use hyq_conformance::fixtures::Robot;

    hyq_conformance::conformance_tests!(
        hyq_rapier::RapierBackend,
        hyq_rapier::RapierOptions {
            mass_matrix_once_per_step: true,
            ..Default::default()
        },
        Robot::bundled(hyq_physics::bundled::DEFAULT)
    );
}

mod mass_matrix_once_per_step_four_iterations {
    use hyq_conformance::fixtures::Robot;

    hyq_conformance::conformance_tests!(
        hyq_rapier::RapierBackend,
        hyq_rapier::RapierOptions {
            solver_iterations: 4,
            mass_matrix_once_per_step: true,
            ..Default::default()
        },
        Robot::bundled(hyq_physics::bundled::DEFAULT)
    );
}
