//! The environment's configuration: one TOML file with a table per concern, validated once when
//! it is read or changed, never mutated behind the environment's back.
//!
//! ```toml
//! [task]          # hyq-spec's TaskConfig: the spec's §2 user variables by their spec names
//! norm_rew_scaling = 10.0
//! fall_penalty = 1.0
//!
//! [goal]          # where the goal is (see GoalConfig)
//! mode = "ahead"
//! distance_m = 5.0
//!
//! [action]        # how actions become joint targets (see ActionConfig)
//! mode = "normalized"
//!
//! [control]       # PD gains and sub-steps (see ControlConfig)
//! sim_steps_per_env_step = 10
//!
//! [physics]       # hyq-physics' PhysicsParams, shared by every engine
//! dt = 0.001
//!
//! [physics.rapier]   # the rapier backend's options, read when a rapier env is built
//! solver_iterations = 2
//!
//! [physics.dart]     # the DART backend's options, read when a DART env is built
//!
//! [physics.mujoco]   # the MuJoCo backend's options, read when a MuJoCo env is built
//! noslip_iterations = 10
//!
//! [reset]         # spawn placement and reset noise (see ResetConfig)
//! joint_noise_rad = 0.0
//! ```
//!
//! Every table and every key is optional: a missing one takes its default. Unknown keys are
//! errors naming the key. [`EnvConfig::set`] changes one value by its dotted key
//! (`"task.fall_penalty"`, `"physics.rapier.solver_iterations"`), the way the CLI's `--set` and
//! the Python keyword arguments do, and validates the whole configuration again.

use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;

use hyq_physics::PhysicsParams;
use hyq_spec::TaskConfig;
use serde::de::{self, DeserializeOwned, Deserializer};
use serde::ser::Serializer;
use serde::{Deserialize, Serialize};
use thiserror::Error;

/// Half the side (m) of the cube, centred on the world origin, in which every position must lie
/// on each axis: the spawn point, the goal, and the trunk during an episode (a trunk that leaves
/// it ends the episode as `diverged`). The reason is rapier's f32 positions: at 100 m they step
/// by 7.6 µm, under 1 % of the trunk's motion in a 1 ms sub-step at 1 m/s, and a 3 s trot from
/// x = 100 m moves 1.0061 m against 1.0086 m from the origin (the spread seen between origins 0
/// and 10 m too); from 1 km it moves 1.9 % less, from 10 km it cannot move at all. One bound
/// for every engine keeps runs on different engines comparable. It also bounds every distance,
/// which with the bounds below keeps every reward term and every sum over an episode finite.
pub const WORLD_HALF_EXTENT_M: f64 = 100.0;

/// The largest k_exp (`task.exp_rew_scaling`): R_e(0) = (e^k − 1)/k is then about 2.8e214, so a
/// step's r_e and any sum of them over the longest episode (2^63 steps) stay finite. (e^k
/// itself overflows f64 above k ≈ 709.78.)
pub const EXP_REW_SCALING_MAX: f64 = 500.0;

/// The largest `base_rew_scaling`, `norm_rew_scaling`, `reach_target_bonus_reward`,
/// `reach_bounds_penalty` and `fall_penalty`. With every distance bounded by the world
/// ([`WORLD_HALF_EXTENT_M`]) and K ≥ 10⁻⁶ m, r_b, r_n, the bonus and the penalties then stay
/// below 4·10²⁰ per step, and every sum over an episode finite.
pub const REWARD_SCALE_MAX: f64 = 1e12;

/// The widest reset joint noise (rad, `reset.joint_noise_rad`): a full turn. Wider noise only
/// piles the angles up at the joint limits, where they are clipped.
pub const JOINT_NOISE_MAX_RAD: f64 = std::f64::consts::TAU;

/// The reason given when a position is outside the world (see [`WORLD_HALF_EXTENT_M`]).
pub(crate) fn outside_world_reason() -> String {
    format!(
        "must lie within ±{WORLD_HALF_EXTENT_M} m of the origin on each axis (m), the world of \
         every engine: beyond it rapier's f32 positions are too coarse for faithful physics"
    )
}

/// Whether `v` is a coordinate inside the world (finite, |v| ≤ [`WORLD_HALF_EXTENT_M`]).
pub(crate) fn in_world(v: f64) -> bool {
    v.is_finite() && v.abs() <= WORLD_HALF_EXTENT_M
}

/// The largest configuration file read (bytes): 1 MiB, hundreds of times any real
/// configuration, so that a wrong path (`/dev/zero`, a log file) is refused at once rather than
/// read until memory runs out.
pub const CONFIG_FILE_MAX_BYTES: usize = 1 << 20;

/// The names of the engine tables `[physics.<name>]` a configuration may hold, one per backend
/// crate (`hyq-rapier`, `hyq-dart`, `hyq-mujoco`). A table is read only by the backend of that
/// name; the list exists so that a misspelt engine table is an error rather than silently
/// ignored.
pub const ENGINE_TABLES: [&str; 3] = ["rapier", "dart", "mujoco"];

