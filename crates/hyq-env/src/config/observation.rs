//! `[observation]`: rows added after the spec's §3 observation, opt in. With none (the
//! default) the observation is the spec's, row for row.

use serde::{Deserialize, Serialize};

use super::validate::invalid;
use super::{ConfigError, EnvConfig, Table};

/// The most height-scan points (`observation.height_scan_*`): 1024, legged_gym's 187 with
/// room to spare.
pub const MAX_SCAN_POINTS: usize = 1024;

/// How far (m) from the trunk a height-scan point may be, along x or y.
pub const MAX_SCAN_REACH_M: f64 = 5.0;

/// Observation rows beyond the spec's (`[observation]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ObservationConfig {
    /// Row groups appended after the spec's rows, each at most once, always in the order
    /// `height_scan`, `goal_vector`, `trunk_velocity` whatever the order listed: `"height_scan"`
    /// (the ground's height at a grid of points around the trunk, in its heading frame, minus the
    /// trunk's height: legged_gym's `measured_heights`), `"goal_vector"` (G − C in the trunk's
    /// frame, 3 rows), `"trunk_velocity"` (the trunk's linear and angular velocity in its frame,
    /// 6 rows). (default: [], the spec's observation)
    pub extra: Vec<ObservationExtra>,
    /// The height scan's [back, front] extent along the trunk's heading (m), within ±5,
    /// back < front. (default: [−0.8, 0.8])
    pub height_scan_x_m: [f64; 2],
    /// The height scan's [right, left] extent across it (m), within ±5, right < left.
    /// (default: [−0.5, 0.5])
    pub height_scan_y_m: [f64; 2],
    /// The spacing of height-scan points (m), > 0.01; at most [`MAX_SCAN_POINTS`] points.
    /// (default: 0.1, legged_gym's 17 × 11 grid)
    pub height_scan_spacing_m: f64,
}

impl Default for ObservationConfig {
    fn default() -> Self {
        Self {
            extra: Vec::new(),
            height_scan_x_m: [-0.8, 0.8],
            height_scan_y_m: [-0.5, 0.5],
            height_scan_spacing_m: 0.1,
        }
    }
}

/// A group of observation rows beyond the spec's; see [`ObservationConfig::extra`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ObservationExtra {
    /// The ground's height around the trunk.
    HeightScan,
    /// The goal in the trunk's frame.
    GoalVector,
    /// The trunk's velocity in its frame.
    TrunkVelocity,
}

impl ObservationExtra {
    /// The group as written in TOML, and the prefix of its rows' names.
    pub const fn as_str(self) -> &'static str {
        match self {
            ObservationExtra::HeightScan => "height_scan",
            ObservationExtra::GoalVector => "goal_vector",
            ObservationExtra::TrunkVelocity => "trunk_velocity",
        }
    }
}

impl ObservationConfig {
    /// Whether every key holds its default (the table is then not written).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// The groups asked for, in their fixed order.
    pub fn groups(&self) -> Vec<ObservationExtra> {
        let mut g = self.extra.clone();
        g.sort_unstable();
        g
    }

    /// The height scan's positions along x (back to front) and along y (right to left) in the
    /// trunk's heading frame (m): from each extent's low end by the spacing, its high end
    /// included when the spacing divides the extent (to a micrometre).
    pub fn scan_axes(&self) -> (Vec<f64>, Vec<f64>) {
        let axis = |[lo, hi]: [f64; 2]| -> Vec<f64> {
            let s = self.height_scan_spacing_m;
            let n = ((hi - lo) / s + 1e-6).floor() as usize;
            (0..=n).map(|i| lo + i as f64 * s).collect()
        };
        (axis(self.height_scan_x_m), axis(self.height_scan_y_m))
    }

    /// The height scan's points (x, y) in the trunk's heading frame, x-major: back to front,
    /// and right to left within each.
    pub fn scan_points(&self) -> Vec<[f64; 2]> {
        let (xs, ys) = self.scan_axes();
        xs.iter()
            .flat_map(|&x| ys.iter().map(move |&y| [x, y]))
            .collect()
    }
}

/// `[observation]`: each group at most once, the scan's extents ordered and within reach, its
/// spacing positive and its points capped.
impl Table for ObservationConfig {
    fn validate(&self, _: &EnvConfig) -> Result<(), ConfigError> {
        let groups = self.groups();
        if let Some(w) = groups.windows(2).find(|w| w[0] == w[1]) {
            return Err(invalid(
                "observation.extra",
                w[0].as_str(),
                "is listed twice: each group is added once",
            ));
        }
        for (key, [lo, hi]) in [
            ("observation.height_scan_x_m", self.height_scan_x_m),
            ("observation.height_scan_y_m", self.height_scan_y_m),
        ] {
            let inside = |v: f64| v.is_finite() && v.abs() <= MAX_SCAN_REACH_M;
            if !(inside(lo) && inside(hi) && lo < hi) {
                return Err(invalid(
                    key,
                    [lo, hi],
                    &format!(
                        "must be [low, high] with low < high, each within ±{MAX_SCAN_REACH_M} m"
                    ),
                ));
            }
        }
        let s = self.height_scan_spacing_m;
        if !(s.is_finite() && s > 0.01) {
            return Err(invalid(
                "observation.height_scan_spacing_m",
                s,
                "must be finite and > 0.01 m",
            ));
        }
        let per_axis = |[lo, hi]: [f64; 2]| ((hi - lo) / s).floor() + 1.0;
        let n = per_axis(self.height_scan_x_m) * per_axis(self.height_scan_y_m);
        if n > MAX_SCAN_POINTS as f64 {
            return Err(invalid(
                "observation.height_scan_spacing_m",
                s,
                &format!("gives {n} scan points, more than the cap of {MAX_SCAN_POINTS}"),
            ));
        }
        Ok(())
    }
}
