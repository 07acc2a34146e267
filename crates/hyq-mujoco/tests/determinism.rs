//! Same state and same inputs give bitwise the same results on MuJoCo: across runs, after
//! `set_state` on a world with any history (falls, contacts, joint limits, a divergence), and
//! for a world built with a non-default time step. MuJoCo carries state between steps besides
//! positions and velocities (the solver's warm start `qacc_warmstart`, the contact list, applied
//! forces, warning counters); `set_state` resets all of it (`mj_resetData`), which is what makes
//! a reused world replay a fresh one.
//!
//! The bodies are hyq-conformance's `determinism`, run here on the bundled HyQ.

use hyq_conformance::determinism;
use hyq_conformance::fixtures::Robot;
use hyq_mujoco::{MujocoBackend, MujocoOptions};

fn hyq() -> Robot {
    Robot::bundled("hyq")
}

#[test]
fn two_fresh_worlds_give_identical_runs() {
    determinism::two_fresh_worlds_give_identical_runs::<MujocoBackend>(
        &hyq(),
        &MujocoOptions::default(),
    );
}

#[test]
fn set_state_after_any_history_replays_a_fresh_world() {
    determinism::set_state_after_any_history_replays_a_fresh_world::<MujocoBackend>(
        &hyq(),
        &MujocoOptions::default(),
    );
}

#[test]
fn another_time_step_is_deterministic_too_and_differs() {
    determinism::another_time_step_is_deterministic_too_and_differs::<MujocoBackend>(
        &hyq(),
        &MujocoOptions::default(),
    );
}
