//! `env_scene` (the scene of `hyq render` and Python's `rgb_array`) shows the environment's
//! task: under the spec's task the goal and no velocity display; under `task.kind =
//! "velocity"` the velocity display with the command the step was judged by and the trunk's
//! measured velocity from the info, and no goal; and the rendered frame of the velocity task
//! differs from the same state's frame without the display.

// In tests and benches a failed unwrap is a failed run, with its location.
#![allow(clippy::unwrap_used)]

use hyq_env::{Env, EnvConfig, ResetOptions};
use hyq_rapier::RapierBackend;
use hyq_render::{RenderConfig, Renderer, env_scene};

fn env(pairs: &[(&str, &str)]) -> Env<RapierBackend> {
    let config = EnvConfig::load(None, pairs).unwrap();
    let mut env = Env::<RapierBackend>::new(hyq_physics::bundled::hyq(), config).unwrap();
    env.reset(Some(0), &ResetOptions::default()).unwrap();
    let a = vec![0.0; env.model().num_joints()];
    for _ in 0..20 {
        env.step(&a).unwrap();
    }
    env
}

#[test]
fn the_goal_task_shows_its_goal_and_no_velocity_display() {
    let env = env(&[]);
    let scene = env_scene(&env, 0.0);
    assert!(scene.velocity.is_none());
    let goal = scene.goal.unwrap();
    assert_eq!(goal.coords.as_slice(), env.info().goal.as_slice());
}

#[test]
fn the_velocity_task_shows_its_command_and_measured_velocity_and_no_goal() {
    let env = env(&[
        ("task.kind", "velocity"),
        ("command.lin_vel_x", "[0.6, 0.6]"),
        ("command.lin_vel_y", "[-0.2, -0.2]"),
        ("command.ang_vel_yaw", "[0.4, 0.4]"),
    ]);
    let scene = env_scene(&env, 1.0);
    assert!(scene.goal.is_none());
    let hud = scene.velocity.unwrap();
    let info = env.info().velocity.unwrap();
    assert_eq!(hud.command, [0.6, -0.2, 0.4]);
    assert_eq!(
        hud.measured,
        [info.lin_vel[0], info.lin_vel[1], info.ang_vel[2]]
    );
    let mut r = Renderer::new(env.model().clone(), RenderConfig::default()).unwrap();
    let with = r.render(&scene).unwrap();
    let mut bare = scene;
    bare.velocity = None;
    let without = r.render(&bare).unwrap();
    let changed = with
        .rgb
        .chunks_exact(3)
        .zip(without.rgb.chunks_exact(3))
        .filter(|(a, b)| a != b)
        .count();
    assert!(changed > 500, "the display changed {changed} pixels");
}