/// The whole configuration of an environment (see the module docs for the file layout).
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct EnvConfig {
    /// The spec's user variables (rewards, penalties, tolerances, t_max), hyq-spec's
    /// [`TaskConfig`] with the spec's names and ranges, plus upper bounds that keep every reward
    /// finite: k_exp at most [`EXP_REW_SCALING_MAX`], the other scalings, the bonus and the
    /// penalties at most [`REWARD_SCALE_MAX`]. (default: the spec's §2 table)
    pub task: TaskConfig,
    /// Where the goal is. (default: 5 m ahead along +x at the nominal standing height)
    pub goal: GoalConfig,
    /// How actions become joint targets. (default: normalized, clipped)
    pub action: ActionConfig,
    /// The PD actuator's gains and the number of physics sub-steps per env step.
    /// (default: the robot profile's gains, 10 sub-steps)
    pub control: ControlConfig,
    /// Physics settings shared by every engine, plus one optional table per engine.
    /// (default: dt 0.001 s, gravity −9.81 z, friction 1, contact distance 1 mm)
    pub physics: PhysicsConfig,
    /// Spawn placement and reset noise. (default: at the origin, facing +x, no noise)
    pub reset: ResetConfig,
}

/// How the goal G of each episode is chosen (`[goal]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GoalConfig {
    /// `"ahead"`: `distance_m` along +x from the spawn point; `"fixed"`: `position`;
    /// `"random"`: a seeded draw from `distance_range_m` and `heading_range_deg`.
    /// (default: `"ahead"`)
    pub mode: GoalMode,
    /// Distance (m) of the goal along +x from the spawn point in `"ahead"` mode. > 0, and the
    /// goal within the world ([`WORLD_HALF_EXTENT_M`]). (default: 5.0)
    pub distance_m: f64,
    /// The goal's world coordinates [x, y, z] (m) in `"fixed"` mode, where it is required; each
    /// within ±[`WORLD_HALF_EXTENT_M`]. (default: unset)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub position: Option<[f64; 3]>,
    /// [min, max] distance (m) from the spawn point, drawn uniformly, in `"random"` mode.
    /// 0 < min ≤ max, and a goal max away in any direction within the world
    /// ([`WORLD_HALF_EXTENT_M`]). (default: [3.0, 7.0])
    pub distance_range_m: [f64; 2],
    /// [min, max] heading (degrees, about +z from +x, positive to the left), drawn uniformly,
    /// in `"random"` mode. Within [−180, 180], min ≤ max. (default: [0.0, 0.0], straight
    /// ahead: the spec's yaw multiplier (§5.1) penalises any heading away from +x, so goals off
    /// the x axis are opt-in)
    pub heading_range_deg: [f64; 2],
    /// The goal's height z (m) in `"ahead"` and `"random"` modes, within ±[`WORLD_HALF_EXTENT_M`].
    /// (default: unset, meaning the
    /// robot's nominal standing height from its profile, `spawn.standing_height`: 0.5895 m for
    /// HyQ)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub height_m: Option<f64>,
}

impl Default for GoalConfig {
    fn default() -> Self {
        Self {
            mode: GoalMode::Ahead,
            distance_m: 5.0,
            position: None,
            distance_range_m: [3.0, 7.0],
            heading_range_deg: [0.0, 0.0],
            height_m: None,
        }
    }
}

/// How the goal is chosen; see [`GoalConfig`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum GoalMode {
    /// `distance_m` straight ahead (+x) of the spawn point.
    Ahead,
    /// A fixed world position.
    Fixed,
    /// A seeded random distance and heading from the spawn point.
    Random,
}

impl GoalMode {
    /// The mode as written in TOML (`"ahead"`, `"fixed"`, `"random"`).
    pub const fn as_str(self) -> &'static str {
        match self {
            GoalMode::Ahead => "ahead",
            GoalMode::Fixed => "fixed",
            GoalMode::Random => "random",
        }
    }
}

/// How an action becomes the 12 joint targets of the PD actuator (`[action]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ActionConfig {
    /// `"normalized"`: a ∈ [−1, 1] maps linearly onto each joint's range (−1 the lower limit,
    /// +1 the upper); `"absolute"`: targets in radians; `"delta"`: target = the joint's angle at
    /// the start of the step + a · `max_delta_rad`, a ∈ [−1, 1]; `"offset"`: target = the
    /// robot's standing angle + a · `max_offset_rad`, a ∈ [−1, 1] (a project-defined mode, spec
    /// §7.1). Targets are always clipped to the joint limits. (default: `"normalized"`)
    pub mode: ActionMode,
    /// What a finite value outside the action space does: `"clip"` clips it to the space (and
    /// the step's info says so), `"error"` refuses the step. Non-finite values are always
    /// errors. (default: `"clip"`)
    pub out_of_range: OutOfRange,
    /// The largest change of a joint target per env step in `"delta"` mode (rad). Finite, > 0.
    /// (default: 0.1, i.e. up to 10 rad/s at 100 env steps per second, within HyQ's 12 rad/s)
    pub max_delta_rad: f64,
    /// The largest distance of a joint target from the standing pose in `"offset"` mode (rad).
    /// Finite, > 0. (default: 0.5, within every HyQ joint's room on both sides of standing
    /// but the hip flexions' 0.47 rad to one limit)
    pub max_offset_rad: f64,
}

