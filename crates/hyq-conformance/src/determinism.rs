//! Longer determinism runs than the suite's, for a backend crate to run from its own
//! `tests/determinism.rs` (one `#[test]` per function, whose file says why the engine keeps the
//! contract): two fresh worlds give the same run bit for bit, `set_state` after any history
//! (a long random run, a limp collapse, a divergence) replays a fresh world, and a world built
//! with another time step is deterministic too and differs.
//!
//! The runs drive the joints into their limits: PD sub-steps towards random targets anywhere
//! inside the limits ([`random_pd_run`] with no margin), [`STEPS`] of them.

use std::sync::Arc;

use super::fixtures::{
    Robot, build, build_default, first_difference, random_pd_run, set, step_zero,
};
use hyq_physics::error::PhysicsError;
use hyq_physics::{Backend, PhysicsParams};

/// Sub-steps of each compared run (2 s at the default time step).
pub const STEPS: usize = 2000;

/// [`random_pd_run`] of the first `steps` sub-steps, with targets anywhere inside the limits.
fn run<B: Backend>(b: &mut B, seed: u64, steps: usize) -> Vec<u64> {
    random_pd_run(b, seed, 0.0, 0..steps)
}

/// Two freshly built worlds driven alike give bitwise the same run.
pub fn two_fresh_worlds_give_identical_runs<B: Backend>(robot: &Robot, options: &B::Options) {
    let a = run(&mut build_default::<B>(robot, options), 3, STEPS);
    let b = run(&mut build_default::<B>(robot, options), 3, STEPS);
    assert_eq!(first_difference(&a, &b), None);
}

/// A world set to the spawn state replays a fresh world's run bitwise, whatever it went
/// through before: a long random run (feet land and lift, joints hit limits), a limp collapse
/// (trunk and shins on the ground), a divergence.
pub fn set_state_after_any_history_replays_a_fresh_world<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let model = Arc::clone(&robot.model);
    let reference = run(&mut build_default::<B>(robot, options), 4, STEPS);
    let mut world: B = build_default(robot, options);
    for history in 0..3 {
        match history {
            0 => {
                run(&mut world, 99, 3 * STEPS);
            }
            1 => {
                for _ in 0..3000 {
                    step_zero(&mut world);
                }
            }
            _ => {
                let huge = vec![1e300; model.num_joints()];
                let diverged = (0..50).any(|_| {
                    world
                        .set_joint_torques(&huge)
                        .expect("finite torques are valid");
                    matches!(world.step(), Err(PhysicsError::Diverged { .. }))
                });
                assert!(
                    diverged,
                    "1e300 N·m must make the simulation diverge on {}",
                    B::NAME
                );
            }
        }
        set(&mut world, &model.spawn_state());
        let replay = run(&mut world, 4, STEPS);
        assert_eq!(
            first_difference(&reference, &replay),
            None,
            "after history {history}"
        );
    }
}

/// Worlds built with half the default time step are deterministic too, and their run differs
/// from the default step's (the time step reaches the engine).
pub fn another_time_step_is_deterministic_too_and_differs<B: Backend>(
    robot: &Robot,
    options: &B::Options,
) {
    let params = PhysicsParams {
        dt: 0.0005,
        ..PhysicsParams::default()
    };
    let a = run(&mut build::<B>(robot, &params, options), 8, STEPS);
    let b = run(&mut build::<B>(robot, &params, options), 8, STEPS);
    assert_eq!(first_difference(&a, &b), None);
    let default_dt = run(&mut build_default::<B>(robot, options), 8, STEPS);
    assert!(
        first_difference(&a, &default_dt).is_some(),
        "the time step must matter"
    );
}
