//! One env step of the spec, composed: spec §4 eq. (1), §5 and §6.
//!
//! r_total = (r_b + r_n + r_e + r_reach) · m_yaw · m_pitch · m_height
//!           − reach_bounds_penalty · [§6.2] − fall_penalty · [§6.3]
//!
//! with r_b = k_base (D^{t−1} − D^t), r_n = k_norm (D^{t−1} − D^t) / K,
//! r_e = R_e(D_n^t) − R_e(D_n^{t−1}), r_reach = bonus · [§6.1], m = 1 within the angle limit
//! else max(0, cos angle), m_height = 1 unless the opt-in §5.2 penalty is set, and the four
//! termination conditions of §6 checked independently.
//!
//! [`EpisodeRules`] is built once per episode from the configuration, the initial position C^0
//! and the goal G; it validates all three (K = ‖G − C^0‖ must be usable when r_n or r_e is on).
//! [`EpisodeRules::evaluate_step`] then turns a [`StepSnapshot`] into a [`StepOutcome`] carrying
//! every term separately. It is pure and allocates nothing.

use crate::attitude::{RollPitchYaw, roll_pitch_yaw};
use crate::config::{ConfigError, TaskConfig};
use crate::distance::{MIN_START_GOAL_DISTANCE, StartGoalDistance, distance_to_goal};
use crate::penalty::{
    fixed_penalty, height::height_multiplier, orientation::orientation_multiplier,
};
use crate::reward::{
    base::base_reward, exponential::exponential_reward, normalised::normalised_reward,
    reach::reach_reward,
};
use crate::termination::joint_limit::{
    JointCountMismatch, JointLimitHit, JointRange, first_joint_at_limit,
};
use crate::termination::{Terminations, reach::goal_reached, timeout::timed_out};
use crate::terms::{REWARD_TERMS, RewardTerm, TermKind, terms_of};
use nalgebra::{Point3, UnitQuaternion};
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// The rules of one episode: a validated configuration, the initial position C^0 and the goal G.
///
/// Built by [`EpisodeRules::new`], which rejects an invalid configuration and a goal too close to
/// the start for the rewards that divide by K. Immutable afterwards.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct EpisodeRules {
    config: TaskConfig,
    initial: Point3<f64>,
    goal: Point3<f64>,
    start_goal_distance: Option<StartGoalDistance>,
    /// (k_norm, K) when r_n is on: holding K with the scale makes "r_n on without K"
    /// unrepresentable.
    normalised: Option<(f64, StartGoalDistance)>,
    /// (k_exp, K) when r_e is on.
    exponential: Option<(f64, StartGoalDistance)>,
    yaw_limit_rad: f64,
    pitch_limit_rad: f64,
}

/// Why an episode's rules could not be built.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum EpisodeError {
    /// The configuration has an invalid value.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// The goal or the initial position has a NaN or infinite coordinate.
    #[error("{what} ({x}, {y}, {z}) is not finite")]
    NonFinitePosition {
        /// `"goal"` or `"initial position"`.
        what: &'static str,
        /// x, m.
        x: f64,
        /// y, m.
        y: f64,
        /// z, m.
        z: f64,
    },
    /// K = ‖G − C^0‖ is below [`MIN_START_GOAL_DISTANCE`] while r_n or r_e, which divide by it,
    /// is on.
    #[error(
        "goal ({}, {}, {}) is {distance} m from the initial position ({}, {}, {}): \
         norm_rew_scaling and exp_rew_scaling divide by this distance K, which must be at least \
         {MIN_START_GOAL_DISTANCE} m (move the goal, or set both to \"off\")",
        goal[0], goal[1], goal[2], initial[0], initial[1], initial[2]
    )]
    GoalAtStart {
        /// G, m.
        goal: [f64; 3],
        /// C^0, m.
        initial: [f64; 3],
        /// K, m.
        distance: f64,
    },
}

