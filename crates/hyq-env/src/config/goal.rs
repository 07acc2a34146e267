//! `[goal]`: where the goal G of each episode is, and the checks that keep every goal the mode
//! can give inside the world.

use serde::{Deserialize, Serialize};

use super::reset::spawn_in_world;
use super::validate::{finite_positive, invalid};
use super::{ConfigError, EnvConfig, Table, in_world, outside_world_reason};

/// How the goal G of each episode is chosen (`[goal]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct GoalConfig {
    /// `"ahead"`: `distance_m` along +x from the spawn point; `"fixed"`: `position`;
    /// `"random"`: a seeded draw from `distance_range_m` and `heading_range_deg`.
    /// (default: `"ahead"`)
    pub mode: GoalMode,
    /// Distance (m) of the goal along +x from the spawn point in `"ahead"` mode. > 0, and the
    /// goal within the world ([`WORLD_HALF_EXTENT_M`](super::WORLD_HALF_EXTENT_M)). (default: 5.0)
    pub distance_m: f64,
    /// The goal's world coordinates [x, y, z] (m) in `"fixed"` mode, where it is required; each
    /// within ±[`WORLD_HALF_EXTENT_M`](super::WORLD_HALF_EXTENT_M). (default: unset)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub position: Option<[f64; 3]>,
    /// [min, max] distance (m) from the spawn point, drawn uniformly, in `"random"` mode.
    /// 0 < min ≤ max, and a goal max away in any direction within the world
    /// ([`WORLD_HALF_EXTENT_M`](super::WORLD_HALF_EXTENT_M)). (default: [3.0, 7.0])
    pub distance_range_m: [f64; 2],
    /// [min, max] heading (degrees, about +z from +x, positive to the left), drawn uniformly,
    /// in `"random"` mode. Within [−180, 180], min ≤ max. (default: [0.0, 0.0], straight
    /// ahead: the spec's yaw multiplier (§5.1) penalises any heading away from +x, so goals off
    /// the x axis are opt-in)
    pub heading_range_deg: [f64; 2],
    /// The goal's height z (m) in `"ahead"` and `"random"` modes, within ±[`WORLD_HALF_EXTENT_M`](super::WORLD_HALF_EXTENT_M).
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

/// `[goal]`: the keys of the mode only, each value in its range, and every goal the mode can
/// give from the spawn point inside the world. The goal is placed from the spawn point, so a
/// spawn point outside the world is reported first, as `[reset]`'s error, rather than blamed on
/// the goal.
impl Table for GoalConfig {
    fn validate(&self, config: &EnvConfig) -> Result<(), ConfigError> {
        spawn_in_world(&config.reset)?;
        goal_keys_match_mode(self)?;
        goal_values(self)?;
        goal_in_world(self, config.reset.spawn_xy_m)
    }
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
        // The spawn point is named too: the goal is placed from it, and either may be the
        // value to change.
        GoalMode::Ahead => (!in_world(x + g.distance_m)).then(|| {
            invalid(
                "goal.distance_m",
                g.distance_m,
                &format!(
                    "the goal {:?} m ahead of the spawn point reset.spawn_xy_m = [{x:?}, \
                     {y:?}] is at x = {:?}, and {}: move the spawn point or the goal",
                    g.distance_m,
                    x + g.distance_m,
                    outside_world_reason()
                ),
            )
        }),
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
