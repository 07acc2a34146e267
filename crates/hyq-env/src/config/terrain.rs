//! `[terrain]`: the ground the robot walks on. Flat by default (the spec's environment, exactly
//! as without the table); rough ground, a slope, stairs or a user's height file otherwise, each
//! made into one height grid ([`hyq_physics::HeightGrid`]) that every engine builds.

use std::fmt;
use std::path::PathBuf;

use hyq_physics::bounds::short;
use hyq_physics::terrain::generate::{self, Climb, Extent, Relief, Rough, Slope, Stairs};
use serde::de::{self, Visitor};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::in_world;
use super::validate::{finite_positive, in_range, invalid};
use super::{ConfigError, EnvConfig, GoalConfig, GoalMode, Table, TaskKind};

/// The steepest slope (degrees) the robot is put down on: steeper, a standing quadruped's
/// feet slide or it tips over before the episode starts.
pub const MAX_SLOPE_DEG: f64 = 30.0;

/// The most difficulty levels of a terrain curriculum (`terrain.levels`).
pub const MAX_LEVELS: u32 = 100;

/// The ground (`[terrain]`).
///
/// Every generated terrain is one grid of `size_m` at `resolution_m` centred on `center_m`;
/// its relief is anchored at the spawn point (`reset.spawn_xy_m`): a slope passes through
/// height 0 there and stairs start `start_m` ahead of it. A key of another kind is refused
/// unless it holds its default (as a written-out configuration holds it), as `[goal]`'s keys
/// of another mode are: it would otherwise be silently ignored.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct TerrainConfig {
    /// `"flat"` (the plane z = 0), `"rough"`, `"slope"`, `"stairs"` or `"heightfield"` (a
    /// user's file, `file`). (default: `"flat"`)
    pub kind: TerrainKind,
    /// Rough: heights are drawn uniformly in ± this (m), in [0, 1]. (default: 0.05)
    pub amplitude_m: f64,
    /// Rough: the distance (m) between drawn heights, the size of a bump; at least
    /// `resolution_m`. (default: 0.4)
    pub feature_m: f64,
    /// Slope: its angle (degrees) within ±[`MAX_SLOPE_DEG`], negative descending towards
    /// `direction_deg`. (default: 10.0)
    pub slope_deg: f64,
    /// Slope and stairs: the direction they rise in (degrees about +z from +x, +x being towards
    /// the default goal), within ±360. (default: 0.0)
    pub direction_deg: f64,
    /// Stairs: the height of a step (m), in (0, 1]. (default: 0.1)
    pub step_height_m: f64,
    /// Stairs: the depth of a step (m), at least twice `resolution_m`. (default: 0.3)
    pub step_depth_m: f64,
    /// Stairs: `"up"` or `"down"` along `direction_deg`. (default: `"up"`)
    pub stairs: StairsClimb,
    /// Stairs: where the first step begins, ahead of the spawn point along `direction_deg`
    /// (m), within ±100. (default: 1.0)
    pub start_m: f64,
    /// Heightfield: the file of heights, NumPy `.npy` (a[i, j] at the i-th x and j-th y) or a
    /// grayscale PNG (a map seen from above), laid over the grid's rectangle; relative paths
    /// are read from the working directory. Required for `"heightfield"`. (default: unset)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub file: Option<PathBuf>,
    /// Heightfield: metres per unit of a `.npy` file's values, or the height of white in a
    /// PNG; finite and > 0. (default: 1.0)
    pub vertical_scale: f64,
    /// The grid's side lengths along x and y (m), each in (0, 200], the whole rectangle inside
    /// the world, and under every goal `[goal]` can give in the goal task (outside it there is
    /// no ground). (default: [16.0, 16.0], every goal up to 8 m from the spawn point)
    pub size_m: [f64; 2],
    /// The grid's centre [x, y] (m). (default: unset, the spawn point)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub center_m: Option<[f64; 2]>,
    /// The spacing of generated heights (m); at most 1,048,576 heights in all, and at most the
    /// field's smaller side. (default: 0.05)
    pub resolution_m: f64,
    /// Rough ground's random stream: a non-negative integer (the same ground every episode),
    /// or `"episode"` (new ground each episode, drawn from the reset seed). (default: 0)
    pub seed: TerrainSeed,
    /// A curriculum (legged_gym's rule): the relief (amplitude, slope, step height) is scaled
    /// by (level + 1) / `levels`, starting at level 0; an episode that brings the robot at
    /// least half way to the goal raises the level for the next, one that brings it less than
    /// a quarter of the way lowers it. Rough, slope and stairs only. (default: false)
    pub curriculum: bool,
    /// The number of curriculum levels, in 1..=[`MAX_LEVELS`]. (default: 10)
    pub levels: u32,
}

