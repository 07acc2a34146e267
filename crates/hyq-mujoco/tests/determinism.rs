//! Same state and same inputs give bitwise the same results on MuJoCo: across runs, after
//! `set_state` on a world with any history (falls, contacts, joint limits, a divergence), and
//! for a world built with a non-default time step. MuJoCo carries state between steps besides
//! positions and velocities (the solver's warm start `qacc_warmstart`, the contact list, applied
//! forces, warning counters); `set_state` resets all of it (`mj_resetData`), which is what makes
//! a reused world replay a fresh one.

mod common;

use common::{first_difference, hyq, random_trajectory};
use hyq_mujoco::{MujocoBackend, MujocoOptions};
use hyq_physics::{Backend, PhysicsError, PhysicsParams, bundled};

const STEPS: usize = 2000;

#[test]
fn two_fresh_worlds_give_identical_runs() {
    let a = random_trajectory(&mut hyq(), 3, STEPS);
    let b = random_trajectory(&mut hyq(), 3, STEPS);
    assert_eq!(first_difference(&a, &b), None);
}

#[test]
fn set_state_after_any_history_replays_a_fresh_world() {
    let model = bundled::hyq();
    let reference = random_trajectory(&mut hyq(), 4, STEPS);
    let mut world = hyq();
    for history in 0..3 {
        match history {
            // A long random run: feet land and lift, joints hit limits.
            0 => {
                random_trajectory(&mut world, 99, 3 * STEPS);
            }
            // A limp collapse: trunk and shins on the ground.
            1 => {
                let zero = vec![0.0; model.num_joints()];
                for _ in 0..3000 {
                    world.set_joint_torques(&zero).expect("valid torques");
                    world.step().expect("a limp fall stays finite");
                }
            }
            // A divergence.
            _ => {
                let huge = vec![1e300; model.num_joints()];
                let diverged = (0..50).any(|_| {
                    world
                        .set_joint_torques(&huge)
                        .expect("finite torques are valid");
                    matches!(world.step(), Err(PhysicsError::Diverged { .. }))
                });
                assert!(diverged, "1e300 N·m must make the simulation diverge");
            }
        }
        world
            .set_state(&model.spawn_state())
            .expect("the spawn state is valid");
        let replay = random_trajectory(&mut world, 4, STEPS);
        assert_eq!(
            first_difference(&reference, &replay),
            None,
            "after history {history}"
        );
    }
}

#[test]
fn another_time_step_is_deterministic_too_and_differs() {
    let params = PhysicsParams {
        dt: 0.0005,
        ..PhysicsParams::default()
    };
    let build = || {
        MujocoBackend::build(bundled::hyq(), &params, &MujocoOptions::default()).expect("builds")
    };
    let a = random_trajectory(&mut build(), 8, STEPS);
    let b = random_trajectory(&mut build(), 8, STEPS);
    assert_eq!(first_difference(&a, &b), None);
    let default_dt = random_trajectory(&mut hyq(), 8, STEPS);
    assert!(
        first_difference(&a, &default_dt).is_some(),
        "the time step must matter"
    );
}