/// What the rules need to know about one env step: the small typed snapshot the environment
/// passes after stepping the physics.
#[derive(Clone, Copy, Debug)]
pub struct StepSnapshot<'a> {
    /// t, env steps taken since reset, counting this one (1 after the first step).
    pub step: u64,
    /// C^{t−1}, the trunk centre before the step (world, m); C^0 on the first step.
    pub previous_position: Point3<f64>,
    /// C^t, the trunk centre after the step (world, m).
    pub position: Point3<f64>,
    /// The trunk's orientation after the step (world).
    pub orientation: UnitQuaternion<f64>,
    /// θ^i after the step, rad, in the robot description's joint order.
    pub joint_angles: &'a [f64],
    /// [θ_min^i, θ_max^i], paired with `joint_angles` by index
    /// ([`crate::RobotDescription::joint_ranges`]).
    pub joint_ranges: &'a [JointRange],
    /// Whether the trunk touched the ground in any physics sub-step of this step (§6.3).
    pub trunk_contact: bool,
}

/// A snapshot the rules cannot evaluate.
#[derive(Clone, Copy, Debug, PartialEq, Error)]
pub enum StepError {
    /// `step` is 0: t counts the steps taken, so it is at least 1 when a step is evaluated.
    #[error("step t = 0: a step is evaluated after it is taken, so t >= 1")]
    StepZero,
    /// Joint angles and ranges of different lengths.
    #[error(transparent)]
    JointCount(#[from] JointCountMismatch),
    /// A NaN or infinite input (the physics diverged, or the environment passed a bad value).
    #[error("{what} is not finite ({value})")]
    NonFinite {
        /// `"previous_position"`, `"position"`, `"orientation"` or `"joint angle"`.
        what: &'static str,
        /// For a joint angle, the joint's index; else 0.
        index: usize,
        /// The first non-finite value found.
        value: f64,
    },
}

/// Every term of one step's reward, kept apart (keys as in the spec: r_b, r_n, r_e, r_reach,
/// m_yaw, m_pitch, m_height, joint_penalty, fall_penalty, total).
///
/// Each field but `total` is a row of [`crate::terms::REWARD_TERMS`], which says how it enters
/// the reward; `total` is [`RewardBreakdown::compose`] of the other fields, to the bit.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
pub struct RewardBreakdown {
    /// Base reward r_b (§4.1), 0 when `base_rew_scaling` is unset.
    pub r_b: f64,
    /// Normalised reward r_n (§4.2), 0 when `norm_rew_scaling` is unset.
    pub r_n: f64,
    /// Exponential reward r_e (§4.3), 0 when `exp_rew_scaling` is unset.
    pub r_e: f64,
    /// Reach bonus r_reach (§4.4), 0 unless the goal was reached on this step.
    pub r_reach: f64,
    /// Yaw multiplier m_yaw in [0, 1] (§5.1.1).
    pub m_yaw: f64,
    /// Pitch multiplier m_pitch in [0, 1] (§5.1.2).
    pub m_pitch: f64,
    /// Height multiplier m_height in [0, 1] (§5.2, opt-in; 1 when off).
    pub m_height: f64,
    /// The joint-limit penalty subtracted (§5.3): `reach_bounds_penalty` on a §6.2 step, else 0.
    pub joint_penalty: f64,
    /// The fall penalty subtracted (§5.4): `fall_penalty` on a §6.3 step, else 0.
    pub fall_penalty: f64,
    /// The step's reward: [`RewardBreakdown::compose`] of the terms above.
    pub total: f64,
}

impl RewardBreakdown {
    /// (r_b + r_n + r_e + r_reach) · m_yaw · m_pitch · m_height − joint_penalty − fall_penalty:
    /// the rewards summed, then multiplied by each multiplier, then each penalty subtracted,
    /// left to right in the order of [`crate::terms::REWARD_TERMS`] (so eq. (1)'s sum is
    /// [`crate::reward::reward_before_penalties`] to the bit).
    pub fn compose(&self) -> f64 {
        let mut rewards = terms_of(TermKind::Reward).map(|t| (t.get)(self));
        let sum = match rewards.next() {
            // Starting from the first term, not from 0.0, keeps a sum of −0.0 terms −0.0.
            Some(first) => rewards.fold(first, |sum, r| sum + r),
            None => 0.0,
        };
        let scaled = terms_of(TermKind::Multiplier).fold(sum, |r, t| r * (t.get)(self));
        terms_of(TermKind::Penalty).fold(scaled, |r, t| r - (t.get)(self))
    }

