//! One step of the velocity task: every term from a [`VelocitySnapshot`], their scaled sum
//! `Σ s_i · r_i · Δt_env` (clipped below at 0 when `only_positive`), and whether the step
//! ends the episode ([`crate::termination`]).
//!
//! The gait terms are gated by the command's norm ‖c‖ (all three components): `feet_air_time`
//! and `foot_slip` count when ‖c‖ > `command_gate`, `stand_still` when ‖c‖ ≤ `command_gate`.

use crate::command::Command;
use crate::scales::{RewardScales, TermValues};
use crate::termination;
use crate::terms;

/// Everything a step of the task is judged on, as plain numbers (trunk-frame vectors unless
/// said otherwise; joints in action order; feet in the robot's order).
#[derive(Clone, Copy, Debug)]
pub struct VelocitySnapshot<'a> {
    /// The command the step's policy saw.
    pub command: Command,
    /// Rᵀ v (m/s).
    pub lin_vel: [f64; 3],
    /// Rᵀ ω (rad/s).
    pub ang_vel: [f64; 3],
    /// Rᵀ (0, 0, −1).
    pub gravity: [f64; 3],
    /// q (rad).
    pub joint_angles: &'a [f64],
    /// q̇ at the end of the step (rad/s).
    pub joint_speeds: &'a [f64],
    /// q̇ at the end of the previous step (rad/s).
    pub previous_joint_speeds: &'a [f64],
    /// q₀ (rad).
    pub standing: &'a [f64],
    /// Each joint's soft limits (rad), from [`terms::soft_limits`].
    pub soft_limits: &'a [[f64; 2]],
    /// The joint torques of the step's last sub-step (N·m).
    pub torques: &'a [f64],
    /// The step's action.
    pub action: &'a [f64],
    /// The previous step's action (the step's own after reset).
    pub previous_action: &'a [f64],
    /// Which feet touched the ground during the step.
    pub foot_contacts: &'a [bool],
    /// Each foot's horizontal velocity (m/s, world frame).
    pub foot_velocity_xy: &'a [[f64; 2]],
    /// Each foot's air time at touchdown this step (s), 0 for a foot not touching down
    /// ([`AirTime::update`]).
    pub air_at_touchdown: &'a [f64],
    /// Whether the trunk touched the ground during the step.
    pub trunk_contact: bool,
    /// Whether trunk contact ends the episode.
    pub trunk_contact_ends: bool,
    /// Δt_env (s).
    pub env_dt: f64,
}

/// What a step of the task gives.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct VelocityOutcome {
    /// Every term, unscaled.
    pub terms: TermValues,
    /// The step's reward: Σ s_i · r_i · Δt_env, clipped below at 0 when `only_positive`.
    pub total: f64,
    /// Whether the step ends the episode (upside down, or trunk contact when it ends one).
    pub terminated: bool,
}

/// Judges one step of the task with `scales`.
pub fn evaluate(scales: &RewardScales, s: &VelocitySnapshot<'_>) -> VelocityOutcome {
    let c = s.command;
    let moving = c.norm() > scales.command_gate;
    let terminated = termination::terminated(s.gravity, s.trunk_contact, s.trunk_contact_ends);
    let sigma = scales.tracking_sigma;
    let values = TermValues {
        tracking_lin_vel: terms::tracking_lin_vel(
            [c.lin_vel_x, c.lin_vel_y],
            [s.lin_vel[0], s.lin_vel[1]],
            sigma,
        ),
        tracking_ang_vel: terms::tracking_ang_vel(c.ang_vel_yaw, s.ang_vel[2], sigma),
        lin_vel_z: terms::lin_vel_z(s.lin_vel[2]),
        ang_vel_xy: terms::ang_vel_xy(s.ang_vel),
        orientation: terms::orientation(s.gravity),
        torques: terms::torques(s.torques),
        torques_abs: terms::torques_abs(s.torques),
        joint_acc: terms::joint_acc(s.joint_speeds, s.previous_joint_speeds, s.env_dt),
        action_rate: terms::action_rate(s.action, s.previous_action),
        feet_air_time: terms::feet_air_time(
            s.air_at_touchdown,
            scales.feet_air_time_threshold_s,
            moving,
        ),
        foot_slip: terms::foot_slip(s.foot_velocity_xy, s.foot_contacts, moving),
        stand_still: terms::stand_still(s.joint_angles, s.standing, !moving),
        joint_limits: terms::joint_limits(s.joint_angles, s.soft_limits),
        termination: f64::from(u8::from(terminated)),
    };
    VelocityOutcome {
        terms: values,
        total: total(scales, &values, s.env_dt),
        terminated,
    }
}

