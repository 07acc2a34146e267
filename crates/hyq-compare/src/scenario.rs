//! The comparison scenarios: what the robot is asked to do, with which configuration, and the
//! open-loop action script both backends receive.
//!
//! Every scenario's actions depend only on time (and the seed), never on the simulated state, so
//! the script is computed once, before either backend runs, and both receive the identical
//! sequence of actions bit for bit. That rules out the `delta` action mode (its targets depend on
//! the current joint angles): a configuration in that mode is refused.
//!
//! | scenario | configuration | actions | default length | expected end |
//! |---|---|---|---|---|
//! | `stand` | default | hold the standing pose ([`Stand`]) | 5 s | timeout |
//! | `fall` | default; starts pushed: trunk rolling at 6 rad/s and moving sideways at 1.5 m/s | standing targets | 3 s | `fell` |
//! | `limit` | default | standing, except the limit joint driven to its upper limit (normalized action +1) | 3 s | `joint_limit` |
//! | `trot` | default (goal 5 m ahead) | the scripted open-loop [`Trot`], the profile's `[gait]` | 10 s | timeout |
//! | `random` | default | uniform random actions ([`RandomPolicy`] seeded with the seed) | 5 s | usually `joint_limit` |
//! | `reach` | goal fixed 1 m ahead, [`REACH_LATERAL_M`] to the side, at the robot's standing height; `accepted_error = 0.3` m, `reach_target_bonus_reward = 10` | the trot | 10 s | `reached` |
//!
//! Robot facts come from the model's profile, never from this crate: the limit joint is the
//! hip joint of the first leg of the profile's `[gait]` table (HyQ's and ANYmal C's `lf_hfe`),
//! the trot is the profile's, and the reach goal's height is the profile's
//! `[spawn] standing_height` (HyQ 0.5895 m, ANYmal C 0.5341 m). A robot without a `[gait]`
//! table can run `stand`, `fall` and `random`; `limit`, `trot` and `reach` say what is missing.
//!
//! `reach`: the spec's default reach cube (1 mm side, §6.1) is never hit by an open-loop gait
//! whose trunk bobs and drifts by centimetres, so the scenario places the goal near the trot's
//! path (1 m ahead, 0.1 m to the right) and widens the cube to 0.3 m (a user variable, spec
//! §2). Where the trunk crosses x = 1 m, seed 0: HyQ's trot has drifted 0.20–0.22 m to the
//! right on rapier, DART and MuJoCo, so it enters the cube on all three; ANYmal C's 0.04–0.05 m
//! to the right on rapier and MuJoCo but 0.20 m to the left on DART, which then misses the cube
//! and runs to the time limit (a divergence the comparison reports).

use std::fmt;
use std::str::FromStr;
use std::sync::Arc;

use hyq_env::{
    ActionMode, ActionSpace, EnvConfig, GoalMode, Policy, PolicyInput, RandomPolicy, Stand, Trot,
};
use hyq_physics::na::Vector3;
use hyq_physics::{RobotModel, RobotState};
use serde::Serialize;

use crate::error::CompareError;

/// The normalized action of the limit joint ([`Scenario::limit_joint`]) in the `limit`
/// scenario: +1 is its upper limit.
pub const LIMIT_ACTION: f64 = 1.0;

/// The trunk's angular velocity at the start of `fall` (rad/s, world): a sideways shove.
pub const FALL_PUSH_ANGVEL: [f64; 3] = [6.0, 0.0, 0.0];
/// The trunk's linear velocity at the start of `fall` (m/s, world).
pub const FALL_PUSH_LINVEL: [f64; 3] = [0.0, -1.5, 0.0];

/// How far ahead (+x) the goal of the `reach` scenario lies (m).
pub const REACH_AHEAD_M: f64 = 1.0;
/// The goal's sideways offset in the `reach` scenario (m, world y): to the right, where the
/// bundled robots' trots drift.
pub const REACH_LATERAL_M: f64 = -0.1;
/// The reach cube's side in the `reach` scenario (m; the spec's `accepted_error`).
pub const REACH_ACCEPTED_ERROR_M: f64 = 0.3;
/// The reach bonus in the `reach` scenario, so that r_reach shows in the reward sums.
pub const REACH_BONUS: f64 = 10.0;

