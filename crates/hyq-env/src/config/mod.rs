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
//!
//! [terrain]       # the ground (see TerrainConfig)
//! kind = "flat"
//!
//! [observation]   # rows beyond the spec's (see ObservationConfig)
//! extra = []
//!
//! [randomize]     # robustness options, all off by default (see RandomizeConfig)
//! ground_friction = [0.5, 1.25]
//!
//! [command]       # the velocity task's commands (task.kind = "velocity"; see CommandConfig)
//! lin_vel_x = [-1.0, 1.0]
//!
//! [velocity]      # the velocity task's reward scales (see VelocityConfig)
//! preset = "legged_gym"
//!
//! [regularizers]  # gait regularisers added to the goal task's reward, all off by default
//! action_rate = -0.01
//! ```
//!
//! Every table and every key is optional: a missing one takes its default. Unknown keys are
//! errors naming the key. [`EnvConfig::set`] changes one value by its dotted key
//! (`"task.fall_penalty"`, `"physics.rapier.solver_iterations"`), the way the CLI's `--set` and
//! the Python keyword arguments do, and validates the whole configuration again.
//!
//! The code is split by phase: one file per table (its struct with each key's meaning, unit and
//! default, its `Default`, and its [`Table::validate`]), registered by one row of
//! [`EnvConfig`] below; `parse` reads files, dotted-key overrides and TOML text, for every
//! front alike; `validate` holds the checks and bounds the tables share; `messages` the errors
//! and their one-line wording. A new table is a new file here and its row (ARCHITECTURE.md,
//! "Adding a configuration table or key").

mod action;
mod control;
mod goal;
mod messages;
mod observation;
mod parse;
mod physics;
mod presets;
mod randomize;
mod regularizers;
mod reset;
mod task;
mod terrain;
mod validate;
mod velocity;

pub use action::{ActionConfig, ActionMode, OutOfRange};
pub use control::{ControlConfig, Gains};
pub use goal::{GoalConfig, GoalMode};
pub use hyq_spec::{EXP_REW_SCALING_MAX, REWARD_SCALE_MAX, TaskConfig};
pub use hyq_tasks::{CommandConfig, RegularizerConfig, RegularizerPreset, VelocityConfig};
pub use messages::{ConfigError, LoadError};
pub use observation::{MAX_SCAN_POINTS, MAX_SCAN_REACH_M, ObservationConfig, ObservationExtra};
pub use parse::CONFIG_FILE_MAX_BYTES;
pub use physics::{ENGINE_TABLES, PhysicsConfig};
pub use presets::{PRESET_RANGES, Preset, PresetRange, preset_table};
pub use randomize::{
    COM_OFFSET_MAX_M, FRICTION_MAX, NOISE_MAX, NoiseDistribution, ObsNoiseConfig,
    PUSH_SPEED_MAX_MPS, RandomizeConfig, Range, SCALE_MAX,
};
pub use reset::{JOINT_NOISE_MAX_RAD, ResetConfig};
pub use task::{TaskKind, TaskTable};
pub(crate) use terrain::keyed as terrain_error;
pub use terrain::{
    MAX_LEVELS, MAX_SLOPE_DEG, StairsClimb, TerrainConfig, TerrainKind, TerrainSeed,
};
pub use validate::{Table, WORLD_HALF_EXTENT_M};
pub(crate) use validate::{in_world, outside_world_reason};

use serde::{Deserialize, Serialize};

