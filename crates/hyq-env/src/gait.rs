//! What the gait terms keep between env steps, for both rule sets that judge a gait (the
//! velocity task and `[regularizers]`): the action being taken and the one before, the last
//! step's joint speeds, the feet's air times and their horizontal velocities from the body
//! poses the backend writes into [`GaitHistory::poses_mut`].

use hyq_physics::RobotModel;
use hyq_physics::na::Isometry3;
use hyq_tasks::step::{AirTime, FootVelocity};

/// The state between steps (see the module docs).
#[derive(Clone, Debug)]
pub(crate) struct GaitHistory {
    air: AirTime,
    /// The action of the step being taken, then of the last step.
    action: Vec<f64>,
    previous_action: Vec<f64>,
    previous_qd: Vec<f64>,
    /// The feet's body indices.
    feet: Vec<usize>,
    poses: Vec<Isometry3<f64>>,
    foot_velocity: FootVelocity,
    env_dt: f64,
}

/// What a step's gait terms read from the history, after [`GaitHistory::advance`].
pub(crate) struct GaitStep<'a> {
    pub(crate) action: &'a [f64],
    pub(crate) previous_action: &'a [f64],
    pub(crate) previous_joint_speeds: &'a [f64],
    /// Each foot's air time at touchdown this step, 0 for the others.
    pub(crate) air_at_touchdown: &'a [f64],
    /// Each foot's horizontal velocity over the step (m/s, world).
    pub(crate) foot_velocity_xy: &'a [[f64; 2]],
    pub(crate) env_dt: f64,
}

impl GaitHistory {
    /// The history of `model`'s joints and feet, stepped every `env_dt` seconds.
    pub(crate) fn new(model: &RobotModel, env_dt: f64) -> Self {
        let n = model.num_joints();
        let feet: Vec<usize> = model.tracked()[..model.num_feet()]
            .iter()
            .map(|t| t.link)
            .collect();
        Self {
            air: AirTime::new(feet.len()),
            action: vec![0.0; n],
            previous_action: vec![0.0; n],
            previous_qd: vec![0.0; n],
            poses: vec![Isometry3::identity(); model.links().len()],
            foot_velocity: FootVelocity::new(feet.len()),
            feet,
            env_dt,
        }
    }

    /// Starts an episode from the robot at rest (the body poses after reset were just read into
    /// [`GaitHistory::poses_mut`]): no previous action, joint speeds 0, every foot standing.
    pub(crate) fn reset(&mut self) {
        self.air.reset();
        self.action.fill(0.0);
        self.previous_action.fill(0.0);
        self.previous_qd.fill(0.0);
        let poses = &self.poses;
        self.foot_velocity
            .reset(self.feet.iter().map(|&link| body_xy(&poses[link])));
    }

    /// Records the step's action, as given, before its sub-steps run.
    pub(crate) fn begin_step(&mut self, action: impl Iterator<Item = f64>) {
        std::mem::swap(&mut self.action, &mut self.previous_action);
        for (a, v) in self.action.iter_mut().zip(action) {
            *a = v;
        }
    }

    /// The body poses buffer, for the backend to fill after a reset or a step.
    pub(crate) fn poses_mut(&mut self) -> &mut [Isometry3<f64>] {
        &mut self.poses
    }

    /// The action of the step being taken (after [`GaitHistory::begin_step`]).
    pub(crate) fn action(&self) -> &[f64] {
        &self.action
    }

    /// Moves the feet's air times and velocities on by the step that ended with the latched
    /// `feet` contact flags (the body poses were just read into [`GaitHistory::poses_mut`]).
    pub(crate) fn advance(&mut self, feet: &[bool]) -> GaitStep<'_> {
        let poses = &self.poses;
        let positions = self.feet.iter().map(|&link| body_xy(&poses[link]));
        let foot_velocity_xy = self.foot_velocity.update(positions, self.env_dt);
        let air_at_touchdown = self.air.update(feet, self.env_dt);
        GaitStep {
            action: &self.action,
            previous_action: &self.previous_action,
            previous_joint_speeds: &self.previous_qd,
            air_at_touchdown,
            foot_velocity_xy,
            env_dt: self.env_dt,
        }
    }

    /// Ends the step judged with joint speeds `qd`: they are the next step's previous ones.
    pub(crate) fn end_step(&mut self, qd: &[f64]) {
        self.previous_qd.copy_from_slice(qd);
    }
}

/// A body's horizontal position (m, world) from its pose.
pub(crate) fn body_xy(pose: &Isometry3<f64>) -> [f64; 2] {
    let p = pose.translation.vector;
    [p.x, p.y]
}
