//! The environment's ground (`[terrain]`): the terrain each episode runs on, the robot put down
//! on it at reset, the goal's height over it, and the curriculum's level.
//!
//! Flat ground (the default) changes nothing: the robot spawns as the spec says and the goal
//! stays at its configured height. Over a height field (rules in docs/spec.md, "Terrain"):
//!
//! - the robot spawns standing on the surface under its spawn point: its trunk tilted to the
//!   plane fitted under its feet (yaw as configured), then raised until its lowest foot is as
//!   far above the surface as it is above flat ground at the spawn height (1.04 mm for HyQ);
//! - in `"ahead"` and `"random"` goal modes the goal's height is the configured height above
//!   the surface under the goal (a `"fixed"` goal is where it is given);
//! - rough ground with `seed = "episode"` is drawn anew at each reset from the reset seed's
//!   terrain stream; with a curriculum the relief is scaled by (level + 1) / levels.

use hyq_physics::na::{Isometry3, Point3};
use hyq_physics::terrain::file::{Placement, read};
use hyq_physics::terrain::generate::generate;
use hyq_physics::terrain::placement::place;
use hyq_physics::{RobotModel, RobotState, Terrain};
use rand::RngExt;
use rand_chacha::ChaCha8Rng;

use crate::config::{
    ConfigError, EnvConfig, GoalMode, MAX_SLOPE_DEG, TerrainConfig, TerrainKind, TerrainSeed,
    terrain_error,
};

/// The share of the start-to-goal distance an episode must cover for the curriculum to raise
/// the level (legged_gym raises it for robots that walked far enough).
pub const LEVEL_UP_PROGRESS: f64 = 0.5;
/// Below this share of the start-to-goal distance covered, the curriculum lowers the level.
pub const LEVEL_DOWN_PROGRESS: f64 = 0.25;

/// The ground of an environment (see the module docs).
#[derive(Clone, Debug)]
pub struct Ground {
    config: TerrainConfig,
    spawn: [f64; 2],
    goal_mode: GoalMode,
    /// The lowest foot's clearance above flat ground at the spawn height (m).
    foot_clearance: f64,
    /// The ground of the current (or next) episode.
    current: Terrain,
    /// Whether the ground is drawn anew at each reset.
    per_episode: bool,
    level: u32,
}

impl Ground {
    /// The ground of `config` for `model`: the terrain built (a height file read), the robot
    /// checked to stand on it at its spawn point. Errors name the `terrain.*` key at fault.
    pub fn new(config: &EnvConfig, model: &RobotModel) -> Result<Self, ConfigError> {
        let t = &config.terrain;
        let mut ground = Self {
            config: t.clone(),
            spawn: config.reset.spawn_xy_m,
            goal_mode: config.goal.mode,
            foot_clearance: flat_foot_clearance(model),
            current: Terrain::Flat,
            per_episode: t.curriculum || redrawn(t),
            level: 0,
        };
        if t.kind == TerrainKind::Flat {
            return Ok(ground);
        }
        // The hardest ground the configuration can give is checked once: the full relief.
        let hardest = ground.build(first_seed(t.seed), 1.0)?;
        // Coverage first: off the field the extended edge cells make any put-down fault up.
        ground.check_coverage(model, &hardest)?;
        ground.check_spawn(model, &hardest)?;
        ground.current = if t.curriculum {
            ground.build(first_seed(t.seed), ground.scale())?
        } else {
            hardest
        };
        Ok(ground)
    }

    /// The ground of the current episode.
    pub fn terrain(&self) -> &Terrain {
        &self.current
    }

    /// The curriculum's level (0 without a curriculum).
    pub fn level(&self) -> u32 {
        self.level
    }

    /// Whether the ground changes from episode to episode.
    pub fn per_episode(&self) -> bool {
        self.per_episode
    }

