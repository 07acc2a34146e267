//! The anchors' ranges as presets (`randomize.preset`), each range with where it comes from.
//! One table ([`PRESET_RANGES`]): the presets' configurations (`Preset::config`, in
//! `randomize.rs` beside the table it builds, so that this file needs nothing of the rest of the
//! configuration) and `docs/robustness.md`'s table are both read from it.
//!
//! Where an anchor's setting has no exact counterpart here, the nearest is used and the source
//! says how it differs: the anchors' pushes set the trunk's velocity (legged_gym, Isaac Lab) or
//! apply a force for a while (Playground), where pushes here add a velocity of a drawn speed in
//! a drawn direction; their gravity-vector noise becomes noise on the trunk quaternion's rows.

use serde::{Deserialize, Serialize};

/// An anchor environment whose ranges a preset takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Preset {
    /// legged_gym (`leggedrobotics/legged_gym`, `legged_robot_config.py`: `domain_rand`,
    /// `noise`).
    LeggedGym,
    /// MuJoCo Playground's Go1 (`google-deepmind/mujoco_playground`, `locomotion/go1/`:
    /// `randomize.py`, `joystick.py`).
    PlaygroundGo1,
    /// Isaac Lab's velocity task (`isaac-sim/IsaacLab`, `locomotion/velocity/
    /// velocity_env_cfg.py`: `EventCfg`, `PolicyCfg` noise).
    IsaacLab,
}

/// One preset range: its preset, its key (under `randomize.`), its value as TOML, and where it
/// comes from.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PresetRange {
    /// The preset.
    pub preset: Preset,
    /// The key under `randomize.`.
    pub key: &'static str,
    /// The value, as TOML.
    pub value: &'static str,
    /// Where the value comes from, and how it differs from the anchor's setting if it does.
    pub source: &'static str,
}

const fn r(
    preset: Preset,
    key: &'static str,
    value: &'static str,
    source: &'static str,
) -> PresetRange {
    PresetRange {
        preset,
        key,
        value,
        source,
    }
}

use Preset::{IsaacLab, LeggedGym, PlaygroundGo1};

/// Every preset's ranges, with their sources.
pub const PRESET_RANGES: &[PresetRange] = &[
    r(
        LeggedGym,
        "ground_friction",
        "[0.5, 1.25]",
        "`domain_rand.friction_range`",
    ),
    r(
        LeggedGym,
        "trunk_added_mass_kg",
        "[-1.0, 1.0]",
        "`domain_rand.added_mass_range` (off there by default: `randomize_base_mass = False`)",
    ),
    r(
        LeggedGym,
        "push_interval_s",
        "[15.0, 15.0]",
        "`domain_rand.push_interval_s`",
    ),
    r(
        LeggedGym,
        "push_velocity_xy_mps",
        "[0.0, 1.0]",
        "`domain_rand.max_push_vel_xy` (legged_gym sets x and y each to U(±1) m/s; here up to \
         1 m/s is added in a random direction)",
    ),
    r(
        LeggedGym,
        "obs_noise.distribution",
        "\"uniform\"",
        "`noise`: U(±scale × noise_level)",
    ),
    r(
        LeggedGym,
        "obs_noise.joint_angle",
        "0.01",
        "`noise_scales.dof_pos`",
    ),
    r(
        LeggedGym,
        "obs_noise.joint_speed",
        "1.5",
        "`noise_scales.dof_vel`",
    ),
    r(
        LeggedGym,
        "obs_noise.quaternion",
        "0.05",
        "`noise_scales.gravity` (on the projected gravity there)",
    ),
    r(
        PlaygroundGo1,
        "ground_friction",
        "[0.4, 1.0]",
        "floor friction U(0.4, 1.0)",
    ),
    r(
        PlaygroundGo1,
        "joint_friction_scale",
        "[0.9, 1.1]",
        "`dof_frictionloss` × U(0.9, 1.1)",
    ),
    r(
        PlaygroundGo1,
        "trunk_com_offset_m",
        "[[-0.05, 0.05], [-0.05, 0.05], [-0.05, 0.05]]",
        "torso `body_ipos` + U(±0.05)",
    ),
    r(
        PlaygroundGo1,
        "link_mass_scale",
        "[0.9, 1.1]",
        "`body_mass` × U(0.9, 1.1) (Playground leaves the inertia; here it follows the mass)",
    ),
    r(
        PlaygroundGo1,
        "trunk_added_mass_kg",
        "[-1.0, 1.0]",
        "torso mass + U(±1)",
    ),
    r(
        PlaygroundGo1,
        "push_interval_s",
        "[1.0, 3.0]",
        "`pert_config.kick_wait_times` (pushes off there by default)",
    ),
    r(
        PlaygroundGo1,
        "push_velocity_xy_mps",
        "[0.0, 3.0]",
        "`pert_config.velocity_kick` (applied there as a force over 0.05–0.2 s)",
    ),
    r(
        PlaygroundGo1,
        "obs_noise.distribution",
        "\"uniform\"",
        "`noise_config`: U(±scale)",
    ),
    r(
        PlaygroundGo1,
        "obs_noise.joint_angle",
        "0.03",
        "`noise_config.scales.joint_pos`",
    ),
    r(
        PlaygroundGo1,
        "obs_noise.joint_speed",
        "1.5",
        "`noise_config.scales.joint_vel`",
    ),
    r(
        PlaygroundGo1,
        "obs_noise.quaternion",
        "0.05",
        "`noise_config.scales.gravity` (on the gravity vector there)",
    ),
    r(
        IsaacLab,
        "trunk_com_offset_m",
        "[[-0.05, 0.05], [-0.05, 0.05], [-0.01, 0.01]]",
        "`base_com`: `randomize_rigid_body_com`",
    ),
    r(
        IsaacLab,
        "push_interval_s",
        "[10.0, 15.0]",
        "`push_robot`: `interval_range_s`",
    ),
    r(
        IsaacLab,
        "push_velocity_xy_mps",
        "[0.0, 0.1]",
        "`push_robot`: `velocity_range` x, y ±0.1 (set there; added here)",
    ),
    r(
        IsaacLab,
        "obs_noise.distribution",
        "\"uniform\"",
        "`Unoise(n_min, n_max)`",
    ),
    r(
        IsaacLab,
        "obs_noise.joint_angle",
        "0.01",
        "`joint_pos` noise",
    ),
    r(
        IsaacLab,
        "obs_noise.joint_speed",
        "1.5",
        "`joint_vel` noise",
    ),
    r(
        IsaacLab,
        "obs_noise.quaternion",
        "0.05",
        "`projected_gravity` noise (on the gravity vector there)",
    ),
];

impl Preset {
    /// Every preset.
    pub const ALL: [Preset; 3] = [Preset::LeggedGym, Preset::PlaygroundGo1, Preset::IsaacLab];

    /// The name as written in TOML.
    pub const fn as_str(self) -> &'static str {
        match self {
            Preset::LeggedGym => "legged_gym",
            Preset::PlaygroundGo1 => "playground_go1",
            Preset::IsaacLab => "isaac_lab",
        }
    }
}

/// [`PRESET_RANGES`] as the Markdown table `docs/robustness.md` shows (a test keeps the two
/// equal): one row per range, its preset, key, value and source.
pub fn preset_table() -> String {
    let mut out =
        String::from("| preset | key (`randomize.`) | value | source |\n|---|---|---|---|\n");
    for r in PRESET_RANGES {
        out.push_str(&format!(
            "| `{}` | `{}` | `{}` | {} |\n",
            r.preset.as_str(),
            r.key,
            r.value,
            r.source
        ));
    }
    out
}