impl Default for TerrainConfig {
    fn default() -> Self {
        Self {
            kind: TerrainKind::Flat,
            amplitude_m: 0.05,
            feature_m: 0.4,
            slope_deg: 10.0,
            direction_deg: 0.0,
            step_height_m: 0.1,
            step_depth_m: 0.3,
            stairs: StairsClimb::Up,
            start_m: 1.0,
            file: None,
            vertical_scale: 1.0,
            size_m: [16.0, 16.0],
            center_m: None,
            resolution_m: 0.05,
            seed: TerrainSeed::Fixed(0),
            curriculum: false,
            levels: 10,
        }
    }
}

/// The kinds of ground; see [`TerrainConfig::kind`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TerrainKind {
    /// The plane z = 0.
    Flat,
    /// Random bumps.
    Rough,
    /// A plane slope.
    Slope,
    /// Straight stairs.
    Stairs,
    /// A user's file of heights.
    Heightfield,
}

impl TerrainKind {
    /// The kind as written in TOML.
    pub const fn as_str(self) -> &'static str {
        match self {
            TerrainKind::Flat => "flat",
            TerrainKind::Rough => "rough",
            TerrainKind::Slope => "slope",
            TerrainKind::Stairs => "stairs",
            TerrainKind::Heightfield => "heightfield",
        }
    }

    /// Every kind, in declaration order: the one list of them (the comparison ledger's grounds
    /// and `hyq compare --terrain`'s values are read from it).
    pub const ALL: [TerrainKind; 5] = [
        TerrainKind::Flat,
        TerrainKind::Rough,
        TerrainKind::Slope,
        TerrainKind::Stairs,
        TerrainKind::Heightfield,
    ];

    /// Whether the kind is made from the `[terrain]` table's keys alone (every kind but a
    /// user's height file), so that a name is all a command needs to build it.
    pub const fn is_generated(self) -> bool {
        !matches!(self, TerrainKind::Heightfield)
    }
}

/// Which way stairs go; see [`TerrainConfig::stairs`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum StairsClimb {
    /// Each step higher.
    Up,
    /// Each step lower.
    Down,
}

impl StairsClimb {
    /// The direction as written in TOML.
    pub const fn as_str(self) -> &'static str {
        match self {
            StairsClimb::Up => "up",
            StairsClimb::Down => "down",
        }
    }
}

/// Where rough ground's random heights come from; see [`TerrainConfig::seed`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TerrainSeed {
    /// The same ground every episode.
    Fixed(u64),
    /// New ground each episode, from the reset seed's terrain stream.
    Episode,
}

impl Serialize for TerrainSeed {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            TerrainSeed::Fixed(n) => s.serialize_u64(*n),
            TerrainSeed::Episode => s.serialize_str("episode"),
        }
    }
}

