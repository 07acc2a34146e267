//! Worlds on several threads, for a backend crate to run from its own `tests/threads.rs` (one
//! `#[test]` per function, whose file says why the engine keeps the contract): worlds stepping
//! on several threads at once each give bitwise the run they give alone on one thread, and a
//! world moved to another thread mid-run carries on bitwise.
//!
//! The runs are [`random_pd_run`]s with targets anywhere inside the joint limits.

use super::fixtures::{Robot, build_default, first_difference, random_pd_run};
use hyq_physics::Backend;

/// Sub-steps of each compared run.
pub const STEPS: usize = 1500;

/// The first `steps` sub-steps of a random-target run of a fresh world, seeded by `seed`.
fn fresh_run<B: Backend>(robot: &Robot, options: &B::Options, seed: u64, steps: usize) -> Vec<u64> {
    random_pd_run(&mut build_default::<B>(robot, options), seed, 0.0, 0..steps)
}

/// Two worlds stepping at once on two threads (three rounds) give bitwise the runs they give
/// alone on one thread; the two seeds give different runs.
pub fn two_worlds_on_two_threads_match_their_single_thread_runs_bitwise<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let seeds = [11_u64, 12];
    let alone: Vec<Vec<u64>> = seeds
        .iter()
        .map(|&s| fresh_run::<B>(robot, options, s, STEPS))
        .collect();
    for round in 0..3 {
        let together: Vec<Vec<u64>> = std::thread::scope(|scope| {
            let handles: Vec<_> = seeds
                .iter()
                .map(|&s| scope.spawn(move || fresh_run::<B>(robot, options, s, STEPS)))
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

/// A world that runs the first half of a run on one thread and the second on another gives
/// the whole run bitwise.
pub fn a_world_moved_to_another_thread_carries_on_bitwise<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let whole = fresh_run::<B>(robot, options, 5, 2 * STEPS);
    let mut world: B = build_default(robot, options);
    let mut trace = random_pd_run(&mut world, 5, 0.0, 0..STEPS);
    let rest = std::thread::spawn(move || random_pd_run(&mut world, 5, 0.0, STEPS..2 * STEPS))
        .join()
        .expect("the other thread panicked");
    trace.extend(rest);
    assert_eq!(first_difference(&whole, &trace), None);
}
