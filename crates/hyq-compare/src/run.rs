//! Running one side of a comparison: the environment on one backend, fed the scenario's action
//! script, recording what the comparison needs at every env step; the standing height; and the
//! one-step runs from shared states.

use std::sync::Arc;

use hyq_env::{Env, EnvConfig, EpisodeRandomization, Reasons, ResetOptions, VelocityInfo};
use hyq_physics::na::{Isometry3, UnitQuaternion};
use hyq_physics::{Backend, RobotModel, RobotState, TrunkState};
use serde::Serialize;

use crate::error::CompareError;

/// The sums of each reward and penalty term over a run (hyq-spec's [`hyq_env::TermSums`],
/// written flat beside the return in the report) and the return.
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct TermSums {
    /// Σ of each term.
    #[serde(flatten)]
    pub terms: hyq_env::TermSums,
    /// Σ reward (the return).
    #[serde(rename = "return")]
    pub ret: f64,
}

/// What one backend did with the action script, sampled after reset (index 0) and after every
/// env step t (index t) until the episode ended.
#[derive(Clone, Debug)]
pub struct Trajectory {
    /// The side's label (e.g. `"rapier"`, `"dart"`).
    pub label: String,
    /// The engine's name (`Backend::NAME`).
    pub engine: &'static str,
    /// Δt_env (s).
    pub env_dt: f64,
    /// Joints per sample.
    pub num_joints: usize,
    /// The tracked bodies' names (feet, then the trunk).
    pub tracked: Vec<String>,
    /// Trunk position C^t (m).
    pub positions: Vec<[f64; 3]>,
    /// Trunk orientation.
    pub orientations: Vec<UnitQuaternion<f64>>,
    /// Joint angles (rad), `num_joints` per sample.
    pub joint_angles: Vec<f64>,
    /// Latched contact flags (rows 24–28), one per tracked body per sample; all false after
    /// reset.
    pub contacts: Vec<bool>,
    /// Feet per sample (the first tracked bodies).
    pub num_feet: usize,
    /// Each foot collision sphere's centre in the world (m), `num_feet` per sample, from the
    /// engine's own body poses (`Backend::link_poses`).
    pub foot_centres: Vec<[f64; 3]>,
    /// The full state after each sample (for the one-step comparison).
    pub states: Vec<RobotState>,
    /// The joint targets of the step that followed each sample (rad); the last sample's are
    /// those of the last step (nothing followed it).
    pub targets: Vec<f64>,
    /// The actions of every step, as fed (step-major), `num_joints` per step.
    pub actions: Vec<f64>,
    /// The action space's low end, per joint.
    pub action_low: Vec<f64>,
    /// The action space's high end, per joint.
    pub action_high: Vec<f64>,
    /// Why the episode ended (empty if the script ran out first, which cannot happen: the
    /// episode's t_max is the script's length).
    pub reasons: Reasons,
    /// The step on which it ended.
    pub end_step: u64,
    /// Reward-term sums.
    pub sums: TermSums,
    /// The goal G (m).
    pub goal: [f64; 3],
    /// D^0 = K, the trunk's distance to the goal after reset (m).
    pub initial_distance_m: f64,
    /// D^T, its distance to the goal after the last step (m).
    pub final_distance_m: f64,
    /// `[randomize]`'s draws for the episode and its pushes, when it is on: the draws are the
    /// same on every engine for the same seed.
    pub randomize: Option<EpisodeRandomization>,
    /// Under `task.kind = "velocity"`, what each step reported (its command and the trunk's
    /// velocity in its frame), one per step; empty under the spec's task.
    pub velocity: Vec<VelocityInfo>,
}

impl Trajectory {
    /// Samples recorded (steps taken + 1).
    pub fn len(&self) -> usize {
        self.positions.len()
    }

    /// Always false: the reset sample is always there.
    pub fn is_empty(&self) -> bool {
        self.positions.is_empty()
    }

    /// The joint angles of sample `t`.
    pub fn q(&self, t: usize) -> &[f64] {
        &self.joint_angles[t * self.num_joints..(t + 1) * self.num_joints]
    }

    /// The contact flags of sample `t`.
    pub fn contacts_at(&self, t: usize) -> &[bool] {
        let k = self.tracked.len();
        &self.contacts[t * k..(t + 1) * k]
    }

    /// The feet's contact flags, `num_feet` per sample (the trunk's left out).
    pub fn foot_contacts(&self) -> Vec<bool> {
        let k = self.tracked.len().max(1);
        self.contacts
            .chunks_exact(k)
            .flat_map(|c| &c[..self.num_feet.min(k)])
            .copied()
            .collect()
    }

