//! The scene of an environment's current state (the `env` feature): the one way the CLI's
//! `hyq render` and the Python binding's `rgb_array` build their frames' scenes.

use hyq_env::Env;
use hyq_physics::Backend;
use hyq_physics::na::Point3;

use crate::scene::{Overlay, RobotPose, Scene};

/// The scene of the state `env`'s last reset or step left: the trunk pose and joint angles,
/// the contact flags of [`Env::contacts`] (latched over the step's sub-steps, so a foot that
/// touched the ground during the step is drawn in contact), the goal, and the overlay
/// (simulated time, D^t, and `episode_return`, the episode's return so far), on the
/// environment's ground ([`Env::terrain`]).
pub fn env_scene<B: Backend>(env: &Env<B>, episode_return: f64) -> Scene<'_> {
    let info = env.info();
    Scene::new(
        RobotPose::Joints {
            trunk: &env.trunk().pose,
            q: env.joint_angles(),
        },
        env.contacts(),
    )
    .with_goal(Point3::from(info.goal))
    .with_overlay(Overlay {
        time_s: info.t as f64 * env.env_dt(),
        distance_to_goal_m: info.distance_to_goal,
        episode_return,
    })
    .with_terrain(env.terrain())
}