impl Default for ActionConfig {
    fn default() -> Self {
        Self {
            mode: ActionMode::Normalized,
            out_of_range: OutOfRange::Clip,
            max_delta_rad: 0.1,
            max_offset_rad: 0.5,
        }
    }
}

/// The action modes; see [`ActionConfig::mode`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ActionMode {
    /// [−1, 1] onto each joint's range.
    Normalized,
    /// Radians, within the joint limits.
    Absolute,
    /// [−1, 1] times `max_delta_rad` from the current angle.
    Delta,
    /// [−1, 1] times `max_offset_rad` from the standing pose.
    Offset,
}

/// What happens to a finite action value outside the action space; see
/// [`ActionConfig::out_of_range`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OutOfRange {
    /// Clip to the action space.
    Clip,
    /// Refuse the step with an error naming the index and value.
    Error,
}

/// The PD actuator and the sub-stepping (`[control]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ControlConfig {
    /// Physics sub-steps per env step (the spec's §6.3 "10 simulator steps per gym step"); the
    /// env step lasts `sim_steps_per_env_step · physics.dt`. In 1..=1000. (default: 10)
    pub sim_steps_per_env_step: u32,
    /// Proportional gains (N·m/rad): `"profile"` for the robot profile's, one number for every
    /// joint, or one per joint in action order. Finite, ≥ 0. (default: `"profile"`, 1000 for
    /// HyQ)
    pub kp: Gains,
    /// Derivative gains (N·m·s/rad), as `kp`. (default: `"profile"`, 20 for HyQ)
    pub kd: Gains,
    /// Whether the actuator honours the URDF velocity limits (hyq-physics' actuator rule 2).
    /// (default: true)
    pub velocity_limit: bool,
}

impl Default for ControlConfig {
    fn default() -> Self {
        Self {
            sim_steps_per_env_step: 10,
            kp: Gains::Profile,
            kd: Gains::Profile,
            velocity_limit: true,
        }
    }
}

/// Gains as written in `[control]`: the profile's, one for all joints, or one per joint.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Gains {
    /// The robot profile's gains (written `"profile"`).
    #[default]
    Profile,
    /// The same gain for every joint (a number).
    All(f64),
    /// One gain per joint in action order (an array).
    PerJoint(Vec<f64>),
}

impl Gains {
    /// The gains for `n` joints, `profile` being the profile's; `None` when a per-joint list has
    /// the wrong length.
    pub fn resolve(&self, profile: &[f64]) -> Option<Vec<f64>> {
        match self {
            Gains::Profile => Some(profile.to_vec()),
            Gains::All(g) => Some(vec![*g; profile.len()]),
            Gains::PerJoint(v) => (v.len() == profile.len()).then(|| v.clone()),
        }
    }
}

/// As written in TOML: `"profile"`, a number, or an array of numbers.
impl fmt::Display for Gains {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Gains::Profile => f.write_str("\"profile\""),
            Gains::All(g) => write!(f, "{g:?}"),
            Gains::PerJoint(v) => write!(f, "{v:?}"),
        }
    }
}