    /// The feet over time, for the gait diagnostics; `contacts` is [`Self::foot_contacts`].
    pub fn feet<'a>(&'a self, contacts: &'a [bool]) -> crate::gait::Feet<'a> {
        crate::gait::Feet {
            num_feet: self.num_feet,
            contacts,
            centres: &self.foot_centres,
        }
    }

    /// The joint targets of the step after sample `t`.
    pub fn targets_after(&self, t: usize) -> &[f64] {
        &self.targets[t * self.num_joints..(t + 1) * self.num_joints]
    }
}

fn env_error(label: &str, e: impl std::fmt::Display) -> CompareError {
    CompareError::Env {
        backend: label.to_owned(),
        message: e.to_string(),
    }
}

/// Builds the environment of one side on backend `B`.
pub fn build_env<B: Backend>(
    label: &str,
    model: Arc<RobotModel>,
    config: EnvConfig,
) -> Result<Env<B>, CompareError> {
    Env::<B>::new(model, config).map_err(|e| CompareError::Build {
        backend: label.to_owned(),
        message: e.to_string(),
    })
}

/// Resets `env` with `seed` and feeds it `script` (one action per env step, flattened) until
/// the episode ends, recording a [`Trajectory`].
pub fn run_script<B: Backend>(
    label: &str,
    env: &mut Env<B>,
    seed: u64,
    start: Option<&RobotState>,
    script: &[f64],
) -> Result<Trajectory, CompareError> {
    let n = env.action_space().len();
    let mut actions = script.chunks_exact(n.max(1));
    run_episode(label, env, Some(seed), start, |_, action| {
        actions.next().map(|a| action.copy_from_slice(a)).is_some()
    })
}

/// Resets `env` (with `seed`, or continuing its streams when `None`) and runs one episode in
/// which `next` writes each action from the environment it sees (closed loop) or from a script
/// (open loop), until the episode ends or `next` returns false; records a [`Trajectory`].
pub fn run_episode<B: Backend>(
    label: &str,
    env: &mut Env<B>,
    seed: Option<u64>,
    start: Option<&RobotState>,
    mut next: impl FnMut(&Env<B>, &mut [f64]) -> bool,
) -> Result<Trajectory, CompareError> {
    let n = env.action_space().len();
    let model = env.model().clone();
    let tracked: Vec<String> = model.tracked().iter().map(|t| t.name.clone()).collect();
    let options = ResetOptions {
        state: start.cloned(),
        ..ResetOptions::default()
    };
    let reset = env.reset(seed, &options).map_err(|e| env_error(label, e))?;
    let (goal, initial_distance_m) = (reset.info.goal, reset.info.distance_to_goal);
    let steps = usize::try_from(env.config().task.max_time_steps).unwrap_or(0);
    let mut traj = Trajectory {
        label: label.to_owned(),
        engine: B::NAME,
        env_dt: env.env_dt(),
        num_joints: n,
        tracked,
        positions: Vec::with_capacity(steps + 1),
        orientations: Vec::with_capacity(steps + 1),
        joint_angles: Vec::with_capacity((steps + 1) * n),
        contacts: Vec::new(),
        num_feet: model.num_feet(),
        foot_centres: Vec::with_capacity((steps + 1) * model.num_feet()),
        states: Vec::with_capacity(steps + 1),
        targets: Vec::with_capacity((steps + 1) * n),
        actions: Vec::with_capacity(steps * n),
        action_low: env.action_space().low().to_vec(),
        action_high: env.action_space().high().to_vec(),
        reasons: Reasons::NONE,
        end_step: 0,
        sums: TermSums::default(),
        goal,
        initial_distance_m,
        final_distance_m: initial_distance_m,
        randomize: env.episode_draw().map(EpisodeRandomization::starting),
        velocity: Vec::new(),
    };
    let mut poses = vec![Isometry3::identity(); model.links().len()];
    let mut record = |traj: &mut Trajectory, env: &Env<B>| {
        let trunk: &TrunkState = env.trunk();
        let p = trunk.pose.translation.vector;
        traj.positions.push([p.x, p.y, p.z]);
        traj.orientations.push(trunk.pose.rotation);
        traj.joint_angles.extend_from_slice(env.joint_angles());
        // The simulated contacts (feet, then the trunk), not the observed flags, which
        // observation noise may flip.
        traj.contacts.extend_from_slice(env.contacts());
        env.backend().link_poses(&mut poses);
        traj.foot_centres
            .extend(foot_centres(&model, &poses).take(traj.num_feet));
        traj.states.push(env.backend().state());
    };
    record(&mut traj, env);
    let mut action = vec![0.0; n];
    while next(env, &mut action) {
        let step = env.step(&action).map_err(|e| env_error(label, e))?;
        let info = step.info;
        let r = &info.reward;
        traj.sums.terms.add(r);
        // The step's reward: the spec's total, plus the gait regularisers' sum when they are on;
        // under the velocity task, the task's.
        traj.sums.ret += info.total_reward();
        traj.velocity.extend(info.velocity);
        traj.targets.extend_from_slice(&info.joint_targets);
        traj.actions.extend_from_slice(&action);
        traj.reasons = info.reasons;
        traj.final_distance_m = info.distance_to_goal;
        let done = info.reasons.done();
        traj.end_step = info.t;
        record(&mut traj, env);
        if done {
            break;
        }
    }
    if let (Some(r), Some((_, pushes))) = (traj.randomize.as_mut(), env.last_push()) {
        r.pushes = pushes;
    }
    // The last sample has no step after it: repeat the last step's targets so that every
    // sample has targets (the one-step comparison never samples the last state).
    let last = traj.targets[traj.targets.len().saturating_sub(n)..].to_vec();
    traj.targets.extend_from_slice(&last);
    Ok(traj)
}