/// The longest run `--seconds` may ask for (s): keeps a typo from filling memory.
pub const MAX_SECONDS: f64 = 600.0;

/// A comparison scenario (see the module docs for each).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Scenario {
    /// Hold the standing pose.
    Stand,
    /// A pushed robot tipping over onto its side.
    Fall,
    /// One joint driven to its limit.
    Limit,
    /// The scripted trot along +x.
    Trot,
    /// Uniform random actions.
    Random,
    /// The trot to a goal it reaches.
    Reach,
}

impl Scenario {
    /// Every scenario, in the order of the docs.
    pub const ALL: [Scenario; 6] = [
        Scenario::Stand,
        Scenario::Fall,
        Scenario::Limit,
        Scenario::Trot,
        Scenario::Random,
        Scenario::Reach,
    ];

    /// Every scenario's name, in [`Scenario::ALL`]'s order.
    pub const NAMES: [&'static str; 6] = ["stand", "fall", "limit", "trot", "random", "reach"];

    /// The scenario's name (`"stand"`, …).
    pub const fn name(self) -> &'static str {
        Self::NAMES[self as usize]
    }

    /// One sentence saying what the scenario does with `model` (its limit joint, its reach
    /// goal).
    pub fn description(self, model: &RobotModel) -> String {
        match self {
            Scenario::Stand => "hold the standing pose (default configuration)".to_owned(),
            Scenario::Fall => "a pushed robot: it starts in the standing pose with the trunk \
                 rolling at 6 rad/s about +x and moving at 1.5 m/s towards −y, holds the \
                 standing targets, and tips over onto its side"
                .to_owned(),
            Scenario::Limit => {
                let joint = self
                    .limit_joint(model)
                    .map_or("the limit joint", |j| model.joints()[j].name.as_str());
                format!(
                    "stand, with {joint} driven to its upper limit (normalized action +1) until \
                     the spec's joint-limit rule (§6.2) ends the episode"
                )
            }
            Scenario::Trot => {
                "the scripted open-loop trot along +x (hyq-env's Trot, the profile's [gait])"
                    .to_owned()
            }
            Scenario::Random => "uniform random normalized actions, redrawn every env step".into(),
            Scenario::Reach => {
                let g = reach_goal(model);
                format!(
                    "the trot towards a goal near its path, at ({}, {}, {}) m (z: the robot's \
                     standing height), with a 0.3 m reach cube (accepted_error) and a reach \
                     bonus of 10",
                    g[0], g[1], g[2]
                )
            }
        }
    }

    /// The joint the `limit` scenario drives to its upper limit: the hip joint of the first
    /// leg of `model`'s `[gait]` table.
    pub fn limit_joint(self, model: &RobotModel) -> Result<usize, CompareError> {
        model
            .gait()
            .and_then(|g| g.legs.first())
            .map(|leg| leg.hip)
            .ok_or_else(|| CompareError::Scenario {
                scenario: self.name(),
                reason: format!(
                    "the robot profile of {} has no [gait] table, whose first leg's hip joint \
                     this scenario drives",
                    model.name()
                ),
            })
    }

    /// The scenario's default length (s of simulated time).
    pub const fn default_seconds(self) -> f64 {
        match self {
            Scenario::Stand | Scenario::Random => 5.0,
            Scenario::Fall | Scenario::Limit => 3.0,
            Scenario::Trot | Scenario::Reach => 10.0,
        }
    }

    /// The scenario's configuration for `model`, `seconds` long: the defaults, the scenario's
    /// changes, and `max_time_steps` = ⌈seconds / Δt_env⌉. Validated.
    pub fn config(self, model: &RobotModel, seconds: f64) -> Result<EnvConfig, CompareError> {
        check_seconds(seconds)?;
        let mut config = EnvConfig::default();
        match self {
            Scenario::Stand | Scenario::Limit | Scenario::Trot | Scenario::Random => {}
            Scenario::Fall => {}
            Scenario::Reach => {
                config.goal.mode = GoalMode::Fixed;
                config.goal.position = Some(reach_goal(model));
                config.task.accepted_error = REACH_ACCEPTED_ERROR_M;
                config.task.reach_target_bonus_reward = REACH_BONUS;
            }
        }
        config.task.max_time_steps = steps_for(seconds, config.env_dt());
        config.validate()?;
        Ok(config)
    }

