//! The gait regularisers in the environment (`[regularizers]`, docs/regularizers.md): the state
//! hyq-tasks' terms need between steps (the previous action and joint speeds, the feet's air
//! times and positions), and what a step reports ([`RegularizerInfo`], the info's
//! `regularizers.<term>` keys: [`REGULARIZER_INFO_KEYS`]).
//!
//! The spec's rules run unchanged; the step's reward is the spec's plus the regularisers'
//! `Σ s·r·Δt_env` (docs/spec.md §7.12). Off (every scale 0), the environment holds none of
//! this state and reports nothing of it.

use hyq_physics::na::Isometry3;
use hyq_physics::{RobotModel, TrunkState};
use hyq_tasks::regularizers::{RegularizerSnapshot, reward, values};
use hyq_tasks::step::{AirTime, FootVelocity};
use hyq_tasks::{REGULARIZER_NAMES, RegularizerScales, ReportedRegularizers};
use serde::Serialize;

use crate::config::{EnvConfig, TaskKind};
use crate::divergence::Divergence;
use crate::velocity::body_xy;

/// What the regularisers report on a step (the info's `regularizers`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct RegularizerInfo {
    /// The terms that are on, unscaled (0 after reset and on a diverged step).
    pub terms: ReportedRegularizers,
    /// Σ s·r·Δt_env over them: what the step's reward adds to the spec's (0 after reset and
    /// on a diverged step).
    pub reward: f64,
}

mod keys;
pub use keys::{REGULARIZER_INFO_KEYS, REGULARIZER_PREFIX, regularizer_info_keys};

/// The regularisers' state in an environment.
#[derive(Clone, Debug)]
pub(crate) struct Regularizers {
    scales: RegularizerScales,
    on: [bool; REGULARIZER_NAMES.len()],
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
    /// What the last reset or step reported.
    pub(crate) info: RegularizerInfo,
}

impl Regularizers {
    /// The regularisers for `model` under `config` (validated), or `None` when every scale is
    /// 0 or the task is not the spec's.
    pub(crate) fn new(model: &RobotModel, config: &EnvConfig) -> Option<Box<Self>> {
        let table = &config.regularizers;
        if table.is_off() || config.task.kind != TaskKind::Goal {
            return None;
        }
        let scales = table.resolve(model.standing_height());
        let n = model.num_joints();
        let feet: Vec<usize> = model.tracked()[..model.num_feet()]
            .iter()
            .map(|t| t.link)
            .collect();
        Some(Box::new(Self {
            on: scales.on(),
            scales,
            air: AirTime::new(feet.len()),
            action: vec![0.0; n],
            previous_action: vec![0.0; n],
            previous_qd: vec![0.0; n],
            poses: vec![Isometry3::identity(); model.links().len()],
            foot_velocity: FootVelocity::new(feet.len()),
            feet,
            env_dt: config.env_dt(),
            info: RegularizerInfo::default(),
        }))
    }

    /// The report of a reset or a diverged step: the terms that are on, all 0.
    fn neutral(&self) -> RegularizerInfo {
        RegularizerInfo {
            terms: ReportedRegularizers {
                on: self.on,
                ..ReportedRegularizers::default()
            },
            reward: 0.0,
        }
    }

    /// Starts an episode from the robot at rest (the body poses after reset were just read into
    /// [`Regularizers::poses_mut`]): no previous action, joint speeds 0, every foot standing.
    pub(crate) fn reset(&mut self) {
        self.air.reset();
        self.action.fill(0.0);
        self.previous_action.fill(0.0);
        self.previous_qd.fill(0.0);
        let poses = &self.poses;
        self.foot_velocity
            .reset(self.feet.iter().map(|&link| body_xy(&poses[link])));
        self.info = self.neutral();
    }

    /// Records the step's action, as given, before its sub-steps run.
    pub(crate) fn begin_step(&mut self, action: impl Iterator<Item = f64>) {
        std::mem::swap(&mut self.action, &mut self.previous_action);
        for (a, v) in self.action.iter_mut().zip(action) {
            *a = v;
        }
    }

    /// The body poses buffer, for the backend to fill after the step.
    pub(crate) fn poses_mut(&mut self) -> &mut [Isometry3<f64>] {
        &mut self.poses
    }

    /// Judges the step that ended in `trunk` (its height above the ground `base_height`) and
    /// `qd`, with the last sub-step's `torques`, the latched `feet` flags and the `penalised`
    /// bodies' latched flags (the body poses were just read into [`Regularizers::poses_mut`]).
    /// A term that is on and not finite (a joint speed's change over a Δt_env of 10⁻²⁰⁰ s, say)
    /// is the step's divergence: nothing non-finite is reported.
    pub(crate) fn evaluate_step(
        &mut self,
        base_height: f64,
        qd: &[f64],
        torques: &[f64],
        feet: &[bool],
        penalised: &[bool],
    ) -> Result<(), Divergence> {
        let poses = &self.poses;
        let positions = self.feet.iter().map(|&link| body_xy(&poses[link]));
        self.foot_velocity.update(positions, self.env_dt);
        let air = self.air.update(feet, self.env_dt);
        let v = values(
            &self.scales,
            &RegularizerSnapshot {
                action: &self.action,
                previous_action: &self.previous_action,
                torques,
                joint_speeds: qd,
                previous_joint_speeds: &self.previous_qd,
                air_at_touchdown: air,
                foot_velocity_xy: self.foot_velocity.velocity(),
                foot_contacts: feet,
                base_height,
                penalised_contacts: penalised,
                env_dt: self.env_dt,
            },
        );
        self.previous_qd.copy_from_slice(qd);
        let mut masked = v.to_array();
        for (x, on) in masked.iter_mut().zip(self.on) {
            if !on {
                *x = 0.0;
            }
        }
        let total = reward(&self.scales.terms, &v, self.env_dt);
        let bad = REGULARIZER_NAMES
            .iter()
            .zip(masked)
            .map(|(name, x)| (*name, x))
            .chain([("reward", total)])
            .find(|(_, x)| !x.is_finite());
        if let Some((name, value)) = bad {
            return Err(Divergence::NonFiniteReading {
                what: format!("regularizers.{name}"),
                value,
            });
        }
        self.info = RegularizerInfo {
            terms: ReportedRegularizers {
                values: hyq_tasks::RegularizerTerms::from_array(masked),
                on: self.on,
            },
            reward: total,
        };
        Ok(())
    }

    /// Reports a diverged step: reward and terms 0.
    pub(crate) fn diverged(&mut self) {
        self.info = self.neutral();
    }
}

/// The trunk's height above the ground under its frame origin (m).
pub(crate) fn base_height(trunk: &TrunkState, terrain: &hyq_physics::Terrain) -> f64 {
    let p = trunk.pose.translation.vector;
    p.z - terrain.height_at(p.x, p.y)
}