impl Serialize for Gains {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Gains::Profile => s.serialize_str("profile"),
            Gains::All(g) => s.serialize_f64(*g),
            Gains::PerJoint(v) => v.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Gains {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> de::Visitor<'de> for V {
            type Value = Gains;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("\"profile\", a number, or an array of one number per joint")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Gains, E> {
                if v == "profile" {
                    Ok(Gains::Profile)
                } else {
                    Err(E::invalid_value(de::Unexpected::Str(v), &self))
                }
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Gains, E> {
                Ok(Gains::All(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Gains, E> {
                Ok(Gains::All(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Gains, E> {
                Ok(Gains::All(v as f64))
            }
            fn visit_seq<A: de::SeqAccess<'de>>(self, mut seq: A) -> Result<Gains, A::Error> {
                let mut out = Vec::new();
                while let Some(g) = seq.next_element::<f64>()? {
                    out.push(g);
                }
                Ok(Gains::PerJoint(out))
            }
        }
        d.deserialize_any(V)
    }
}

/// `[physics]`: hyq-physics' engine-independent [`PhysicsParams`] as plain keys, plus one
/// optional sub-table per engine (`[physics.rapier]`, `[physics.dart]`, `[physics.mujoco]`, see
/// [`ENGINE_TABLES`]) that is deserialised into that backend's `Options` when an environment
/// on it is built, so one file serves every engine.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PhysicsConfig {
    /// dt, gravity, friction, contact distance (see [`PhysicsParams`] for each default).
    pub params: PhysicsParams,
    /// The engine tables, by engine name, as written.
    pub engines: BTreeMap<String, toml::Table>,
}

impl PhysicsConfig {
    /// The options of engine `name` (`[physics.<name>]`), or `O::default()` when the table is
    /// absent. Errors name the table and the key.
    pub fn engine_options<O: DeserializeOwned + Default>(
        &self,
        name: &str,
    ) -> Result<O, ConfigError> {
        match self.engines.get(name) {
            None => Ok(O::default()),
            Some(table) => O::deserialize(toml::Value::Table(table.clone())).map_err(|e| {
                ConfigError::Invalid {
                    key: format!("physics.{name}"),
                    value: table.to_string().trim().replace('\n', ", "),
                    expected: e.to_string(),
                }
            }),
        }
    }
}

impl Serialize for PhysicsConfig {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut table = toml::Table::try_from(&self.params).map_err(serde::ser::Error::custom)?;
        for (name, engine) in &self.engines {
            table.insert(name.clone(), toml::Value::Table(engine.clone()));
        }
        table.serialize(s)
    }
}

impl<'de> Deserialize<'de> for PhysicsConfig {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let mut table = toml::Table::deserialize(d)?;
        let mut engines = BTreeMap::new();
        for name in ENGINE_TABLES {
            match table.remove(name) {
                None => {}
                Some(toml::Value::Table(t)) => {
                    engines.insert(name.to_owned(), t);
                }
                Some(other) => {
                    return Err(de::Error::custom(format!(
                        "physics.{name} must be a table of {name} options, not `{other}`"
                    )));
                }
            }
        }
        if let Some((key, _)) = table.iter().find(|(_, v)| v.is_table()) {
            return Err(de::Error::custom(format!(
                "unknown engine table `physics.{key}` (engine tables: {})",
                ENGINE_TABLES.join(", ")
            )));
        }
        let params =
            PhysicsParams::deserialize(toml::Value::Table(table)).map_err(de::Error::custom)?;
        Ok(PhysicsConfig { params, engines })
    }
}

/// Where and how the robot is placed at reset (`[reset]`).
///
/// The robot always starts at rest, trunk level (up to `yaw_deg`), joints at the profile's
/// standing pose, the trunk frame at the profile's spawn height. Noise is drawn from the reset
/// seed's noise stream, separate from the goal stream.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ResetConfig {
    /// The spawn point's [x, y] (m, world), each within ±[`WORLD_HALF_EXTENT_M`]. (default:
    /// [0.0, 0.0])
    pub spawn_xy_m: [f64; 2],
    /// The trunk's yaw at spawn (degrees, about +z, positive to the left). In [−180, 180].
    /// (default: 0.0, facing +x)
    pub yaw_deg: f64,
    /// Uniform noise added to the yaw at each reset: ± this many degrees. In [0, 180].
    /// (default: 0.0, off)
    pub yaw_noise_deg: f64,
    /// Uniform noise added to each standing joint angle at each reset: ± this many radians,
    /// then clipped to the joint's limits. In [0, [`JOINT_NOISE_MAX_RAD`]]. (default: 0.0, off)
    pub joint_noise_rad: f64,
}

impl Default for ResetConfig {
    fn default() -> Self {
        Self {
            spawn_xy_m: [0.0, 0.0],
            yaw_deg: 0.0,
            yaw_noise_deg: 0.0,
            joint_noise_rad: 0.0,
        }
    }
}

/// Why [`EnvConfig::load`] failed: the file's error, or an override's; either reads as the
/// [`ConfigError`] it holds.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum LoadError {
    /// The file could not be read, or its configuration is invalid.
    #[error(transparent)]
    File(ConfigError),
    /// An override names an unknown key or a bad value, or leaves the configuration invalid.
    #[error(transparent)]
    Overrides(ConfigError),
}

impl From<LoadError> for ConfigError {
    fn from(e: LoadError) -> Self {
        match e {
            LoadError::File(e) | LoadError::Overrides(e) => e,
        }
    }
}

/// An invalid configuration; every variant names the key and, where there is one, the value.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum ConfigError {
    /// The configuration file could not be read.
    #[error("cannot read configuration file {path}: {message}")]
    Io {
        /// The path that was tried.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The text is not valid TOML, has an unknown key, or a value of the wrong type or range
    /// (the message names the key and shows the line).
    #[error("configuration {origin}: {message}")]
    Parse {
        /// Where the text came from (a path, or "text").
        origin: String,
        /// The parser's message.
        message: String,
    },
    /// A value out of its valid range.
    #[error("invalid {key} = {value}: {expected}")]
    Invalid {
        /// The dotted key, e.g. `goal.distance_m`.
        key: String,
        /// The rejected value as written.
        value: String,
        /// What the key accepts.
        expected: String,
    },
    /// A key given to [`EnvConfig::set`] that names no setting, or a change it refused.
    #[error("setting {key} = {value}: {message}")]
    Set {
        /// The dotted key as given.
        key: String,
        /// The value as given.
        value: String,
        /// What was wrong.
        message: String,
    },
}

/// `reset.spawn_xy_m`: inside the world.
fn validate_spawn(r: &ResetConfig) -> Result<(), ConfigError> {
    if !r.spawn_xy_m.iter().all(|v| in_world(*v)) {
        return Err(invalid(
            "reset.spawn_xy_m",
            r.spawn_xy_m,
            &outside_world_reason(),
        ));
    }
    Ok(())
}

