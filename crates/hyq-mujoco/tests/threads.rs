//! Several MuJoCo worlds stepping on several threads at once work, and each gives bitwise the
//! trajectory it gives alone on one thread: each world owns its model and data, and the shim's
//! error handling is per thread. Worlds are also built on several threads at once (MuJoCo's
//! model compiler keeps process-wide state; the crate compiles one model at a time).
//!
//! The bodies shared with the other backends are hyq-conformance's `threads`, run
//! here on the bundled HyQ; building on several threads at once is MuJoCo's own concern.

use hyq_conformance::fixtures::{Robot, build_default, first_difference, random_pd_run};
use hyq_conformance::threads;
use hyq_mujoco::{MujocoBackend, MujocoOptions};

fn hyq() -> Robot {
    Robot::bundled("hyq")
}

fn assert_send<T: Send>() {}

#[test]
fn mujoco_backend_is_send() {
    assert_send::<MujocoBackend>();
}

#[test]
fn two_worlds_on_two_threads_match_their_single_thread_runs_bitwise() {
    threads::two_worlds_on_two_threads_match_their_single_thread_runs_bitwise::<MujocoBackend>(
        &hyq(),
        &MujocoOptions::default(),
    );
}

#[test]
fn worlds_built_on_several_threads_at_once_are_all_alike() {
    let robot = hyq();
    let options = MujocoOptions::default();
    let fresh_run = || {
        let mut world: MujocoBackend = build_default(&robot, &options);
        random_pd_run(&mut world, 21, 0.0, 0..200)
    };
    let reference = fresh_run();
    let runs: Vec<Vec<u64>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..4).map(|_| scope.spawn(fresh_run)).collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("a building thread panicked"))
            .collect()
    });
    for run in runs {
        assert_eq!(first_difference(&reference, &run), None);
    }
}

#[test]
fn a_world_moved_to_another_thread_carries_on_bitwise() {
    threads::a_world_moved_to_another_thread_carries_on_bitwise::<MujocoBackend>(
        &hyq(),
        &MujocoOptions::default(),
    );
}