/// Each tracked body's first collision shape's centre in the world (its body's origin if it has
/// none), in tracked order, from the bodies' world `poses`.
fn foot_centres<'a>(
    model: &'a RobotModel,
    poses: &'a [Isometry3<f64>],
) -> impl Iterator<Item = [f64; 3]> + 'a {
    model.tracked().iter().map(|t| {
        let pose = poses[t.link];
        let centre = t
            .shapes
            .first()
            .and_then(|&s| model.links()[t.link].collisions.get(s))
            .map_or(pose, |shape| pose * shape.origin);
        let p = centre.translation.vector;
        [p.x, p.y, p.z]
    })
}

/// How long the standing-height run holds the pose (s): HyQ settles within about 1 s.
pub const STANDING_SECONDS: f64 = 2.0;

/// The trunk height (m) after holding the standing pose for [`STANDING_SECONDS`] on backend `B`
/// under `config` (the default configuration with the side's overrides).
pub fn standing_height<B: Backend>(
    label: &str,
    model: Arc<RobotModel>,
    mut config: EnvConfig,
) -> Result<f64, CompareError> {
    let steps = (STANDING_SECONDS / config.env_dt()).round() as u64;
    config.task.max_time_steps = steps;
    let mut env = build_env::<B>(label, model.clone(), config)?;
    let script = crate::Scenario::Stand.actions(&model, env.config(), 0, steps)?;
    let traj = run_script(label, &mut env, 0, None, &script)?;
    Ok(traj.positions.last().map_or(f64::NAN, |p| p[2]))
}

/// The state one backend reached one physics sub-step after a shared state.
#[derive(Clone, Debug)]
pub struct OneStepResult {
    /// The reference run's sample index the shared state came from.
    pub step: u64,
    /// The state after the sub-step.
    pub after: RobotState,
    /// Whether any tracked body touched the ground during the sub-step.
    pub in_contact: bool,
}

/// Puts `env`'s backend into each shared state, applies the torques the shared actuator gives
/// for that state and the targets that followed it in the reference run, advances one physics
/// sub-step, and reads the state. The torques are computed once from the shared state, so both
/// backends receive the same numbers.
pub fn one_step<B: Backend>(
    label: &str,
    env: &mut Env<B>,
    shared: &[(u64, &RobotState, &[f64])],
) -> Result<Vec<OneStepResult>, CompareError> {
    let actuator = env.actuator().clone();
    let n = actuator.num_joints();
    let backend = env.backend_mut();
    let mut tau = vec![0.0; n];
    let mut contacts = vec![false; backend.model().tracked().len()];
    let mut out = Vec::with_capacity(shared.len());
    for (step, state, targets) in shared {
        let fail = |message: String| CompareError::OneStep {
            backend: label.to_owned(),
            step: *step,
            message,
        };
        actuator
            .torques(targets, &state.q, &state.qd, &mut tau)
            .map_err(|e| fail(e.to_string()))?;
        backend.set_state(state).map_err(|e| fail(e.to_string()))?;
        backend
            .set_joint_torques(&tau)
            .map_err(|e| fail(e.to_string()))?;
        backend.step().map_err(|e| fail(e.to_string()))?;
        backend.contacts(&mut contacts);
        out.push(OneStepResult {
            step: *step,
            after: backend.state(),
            in_contact: contacts.iter().any(|c| *c),
        });
    }
    Ok(out)
}