/// `[goal]`: the keys of the mode only, each value in its range, and every goal the mode can
/// give (from the spawn point `spawn_xy`) inside the world.
fn validate_goal(g: &GoalConfig, spawn_xy: [f64; 2]) -> Result<(), ConfigError> {
    goal_keys_match_mode(g)?;
    goal_values(g)?;
    goal_in_world(g, spawn_xy)
}

/// A key of another goal mode would be silently ignored: it is an error, unless it holds its
/// default (as a written-out configuration holds it).
fn goal_keys_match_mode(g: &GoalConfig) -> Result<(), ConfigError> {
    let d = GoalConfig::default();
    let (ahead, fixed, random) = (
        g.mode == GoalMode::Ahead,
        g.mode == GoalMode::Fixed,
        g.mode == GoalMode::Random,
    );
    let misplaced = [
        ("goal.position", !fixed && g.position.is_some(), "\"fixed\""),
        (
            "goal.distance_m",
            !ahead && g.distance_m != d.distance_m,
            "\"ahead\"",
        ),
        (
            "goal.distance_range_m",
            !random && g.distance_range_m != d.distance_range_m,
            "\"random\"",
        ),
        (
            "goal.heading_range_deg",
            !random && g.heading_range_deg != d.heading_range_deg,
            "\"random\"",
        ),
        (
            "goal.height_m",
            fixed && g.height_m.is_some(),
            "\"ahead\" or \"random\"",
        ),
    ];
    if let Some((key, _, modes)) = misplaced.iter().find(|(_, wrong, _)| *wrong) {
        let value = match *key {
            "goal.position" => format!("{:?}", g.position.unwrap_or_default()),
            "goal.distance_m" => format!("{:?}", g.distance_m),
            "goal.distance_range_m" => format!("{:?}", g.distance_range_m),
            "goal.heading_range_deg" => format!("{:?}", g.heading_range_deg),
            _ => format!("{:?}", g.height_m.unwrap_or_default()),
        };
        return Err(ConfigError::Invalid {
            key: (*key).to_owned(),
            value,
            expected: format!(
                "is only read when goal.mode = {modes}, and the mode is \"{}\": set \
                 goal.mode, or remove the key",
                g.mode.as_str()
            ),
        });
    }
    Ok(())
}

/// The goal's values in their ranges.
fn goal_values(g: &GoalConfig) -> Result<(), ConfigError> {
    finite_positive("goal.distance_m", g.distance_m)?;
    match (g.mode, g.position) {
        (GoalMode::Fixed, None) => {
            return Err(invalid(
                "goal.position",
                "unset",
                "goal.mode = \"fixed\" needs goal.position = [x, y, z] (m)",
            ));
        }
        (_, Some(p)) if !p.iter().all(|v| v.is_finite()) => {
            return Err(invalid("goal.position", p, "must be finite"));
        }
        _ => {}
    }
    let [dmin, dmax] = g.distance_range_m;
    if !(dmin.is_finite() && dmax.is_finite() && dmin > 0.0 && dmin <= dmax) {
        return Err(invalid(
            "goal.distance_range_m",
            g.distance_range_m,
            "must be finite with 0 < min <= max (m)",
        ));
    }
    let [hmin, hmax] = g.heading_range_deg;
    if !((-180.0..=180.0).contains(&hmin) && (-180.0..=180.0).contains(&hmax) && hmin <= hmax) {
        return Err(invalid(
            "goal.heading_range_deg",
            g.heading_range_deg,
            "must be within [-180, 180] degrees with min <= max",
        ));
    }
    if let Some(h) = g.height_m
        && !in_world(h)
    {
        return Err(invalid("goal.height_m", h, &outside_world_reason()));
    }
    Ok(())
}

/// Every goal the mode can give, from the spawn point `spawn_xy`, lies in the world.
fn goal_in_world(g: &GoalConfig, spawn_xy: [f64; 2]) -> Result<(), ConfigError> {
    let [x, y] = spawn_xy;
    let dmax = g.distance_range_m[1];
    let outside = match g.mode {
        GoalMode::Ahead => (!in_world(x + g.distance_m))
            .then(|| invalid("goal.distance_m", g.distance_m, &outside_world_reason())),
        GoalMode::Fixed => g
            .position
            .filter(|p| !p.iter().all(|v| in_world(*v)))
            .map(|p| invalid("goal.position", p, &outside_world_reason())),
        GoalMode::Random => (!(in_world(x.abs() + dmax) && in_world(y.abs() + dmax))).then(|| {
            invalid(
                "goal.distance_range_m",
                g.distance_range_m,
                &format!(
                    "{} (from the spawn point [{x:?}, {y:?}], a goal {dmax:?} m away \
                     can leave it)",
                    outside_world_reason()
                ),
            )
        }),
    };
    outside.map_or(Ok(()), Err)
}

/// `[control]`: the sub-step count and the gains.
fn validate_control(c: &ControlConfig) -> Result<(), ConfigError> {
    if !(1..=1000).contains(&c.sim_steps_per_env_step) {
        return Err(invalid(
            "control.sim_steps_per_env_step",
            c.sim_steps_per_env_step,
            "must be in 1..=1000",
        ));
    }
    gains_ok("control.kp", &c.kp)?;
    gains_ok("control.kd", &c.kd)?;
    Ok(())
}