    /// Every term with its value, in the order of [`crate::terms::REWARD_TERMS`].
    pub fn terms(&self) -> impl Iterator<Item = (&'static RewardTerm, f64)> + '_ {
        REWARD_TERMS.iter().map(move |t| (t, (t.get)(self)))
    }
}

/// Everything the rules say about one env step.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct StepOutcome {
    /// The reward and each of its terms.
    pub reward: RewardBreakdown,
    /// D^t = ‖G − C^t‖, m.
    pub distance: f64,
    /// D_n^t = D^t / K, or `None` when K is too small to divide by (allowed only while r_n and
    /// r_e are off).
    pub normalised_distance: Option<f64>,
    /// The trunk's roll, pitch and yaw (rad) the multipliers used.
    pub attitude: RollPitchYaw,
    /// Every termination condition that holds.
    pub terminations: Terminations,
    /// The first joint at a limit, when §6.2 holds.
    pub joint_at_limit: Option<JointLimitHit>,
}

impl StepOutcome {
    /// Gymnasium's `terminated`: reached, joint limit or fell.
    pub fn terminated(&self) -> bool {
        self.terminations.terminated()
    }

    /// Gymnasium's `truncated`: timeout and not terminated.
    pub fn truncated(&self) -> bool {
        self.terminations.truncated()
    }
}

/// The index and value of the first NaN or infinite number in `values`.
fn first_non_finite<'a>(values: impl IntoIterator<Item = &'a f64>) -> Option<(usize, f64)> {
    values
        .into_iter()
        .copied()
        .enumerate()
        .find(|(_, v)| !v.is_finite())
}

impl EpisodeRules {
    /// The rules for an episode starting at `initial` (C^0) with goal `goal` (G).
    ///
    /// Validates `config` ([`TaskConfig::validate`]), that both positions are finite, and, when
    /// r_n or r_e is on, that K = ‖G − C^0‖ ≥ [`MIN_START_GOAL_DISTANCE`] (else
    /// [`EpisodeError::GoalAtStart`], which names the goal).
    pub fn new(
        config: &TaskConfig,
        initial: Point3<f64>,
        goal: Point3<f64>,
    ) -> Result<Self, EpisodeError> {
        config.validate()?;
        for (what, p) in [("initial position", &initial), ("goal", &goal)] {
            if first_non_finite(p.iter()).is_some() {
                return Err(EpisodeError::NonFinitePosition {
                    what,
                    x: p.x,
                    y: p.y,
                    z: p.z,
                });
            }
        }
        let start_goal_distance = StartGoalDistance::new(&initial, &goal);
        let with_k =
            |scale: Option<f64>| -> Result<Option<(f64, StartGoalDistance)>, EpisodeError> {
                match (scale, start_goal_distance) {
                    (None, _) => Ok(None),
                    (Some(s), Some(k)) => Ok(Some((s, k))),
                    (Some(_), None) => Err(EpisodeError::GoalAtStart {
                        goal: goal.coords.into(),
                        initial: initial.coords.into(),
                        distance: distance_to_goal(&initial, &goal),
                    }),
                }
            };
        Ok(EpisodeRules {
            config: *config,
            initial,
            goal,
            start_goal_distance,
            normalised: with_k(config.norm_rew_scaling)?,
            exponential: with_k(config.exp_rew_scaling)?,
            yaw_limit_rad: config.yaw_limit_deg.to_radians(),
            pitch_limit_rad: config.pitch_limit_deg.to_radians(),
        })
    }

