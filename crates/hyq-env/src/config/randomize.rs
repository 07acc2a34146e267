//! `[randomize]`: which variations an environment draws per episode and per step, and from
//! which ranges. Every key is optional and off when absent, so an empty (or absent) table is the
//! spec's environment exactly.

use serde::{Deserialize, Serialize};

use super::presets::{PRESET_RANGES, Preset};
use super::{ConfigError, EnvConfig, Table};

/// A range `[lo, hi]` drawn uniformly (lo = hi draws that value).
pub type Range = [f64; 2];

/// The largest factor a scale range may reach (kp, kd, effort, masses, damping, friction): a
/// factor of 100 is far beyond any randomisation in use (the anchors stay within 0.5–2), and
/// larger ones describe another robot rather than a varied one.
pub const SCALE_MAX: f64 = 100.0;

/// The largest trunk centre-of-mass offset on any axis (m): half a metre is beyond any trunk's
/// size (HyQ's is 1 m long); the anchors move it by at most 5 cm.
pub const COM_OFFSET_MAX_M: f64 = 0.5;

/// The largest push speed on any axis (m/s): the anchors' strongest kick is 3 m/s.
pub const PUSH_SPEED_MAX_MPS: f64 = 100.0;

/// The largest mass added to or removed from the trunk (kg): the robot bounds table's largest
/// moving body ([`hyq_physics::bounds::BODY_MASS`], what every engine holds faithfully). Whether
/// the trunk's drawn mass itself stays inside that table depends on the robot, and is checked
/// when an environment is built ([`crate::randomize::check_for_robot`]).
pub const ADDED_MASS_MAX_KG: f64 = hyq_physics::bounds::BODY_MASS.high;

/// The smallest contact stiffness or damping factor: a contact 100 times softer (or less
/// damped) than an engine's own lets a standing robot sink centimetres, beyond any variation in
/// use.
pub const CONTACT_SCALE_MIN: f64 = 0.01;

/// The largest ground friction coefficient.
pub const FRICTION_MAX: f64 = 10.0;

/// The largest observation-noise deviation (in each row's unit): beyond it the noise would hide
/// every row's signal, and it keeps every noisy value finite.
pub const NOISE_MAX: f64 = 1000.0;

/// `[randomize]` (see the module docs and `docs/robustness.md`): ranges drawn per episode at
/// reset, observation noise drawn per step, pushes. A `preset` fills every range it names;
/// keys written beside it override the preset's.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct RandomizeConfig {
    /// The ranges of an anchor environment (`"legged_gym"`, `"playground_go1"`,
    /// `"isaac_lab"`; see [`Preset`]), under the keys below. (default: none)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub preset: Option<Preset>,
    /// Ground friction coefficient (the value itself), in [0, 10]. (default: off, the
    /// `physics.ground_friction`)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub ground_friction: Option<Range>,
    /// Mass added to the trunk at its centre of mass (kg; negative removes), its inertia
    /// following its mass, within ±1e6 kg; the trunk's drawn mass must stay within the robot
    /// bounds table's [1e-4, 1e6] kg. (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trunk_added_mass_kg: Option<Range>,
    /// Offset of the trunk's centre of mass along its link frame's x, y, z (m, three ranges),
    /// each within ±0.5 m. (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trunk_com_offset_m: Option<[Range; 3]>,
    /// Factor of every body's mass and inertia, drawn per body, in (0, 100]; every drawn body
    /// must stay within the robot bounds table (mass in [1e-4, 1e6] kg, principal moments in
    /// [1e-8, 1e6] kg·m²). (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub link_mass_scale: Option<Range>,
    /// Factor of every joint's kp, drawn per joint, in (0, 100]. (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kp_scale: Option<Range>,
    /// Factor of every joint's kd, drawn per joint, in (0, 100]. (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub kd_scale: Option<Range>,
    /// Factor of every joint's effort limit, drawn per joint, in (0, 100]. (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub effort_scale: Option<Range>,
    /// Factor of every joint's viscous damping, drawn per joint, in [0, 100]. (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint_damping_scale: Option<Range>,
    /// Factor of every joint's Coulomb friction (the shared actuator's), drawn per joint, in
    /// [0, 100]. (default: off; HyQ's and ANYmal C's joints have none to scale)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint_friction_scale: Option<Range>,
    /// The actuator's delay in physics sub-steps, an integer range drawn per episode: the PD law
    /// sees the joint targets this many sub-steps late; at most one env step
    /// (`control.sim_steps_per_env_step`). (default: off, 0)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub actuator_delay_substeps: Option<[u32; 2]>,
    /// Factor of the engine's own ground-contact stiffness, in [0.01, 100]; each engine maps
    /// it onto its contact model (docs/randomization.md). (default: off, 1)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_stiffness_scale: Option<Range>,
    /// Factor of the engine's own ground-contact damping, in [0.01, 100]. (default: off, 1)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_damping_scale: Option<Range>,
    /// The ground contact's restitution coefficient, in [0, 1] (0 is inelastic, the spec's
    /// contact). (default: off, 0)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub restitution: Option<Range>,
    /// Noise on what the policy observes, drawn per step. (default: off)
    #[serde(skip_serializing_if = "ObsNoiseConfig::is_off")]
    pub obs_noise: ObsNoiseConfig,
    /// Time between pushes (s), drawn anew after each push, > 0; the first push comes one draw
    /// after reset. Needs a push velocity. (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub push_interval_s: Option<Range>,
    /// Speed of a push along the ground (m/s), in a direction drawn uniformly, ≥ 0. (default:
    /// off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub push_velocity_xy_mps: Option<Range>,
    /// Vertical speed of a push (m/s, up positive). (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub push_velocity_z_mps: Option<Range>,
}