/// `[reset]`: the yaw and the noise in their ranges.
fn validate_reset_noise(r: &ResetConfig) -> Result<(), ConfigError> {
    if !(-180.0..=180.0).contains(&r.yaw_deg) {
        return Err(invalid(
            "reset.yaw_deg",
            r.yaw_deg,
            "must be in [-180, 180] degrees",
        ));
    }
    if !(0.0..=180.0).contains(&r.yaw_noise_deg) {
        return Err(invalid(
            "reset.yaw_noise_deg",
            r.yaw_noise_deg,
            "must be in [0, 180] degrees",
        ));
    }
    if !(0.0..=JOINT_NOISE_MAX_RAD).contains(&r.joint_noise_rad) {
        return Err(invalid(
            "reset.joint_noise_rad",
            r.joint_noise_rad,
            &format!(
                "must be in [0, {JOINT_NOISE_MAX_RAD}] rad (a full turn; wider noise only \
                 piles the angles up at the joint limits)"
            ),
        ));
    }
    Ok(())
}

fn invalid(key: &str, value: impl fmt::Debug, expected: &str) -> ConfigError {
    ConfigError::Invalid {
        key: key.to_owned(),
        value: format!("{value:?}"),
        expected: expected.to_owned(),
    }
}

fn finite_positive(key: &str, v: f64) -> Result<(), ConfigError> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(invalid(key, v, "must be finite and > 0"))
    }
}

fn gains_ok(key: &str, g: &Gains) -> Result<(), ConfigError> {
    let ok = |v: &f64| v.is_finite() && *v >= 0.0;
    match g {
        Gains::Profile => Ok(()),
        Gains::All(v) if ok(v) => Ok(()),
        Gains::PerJoint(v) if v.iter().all(ok) => Ok(()),
        other => Err(ConfigError::Invalid {
            key: key.to_owned(),
            value: other.to_string(),
            expected: "gains must be finite and >= 0".to_owned(),
        }),
    }
}

impl EnvConfig {
    /// Parses and validates a configuration from TOML text; `origin` (a path, or "text")
    /// appears in errors.
    ///
    /// Errors give the line of the offending key where the text has it: the parser's position for
    /// syntax, unknown keys and wrong types; for a value out of its range, the line of that key
    /// (the checks of `[task]` run when the whole table is read, where the parser would point at
    /// the table instead).
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Self, ConfigError> {
        let at = |key: &str, message: String| ConfigError::Parse {
            origin: origin.to_owned(),
            message: match line_of(text, key) {
                Some(line) => format!("line {line}: {message}"),
                None => message,
            },
        };
        let config: EnvConfig =
            toml::from_str(text).map_err(|e| match task_check(e.message()) {
                Some((key, message)) => at(&key, message),
                None => ConfigError::Parse {
                    origin: origin.to_owned(),
                    message: one_line(&e.to_string()),
                },
            })?;
        config.validate().map_err(|e| match &e {
            ConfigError::Invalid { key, .. } => at(key, e.to_string()),
            _ => e,
        })?;
        Ok(config)
    }

    /// The configuration the fronts build (`hyq --config FILE --set KEY=VALUE`, and Python's
    /// `config_file=` with keyword arguments): the defaults, or `file`'s, with `overrides`
    /// (dotted key, TOML value) set on top by [`EnvConfig::set_all`], validated. The error says
    /// which of the two was wrong.
    pub fn load<K: AsRef<str>, V: AsRef<str>>(
        file: Option<&Path>,
        overrides: &[(K, V)],
    ) -> Result<Self, LoadError> {
        let mut config = match file {
            Some(path) => Self::from_file(path).map_err(LoadError::File)?,
            None => Self::default(),
        };
        if !overrides.is_empty() {
            let pairs: Vec<(&str, &str)> = overrides
                .iter()
                .map(|(k, v)| (k.as_ref(), v.as_ref()))
                .collect();
            config.set_all(&pairs).map_err(LoadError::Overrides)?;
        }
        Ok(config)
    }

    /// Reads, parses and validates a configuration file of at most
    /// [`CONFIG_FILE_MAX_BYTES`].
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, ConfigError> {
        use std::io::Read;
        let path = path.as_ref();
        let io = |message: String| ConfigError::Io {
            path: path.display().to_string(),
            message,
        };
        let mut bytes = Vec::new();
        std::fs::File::open(path)
            .and_then(|f| {
                f.take(CONFIG_FILE_MAX_BYTES as u64 + 1)
                    .read_to_end(&mut bytes)
            })
            .map_err(|e| io(e.to_string()))?;
        if bytes.len() > CONFIG_FILE_MAX_BYTES {
            return Err(io(format!(
                "larger than {} MiB, which no configuration is (is it the right file?)",
                CONFIG_FILE_MAX_BYTES >> 20
            )));
        }
        let text = String::from_utf8(bytes).map_err(|e| io(format!("not UTF-8 text: {e}")))?;
        Self::from_toml_str(&text, &path.display().to_string())
    }

