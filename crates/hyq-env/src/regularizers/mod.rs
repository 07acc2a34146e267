//! The gait regularisers in the environment (`[regularizers]`, docs/regularizers.md): the state
//! hyq-tasks' terms need between steps (the previous action and joint speeds, the feet's air
//! times and positions), and what a step reports ([`RegularizerInfo`], the info's
//! `regularizers.<term>` keys: [`REGULARIZER_INFO_KEYS`]).
//!
//! The spec's rules run unchanged; the step's reward is the spec's plus the regularisers'
//! `Σ s·r·Δt_env` (docs/spec.md §7.12). Off (every scale 0), the environment holds none of
//! this state and reports nothing of it.

use hyq_physics::na::{Point3, Vector3};
use hyq_physics::{RobotModel, TrunkState};
use hyq_tasks::observation::projected_gravity;
use hyq_tasks::regularizers::{RegularizerSnapshot, reward, values};
use hyq_tasks::{GoalGeometry, REGULARIZER_NAMES, RegularizerScales, ReportedRegularizers};
use serde::Serialize;

use crate::config::{EnvConfig, TaskKind};
use crate::divergence::Divergence;
use crate::gait::GaitHistory;

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
    /// The previous action and joint speeds, the feet's air times and velocities.
    pub(crate) gait: GaitHistory,
    env_dt: f64,
    /// The trunk's distance off the start–goal line after the last reset or step (m).
    goal_line: f64,
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
        Some(Box::new(Self {
            on: scales.on(),
            scales,
            gait: GaitHistory::new(model, config.env_dt()),
            env_dt: config.env_dt(),
            goal_line: 0.0,
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
    /// the gait history).
    pub(crate) fn reset(&mut self) {
        self.gait.reset();
        // The trunk starts at C^0, on the line.
        self.goal_line = 0.0;
        self.info = self.neutral();
    }

    /// Judges the step that ended in the `trunk` reading and `qd`, with the last sub-step's
    /// `torques`, the latched `feet` flags and the `penalised` bodies' latched flags, and the goal
    /// task's `goal` geometry (the body poses were just read into the gait history).
    /// A term that is on and not finite (a joint speed's change over a Δt_env of 10⁻²⁰⁰ s, say)
    /// is the step's divergence: nothing non-finite is reported.
    pub(crate) fn evaluate_step(
        &mut self,
        trunk: TrunkReading,
        qd: &[f64],
        torques: &[f64],
        feet: &[bool],
        penalised: &[bool],
        goal: GoalGeometry,
    ) -> Result<(), Divergence> {
        let g = self.gait.advance(feet);
        let v = values(
            &self.scales,
            &RegularizerSnapshot {
                action: g.action,
                previous_action: g.previous_action,
                torques,
                joint_speeds: qd,
                previous_joint_speeds: g.previous_joint_speeds,
                air_at_touchdown: g.air_at_touchdown,
                foot_velocity_xy: g.foot_velocity_xy,
                foot_contacts: feet,
                base_height: trunk.base_height,
                projected_gravity: trunk.projected_gravity,
                penalised_contacts: penalised,
                goal,
                previous_goal_line: self.goal_line,
                env_dt: g.env_dt,
            },
        );
        self.gait.end_step(qd);
        self.goal_line = v.goal_line;
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

/// The goal terms' geometry: the `trunk`'s position and heading, the episode's `start` and
/// `goal` (world x and y).
pub(crate) fn goal_geometry(
    trunk: &TrunkState,
    start: [f64; 3],
    goal: &Point3<f64>,
) -> GoalGeometry {
    let p = trunk.pose.translation.vector;
    let heading = trunk.pose.rotation * Vector3::x();
    GoalGeometry {
        trunk: [p.x, p.y],
        heading: [heading.x, heading.y],
        start: [start[0], start[1]],
        goal: [goal.x, goal.y],
    }
}

/// What the trunk terms read of the trunk at the end of a step.
#[derive(Clone, Copy, Debug)]
pub(crate) struct TrunkReading {
    /// The trunk's height above the ground under its frame origin (m).
    pub(crate) base_height: f64,
    /// Gravity's direction in the trunk's frame.
    pub(crate) projected_gravity: [f64; 3],
}

impl TrunkReading {
    /// The reading of `trunk` over `terrain`.
    pub(crate) fn new(trunk: &TrunkState, terrain: &hyq_physics::Terrain) -> Self {
        let p = trunk.pose.translation.vector;
        Self {
            base_height: p.z - terrain.height_at(p.x, p.y),
            projected_gravity: projected_gravity(&trunk.pose.rotation),
        }
    }
}