/// `[randomize.obs_noise]`: per row group, a deviation in the rows' unit (rad, rad/s, quaternion
/// units, m/s², m), and the probability of flipping each contact flag.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ObsNoiseConfig {
    /// `"gaussian"`: the deviation is the standard deviation; `"uniform"`: the noise is
    /// U(−d, d) (legged_gym's and Isaac Lab's convention). (default: `"gaussian"`)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub distribution: Option<NoiseDistribution>,
    /// Joint angle rows (rad), in [0, 1000]. (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint_angle: Option<f64>,
    /// Joint speed rows (rad/s). (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub joint_speed: Option<f64>,
    /// Trunk quaternion rows (clipped to [−1, 1] after the noise). (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub quaternion: Option<f64>,
    /// Trunk acceleration rows (m/s²). (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trunk_accel: Option<f64>,
    /// Trunk position rows (m). (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub trunk_position: Option<f64>,
    /// The velocity task's `base_lin_vel_*` rows (m/s); no rows under the spec's task.
    /// (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub base_lin_vel: Option<f64>,
    /// The velocity task's `base_ang_vel_*` rows (rad/s). (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub base_ang_vel: Option<f64>,
    /// The velocity task's `projected_gravity_*` rows (1). (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub projected_gravity: Option<f64>,
    /// Probability in [0, 1] that each contact flag reads flipped. (default: off)
    #[serde(skip_serializing_if = "Option::is_none")]
    pub contact_flip: Option<f64>,
}

/// How observation noise is distributed; see [`ObsNoiseConfig::distribution`].
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum NoiseDistribution {
    /// Normal, the deviation its standard deviation.
    #[default]
    Gaussian,
    /// Uniform in ±the deviation.
    Uniform,
}

impl ObsNoiseConfig {
    /// Whether no row gets noise.
    pub fn is_off(&self) -> bool {
        self.deviations().iter().all(|(_, d)| d.is_none()) && self.contact_flip.is_none()
    }

    /// Each deviation with its key.
    pub fn deviations(&self) -> [(&'static str, Option<f64>); 8] {
        [
            ("joint_angle", self.joint_angle),
            ("joint_speed", self.joint_speed),
            ("quaternion", self.quaternion),
            ("trunk_accel", self.trunk_accel),
            ("trunk_position", self.trunk_position),
            ("base_lin_vel", self.base_lin_vel),
            ("base_ang_vel", self.base_ang_vel),
            ("projected_gravity", self.projected_gravity),
        ]
    }

    /// `self` with every unset key taken from `under`.
    fn over(&self, under: &Self) -> Self {
        Self {
            distribution: self.distribution.or(under.distribution),
            joint_angle: self.joint_angle.or(under.joint_angle),
            joint_speed: self.joint_speed.or(under.joint_speed),
            quaternion: self.quaternion.or(under.quaternion),
            trunk_accel: self.trunk_accel.or(under.trunk_accel),
            trunk_position: self.trunk_position.or(under.trunk_position),
            base_lin_vel: self.base_lin_vel.or(under.base_lin_vel),
            base_ang_vel: self.base_ang_vel.or(under.base_ang_vel),
            projected_gravity: self.projected_gravity.or(under.projected_gravity),
            contact_flip: self.contact_flip.or(under.contact_flip),
        }
    }
}

impl RandomizeConfig {
    /// Whether nothing is randomised: no preset and no key (the spec's environment).
    pub fn is_off(&self) -> bool {
        *self == Self::default()
    }

