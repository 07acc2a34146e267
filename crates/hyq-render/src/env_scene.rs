//! The scene of an environment's current state (the `env` feature): the one way the CLI's
//! `hyq render` and the Python binding's `rgb_array` build their frames' scenes.

use hyq_env::Env;
use hyq_physics::Backend;
use hyq_physics::na::Point3;

use crate::scene::{Overlay, RobotPose, Scene, VelocityHud};

/// The scene of the state `env`'s last reset or step left: the trunk pose and joint angles,
/// the contact flags of [`Env::contacts`] (latched over the step's sub-steps, so a foot that
/// touched the ground during the step is drawn in contact), the goal, and the overlay
/// (simulated time, D^t, and `episode_return`, the episode's return so far), on the
/// environment's ground ([`Env::terrain`]).
///
/// Under `task.kind = "velocity"` the goal, which that task does not pursue, is left out and
/// the task's display is drawn instead ([`VelocityHud`]): the command the last step was judged
/// by and the trunk's velocity in its frame at the end of that step (after reset, the
/// episode's first command and zeros), as the info's `velocity` reports them.
pub fn env_scene<B: Backend>(env: &Env<B>, episode_return: f64) -> Scene<'_> {
    let info = env.info();
    let scene = Scene::new(
        RobotPose::Joints {
            trunk: &env.trunk().pose,
            q: env.joint_angles(),
        },
        env.contacts(),
    )
    .with_overlay(Overlay {
        time_s: info.t as f64 * env.env_dt(),
        distance_to_goal_m: info.distance_to_goal,
        episode_return,
    })
    .with_terrain(env.terrain());
    match &info.velocity {
        Some(v) => scene.with_velocity(VelocityHud {
            command: v.command,
            measured: [v.lin_vel[0], v.lin_vel[1], v.ang_vel[2]],
        }),
        None => scene.with_goal(Point3::from(info.goal)),
    }
}