/// Σ s_i · r_i · Δt, clipped below at 0 when `only_positive`. A term whose scale is 0 adds
/// nothing even when its value is not finite (the anchors drop such terms).
pub fn total(scales: &RewardScales, values: &TermValues, dt: f64) -> f64 {
    let sum: f64 = scales
        .terms
        .to_array()
        .iter()
        .zip(values.to_array())
        .filter(|(s, _)| **s != 0.0)
        .map(|(s, v)| s * v * dt)
        .sum();
    if scales.only_positive {
        sum.max(0.0)
    } else {
        sum
    }
}

/// Each foot's time in the air, counted per env step (Playground's order, which counts a
/// touchdown only after time in the air: legged_gym's counts every step in contact as one).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct AirTime {
    air: Vec<f64>,
    at_touchdown: Vec<f64>,
}

impl AirTime {
    /// Air times of `feet` feet, all 0 (standing).
    pub fn new(feet: usize) -> Self {
        Self {
            air: vec![0.0; feet],
            at_touchdown: vec![0.0; feet],
        }
    }

    /// Back to all feet standing.
    pub fn reset(&mut self) {
        self.air.fill(0.0);
        self.at_touchdown.fill(0.0);
    }

    /// Counts one env step of `dt` with `contacts`; returns each foot's air time at touchdown
    /// this step (the time since it left the ground, this step included), 0 for the others.
    ///
    /// # Panics
    /// If `contacts` is not one flag per foot.
    pub fn update(&mut self, contacts: &[bool], dt: f64) -> &[f64] {
        assert_eq!(contacts.len(), self.air.len(), "one contact flag per foot");
        for ((air, out), contact) in self
            .air
            .iter_mut()
            .zip(&mut self.at_touchdown)
            .zip(contacts)
        {
            let first_contact = *contact && *air > 0.0;
            *air += dt;
            *out = if first_contact { *air } else { 0.0 };
            if *contact {
                *air = 0.0;
            }
        }
        &self.at_touchdown
    }

    /// Each foot's current air time (s).
    pub fn air(&self) -> &[f64] {
        &self.air
    }
}

/// Each foot's horizontal velocity over the last env step, from its positions at the steps'
/// ends (no engine reports body velocities through the seam): (p − p_prev) / Δt, world frame.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct FootVelocity {
    xy: Vec<[f64; 2]>,
    velocity: Vec<[f64; 2]>,
}

impl FootVelocity {
    /// The velocities of `feet` feet, all 0, at positions 0.
    pub fn new(feet: usize) -> Self {
        Self {
            xy: vec![[0.0; 2]; feet],
            velocity: vec![[0.0; 2]; feet],
        }
    }

    /// Starts from the feet at `positions` (one per foot), at rest.
    pub fn reset(&mut self, positions: impl IntoIterator<Item = [f64; 2]>) {
        for (xy, p) in self.xy.iter_mut().zip(positions) {
            *xy = p;
        }
        self.velocity.fill([0.0; 2]);
    }

    /// Moves the feet to `positions` after a step of `dt`; returns each foot's velocity over it.
    pub fn update(
        &mut self,
        positions: impl IntoIterator<Item = [f64; 2]>,
        dt: f64,
    ) -> &[[f64; 2]] {
        for ((xy, v), p) in self.xy.iter_mut().zip(&mut self.velocity).zip(positions) {
            *v = [(p[0] - xy[0]) / dt, (p[1] - xy[1]) / dt];
            *xy = p;
        }
        &self.velocity
    }

    /// Each foot's velocity over the last step (m/s).
    pub fn velocity(&self) -> &[[f64; 2]] {
        &self.velocity
    }
}
