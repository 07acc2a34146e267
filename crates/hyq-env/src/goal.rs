//! Goals and reset states (spec §7.5 and §7.6, beyond the original spec: the default goal is 5 m
//! straight ahead of the spawn point along +x at the robot's nominal standing trunk height).
//!
//! With S = (x_s, y_s) the spawn point and h the goal height (`goal.height_m`, else the robot
//! profile's `spawn.standing_height`, where the trunk frame settles standing: 0.5895 m for HyQ):
//!
//! - `ahead`:  G = (x_s + d, y_s, h), d = `distance_m`;
//! - `fixed`:  G = `position`;
//! - `random`: G = (x_s + d cos ψ, y_s + d sin ψ, h), d ~ U(`distance_range_m`),
//!   ψ ~ U(`heading_range_deg`), both from the reset seed's goal stream.
//!
//! The reset state: trunk frame at (x_s, y_s, spawn height), level, yaw = `yaw_deg` + U(±
//! `yaw_noise_deg`), joints at the standing pose + U(± `joint_noise_rad`) each, clipped to the
//! joint limits, everything at rest; noise comes from the reset seed's noise stream and is drawn
//! only when switched on.

use hyq_physics::na::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use hyq_physics::{RobotModel, RobotState, TrunkState};
use hyq_spec::distance::{MIN_START_GOAL_DISTANCE, StartGoalDistance};
use hyq_spec::{EpisodeRules, TaskConfig};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use hyq_physics::bounds::short;

use crate::config::{ConfigError, EnvConfig, GoalMode, ResetConfig, WORLD_HALF_EXTENT_M};
use crate::error::EnvError;

/// Draws (or computes) each episode's goal from the configuration.
#[derive(Clone, Debug, PartialEq)]
pub struct GoalSampler {
    mode: GoalMode,
    spawn: Point3<f64>,
    height: f64,
    distance: f64,
    position: Option<[f64; 3]>,
    distance_range: [f64; 2],
    heading_range_rad: [f64; 2],
}

impl GoalSampler {
    /// The goals of `config` for `model` (spawn point from `[reset]`, heights from the profile).
    pub fn new(config: &EnvConfig, model: &RobotModel) -> Self {
        let g = &config.goal;
        let [x, y] = config.reset.spawn_xy_m;
        Self {
            mode: g.mode,
            spawn: Point3::new(x, y, model.spawn_height()),
            height: g.height_m.unwrap_or(model.standing_height()),
            distance: g.distance_m,
            position: g.position,
            distance_range: g.distance_range_m,
            heading_range_rad: g.heading_range_deg.map(f64::to_radians),
        }
    }

    /// The spawn point: where the trunk frame starts (before noise).
    pub fn spawn(&self) -> Point3<f64> {
        self.spawn
    }

    /// Checks that the rules accept the configured goal from the spawn point (a fixed or ahead
    /// goal at the start is an error, since D_n = D / K is reported every step); random goals
    /// are at least `distance_range_m[0]` > 0 away horizontally.
    pub fn check(&self, task: &TaskConfig) -> Result<(), EnvError> {
        let goal = match self.mode {
            GoalMode::Ahead => self.ahead(),
            GoalMode::Fixed => self.fixed(),
            GoalMode::Random => return Ok(()),
        };
        episode_rules(task, self.spawn, goal).map(|_| ())
    }

    fn ahead(&self) -> Point3<f64> {
        Point3::new(self.spawn.x + self.distance, self.spawn.y, self.height)
    }

    fn fixed(&self) -> Point3<f64> {
        // Invariant: the configuration's validation requires `position` in fixed mode.
        let [x, y, z] = self.position.unwrap_or([f64::NAN; 3]);
        Point3::new(x, y, z)
    }

