//! Invariant: the field's robots from example-robot-data 6.0.0 (`assets/{a1,go1_urdf,anymal_b,
//! laikago}/`, loaded from their profiles through the front ends' resolver) run through `Env`
//! on every engine: each settles within 1 mm of its profile's standing height after 1 s of the
//! `stand` policy with every foot down, and its scripted trot (the profile's `[gait]`) walks at
//! least 1 m toward the default goal in 10 s with nothing but the time limit ending the
//! episode, on rapier and (with `--features dart` / `mujoco`) on DART and MuJoCo. The figures
//! measured are in `docs/adding-a-robot.md` ("Robots tried") and each profile's `[gait]`.

use std::sync::Arc;

use hyq_env::policy::{Policy, Stand, Trot};
use hyq_env::{Env, EnvConfig, Reason, ResetOptions};
use hyq_physics::{Backend, RobotModel};

const ROBOTS: [&str; 4] = ["a1", "go1_urdf", "anymal_b", "laikago"];

fn robot(name: &str) -> Arc<RobotModel> {
    let path = format!(
        "{}/../../assets/{name}/profile.toml",
        env!("CARGO_MANIFEST_DIR")
    );
    hyq_physics::resolve_robot(&path).unwrap_or_else(|e| panic!("{e}"))
}

fn make_env<B: Backend>(model: &Arc<RobotModel>) -> Env<B> {
    let mut env =
        Env::<B>::new(Arc::clone(model), EnvConfig::default()).unwrap_or_else(|e| panic!("{e}"));
    env.reset(Some(0), &ResetOptions::default())
        .unwrap_or_else(|e| panic!("{e}"));
    env
}

/// Holds the standing pose for 1 s; asserts every foot is down and the trunk within 1 mm of
/// the profile's standing height (which is one engine's figure; the engines differ by up to
/// 0.5 mm: the engines' `tests/field_robots.rs`).
fn stands_at_its_profile_height<B: Backend>(model: &Arc<RobotModel>) {
    let mut env = make_env::<B>(model);
    let mut a = vec![0.0; model.num_joints()];
    for _ in 0..100 {
        Stand.act(&env.policy_input(), &mut a);
        let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        assert!(
            !s.terminated,
            "{} standing ended: {:?}",
            model.name(),
            s.info.reasons
        );
    }
    let layout = env.observation_layout().clone();
    let obs = env.observation();
    assert!(
        obs[layout.foot_contacts()].iter().all(|&c| c == 1.0),
        "{}: every tracked foot down",
        model.name()
    );
    let z = obs[layout.trunk_position()][2];
    println!("{} on {}: stands at {z:.5} m", model.name(), B::NAME);
    assert!(
        (z - model.standing_height()).abs() < 1e-3,
        "{} on {}: settled at {z}, profile says {}",
        model.name(),
        B::NAME,
        model.standing_height()
    );
}

/// Runs the profile's trot for the default episode (10 s): only the time limit ends it, and
/// the trunk gets at least 1 m closer to the goal.
fn trots_a_metre_toward_the_goal<B: Backend>(model: &Arc<RobotModel>) {
    let mut env = make_env::<B>(model);
    let mut trot = Trot::from_profile(model).unwrap_or_else(|e| panic!("{e}"));
    let mut a = vec![0.0; model.num_joints()];
    let start = env.info().distance_to_goal;
    loop {
        trot.act(&env.policy_input(), &mut a);
        let s = env.step(&a).unwrap_or_else(|e| panic!("{e}"));
        if s.terminated || s.truncated {
            assert!(
                !s.terminated && s.info.reasons.contains(Reason::Timeout),
                "{} on {}: ended at t = {} by {:?}",
                model.name(),
                B::NAME,
                s.info.t,
                s.info.reasons
            );
            assert_eq!(s.info.t, 1000);
            break;
        }
    }
    let progress = start - env.info().distance_to_goal;
    println!(
        "{} on {}: trot progress {progress:.3} m toward the goal in 10 s",
        model.name(),
        B::NAME
    );
    assert!(
        progress >= 1.0,
        "{} on {}: {progress} m",
        model.name(),
        B::NAME
    );
}

fn every_robot_stands_and_trots<B: Backend>() {
    for name in ROBOTS {
        let model = robot(name);
        stands_at_its_profile_height::<B>(&model);
        trots_a_metre_toward_the_goal::<B>(&model);
    }
}

#[test]
fn the_field_robots_stand_and_trot_on_rapier() {
    every_robot_stands_and_trots::<hyq_rapier::RapierBackend>();
}

#[cfg(feature = "dart")]
#[test]
fn the_field_robots_stand_and_trot_on_dart() {
    every_robot_stands_and_trots::<hyq_dart::DartBackend>();
}

#[cfg(feature = "mujoco")]
#[test]
fn the_field_robots_stand_and_trot_on_mujoco() {
    every_robot_stands_and_trots::<hyq_mujoco::MujocoBackend>();
}
