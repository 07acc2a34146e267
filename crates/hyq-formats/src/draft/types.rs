//! What the drafting steps share: the error, the robot description a draft is built from, and
//! the comments that say where each drafted value came from.

use hyq_physics::{ModelError, Profile, RobotModel};

use crate::mjcf_read::{MjcfReadError, MjcfRobot};

/// The joint velocity limit (rad/s) drafted where the file gives none (MJCF has no such
/// attribute): of the order of the field's quadrupeds' (Go1's knee 20 rad/s, its hip 30).
pub const DEFAULT_VELOCITY: f64 = 20.0;

/// The gap (m) between the ground and the robot's lowest point at spawn.
pub const CLEARANCE: f64 = 0.001;

/// The scripted trot drafted for a named quadruped: frequency (Hz), hip amplitude (rad), knee
/// lift (rad), ramp (s): ANYmal C's tuned figures.
pub const TROT: [f64; 4] = [2.0, 0.15, 0.3, 1.0];

/// Why a profile could not be drafted: one line, naming the file and what was wrong.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{0}")]
pub struct DraftError(pub String);

impl DraftError {
    /// An error about `origin` (a file), folded onto one line.
    pub(crate) fn at(origin: &str, message: impl std::fmt::Display) -> Self {
        DraftError(hyq_physics::one_line(&format!("{origin}: {message}")))
    }
}

impl From<MjcfReadError> for DraftError {
    fn from(e: MjcfReadError) -> Self {
        DraftError(e.0)
    }
}

/// The robot description a draft is built from: a URDF, or an MJCF robot (whose actuators,
/// keyframes and armature a URDF cannot hold).
#[derive(Debug, Clone)]
pub(crate) enum Source {
    /// A URDF file, parsed.
    Urdf(urdf_rs::Robot),
    /// An MJCF file, read.
    Mjcf(Box<MjcfRobot>),
}

impl Source {
    /// The robot as a URDF description (links, joints, collisions).
    pub(crate) fn description(&self) -> &urdf_rs::Robot {
        match self {
            Source::Urdf(r) => r,
            Source::Mjcf(m) => &m.robot,
        }
    }

    /// The model of this robot with `profile`.
    pub(crate) fn model(&self, profile: &Profile) -> Result<RobotModel, ModelError> {
        match self {
            Source::Urdf(r) => RobotModel::from_urdf_model(r, profile),
            Source::Mjcf(m) => m.model(profile),
        }
    }

    /// "URDF" or "MJCF", for comments.
    pub(crate) fn format(&self) -> &'static str {
        match self {
            Source::Urdf(_) => "URDF",
            Source::Mjcf(_) => "MJCF",
        }
    }
}

/// Where each drafted value came from, one comment (possibly several sentences) per part of
/// the profile, written above it; per-entry comments sit beside their entries.
#[derive(Debug, Clone, Default)]
pub(crate) struct Notes {
    /// The file's header: what made it and from what.
    pub(crate) header: Vec<String>,
    /// The robot file and what the reader left out.
    pub(crate) robot_file: String,
    /// The trunk.
    pub(crate) trunk: String,
    /// The feet: how they were found.
    pub(crate) feet: String,
    /// One per foot.
    pub(crate) foot: Vec<String>,
    /// The joints: order, names, standing pose, limits.
    pub(crate) joints: String,
    /// One per joint.
    pub(crate) joint: Vec<String>,
    /// The spawn height.
    pub(crate) spawn_height: String,
    /// The standing height.
    pub(crate) standing_height: String,
    /// The gains.
    pub(crate) gains: String,
    /// The gait, or why there is none.
    pub(crate) gait: String,
}