    /// The ranges in effect: the preset's, with every key written here over them (`preset`
    /// itself cleared).
    pub fn effective(&self) -> Self {
        let Some(preset) = self.preset else {
            return self.clone();
        };
        let base = preset.config();
        Self {
            preset: None,
            ground_friction: self.ground_friction.or(base.ground_friction),
            trunk_added_mass_kg: self.trunk_added_mass_kg.or(base.trunk_added_mass_kg),
            trunk_com_offset_m: self.trunk_com_offset_m.or(base.trunk_com_offset_m),
            link_mass_scale: self.link_mass_scale.or(base.link_mass_scale),
            kp_scale: self.kp_scale.or(base.kp_scale),
            kd_scale: self.kd_scale.or(base.kd_scale),
            effort_scale: self.effort_scale.or(base.effort_scale),
            joint_damping_scale: self.joint_damping_scale.or(base.joint_damping_scale),
            joint_friction_scale: self.joint_friction_scale.or(base.joint_friction_scale),
            actuator_delay_substeps: self
                .actuator_delay_substeps
                .or(base.actuator_delay_substeps),
            contact_stiffness_scale: self
                .contact_stiffness_scale
                .or(base.contact_stiffness_scale),
            contact_damping_scale: self.contact_damping_scale.or(base.contact_damping_scale),
            restitution: self.restitution.or(base.restitution),
            obs_noise: self.obs_noise.over(&base.obs_noise),
            push_interval_s: self.push_interval_s.or(base.push_interval_s),
            push_velocity_xy_mps: self.push_velocity_xy_mps.or(base.push_velocity_xy_mps),
            push_velocity_z_mps: self.push_velocity_z_mps.or(base.push_velocity_z_mps),
        }
    }

    /// Whether an option that changes the physics (friction, masses, damping, the contact) is
    /// on.
    pub fn varies_dynamics(&self) -> bool {
        self.ground_friction.is_some()
            || self.trunk_added_mass_kg.is_some()
            || self.trunk_com_offset_m.is_some()
            || self.link_mass_scale.is_some()
            || self.joint_damping_scale.is_some()
            || self.contact_stiffness_scale.is_some()
            || self.contact_damping_scale.is_some()
            || self.restitution.is_some()
    }

    /// Whether pushes are on.
    pub fn pushes(&self) -> bool {
        self.push_interval_s.is_some()
    }

    /// Checks the ranges in effect (see [`RandomizeConfig::effective`]) against what keeps
    /// every drawn world physical and every number finite; `substeps` is
    /// `control.sim_steps_per_env_step` and `env_step_s` the env step's length (that times
    /// `physics.dt`). The error names the key and the value. What depends on the robot (every
    /// drawn body inside the robot bounds table) is checked when an environment is
    /// built ([`crate::randomize::check_for_robot`]).
    pub fn check(&self, substeps: u32, env_step_s: f64) -> Result<(), ConfigError> {
        let e = self.effective();
        range(
            "randomize.ground_friction",
            e.ground_friction,
            0.0,
            FRICTION_MAX,
            false,
        )?;
        range(
            "randomize.trunk_added_mass_kg",
            e.trunk_added_mass_kg,
            -ADDED_MASS_MAX_KG,
            ADDED_MASS_MAX_KG,
            false,
        )?;
        if let Some(axes) = e.trunk_com_offset_m {
            for r in axes {
                range(
                    "randomize.trunk_com_offset_m",
                    Some(r),
                    -COM_OFFSET_MAX_M,
                    COM_OFFSET_MAX_M,
                    false,
                )
                .map_err(|err| with_value(err, &format!("{axes:?}")))?;
            }
        }
        for (key, r) in [
            ("randomize.link_mass_scale", e.link_mass_scale),
            ("randomize.kp_scale", e.kp_scale),
            ("randomize.kd_scale", e.kd_scale),
            ("randomize.effort_scale", e.effort_scale),
        ] {
            range(key, r, 0.0, SCALE_MAX, true)?;
        }
        for (key, r) in [
            ("randomize.joint_damping_scale", e.joint_damping_scale),
            ("randomize.joint_friction_scale", e.joint_friction_scale),
        ] {
            range(key, r, 0.0, SCALE_MAX, false)?;
        }
        for (key, r) in [
            (
                "randomize.contact_stiffness_scale",
                e.contact_stiffness_scale,
            ),
            ("randomize.contact_damping_scale", e.contact_damping_scale),
        ] {
            range(key, r, CONTACT_SCALE_MIN, SCALE_MAX, false)?;
        }
        range("randomize.restitution", e.restitution, 0.0, 1.0, false)?;
        if let Some([lo, hi]) = e.actuator_delay_substeps
            && (lo > hi || hi > substeps)
        {
            return Err(ConfigError::Invalid {
                key: "randomize.actuator_delay_substeps".into(),
                value: format!("[{lo}, {hi}]"),
                expected: format!(
                    "must be [lo, hi] with lo <= hi <= control.sim_steps_per_env_step = \
                     {substeps}: a delay longer than an env step is not kept"
                ),
            });
        }
        e.obs_noise.validate()?;
        e.validate_pushes(env_step_s)
    }