    /// The state the scenario starts from instead of the standing spawn state, if any: `fall`
    /// starts from the model's spawn state (at the origin, whatever `[reset]` says) with the
    /// push [`FALL_PUSH_ANGVEL`], [`FALL_PUSH_LINVEL`] already given to the trunk.
    pub fn initial_state(self, model: &RobotModel) -> Option<RobotState> {
        match self {
            Scenario::Fall => {
                let mut state = model.spawn_state();
                state.trunk.angvel = Vector3::from(FALL_PUSH_ANGVEL);
                state.trunk.linvel = Vector3::from(FALL_PUSH_LINVEL);
                Some(state)
            }
            _ => None,
        }
    }

    /// The action script: `steps` actions of one value per joint, flattened (step-major), for
    /// `model` under `config`'s action space; `seed` seeds the random policy.
    ///
    /// Errors when the action mode is `delta` (its actions depend on the state, so both backends
    /// could not receive the same script) or the robot lacks a joint the scenario drives.
    pub fn actions(
        self,
        model: &Arc<RobotModel>,
        config: &EnvConfig,
        seed: u64,
        steps: u64,
    ) -> Result<Vec<f64>, CompareError> {
        if config.action.mode == ActionMode::Delta {
            return Err(CompareError::StateDependentActions {
                mode: "delta".into(),
            });
        }
        let space = ActionSpace::new(model, &config.action);
        let n = space.len();
        let mut policy: Box<dyn Policy> = match self {
            Scenario::Stand | Scenario::Fall | Scenario::Limit => Box::new(Stand),
            Scenario::Random => Box::new(RandomPolicy::new(seed)),
            Scenario::Trot | Scenario::Reach => Box::new(Trot::from_profile(model).map_err(
                |e| CompareError::Scenario {
                    scenario: self.name(),
                    reason: e.to_string(),
                },
            )?),
        };
        let limit_joint = match self {
            Scenario::Limit => Some(self.limit_joint(model)?),
            _ => None,
        };
        let standing = model.standing_pose();
        // The policies read neither the observation nor (outside `delta` mode) the joint
        // angles, so an empty observation and the standing pose stand in for the simulated state.
        let len = usize::try_from(steps).map_err(|_| CompareError::Seconds {
            value: steps as f64,
            reason: "too many steps for this machine",
        })?;
        let mut script = vec![0.0; len * n];
        for (t, action) in script.chunks_exact_mut(n).enumerate() {
            let input = PolicyInput {
                t: t as u64,
                env_dt: config.env_dt(),
                observation: &[],
                joint_angles: standing,
                standing,
                space: &space,
            };
            policy.act(&input, action);
            if let Some(j) = limit_joint {
                action[j] = LIMIT_ACTION;
            }
        }
        Ok(script)
    }
}

impl fmt::Display for Scenario {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Scenario {
    type Err = CompareError;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        Scenario::ALL
            .into_iter()
            .find(|sc| sc.name() == s)
            .ok_or_else(|| CompareError::UnknownScenario { name: s.to_owned() })
    }
}

/// The goal of the `reach` scenario for `model` (m, world): [`REACH_AHEAD_M`] ahead,
/// [`REACH_LATERAL_M`] to the side, at the robot's standing height.
pub fn reach_goal(model: &RobotModel) -> [f64; 3] {
    [REACH_AHEAD_M, REACH_LATERAL_M, model.standing_height()]
}

/// Checks a run length: finite, > 0 and at most [`MAX_SECONDS`].
pub fn check_seconds(seconds: f64) -> Result<(), CompareError> {
    if !seconds.is_finite() || seconds <= 0.0 {
        return Err(CompareError::Seconds {
            value: seconds,
            reason: "must be a finite number of seconds > 0",
        });
    }
    if seconds > MAX_SECONDS {
        return Err(CompareError::Seconds {
            value: seconds,
            reason: "must be at most 600 s",
        });
    }
    Ok(())
}

/// The env steps that cover `seconds`: ⌈seconds / env_dt⌉, at least 1. The small slack keeps
/// 5 s at 0.01 s per step at 500 steps despite binary rounding.
fn steps_for(seconds: f64, env_dt: f64) -> u64 {
    ((seconds / env_dt - 1e-9).ceil() as u64).max(1)
}
