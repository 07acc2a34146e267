//! The robot profile: the robot-specific facts that the crates read instead of knowing them.
//!
//! A profile is a small TOML file next to the URDF (see `assets/hyq/profile.toml`): the trunk
//! link, the tracked feet, the actuated joints in observation/action order with the standing
//! pose (and, where the URDF's figures are not the robot's, overrides of their limits), the
//! spawn height, the default PD gains, and optionally the declared bounds of the trunk's
//! observation rows (`[observation]`) and the scripted trot's leg map and parameters
//! (`[gait]`). Nothing in the code knows a robot's link or joint names or how many it has; it
//! all comes from here, so the crates work for other robots.

use serde::{Deserialize, Serialize};

use crate::error::ModelError;

/// A robot profile as written in its TOML file.
///
/// The fields are checked against the URDF when the [`crate::RobotModel`] is built.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Profile {
    /// Name of the robot, used in messages.
    pub name: String,
    /// The URDF's path, relative to the profile file.
    pub urdf: String,
    /// The URDF's root link: the free-floating trunk.
    pub trunk: String,
    /// Tracked feet in observation order.
    pub feet: Vec<FootEntry>,
    /// Actuated joints in observation/action order, each with its standing angle.
    pub joints: Vec<JointEntry>,
    /// Where the robot is placed at reset.
    pub spawn: Spawn,
    /// Default PD gains of every joint.
    pub gains: Gains,
    /// Declared bounds of the trunk's observation rows; the spec's (HyQ's) when absent.
    #[serde(default)]
    pub observation: Option<ObservationBounds>,
    /// The scripted trot's leg map and parameters; the trot refuses a robot without one.
    #[serde(default)]
    pub gait: Option<GaitEntry>,
}

/// A tracked foot: a collision shape whose ground contact is reported.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FootEntry {
    /// Short name, e.g. `lf`.
    pub name: String,
    /// The URDF link that carries the foot's collision shape.
    pub link: String,
    /// The `name` attribute of the foot's `<collision>` element on that link. When absent,
    /// every collision shape of the link counts as the foot.
    #[serde(default)]
    pub collision: Option<String>,
}

/// An actuated joint.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct JointEntry {
    /// Short name used in observations and configuration, e.g. `lf_haa`.
    pub name: String,
    /// The URDF joint's name, e.g. `lf_haa_joint`.
    pub urdf: String,
    /// Nominal standing angle (rad).
    pub standing: f64,
    /// Proportional gain for this joint (N·m/rad); `gains.kp` when absent.
    #[serde(default)]
    pub kp: Option<f64>,
    /// Derivative gain for this joint (N·m·s/rad); `gains.kd` when absent.
    #[serde(default)]
    pub kd: Option<f64>,
    /// Lower position limit (rad) replacing the URDF's, e.g. where the URDF gives none or a
    /// placeholder. Say where the figure comes from in a comment.
    #[serde(default)]
    pub lower: Option<f64>,
    /// Upper position limit (rad) replacing the URDF's.
    #[serde(default)]
    pub upper: Option<f64>,
    /// Effort limit (N·m) replacing the URDF's.
    #[serde(default)]
    pub effort: Option<f64>,
    /// Velocity limit (rad/s) replacing the URDF's.
    #[serde(default)]
    pub velocity: Option<f64>,
}

/// Where the robot is placed at reset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Spawn {
    /// Height (m) of the trunk frame's origin above the ground, trunk level, joints at the
    /// standing pose, at rest.
    pub height: f64,
    /// Nominal standing height (m) of the trunk frame's origin: where it settles when the robot
    /// stands on flat ground at the standing pose under the default gains, as measured in the
    /// simulators. Environments put their default goal at this height. When absent, the spawn
    /// `height` is used.
    #[serde(default)]
    pub standing_height: Option<f64>,
}

/// Default PD gains of the joint actuators.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Gains {
    /// Proportional gain (N·m/rad).
    pub kp: f64,
    /// Derivative gain (N·m·s/rad).
    pub kd: f64,
}

/// Declared `[min, max]` bounds of the trunk's estimated observation rows, per axis x, y, z.
/// Either table may be left out, keeping the spec's bounds for it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ObservationBounds {
    /// Trunk linear acceleration bounds (m/s²) on x, y, z (the spec's: ±50 each).
    #[serde(default)]
    pub trunk_acceleration: Option<[[f64; 2]; 3]>,
    /// Trunk position bounds (m) on x, y, z (the spec's: ±10, ±10, [0, 1]).
    #[serde(default)]
    pub trunk_position: Option<[[f64; 2]; 3]>,
}

/// The scripted trot's description of the robot: which joints swing each leg and when, and how
/// far. See `hyq_env::policy::Trot` for the gait these drive.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GaitEntry {
    /// Gait frequency (Hz): one full cycle of every leg.
    pub frequency_hz: f64,
    /// Hip swing amplitude (rad) about the standing angle.
    pub hip_amplitude: f64,
    /// Extra knee flexion (rad) at the middle of a leg's swing, lifting the foot.
    pub knee_lift: f64,
    /// Time (s) over which the amplitudes ramp up from standing.
    pub ramp_s: f64,
    /// The legs, each with its hip and knee joint (profile short names) and its phase.
    pub legs: Vec<GaitLegEntry>,
}

/// One leg of the gait.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GaitLegEntry {
    /// The joint (short name) that swings the leg fore and aft (HyQ's `hfe`).
    pub hip: String,
    /// The joint (short name) that bends the knee, lifting the foot (HyQ's `kfe`).
    pub knee: String,
    /// The leg's phase as a fraction of a cycle in [0, 1): a trot puts diagonal pairs at 0
    /// and 0.5.
    pub phase: f64,
}

impl Profile {
    /// Parses a profile from TOML text; `origin` (a path or "bundled") appears in errors.
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Self, ModelError> {
        toml::from_str(text).map_err(|e| ModelError::Profile {
            origin: origin.to_owned(),
            message: crate::one_line(&e.to_string()),
        })
    }
}