    /// The validated configuration.
    pub fn config(&self) -> &TaskConfig {
        &self.config
    }

    /// C^0, the initial position.
    pub fn initial(&self) -> Point3<f64> {
        self.initial
    }

    /// G, the goal.
    pub fn goal(&self) -> Point3<f64> {
        self.goal
    }

    /// K = ‖G − C^0‖ when it is usable as a divisor.
    pub fn start_goal_distance(&self) -> Option<StartGoalDistance> {
        self.start_goal_distance
    }

    /// Evaluates one env step: every reward term, multiplier and penalty, D^t, D_n^t, the
    /// attitude and every termination condition that holds. Pure; allocates nothing.
    ///
    /// Errors: t = 0, joint angles and ranges of different lengths, or a non-finite position,
    /// orientation or joint angle.
    pub fn evaluate_step(&self, s: &StepSnapshot<'_>) -> Result<StepOutcome, StepError> {
        if s.step == 0 {
            return Err(StepError::StepZero);
        }
        for (what, values) in [
            ("previous_position", s.previous_position.coords.as_slice()),
            ("position", s.position.coords.as_slice()),
            ("orientation", s.orientation.coords.as_slice()),
        ] {
            if let Some((_, value)) = first_non_finite(values) {
                return Err(StepError::NonFinite {
                    what,
                    index: 0,
                    value,
                });
            }
        }
        if let Some((index, value)) = first_non_finite(s.joint_angles) {
            return Err(StepError::NonFinite {
                what: "joint angle",
                index,
                value,
            });
        }
        let c = &self.config;

        let d_prev = distance_to_goal(&s.previous_position, &self.goal);
        let d = distance_to_goal(&s.position, &self.goal);
        let r_b = c
            .base_rew_scaling
            .map_or(0.0, |k_base| base_reward(d_prev, d, k_base));
        let r_n = self
            .normalised
            .map_or(0.0, |(k_norm, k)| normalised_reward(d_prev, d, k, k_norm));
        let r_e = self.exponential.map_or(0.0, |(k_exp, k)| {
            exponential_reward(k.normalise(d_prev), k.normalise(d), k_exp)
        });

        let reached = goal_reached(&s.position, &self.goal, c.accepted_error);
        let r_reach = reach_reward(reached, c.reach_target_bonus_reward);

        let attitude = roll_pitch_yaw(&s.orientation);
        let m_yaw = orientation_multiplier(attitude.yaw, self.yaw_limit_rad);
        let m_pitch = orientation_multiplier(attitude.pitch, self.pitch_limit_rad);
        let m_height = height_multiplier(s.position.z, c.height_penalty.as_ref());

        let joint_at_limit =
            first_joint_at_limit(s.joint_angles, s.joint_ranges, c.accepted_dist_to_bounds)?;
        let fell = s.trunk_contact;
        let timeout = timed_out(s.step, c.max_time_steps);
        let terminations =
            Terminations::from_flags(reached, joint_at_limit.is_some(), fell, timeout);

        let mut reward = RewardBreakdown {
            r_b,
            r_n,
            r_e,
            r_reach,
            m_yaw,
            m_pitch,
            m_height,
            joint_penalty: fixed_penalty(joint_at_limit.is_some(), c.reach_bounds_penalty),
            fall_penalty: fixed_penalty(fell, c.fall_penalty),
            total: 0.0,
        };
        reward.total = reward.compose();

        Ok(StepOutcome {
            reward,
            distance: d,
            normalised_distance: self.start_goal_distance.map(|k| k.normalise(d)),
            attitude,
            terminations,
            joint_at_limit,
        })
    }
}
