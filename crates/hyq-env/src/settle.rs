//! A robot's standing height as the robot tools measure it: the default environment, seed 0,
//! the standing pose held by [`Stand`] for [`SETTLE_S`]. `hyq robot init` writes it into a
//! drafted profile, and an MJCF file given without a profile (the command line's `--robot
//! ROBOT.xml`, Python's `robot=`) takes it as its standing height, so every front measures a
//! drafted robot the same way.

use std::sync::Arc;

use hyq_physics::{Backend, RobotModel};

use crate::policy::{Policy as _, Stand};
use crate::{Env, EnvConfig, ResetOptions};

/// How long (s) a drafted robot holds its standing pose before its standing height is read.
pub const SETTLE_S: f64 = 1.0;

/// The trunk frame's height (m) after [`SETTLE_S`] of holding the standing pose on engine `B`,
/// default configuration, seed 0; an error (one line) if the environment cannot be built, the
/// episode ends while standing (a fall, the trunk on the ground), or the height is not a
/// positive number.
pub fn settle_height<B: Backend>(model: Arc<RobotModel>) -> Result<f64, String> {
    let n = model.num_joints();
    let mut env = Env::<B>::new(model, EnvConfig::default())
        .map_err(|e| format!("cannot build the {} environment: {e}", B::NAME))?;
    env.reset(Some(0), &ResetOptions::default())
        .map_err(|e| e.to_string())?;
    let steps = (SETTLE_S / env.env_dt()).round() as usize;
    let mut a = vec![0.0; n];
    for _ in 0..steps {
        Stand.act(&env.policy_input(), &mut a);
        let s = env.step(&a).map_err(|e| e.to_string())?;
        if s.terminated || s.truncated {
            return Err(format!(
                "the episode ended while standing: {:?}",
                s.info.reasons
            ));
        }
    }
    let z = env.trunk().pose.translation.vector.z;
    if !z.is_finite() || z <= 0.0 {
        return Err(format!("the trunk ended at a height of {z} m"));
    }
    Ok(z)
}