/// Declares [`EnvConfig`] from its rows (one per table: its doc, its key and its type), and
/// from the same rows [`EnvConfig::TABLES`] and [`EnvConfig::validate`], so that a table is
/// registered once.
macro_rules! env_config {
    (
        $(#[$meta:meta])*
        pub struct EnvConfig {
            $( $(#[$field_meta:meta])* $table:ident: $ty:ty, )*
        }
    ) => {
        $(#[$meta])*
        pub struct EnvConfig {
            $( $(#[$field_meta])* pub $table: $ty, )*
        }

        impl EnvConfig {
            /// The tables, as a file and the dotted keys name them, in file order.
            pub const TABLES: &[&str] = &[$(stringify!($table)),*];

            /// Checks every value against its documented range, table by table in file order
            /// ([`Table::validate`]); the first invalid one is the error, named by its dotted
            /// key. (The engine tables are checked when an environment on that engine is
            /// built, by the backend.)
            pub fn validate(&self) -> Result<(), ConfigError> {
                $( Table::validate(&self.$table, self)?; )*
                Ok(())
            }
        }
    };
}

env_config! {
    /// The whole configuration of an environment (see the module docs for the file layout).
    #[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
    #[serde(deny_unknown_fields, default)]
    pub struct EnvConfig {
        /// Which task (`kind`: `"goal"`, the spec's, or `"velocity"`) and the spec's user
        /// variables (rewards, penalties, tolerances, t_max), hyq-spec's [`TaskConfig`] with
        /// the spec's names and ranges, including the upper bounds that keep every reward
        /// finite. (default: the spec's goal task and its §2 table)
        task: TaskTable,
        /// Where the goal is. (default: 5 m ahead along +x at the nominal standing height)
        goal: GoalConfig,
        /// How actions become joint targets. (default: normalized, clipped)
        action: ActionConfig,
        /// The PD actuator's gains and the number of physics sub-steps per env step.
        /// (default: the robot profile's gains, 10 sub-steps)
        control: ControlConfig,
        /// Physics settings shared by every engine, plus one optional table per engine.
        /// (default: dt 0.001 s, gravity −9.81 z, friction 1, contact distance 1 mm)
        physics: PhysicsConfig,
        /// Spawn placement and reset noise. (default: at the origin, facing +x, no noise)
        reset: ResetConfig,
        /// The ground ([`crate::terrain`]). (default: flat, the spec's, and the table is not
        /// written, so a written default configuration is what it was without terrain)
        #[serde(skip_serializing_if = "TerrainConfig::is_default")]
        terrain: TerrainConfig,
        /// Observation rows beyond the spec's ([`crate::observation`]). (default: none, the
        /// spec's 39 rows for HyQ, and the table is not written)
        #[serde(skip_serializing_if = "ObservationConfig::is_default")]
        observation: ObservationConfig,
        /// Robustness: dynamics, actuator and delay drawn per episode, observation noise,
        /// pushes ([`crate::randomize`]). (default: all off, and the table is not written)
        #[serde(skip_serializing_if = "RandomizeConfig::is_off")]
        randomize: RandomizeConfig,
        /// The velocity task's command: ranges, resampling, standing commands (hyq-tasks'
        /// [`CommandConfig`]; only with `task.kind = "velocity"`). (default: legged_gym's
        /// ranges and 10 s resampling, and the table is not written)
        #[serde(skip_serializing_if = "velocity::is_default_command")]
        command: CommandConfig,
        /// The velocity task's reward scales and trunk-contact termination (hyq-tasks'
        /// [`VelocityConfig`]; only with `task.kind = "velocity"`). (default: legged_gym's
        /// preset, and the table is not written)
        #[serde(skip_serializing_if = "velocity::is_default_velocity")]
        velocity: VelocityConfig,
        /// Gait regularisers added to the goal task's reward, each a scale over a preset
        /// (hyq-tasks' [`RegularizerConfig`]; only with `task.kind = "goal"`). (default: all
        /// off, the spec's reward, and the table is not written)
        #[serde(skip_serializing_if = "RegularizerConfig::is_default")]
        regularizers: RegularizerConfig,
    }
}

impl EnvConfig {
    /// The environment's time step Δt_env = sub-steps × dt (s).
    pub fn env_dt(&self) -> f64 {
        f64::from(self.control.sim_steps_per_env_step) * self.physics.params.dt
    }
}