    /// The relief's scale at the current level.
    fn scale(&self) -> f64 {
        if self.config.curriculum {
            f64::from(self.level + 1) / f64::from(self.config.levels)
        } else {
            1.0
        }
    }

    /// The next episode's ground: with a curriculum the level moves first by the last
    /// episode's `progress` (the share of the start-to-goal distance it covered, if an episode
    /// ran); with `seed = "episode"` the heights are drawn from `rng`.
    pub fn next_episode(
        &mut self,
        rng: &mut ChaCha8Rng,
        progress: Option<f64>,
    ) -> Result<&Terrain, ConfigError> {
        if !self.per_episode {
            return Ok(&self.current);
        }
        let level = self.level;
        if self.config.curriculum
            && let Some(p) = progress
        {
            if p >= LEVEL_UP_PROGRESS {
                self.level = (self.level + 1).min(self.config.levels - 1);
            } else if p < LEVEL_DOWN_PROGRESS {
                self.level = self.level.saturating_sub(1);
            }
        }
        let seed = match self.config.seed {
            TerrainSeed::Fixed(s) => s,
            TerrainSeed::Episode => rng.random::<u64>(),
        };
        // The same ground at the same level needs no new grid (nor a rebuilt world).
        if !redrawn(&self.config) && level == self.level {
            return Ok(&self.current);
        }
        self.current = self.build(seed, self.scale())?;
        Ok(&self.current)
    }

    /// The terrain of `seed` at relief scale `scale`.
    fn build(&self, seed: u64, scale: f64) -> Result<Terrain, ConfigError> {
        let t = &self.config;
        let extent = t.extent(self.spawn);
        let grid = match (t.relief(scale), &t.file) {
            (Some(relief), _) => generate(&extent, &relief, self.spawn, seed),
            (None, Some(path)) => read(
                path,
                &Placement {
                    center: extent.center,
                    size: extent.size,
                    vertical_scale: t.vertical_scale,
                },
            ),
            (None, None) => return Ok(Terrain::Flat),
        }
        .map_err(terrain_error)?;
        Ok(Terrain::field(grid))
    }

    /// Checks that the robot can be put down standing at its spawn point on `terrain`.
    fn check_spawn(&self, model: &RobotModel, terrain: &Terrain) -> Result<(), ConfigError> {
        let mut spawn = model.spawn_state();
        spawn.trunk.pose.translation.x = self.spawn[0];
        spawn.trunk.pose.translation.y = self.spawn[1];
        let placed = place(model, terrain, &spawn, true, self.foot_clearance);
        let (roll, pitch, _) = placed.state.trunk.pose.rotation.euler_angles();
        let tilt = roll.abs().max(pitch.abs()).to_degrees();
        let t = &self.config;
        // The key that shapes the ground under the feet, with its value.
        let (key, value) = match t.kind {
            TerrainKind::Slope => ("terrain.slope_deg", format!("{:?}", t.slope_deg)),
            TerrainKind::Stairs => ("terrain.step_height_m", format!("{:?}", t.step_height_m)),
            TerrainKind::Rough => ("terrain.amplitude_m", format!("{:?}", t.amplitude_m)),
            TerrainKind::Heightfield | TerrainKind::Flat => (
                "terrain.file",
                t.file
                    .as_ref()
                    .map_or_else(String::new, |f| format!("{:?}", f.display().to_string())),
            ),
        };
        let refuse = |why: String| ConfigError::Invalid {
            key: key.to_owned(),
            value: value.clone(),
            expected: format!("the robot cannot be put down standing at its spawn point: {why}"),
        };
        if placed.other_clearance < 0.0 {
            return Err(refuse(format!(
                "a part other than its feet would be {:.0} mm in the ground",
                -1e3 * placed.other_clearance
            )));
        }
        // ±30° itself is allowed: a micro-degree of rounding in the fitted plane is not a tilt.
        if tilt > MAX_SLOPE_DEG + 1e-6 {
            return Err(refuse(format!(
                "the ground under its feet tilts it {tilt:.0}°, more than {MAX_SLOPE_DEG}°"
            )));
        }
        Ok(())
    }