impl<'de> Deserialize<'de> for TerrainSeed {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct SeedVisitor;
        impl Visitor<'_> for SeedVisitor {
            type Value = TerrainSeed;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("a non-negative integer or \"episode\"")
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<TerrainSeed, E> {
                Ok(TerrainSeed::Fixed(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<TerrainSeed, E> {
                u64::try_from(v)
                    .map(TerrainSeed::Fixed)
                    .map_err(|_| E::invalid_value(de::Unexpected::Signed(v), &self))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<TerrainSeed, E> {
                match v {
                    "episode" => Ok(TerrainSeed::Episode),
                    _ => Err(E::invalid_value(de::Unexpected::Str(v), &self)),
                }
            }
        }
        d.deserialize_any(SeedVisitor)
    }
}

impl TerrainConfig {
    /// Whether every key holds its default (the table is then not written).
    pub fn is_default(&self) -> bool {
        *self == Self::default()
    }

    /// The rectangle and resolution of the grid for a robot spawned at `spawn`.
    pub fn extent(&self, spawn: [f64; 2]) -> Extent {
        Extent {
            center: self.center_m.unwrap_or(spawn),
            size: self.size_m,
            resolution: self.resolution_m,
        }
    }

    /// The relief of a generated kind at curriculum scale `scale` (1 without a curriculum);
    /// `None` for flat ground and height files.
    pub fn relief(&self, scale: f64) -> Option<Relief> {
        match self.kind {
            TerrainKind::Flat | TerrainKind::Heightfield => None,
            TerrainKind::Rough => Some(Relief::Rough(Rough {
                amplitude: self.amplitude_m * scale,
                feature: self.feature_m,
            })),
            TerrainKind::Slope => Some(Relief::Slope(Slope {
                angle_deg: self.slope_deg * scale,
                direction_deg: self.direction_deg,
            })),
            TerrainKind::Stairs => Some(Relief::Stairs(Stairs {
                step_height: self.step_height_m * scale,
                step_depth: self.step_depth_m,
                direction_deg: self.direction_deg,
                climb: match self.stairs {
                    StairsClimb::Up => Climb::Up,
                    StairsClimb::Down => Climb::Down,
                },
                start: self.start_m,
            })),
        }
    }
}

impl TerrainConfig {
    /// The field's size and centre: each side in (0, the largest side], the centre finite, and
    /// the whole field inside the world around it (the spawn point when no centre is given).
    fn check_placement(&self, config: &EnvConfig) -> Result<(), ConfigError> {
        let max_side = hyq_physics::terrain::MAX_SIDE_M;
        if !self
            .size_m
            .iter()
            .all(|s| s.is_finite() && *s > 0.0 && *s <= max_side)
        {
            return Err(invalid(
                "terrain.size_m",
                self.size_m,
                &format!("each side must be in (0, {max_side}] m"),
            ));
        }
        if let Some(c) = self.center_m
            && !c.iter().all(|v| v.is_finite())
        {
            return Err(invalid("terrain.center_m", c, "must be finite (m)"));
        }
        let [cx, cy] = self.center_m.unwrap_or(config.reset.spawn_xy_m);
        let inside = |c: f64, side: f64| in_world(c - 0.5 * side) && in_world(c + 0.5 * side);
        if !(inside(cx, self.size_m[0]) && inside(cy, self.size_m[1])) {
            // The centre the user gave is the key at fault; else the size around the spawn point.
            let (key, value) = match self.center_m {
                Some(c) => ("terrain.center_m", c),
                None => ("terrain.size_m", self.size_m),
            };
            return Err(invalid(
                key,
                value,
                &format!(
                    "puts the field's edge outside the world around its centre ({}, {}): {}",
                    short(cx),
                    short(cy),
                    super::outside_world_reason()
                ),
            ));
        }
        Ok(())
    }
}

impl TerrainConfig {
    /// Every goal the `[goal]` table can give lies on the field (the goal task only): outside
    /// the field's rectangle there is no ground, so a robot walking to such a goal walks off
    /// the edge and every episode ends `diverged` before it can reach it. The key blamed is
    /// the field's (`terrain.center_m` when given, else `terrain.size_m`); the message names
    /// the goal's key and, for a height file, the file laid over the field.
    fn check_goal_on_field(&self, config: &EnvConfig) -> Result<(), ConfigError> {
        if config.task.kind != TaskKind::Goal {
            return Ok(());
        }
        let [cx, cy] = self.center_m.unwrap_or(config.reset.spawn_xy_m);
        let [hx, hy] = self.size_m.map(|s| 0.5 * s);
        // A goal on the edge is on the field; the slack absorbs cos 90° != 0.
        let on = |[x, y]: [f64; 2]| (x - cx).abs() <= hx + 1e-9 && (y - cy).abs() <= hy + 1e-9;
        // A field not under the spawn point is refused when the environment is built, naming
        // the robot's feet (`crate::terrain::Ground`): the robot's fault is the first to name.
        if !on(config.reset.spawn_xy_m) {
            return Ok(());
        }
        let Some(goal) = goal_extremes(&config.goal, config.reset.spawn_xy_m)
            .into_iter()
            .find(|g| !on(*g))
        else {
            return Ok(());
        };
        let (key, value) = match self.center_m {
            Some(c) => ("terrain.center_m", c),
            None => ("terrain.size_m", self.size_m),
        };
        let g = &config.goal;
        let goal_key = match g.mode {
            GoalMode::Ahead => format!("goal.distance_m = {}", short(g.distance_m)),
            GoalMode::Fixed => "goal.position".to_owned(),
            GoalMode::Random => "goal.distance_range_m, goal.heading_range_deg".to_owned(),
        };
        let file = match &self.file {
            Some(f) if self.kind == TerrainKind::Heightfield => {
                format!(
                    "; terrain.file {:?} is laid over it",
                    f.display().to_string()
                )
            }
            _ => String::new(),
        };
        Err(invalid(
            key,
            value,
            &format!(
                "the field (x {:.2} .. {:.2}, y {:.2} .. {:.2} m) is not under the goal [{:.2}, \
                 {:.2}] ({goal_key}): off the field there is no ground; widen or move the \
                 field, or bring the goal onto it{file}",
                cx - hx,
                cx + hx,
                cy - hy,
                cy + hy,
                goal[0],
                goal[1]
            ),
        ))
    }
}

impl TerrainConfig {
    /// A generated grid's spacing is never wider than its field: `resolution_m` at most the
    /// field's smaller side (a wider one was silently the side, and then blamed on
    /// `feature_m`). The key named is the one the user changed: the size when the resolution
    /// holds its default.
    fn check_resolution_fits_the_field(&self) -> Result<(), ConfigError> {
        let side = self.size_m[0].min(self.size_m[1]);
        if !(self.kind.is_generated() && (self.resolution_m.is_nan() || self.resolution_m > side)) {
            return Ok(());
        }
        let d = Self::default();
        // A field shrunk below the default spacing is the size's fault, not the resolution's.
        if self.resolution_m == d.resolution_m && self.size_m != d.size_m {
            return Err(invalid(
                "terrain.size_m",
                self.size_m,
                &format!(
                    "each side must be at least terrain.resolution_m = {}, the grid's spacing: \
                     set a finer resolution for a field this small",
                    short(self.resolution_m)
                ),
            ));
        }
        Err(resolution_error(
            self.resolution_m,
            format!(
                "must be at most {} m, the field's smaller side (terrain.size_m = {:?}): the \
                 grid's spacing is never wider than its field",
                short(side),
                self.size_m
            ),
        ))
    }

    /// A generator's refusal of a bump or a step too small for the grid's spacing blames
    /// `resolution_m` when that is the key the user changed (the bump's or step's key holding
    /// its default); every other refusal is [`keyed`] as it comes.
    fn blame_resolution(&self, e: hyq_physics::TerrainError) -> ConfigError {
        let d = Self::default();
        let finer_than = match &e {
            hyq_physics::TerrainError::Invalid { what, .. }
                if self.resolution_m != d.resolution_m =>
            {
                match what.as_str() {
                    "feature_m" if self.feature_m == d.feature_m => Some((
                        format!("terrain.feature_m = {}", short(self.feature_m)),
                        "the grid's spacing must be at most the size of a bump",
                    )),
                    "step_depth_m" if self.step_depth_m == d.step_depth_m => Some((
                        format!("terrain.step_depth_m = {}", short(self.step_depth_m)),
                        "twice the grid's spacing must be at most a step's depth",
                    )),
                    _ => None,
                }
            }
            _ => None,
        };
        match finer_than {
            Some((other, why)) => resolution_error(
                self.resolution_m,
                format!(
                    "is too coarse for {other} ({why}): lower terrain.resolution_m, or set \
                     {}",
                    other.split(' ').next().unwrap_or_default()
                ),
            ),
            None => keyed(e),
        }
    }
}

/// A refusal of `terrain.resolution_m = value`, the value printed short.
fn resolution_error(value: f64, expected: String) -> ConfigError {
    ConfigError::Invalid {
        key: "terrain.resolution_m".to_owned(),
        value: short(value),
        expected,
    }
}

/// The goals of `g` from the spawn point `spawn` that reach furthest along ±x and ±y: the one
/// goal of the `"ahead"` and `"fixed"` modes; for `"random"`, each end of the distance range
/// at each end of the heading range and at every axis direction (0°, ±90°, ±180°) inside it,
/// where x = d cos ψ and y = d sin ψ take their extremes. Every goal the mode can draw lies
/// inside an axis-aligned rectangle that holds these.
fn goal_extremes(g: &GoalConfig, spawn: [f64; 2]) -> Vec<[f64; 2]> {
    let [sx, sy] = spawn;
    match g.mode {
        GoalMode::Ahead => vec![[sx + g.distance_m, sy]],
        // Invariant: `[goal]` is validated first and requires a position in this mode.
        GoalMode::Fixed => g.position.map(|[x, y, _]| vec![[x, y]]).unwrap_or_default(),
        GoalMode::Random => {
            let [lo, hi] = g.heading_range_deg;
            let mut headings = vec![lo, hi];
            headings.extend(
                [-180.0, -90.0, 0.0, 90.0, 180.0]
                    .into_iter()
                    .filter(|a| (lo..=hi).contains(a)),
            );
            let mut goals = Vec::new();
            for d in g.distance_range_m {
                for psi in &headings {
                    let (sin, cos) = psi.to_radians().sin_cos();
                    goals.push([sx + d * cos, sy + d * sin]);
                }
            }
            goals
        }
    }
}

/// `[terrain]`: the generator's ranges for the kind chosen (named `terrain.<key>`), the slope
/// within ±[`MAX_SLOPE_DEG`], a file for `"heightfield"`, the curriculum's levels and kinds.
impl Table for TerrainConfig {
    fn validate(&self, config: &EnvConfig) -> Result<(), ConfigError> {
        keys_match_kind(self)?;
        if self.kind == TerrainKind::Flat {
            return Ok(());
        }
        self.check_placement(config)?;
        self.check_resolution_fits_the_field()?;
        self.check_goal_on_field(config)?;
        in_range(
            "terrain.slope_deg",
            self.slope_deg,
            -MAX_SLOPE_DEG,
            MAX_SLOPE_DEG,
            &format!(
                "must be within ±{MAX_SLOPE_DEG} degrees: on a steeper slope the robot cannot \
                 be put down standing"
            ),
        )?;
        if self.kind == TerrainKind::Heightfield {
            finite_positive("terrain.vertical_scale", self.vertical_scale)?;
            if self.file.is_none() {
                return Err(invalid(
                    "terrain.file",
                    "unset",
                    "is required when terrain.kind = \"heightfield\" (a .npy or .png file)",
                ));
            }
        }
        if !(1..=MAX_LEVELS).contains(&self.levels) {
            return Err(invalid(
                "terrain.levels",
                self.levels,
                &format!("must be in 1..={MAX_LEVELS}"),
            ));
        }
        let extent = self.extent(config.reset.spawn_xy_m);
        match self.relief(1.0) {
            Some(relief) => generate::check(&extent, &relief)
                .map(|_| ())
                .map_err(|e| self.blame_resolution(e)),
            None => Ok(()),
        }
    }
}

/// The kinds that read each key other than `kind`, in the order of the table.
const KIND_KEYS: [(&str, &[TerrainKind]); 16] = {
    use TerrainKind::{Heightfield, Rough, Slope, Stairs};
    const GENERATED: &[TerrainKind] = &[Rough, Slope, Stairs];
    [
        ("amplitude_m", &[Rough]),
        ("feature_m", &[Rough]),
        ("slope_deg", &[Slope]),
        ("direction_deg", &[Slope, Stairs]),
        ("step_height_m", &[Stairs]),
        ("step_depth_m", &[Stairs]),
        ("stairs", &[Stairs]),
        ("start_m", &[Stairs]),
        ("file", &[Heightfield]),
        ("vertical_scale", &[Heightfield]),
        ("size_m", &[Rough, Slope, Stairs, Heightfield]),
        ("center_m", &[Rough, Slope, Stairs, Heightfield]),
        ("resolution_m", GENERATED),
        ("seed", &[Rough]),
        ("curriculum", GENERATED),
        ("levels", GENERATED),
    ]
};

/// `Some(value as written)` when `value` is not `default`.
fn differs<T: PartialEq + fmt::Debug>(value: &T, default: &T) -> Option<String> {
    (value != default).then(|| format!("{value:?}"))
}

/// The value of `t`'s key `key` (one of [`KIND_KEYS`]) if it is not its default.
fn changed(t: &TerrainConfig, key: &str) -> Option<String> {
    let d = TerrainConfig::default();
    match key {
        "amplitude_m" => differs(&t.amplitude_m, &d.amplitude_m),
        "feature_m" => differs(&t.feature_m, &d.feature_m),
        "slope_deg" => differs(&t.slope_deg, &d.slope_deg),
        "direction_deg" => differs(&t.direction_deg, &d.direction_deg),
        "step_height_m" => differs(&t.step_height_m, &d.step_height_m),
        "step_depth_m" => differs(&t.step_depth_m, &d.step_depth_m),
        "stairs" => (t.stairs != d.stairs).then(|| format!("\"{}\"", t.stairs.as_str())),
        "file" => t
            .file
            .as_ref()
            .map(|f| format!("{:?}", f.display().to_string())),
        "vertical_scale" => differs(&t.vertical_scale, &d.vertical_scale),
        "size_m" => differs(&t.size_m, &d.size_m),
        "center_m" => t.center_m.map(|c| format!("{c:?}")),
        "resolution_m" => differs(&t.resolution_m, &d.resolution_m),
        "seed" => (t.seed != d.seed).then(|| seed_text(t.seed)),
        "curriculum" => differs(&t.curriculum, &d.curriculum),
        "levels" => differs(&t.levels, &d.levels),
        "start_m" => differs(&t.start_m, &d.start_m),
        _ => None,
    }
}

/// A key of another kind would be silently ignored: it is an error, unless it holds its
/// default (a written-out configuration holds every key). The first such key, in the order of
/// the table, is named with its value and the kinds that read it.
fn keys_match_kind(t: &TerrainConfig) -> Result<(), ConfigError> {
    for (key, kinds) in KIND_KEYS {
        if kinds.contains(&t.kind) {
            continue;
        }
        if let Some(value) = changed(t, key) {
            let kinds: Vec<String> = kinds
                .iter()
                .map(|k| format!("\"{}\"", k.as_str()))
                .collect();
            return Err(ConfigError::Invalid {
                key: format!("terrain.{key}"),
                value,
                expected: format!(
                    "is only read when terrain.kind = {}, and the kind is \"{}\": set \
                     terrain.kind, or remove the key",
                    kinds.join(" or "),
                    t.kind.as_str()
                ),
            });
        }
    }
    Ok(())
}

/// A terrain seed as written in TOML.
fn seed_text(seed: TerrainSeed) -> String {
    match seed {
        TerrainSeed::Fixed(n) => n.to_string(),
        TerrainSeed::Episode => "\"episode\"".into(),
    }
}

/// A terrain error as a configuration error: a generator's parameter named `terrain.<name>`
/// (its reasons start with the value), a height file's fault under `terrain.file`.
pub(crate) fn keyed(e: hyq_physics::TerrainError) -> ConfigError {
    match e {
        hyq_physics::TerrainError::Invalid { what, reason } => {
            let (value, expected) = reason.split_once(' ').unwrap_or(("", reason.as_str()));
            ConfigError::Invalid {
                key: format!("terrain.{what}"),
                value: value.to_owned(),
                expected: expected.to_owned(),
            }
        }
        hyq_physics::TerrainError::File { path, reason } => ConfigError::Invalid {
            key: "terrain.file".into(),
            value: format!("{:?}", path.display().to_string()),
            expected: reason,
        },
        other => ConfigError::Invalid {
            key: "terrain".into(),
            value: String::new(),
            expected: other.to_string(),
        },
    }
}