    /// This episode's goal; draws from `rng` (two values) only in random mode.
    pub fn sample(&self, rng: &mut ChaCha8Rng) -> Point3<f64> {
        match self.mode {
            GoalMode::Ahead => self.ahead(),
            GoalMode::Fixed => self.fixed(),
            GoalMode::Random => {
                let [dmin, dmax] = self.distance_range;
                let [hmin, hmax] = self.heading_range_rad;
                let d = rng.random_range(dmin..=dmax);
                let heading = rng.random_range(hmin..=hmax);
                Point3::new(
                    self.spawn.x + d * heading.cos(),
                    self.spawn.y + d * heading.sin(),
                    self.height,
                )
            }
        }
    }
}

/// The spawn point leaves the robot room inside the world: standing there, no part of it
/// reaches past the world's edge on any axis, whatever its yaw (a trunk spawned on the edge
/// leaves the world at once, and every episode ends at its first step as `diverged`).
pub(crate) fn check_spawn_fits(model: &RobotModel, reset: &ResetConfig) -> Result<(), ConfigError> {
    let reach = model.standing_reach();
    let [x, y] = reset.spawn_xy_m;
    let room = WORLD_HALF_EXTENT_M - reach;
    let z = model.spawn_height() + reach;
    if x.abs() <= room && y.abs() <= room && z <= WORLD_HALF_EXTENT_M {
        return Ok(());
    }
    Err(ConfigError::Invalid {
        key: "reset.spawn_xy_m".into(),
        value: format!("{:?}", reset.spawn_xy_m),
        expected: format!(
            "leaves robot {:?} no room in the world: standing, it reaches {} m from its trunk \
             frame, and the world ends at ±{WORLD_HALF_EXTENT_M} m on each axis (a trunk \
             leaving it ends the episode as diverged); keep the spawn point within ±{} m",
            model.name(),
            short(reach),
            short(room.max(0.0))
        ),
    })
}

/// The reset state of `model` under `reset` (see the module docs), drawing noise from `rng`
/// only where it is switched on.
pub fn sample_reset_state(
    model: &RobotModel,
    reset: &ResetConfig,
    rng: &mut ChaCha8Rng,
) -> RobotState {
    let mut yaw = reset.yaw_deg.to_radians();
    if reset.yaw_noise_deg > 0.0 {
        let n = reset.yaw_noise_deg.to_radians();
        yaw += rng.random_range(-n..=n);
    }
    let mut q = model.standing_pose().to_vec();
    if reset.joint_noise_rad > 0.0 {
        let n = reset.joint_noise_rad;
        for (angle, joint) in q.iter_mut().zip(model.joints()) {
            *angle = (*angle + rng.random_range(-n..=n)).clamp(joint.lower, joint.upper);
        }
    }
    let [x, y] = reset.spawn_xy_m;
    RobotState {
        trunk: TrunkState {
            pose: Isometry3::from_parts(
                Translation3::new(x, y, model.spawn_height()),
                UnitQuaternion::from_axis_angle(&Vector3::z_axis(), yaw),
            ),
            linvel: Vector3::zeros(),
            angvel: Vector3::zeros(),
        },
        qd: vec![0.0; q.len()],
        q,
    }
}

/// The rules of an episode from `initial` to `goal`, which must be at least
/// [`MIN_START_GOAL_DISTANCE`] apart even when r_n and r_e, which divide by K, are off: the
/// environment reports D_n = D / K on every step (in the info and the record), so K must be a
/// usable divisor. Returns the rules and K.
pub(crate) fn episode_rules(
    task: &TaskConfig,
    initial: Point3<f64>,
    goal: Point3<f64>,
) -> Result<(EpisodeRules, StartGoalDistance), EnvError> {
    let rules = EpisodeRules::new(task, initial, goal)?;
    match rules.start_goal_distance() {
        Some(k) => Ok((rules, k)),
        None => Err(ConfigError::Invalid {
            key: "goal".into(),
            value: format!("{:?}", [goal.x, goal.y, goal.z]),
            expected: format!(
                "is {:?} m from the initial position {:?}: D_n = D / K is reported every step, \
                 so K must be at least {MIN_START_GOAL_DISTANCE:e} m (move the goal)",
                (goal - initial).norm(),
                [initial.x, initial.y, initial.z]
            ),
        }
        .into()),
    }
}