    /// The configuration as TOML text, every key written (defaults included), so that it reads
    /// back to an equal configuration.
    pub fn to_toml_string(&self) -> String {
        // Invariant: every field serialises to TOML (numbers, strings, arrays, tables; the
        // optional fields are skipped when unset), which the round-trip test checks.
        toml::to_string(self).unwrap_or_else(|e| unreachable!("EnvConfig serialises: {e}"))
    }

    /// Sets one value by its dotted key, e.g. `set("task.fall_penalty", "1.5")`,
    /// `set("task.exp_rew_scaling", "off")` or `set("physics.rapier.solver_iterations", "4")`,
    /// then validates the whole configuration. Same as [`EnvConfig::set_all`] with one pair.
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), ConfigError> {
        self.set_all(&[(key, value)])
    }

    /// Sets several values by their dotted keys, then validates the whole configuration once,
    /// so that values that only make sense together can be given together
    /// (`goal.mode=fixed` with `goal.position=[5, 1, 0.6]`). This is what the CLI's `--set`
    /// options and the Python keyword arguments use.
    ///
    /// Each value is read as a TOML value (number, boolean, array, quoted string); anything
    /// that is not one is taken as a bare string, so `mode=random` works unquoted. An unknown
    /// key, or a value of the wrong type or outside its range, is an error naming that key and
    /// value; a combination that is invalid as a whole is an error naming the offending key. On
    /// error the configuration is unchanged.
    pub fn set_all(&mut self, pairs: &[(&str, &str)]) -> Result<(), ConfigError> {
        let mut doc = toml::Table::try_from(&*self).map_err(|e| ConfigError::Parse {
            origin: "configuration".into(),
            message: e.to_string(),
        })?;
        let mut config = self.clone();
        for (key, value) in pairs {
            // One line: the CLI prints errors on one line.
            let fail = |message: String| ConfigError::Set {
                key: (*key).to_owned(),
                value: (*value).to_owned(),
                message: one_line(&message),
            };
            let path: Vec<&str> = key.split('.').collect();
            if path.len() < 2 || path.iter().any(|p| p.is_empty()) {
                return Err(fail(
                    "a key is `table.name`, e.g. `task.fall_penalty` or \
                     `physics.rapier.solver_iterations`"
                        .into(),
                ));
            }
            let parsed = match toml::from_str::<toml::Table>(&format!("v = {value}")) {
                Ok(mut t) => t.remove("v"),
                // An integer TOML cannot hold: say so, rather than read it as a bare string.
                Err(_) if is_integer_literal(value) => {
                    return Err(fail(
                        "not an integer a configuration can hold: TOML's integers are 64-bit \
                         signed, from -9223372036854775808 to 9223372036854775807"
                            .into(),
                    ));
                }
                Err(_) => None,
            }
            .unwrap_or_else(|| toml::Value::String((*value).to_owned()));
            let mut table = &mut doc;
            for part in &path[..path.len() - 1] {
                let entry = table
                    .entry(part.to_string())
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()));
                table = match entry {
                    toml::Value::Table(t) => t,
                    _ => return Err(fail(format!("`{part}` is a value, not a table"))),
                };
            }
            table.insert(path[path.len() - 1].to_owned(), parsed);
            // Deserialised after every pair, so an unknown key or a wrong type is blamed on the
            // pair that brought it.
            config = EnvConfig::deserialize(toml::Value::Table(doc.clone())).map_err(|e| {
                let message = e.to_string();
                fail(task_check(&message).map_or(message, |(_, checked)| checked))
            })?;
        }
        config.validate()?;
        *self = config;
        Ok(())
    }

    /// Checks every value against its documented range; the first invalid one is the error,
    /// named by its dotted key. (The engine tables are checked when an environment on that
    /// engine is built, by the backend.)
    pub fn validate(&self) -> Result<(), ConfigError> {
        self.validate_task()?;
        validate_spawn(&self.reset)?;
        validate_goal(&self.goal, self.reset.spawn_xy_m)?;
        finite_positive("action.max_delta_rad", self.action.max_delta_rad)?;
        finite_positive("action.max_offset_rad", self.action.max_offset_rad)?;
        validate_control(&self.control)?;
        self.validate_physics()?;
        validate_reset_noise(&self.reset)
    }

    /// `[task]`: the spec's ranges (hyq-spec), then the bounds that keep every sum finite.
    fn validate_task(&self) -> Result<(), ConfigError> {
        self.task.validate().map_err(|e| match e {
            hyq_spec::ConfigError::Real {
                field,
                value,
                expected,
            } => invalid(
                &format!("task.{field}"),
                value,
                &format!("must be {expected}"),
            ),
            hyq_spec::ConfigError::Integer {
                field,
                value,
                expected,
            } => invalid(
                &format!("task.{field}"),
                value,
                &format!("must be {expected}"),
            ),
        })?;

        let t = &self.task;
        if let Some(k) = t.exp_rew_scaling
            && k > EXP_REW_SCALING_MAX
        {
            return Err(invalid(
                "task.exp_rew_scaling",
                k,
                &format!(
                    "must be at most {EXP_REW_SCALING_MAX}, so that R_e(0) = (e^k - 1)/k and \
                     every sum of rewards over an episode stay finite"
                ),
            ));
        }
        for (key, value) in [
            ("task.base_rew_scaling", t.base_rew_scaling),
            ("task.norm_rew_scaling", t.norm_rew_scaling),
            (
                "task.reach_target_bonus_reward",
                Some(t.reach_target_bonus_reward),
            ),
            ("task.reach_bounds_penalty", Some(t.reach_bounds_penalty)),
            ("task.fall_penalty", Some(t.fall_penalty)),
        ] {
            if let Some(v) = value
                && v > REWARD_SCALE_MAX
            {
                return Err(invalid(
                    key,
                    v,
                    &format!(
                        "must be at most {REWARD_SCALE_MAX:e}, so that every reward term and \
                         every sum of rewards over an episode stay finite"
                    ),
                ));
            }
        }
        Ok(())
    }

    /// `physics`: the engine-independent parameters (hyq-physics' ranges).
    fn validate_physics(&self) -> Result<(), ConfigError> {
        self.physics.params.validate().map_err(|e| match e {
            hyq_physics::PhysicsError::InvalidParam {
                field,
                value,
                reason,
            } => ConfigError::Invalid {
                key: format!("physics.{field}"),
                value,
                expected: reason.to_owned(),
            },
            other => ConfigError::Invalid {
                key: "physics".into(),
                value: String::new(),
                expected: other.to_string(),
            },
        })?;
        Ok(())
    }

    /// The environment's time step Δt_env = sub-steps × dt (s).
    pub fn env_dt(&self) -> f64 {
        f64::from(self.control.sim_steps_per_env_step) * self.physics.params.dt
    }
}