    /// Checks that the field lies under the robot's feet at its spawn point: outside the
    /// field's rectangle no engine has any ground, so a robot put down there fell through at
    /// the first step (`diverged`). The error names `terrain.center_m` or `terrain.size_m`.
    fn check_coverage(&self, model: &RobotModel, terrain: &Terrain) -> Result<(), ConfigError> {
        let t = &self.config;
        let (key, value) = match t.center_m {
            Some(c) => ("terrain.center_m", format!("{c:?}")),
            None => ("terrain.size_m", format!("{:?}", t.size_m)),
        };
        let refuse = |what: String| ConfigError::Invalid {
            key: key.to_owned(),
            value: value.clone(),
            expected: format!(
                "the field does not lie under {what}: outside it there is no ground; move or \
                 widen it (terrain.center_m, terrain.size_m)"
            ),
        };
        let mut spawn = model.spawn_state();
        spawn.trunk.pose.translation.x = self.spawn[0];
        spawn.trunk.pose.translation.y = self.spawn[1];
        let placed = place(model, terrain, &spawn, true, self.foot_clearance);
        let mut poses = vec![Isometry3::identity(); model.num_links()];
        if model
            .link_poses(&placed.state.trunk.pose, &placed.state.q, &mut poses)
            .is_err()
        {
            unreachable!("the spawn state has one angle per joint and the buffer one pose per body")
        }
        for foot in &model.tracked()[..model.num_feet()] {
            let p = poses[foot.link].translation.vector;
            if !terrain.contains(p.x, p.y) {
                return Err(refuse(format!(
                    "the robot's foot {} at its spawn point [{:.2}, {:.2}]",
                    foot.name, self.spawn[0], self.spawn[1]
                )));
            }
        }
        Ok(())
    }

    /// `state` put down on the current ground (unchanged on flat ground).
    pub fn put_down(&self, model: &RobotModel, state: RobotState) -> RobotState {
        match &self.current {
            Terrain::Flat => state,
            field => place(model, field, &state, true, self.foot_clearance).state,
        }
    }

    /// The goal `goal` on the current ground: in `"ahead"` and `"random"` modes its height is
    /// taken above the surface under it; unchanged on flat ground or in `"fixed"` mode.
    pub fn goal_on_ground(&self, goal: Point3<f64>) -> Point3<f64> {
        match (&self.current, self.goal_mode) {
            (Terrain::Flat, _) | (_, GoalMode::Fixed) => goal,
            (field, _) => Point3::new(goal.x, goal.y, goal.z + field.height_at(goal.x, goal.y)),
        }
    }
}

/// Whether `t` asks for new ground at every reset: rough ground with `seed = "episode"` (the
/// other kinds use no seed).
fn redrawn(t: &TerrainConfig) -> bool {
    t.kind == TerrainKind::Rough && t.seed == TerrainSeed::Episode
}

/// The first terrain seed: the fixed one, or, for a seed drawn per episode, the draw of the
/// default reset seed's stream (the ground a never-seeded environment starts on).
fn first_seed(seed: TerrainSeed) -> u64 {
    match seed {
        TerrainSeed::Fixed(s) => s,
        TerrainSeed::Episode => 0,
    }
}

/// The lowest foot's height above flat ground when the robot stands at its spawn state.
fn flat_foot_clearance(model: &RobotModel) -> f64 {
    let spawn = model.spawn_state();
    let mut poses = vec![Isometry3::identity(); model.num_links()];
    if model
        .link_poses(&spawn.trunk.pose, &spawn.q, &mut poses)
        .is_err()
    {
        return 0.0;
    }
    (0..model.num_feet())
        .map(|t| model.tracked_lowest_z(t, &poses))
        .fold(f64::INFINITY, f64::min)
}
