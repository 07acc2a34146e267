//! The velocity-command task in the environment (`task.kind = "velocity"`, docs/velocity.md):
//! the state hyq-tasks' pure rules need between steps (the command and its seeded stream, the
//! feet's air times and positions, the previous action and joint speeds), the task's
//! observation group, and what a step reports ([`VelocityInfo`]).
//!
//! The spec's rules still run on every step (the goal, its distance and the attitude are still
//! reported), but the reward and the end reasons are the task's: the reward is hyq-tasks'
//! scaled sum, the spec's breakdown is reported neutral, and the episode ends as `fell` when
//! the trunk is upside down (or, with `velocity.terminate_on_trunk_contact`, touched the
//! ground) and as `timeout` at `task.max_time_steps`.

use hyq_physics::{RobotModel, TrunkState};
use hyq_spec::ObservationLayout;
use hyq_tasks::observation::{GroupValues, JointRows, in_body_frame, projected_gravity};
use hyq_tasks::step::{VelocitySnapshot, evaluate};
use hyq_tasks::{Command, CommandSampler, RewardScales, TermValues, terms};
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use crate::action::ActionSpace;
use crate::config::EnvConfig;
use crate::gait::GaitHistory;

mod keys;
pub use hyq_tasks::TERM_NAMES;
pub use keys::{VELOCITY_INFO_KEYS, VELOCITY_PREFIX};

/// The command stream's ChaCha stream number (the goal, noise and terrain streams are 0–2).
pub const COMMAND_STREAM: u64 = 3;
/// The name of the task's observation group.
pub const GROUP: &str = "velocity_task";

/// What a step of the velocity task reports (the info's `velocity`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct VelocityInfo {
    /// The command the step was judged by (after reset, the episode's first), observation
    /// order: v_x, v_y (m/s), ω_z (rad/s).
    pub command: [f64; 3],
    /// The command the returned observation holds (the next step's).
    pub next_command: [f64; 3],
    /// Every term, unscaled (hyq-tasks' `TERM_NAMES`); all 0 after reset and on a diverged
    /// step.
    pub terms: TermValues,
    /// The step's reward (0 after reset and on a diverged step).
    pub reward: f64,
    /// The trunk's velocity in its frame (m/s): what the forward/sideways command is
    /// compared with.
    pub lin_vel: [f64; 3],
    /// The trunk's angular velocity in its frame (rad/s).
    pub ang_vel: [f64; 3],
}

impl VelocityInfo {
    /// What the command is compared with, in the command's order: the trunk's v_x, v_y (m/s)
    /// and ω_z (rad/s) in its frame.
    pub fn measured(&self) -> [f64; 3] {
        [self.lin_vel[0], self.lin_vel[1], self.ang_vel[2]]
    }
}

/// The layout `layout` with the task's group appended (see hyq-tasks' `observation`).
pub fn extend_layout(
    layout: ObservationLayout,
    model: &RobotModel,
    config: &EnvConfig,
) -> ObservationLayout {
    let space = ActionSpace::new(model, &config.action);
    let standing = model.standing_pose();
    let joints: Vec<JointRows<'_>> = model
        .joints()
        .iter()
        .enumerate()
        .map(|(i, j)| JointRows {
            name: &j.name,
            range: [j.lower, j.upper],
            standing: standing[i],
            action: [space.low()[i], space.high()[i]],
        })
        .collect();
    let rows = hyq_tasks::observation::rows(&joints, config.command.ranges());
    layout.with_group(GROUP, "m/s, rad/s, 1, rad, action", rows)
}

/// The velocity task's state in an environment.
#[derive(Clone, Debug)]
pub(crate) struct VelocityTask {
    scales: RewardScales,
    trunk_contact_ends: bool,
    sampler: CommandSampler,
    rng: ChaCha8Rng,
    standing: Vec<f64>,
    soft_limits: Vec<[f64; 2]>,
    /// The previous action and joint speeds, the feet's air times and velocities.
    pub(crate) gait: GaitHistory,
    /// What the last reset or step reported.
    pub(crate) info: VelocityInfo,
    /// Whether the last step ends the episode by the task's rules.
    pub(crate) ended: bool,
}

