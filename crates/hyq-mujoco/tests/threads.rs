//! Several MuJoCo worlds stepping on several threads at once work, and each gives bitwise the
//! trajectory it gives alone on one thread: each world owns its model and data, and the shim's
//! error handling is per thread. Worlds are also built on several threads at once (MuJoCo's
//! model compiler keeps process-wide state; the crate compiles one model at a time).

mod common;

use common::{first_difference, hyq, random_trajectory, random_trajectory_from};
use hyq_mujoco::MujocoBackend;

const STEPS: usize = 1500;

fn assert_send<T: Send>() {}

#[test]
fn mujoco_backend_is_send() {
    assert_send::<MujocoBackend>();
}

#[test]
fn two_worlds_on_two_threads_match_their_single_thread_runs_bitwise() {
    let seeds = [11_u64, 12];
    let alone: Vec<Vec<u64>> = seeds
        .iter()
        .map(|&s| random_trajectory(&mut hyq(), s, STEPS))
        .collect();
    for round in 0..3 {
        let together: Vec<Vec<u64>> = std::thread::scope(|scope| {
            let handles: Vec<_> = seeds
                .iter()
                .map(|&s| scope.spawn(move || random_trajectory(&mut hyq(), s, STEPS)))
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().expect("a stepping thread panicked"))
                .collect()
        });
        for (i, (a, b)) in alone.iter().zip(&together).enumerate() {
            assert_eq!(
                first_difference(a, b),
                None,
                "round {round}: world {i} on its own thread differs from its single-thread run"
            );
        }
    }
    assert_ne!(
        alone[0], alone[1],
        "different seeds must give different runs"
    );
}

#[test]
fn worlds_built_on_several_threads_at_once_are_all_alike() {
    let reference = random_trajectory(&mut hyq(), 21, 200);
    let runs: Vec<Vec<u64>> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..4)
            .map(|_| scope.spawn(|| random_trajectory(&mut hyq(), 21, 200)))
            .collect();
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
    let whole = random_trajectory(&mut hyq(), 5, 2 * STEPS);
    let mut world = hyq();
    let mut trace = random_trajectory(&mut world, 5, STEPS);
    let rest = std::thread::spawn(move || random_trajectory_from(&mut world, 5, STEPS, STEPS))
        .join()
        .expect("the other thread panicked");
    trace.extend(rest);
    assert_eq!(first_difference(&whole, &trace), None);
}
