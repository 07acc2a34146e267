//! `[reset]`: where and how the robot is placed at reset, and the reset noise.

use serde::{Deserialize, Serialize};

use super::validate::{in_range, invalid};
use super::{ConfigError, EnvConfig, Table, in_world, outside_world_reason};

/// The widest reset joint noise (rad, `reset.joint_noise_rad`): a full turn. Wider noise only
/// piles the angles up at the joint limits, where they are clipped.
pub const JOINT_NOISE_MAX_RAD: f64 = std::f64::consts::TAU;

/// Where and how the robot is placed at reset (`[reset]`).
///
/// The robot always starts at rest, trunk level (up to `yaw_deg`), joints at the profile's
/// standing pose, the trunk frame at the profile's spawn height. Noise is drawn from the reset
/// seed's noise stream, separate from the goal stream.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ResetConfig {
    /// The spawn point's [x, y] (m, world), each within ±[`WORLD_HALF_EXTENT_M`](super::WORLD_HALF_EXTENT_M). (default:
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

/// `reset.spawn_xy_m`: inside the world.
pub(super) fn spawn_in_world(r: &ResetConfig) -> Result<(), ConfigError> {
    if !r.spawn_xy_m.iter().all(|v| in_world(*v)) {
        return Err(invalid(
            "reset.spawn_xy_m",
            r.spawn_xy_m,
            &outside_world_reason(),
        ));
    }
    Ok(())
}

/// `[reset]`: the spawn point inside the world, the yaw and the noise in their ranges.
impl Table for ResetConfig {
    fn validate(&self, _: &EnvConfig) -> Result<(), ConfigError> {
        spawn_in_world(self)?;
        in_range(
            "reset.yaw_deg",
            self.yaw_deg,
            -180.0,
            180.0,
            "must be in [-180, 180] degrees",
        )?;
        in_range(
            "reset.yaw_noise_deg",
            self.yaw_noise_deg,
            0.0,
            180.0,
            "must be in [0, 180] degrees",
        )?;
        in_range(
            "reset.joint_noise_rad",
            self.joint_noise_rad,
            0.0,
            JOINT_NOISE_MAX_RAD,
            &format!(
                "must be in [0, {JOINT_NOISE_MAX_RAD}] rad (a full turn; wider noise only \
                 piles the angles up at the joint limits)"
            ),
        )
    }
}