impl VelocityTask {
    /// The task for `model` under `config` (validated), its command stream seeded with `seed`
    /// until a reset gives one, or `None` for the spec's task.
    pub(crate) fn new(model: &RobotModel, config: &EnvConfig, seed: u64) -> Option<Box<Self>> {
        if config.task.kind != crate::config::TaskKind::Velocity {
            return None;
        }
        let scales = config.velocity.resolve();
        let soft_limits = model
            .joints()
            .iter()
            .map(|j| terms::soft_limits(j.lower, j.upper, scales.soft_joint_limit_factor))
            .collect();
        Some(Box::new(Self {
            scales,
            trunk_contact_ends: config.velocity.terminate_on_trunk_contact,
            sampler: CommandSampler::new(config.command, config.env_dt()),
            rng: stream(seed),
            standing: model.standing_pose().to_vec(),
            soft_limits,
            gait: GaitHistory::new(model, config.env_dt()),
            info: VelocityInfo::default(),
            ended: false,
        }))
    }

    /// Starts an episode: reseeds the command stream when `seed` is given (else continues
    /// it), draws the first command, and restarts the per-episode state from the robot at rest
    /// (the body poses after reset were just read into the gait history).
    pub(crate) fn reset(&mut self, seed: Option<u64>) {
        if let Some(s) = seed {
            self.rng = stream(s);
        }
        let command = self.sampler.start(&mut self.rng);
        self.gait.reset();
        self.ended = false;
        self.info = VelocityInfo {
            command: command.as_array(),
            next_command: command.as_array(),
            ..VelocityInfo::default()
        };
    }

    /// Judges the step that ended in `trunk`, `q`, `qd` with the last sub-step's `torques` and
    /// the latched `feet` and `trunk_contact` flags (the body poses were just read into
    /// gait history), then moves the command on for the next observation.
    /// Whether the step ends the episode is then [`VelocityTask::ended`].
    pub(crate) fn evaluate_step(
        &mut self,
        trunk: &TrunkState,
        q: &[f64],
        qd: &[f64],
        torques: &[f64],
        feet: &[bool],
        trunk_contact: bool,
    ) {
        let command = self.sampler.command();
        let rotation = &trunk.pose.rotation;
        let lin_vel = in_body_frame(rotation, &trunk.linvel);
        let ang_vel = in_body_frame(rotation, &trunk.angvel);
        let g = self.gait.advance(feet);
        let outcome = evaluate(
            &self.scales,
            &VelocitySnapshot {
                command,
                lin_vel,
                ang_vel,
                gravity: projected_gravity(rotation),
                joint_angles: q,
                joint_speeds: qd,
                previous_joint_speeds: g.previous_joint_speeds,
                standing: &self.standing,
                soft_limits: &self.soft_limits,
                torques,
                action: g.action,
                previous_action: g.previous_action,
                foot_contacts: feet,
                foot_velocity_xy: g.foot_velocity_xy,
                air_at_touchdown: g.air_at_touchdown,
                trunk_contact,
                trunk_contact_ends: self.trunk_contact_ends,
                env_dt: g.env_dt,
            },
        );
        self.gait.end_step(qd);
        let next = self.sampler.advance(&mut self.rng);
        self.info = VelocityInfo {
            command: command.as_array(),
            next_command: next.as_array(),
            terms: outcome.terms,
            reward: outcome.total,
            lin_vel,
            ang_vel,
        };
        self.ended = outcome.terminated;
    }

    /// Reports a diverged step: reward and terms 0, the command unchanged.
    pub(crate) fn diverged(&mut self) {
        self.ended = false;
        self.info.terms = TermValues::default();
        self.info.reward = 0.0;
        self.info.command = self.info.next_command;
    }

    /// Writes the task's observation group for `trunk` and `q` into `out`.
    pub(crate) fn write_group(&self, trunk: &TrunkState, q: &[f64], out: &mut [f64]) {
        let rotation = &trunk.pose.rotation;
        hyq_tasks::observation::write(
            &GroupValues {
                lin_vel: in_body_frame(rotation, &trunk.linvel),
                ang_vel: in_body_frame(rotation, &trunk.angvel),
                gravity: projected_gravity(rotation),
                command: self.sampler.command().as_array(),
                joint_angles: q,
                standing: &self.standing,
                last_action: self.gait.action(),
            },
            out,
        );
    }

    /// The current command.
    pub(crate) fn command(&self) -> Command {
        self.sampler.command()
    }
}

/// The command stream of `seed`.
fn stream(seed: u64) -> ChaCha8Rng {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    rng.set_stream(COMMAND_STREAM);
    rng
}