    fn validate_pushes(&self, env_step_s: f64) -> Result<(), ConfigError> {
        range(
            "randomize.push_interval_s",
            self.push_interval_s,
            0.0,
            f64::MAX,
            true,
        )?;
        // Pushes come at the start of an env step, at most one per step: an interval shorter
        // than a step would push at every step whatever its value.
        if let Some(r) = self.push_interval_s
            && r[0] < env_step_s
        {
            return Err(ConfigError::Invalid {
                key: "randomize.push_interval_s".into(),
                value: format!("{r:?}"),
                expected: format!(
                    "must have lo >= {env_step_s} s, one env step (control.sim_steps_per_env_step \
                     × physics.dt): pushes come at most once per env step, so a shorter interval \
                     would push at every step"
                ),
            });
        }
        range(
            "randomize.push_velocity_xy_mps",
            self.push_velocity_xy_mps,
            0.0,
            PUSH_SPEED_MAX_MPS,
            false,
        )?;
        range(
            "randomize.push_velocity_z_mps",
            self.push_velocity_z_mps,
            -PUSH_SPEED_MAX_MPS,
            PUSH_SPEED_MAX_MPS,
            false,
        )?;
        let speed = self.push_velocity_xy_mps.is_some() || self.push_velocity_z_mps.is_some();
        match (self.push_interval_s, speed) {
            (Some(r), false) => Err(ConfigError::Invalid {
                key: "randomize.push_interval_s".into(),
                value: format!("{r:?}"),
                expected: "pushes need a speed: set randomize.push_velocity_xy_mps or \
                           randomize.push_velocity_z_mps too"
                    .into(),
            }),
            (None, true) => Err(ConfigError::Invalid {
                key: if self.push_velocity_xy_mps.is_some() {
                    "randomize.push_velocity_xy_mps".into()
                } else {
                    "randomize.push_velocity_z_mps".into()
                },
                value: self
                    .push_velocity_xy_mps
                    .or(self.push_velocity_z_mps)
                    .map_or_else(String::new, |r| format!("{r:?}")),
                expected: "pushes need a time between them: set randomize.push_interval_s too"
                    .into(),
            }),
            _ => Ok(()),
        }
    }
}

/// `[randomize]`: the ranges in effect (a preset's, overridden by the keys written) physical
/// and finite, the delay within an env step.
impl Table for RandomizeConfig {
    fn validate(&self, config: &EnvConfig) -> Result<(), ConfigError> {
        let substeps = config.control.sim_steps_per_env_step;
        self.check(substeps, f64::from(substeps) * config.physics.params.dt)
    }
}

impl ObsNoiseConfig {
    fn validate(&self) -> Result<(), ConfigError> {
        for (name, d) in self.deviations() {
            if let Some(d) = d
                && !(d.is_finite() && (0.0..=NOISE_MAX).contains(&d))
            {
                return Err(ConfigError::Invalid {
                    key: format!("randomize.obs_noise.{name}"),
                    value: format!("{d:?}"),
                    expected: format!("must be a deviation in [0, {NOISE_MAX}]"),
                });
            }
        }
        if let Some(p) = self.contact_flip
            && !(0.0..=1.0).contains(&p)
        {
            return Err(ConfigError::Invalid {
                key: "randomize.obs_noise.contact_flip".into(),
                value: format!("{p:?}"),
                expected: "must be a probability in [0, 1]".into(),
            });
        }
        Ok(())
    }
}

/// `r` (when set) is ordered and finite.
fn ordered(key: &str, r: Range) -> Result<(), ConfigError> {
    let [lo, hi] = r;
    if lo.is_finite() && hi.is_finite() && lo <= hi {
        Ok(())
    } else {
        Err(ConfigError::Invalid {
            key: key.to_owned(),
            value: format!("{r:?}"),
            expected: "must be a finite range [lo, hi] with lo <= hi".into(),
        })
    }
}

/// `r` (when set) is ordered, finite and within [min, max] (`open_min`: lo > min).
fn range(
    key: &str,
    r: Option<Range>,
    min: f64,
    max: f64,
    open_min: bool,
) -> Result<(), ConfigError> {
    let Some(r) = r else { return Ok(()) };
    ordered(key, r)?;
    let [lo, hi] = r;
    let low_ok = if open_min { lo > min } else { lo >= min };
    if low_ok && hi <= max {
        return Ok(());
    }
    let low = if open_min { "lo >" } else { "lo >=" };
    let high = if max == f64::MAX {
        String::new()
    } else {
        format!(" and hi <= {max}")
    };
    let why = match (open_min && min == 0.0, key == "randomize.push_interval_s") {
        (true, true) => {
            ": pushes need time between them (an interval of 0 or less would push at \
                         every step)"
        }
        (true, false) => {
            ": a factor of 0 or less cannot be drawn (a mass, gain or effort must \
                          stay positive)"
        }
        (false, _) => "",
    };
    Err(ConfigError::Invalid {
        key: key.to_owned(),
        value: format!("{r:?}"),
        expected: format!("must have {low} {min}{high}{why}"),
    })
}

/// `err` with its value replaced by `value` (the whole key's, for a key of several ranges).
fn with_value(err: ConfigError, value: &str) -> ConfigError {
    match err {
        ConfigError::Invalid { key, expected, .. } => ConfigError::Invalid {
            key,
            value: value.to_owned(),
            expected,
        },
        other => other,
    }
}

impl Preset {
    /// The preset's ranges as a `[randomize]` table (built from [`PRESET_RANGES`]).
    pub fn config(self) -> RandomizeConfig {
        let mut table = toml::Table::new();
        for range in PRESET_RANGES.iter().filter(|r| r.preset == self) {
            let value: toml::Value = toml::from_str::<toml::Table>(&format!("v = {}", range.value))
                .ok()
                .and_then(|mut t| t.remove("v"))
                .unwrap_or_else(|| unreachable!("preset value {} is TOML", range.value));
            match range.key.split_once('.') {
                Some((table_name, key)) => {
                    let sub = table
                        .entry(table_name.to_owned())
                        .or_insert_with(|| toml::Value::Table(toml::Table::new()));
                    if let toml::Value::Table(sub) = sub {
                        sub.insert(key.to_owned(), value);
                    }
                }
                None => {
                    table.insert(range.key.to_owned(), value);
                }
            }
        }
        RandomizeConfig::deserialize(toml::Value::Table(table)).unwrap_or_else(|e| {
            unreachable!("preset {} is a [randomize] table: {e}", self.as_str())
        })
    }
}

#[cfg(test)]
mod tests {
    //! Every preset is a valid table whose ranges are the table's, and keys written beside a
    //! preset win over it.
    #![allow(clippy::unwrap_used)]