/// A `[task]` range check's message as the parser reports it (`invalid <field> = <value>: must
/// be …`, with the key path the parser may append, `: in `task``), rewritten as the other
/// checks word theirs: the field's whole dotted key, and the value in its shortest form
/// (`-1e308`, not 309 digits). Returns the key and the message; `None` for other messages.
fn task_check(message: &str) -> Option<(String, String)> {
    let rest = message.trim().strip_prefix("invalid ")?;
    let (field, rest) = rest.split_once(" = ")?;
    let known = field
        .split('.')
        .all(|part| !part.is_empty() && part.chars().all(|c| c.is_ascii_lowercase() || c == '_'));
    let (value, rest) = rest.split_once(": ")?;
    if !known {
        return None;
    }
    // Integers as written; reals in their shortest form.
    let value = match (value.parse::<i128>(), value.parse::<f64>()) {
        (Err(_), Ok(v)) => format!("{v:?}"),
        _ => value.to_owned(),
    };
    let rest = rest
        .lines()
        .next()
        .and_then(|l| l.split(": in `").next())
        .unwrap_or(rest)
        .trim_end();
    let key = format!("task.{field}");
    let message = format!("invalid {key} = {value}: {rest}");
    Some((key, message))
}

/// The line (1 first) of the dotted `key` in the TOML `text`, if the text holds it.
fn line_of(text: &str, key: &str) -> Option<usize> {
    let doc = toml::de::DeTable::parse(text).ok()?;
    let mut table = doc.get_ref();
    let mut span = None;
    let mut parts = key.split('.').peekable();
    while let Some(part) = parts.next() {
        let (k, v) = table.get_key_value(part)?;
        span = Some(k.span());
        if parts.peek().is_some() {
            match v.get_ref() {
                toml::de::DeValue::Table(t) => table = t,
                _ => return None,
            }
        }
    }
    span.map(|s| text.get(..s.start).map_or(0, |t| t.matches('\n').count()) + 1)
}

/// Whether `value` is written as a TOML integer (sign, digits, underscores).
fn is_integer_literal(value: &str) -> bool {
    let digits = value.trim().trim_start_matches(['+', '-']);
    !digits.is_empty() && digits.chars().all(|c| c.is_ascii_digit() || c == '_')
}

/// `message` with every number of more than 24 digits (a float the parser or serde printed in
/// full, e.g. `1000000000000000000000000000000.0` for 1e30) in its shortest form (`1e30`). Up to
/// 24 digits stay as written, so integers such as 2^64 − 1 read as given.
fn compact_numbers(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        out.push_str(&rest[..start]);
        let tail = &rest[start..];
        let end = tail
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(tail.len());
        let number = &tail[..end];
        let digits = number.chars().filter(char::is_ascii_digit).count();
        match number.parse::<f64>() {
            Ok(v) if digits > 24 => out.push_str(&format!("{v:?}")),
            _ => out.push_str(number),
        }
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

/// A parser message on one line (the CLI prints errors on one line): TOML's "at line L, column
/// C" header and its explanation, without the source excerpt drawn between them, and numbers
/// in their short form ([`compact_numbers`]).
fn one_line(message: &str) -> String {
    let lines: Vec<&str> = message
        .lines()
        .map(str::trim)
        .filter(|l| {
            !l.is_empty()
                && !l.starts_with('|')
                && !l.chars().next().is_some_and(|c| c.is_ascii_digit())
        })
        .collect();
    compact_numbers(&lines.join(": "))
}
