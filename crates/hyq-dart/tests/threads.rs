//! Several DART worlds stepping on several threads at once work, and each gives bitwise the
//! trajectory it gives alone on one thread: the worlds share no mutable state (DART's Bullet
//! detector has no global state on the step path, unlike its ODE detector).
//!
//! The bodies are hyq-conformance's `threads`, run here on the bundled HyQ.

use hyq_conformance::fixtures::Robot;
use hyq_conformance::threads;
use hyq_dart::{DartBackend, DartOptions};

fn hyq() -> Robot {
    Robot::bundled("hyq")
}

fn assert_send<T: Send>() {}

#[test]
fn dart_backend_is_send() {
    assert_send::<DartBackend>();
}

#[test]
fn two_worlds_on_two_threads_match_their_single_thread_runs_bitwise() {
    threads::two_worlds_on_two_threads_match_their_single_thread_runs_bitwise::<DartBackend>(
        &hyq(),
        &DartOptions::default(),
    );
}

#[test]
fn a_world_moved_to_another_thread_carries_on_bitwise() {
    threads::a_world_moved_to_another_thread_carries_on_bitwise::<DartBackend>(
        &hyq(),
        &DartOptions::default(),
    );
}