    use super::*;

    #[test]
    fn every_preset_is_valid_and_holds_its_rows() {
        for preset in Preset::ALL {
            let c = preset.config();
            assert!(!c.is_off(), "{} sets something", preset.as_str());
            c.check(10, 0.01).unwrap();
            assert_eq!(c.obs_noise.distribution, Some(NoiseDistribution::Uniform));
            let rows = PRESET_RANGES.iter().filter(|r| r.preset == preset).count();
            assert!(rows >= 5, "{} has {rows} rows", preset.as_str());
        }
        let lg = Preset::LeggedGym.config();
        assert_eq!(lg.ground_friction, Some([0.5, 1.25]));
        assert_eq!(lg.obs_noise.joint_speed, Some(1.5));
        let go1 = Preset::PlaygroundGo1.config();
        assert_eq!(
            go1.trunk_com_offset_m,
            Some([[-0.05, 0.05], [-0.05, 0.05], [-0.05, 0.05]])
        );
    }

    #[test]
    fn keys_beside_a_preset_override_it() {
        let c = RandomizeConfig {
            preset: Some(Preset::LeggedGym),
            ground_friction: Some([0.8, 0.9]),
            ..RandomizeConfig::default()
        };
        let e = c.effective();
        assert_eq!(e.preset, None);
        assert_eq!(e.ground_friction, Some([0.8, 0.9]));
        assert_eq!(e.push_interval_s, Some([15.0, 15.0]));
        assert_eq!(
            RandomizeConfig::default().effective(),
            RandomizeConfig::default()
        );
    }
}
