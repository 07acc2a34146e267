//! `[control]`: the PD actuator's gains and the sub-stepping.

use std::fmt;

use serde::de::{self, Deserializer};
use serde::ser::Serializer;
use serde::{Deserialize, Serialize};

use super::validate::invalid;
use super::{ConfigError, EnvConfig, Table};

/// The PD actuator and the sub-stepping (`[control]`).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct ControlConfig {
    /// Physics sub-steps per env step (the spec's §6.3 "10 simulator steps per gym step"); the
    /// env step lasts `sim_steps_per_env_step · physics.dt`. In 1..=1000. (default: 10)
    pub sim_steps_per_env_step: u32,
    /// Proportional gains (N·m/rad): `"profile"` for the robot profile's, one number for every
    /// joint, or one per joint in action order. Finite, ≥ 0. (default: `"profile"`, 1000 for
    /// HyQ)
    pub kp: Gains,
    /// Derivative gains (N·m·s/rad), as `kp`. (default: `"profile"`, 20 for HyQ)
    pub kd: Gains,
    /// Whether the actuator honours the URDF velocity limits (hyq-physics' actuator rule 2).
    /// (default: true)
    pub velocity_limit: bool,
}

impl Default for ControlConfig {
    fn default() -> Self {
        Self {
            sim_steps_per_env_step: 10,
            kp: Gains::Profile,
            kd: Gains::Profile,
            velocity_limit: true,
        }
    }
}

/// Gains as written in `[control]`: the profile's, one for all joints, or one per joint.
#[derive(Clone, Debug, Default, PartialEq)]
pub enum Gains {
    /// The robot profile's gains (written `"profile"`).
    #[default]
    Profile,
    /// The same gain for every joint (a number).
    All(f64),
    /// One gain per joint in action order (an array).
    PerJoint(Vec<f64>),
}

impl Gains {
    /// The gains for `n` joints, `profile` being the profile's; `None` when a per-joint list has
    /// the wrong length.
    pub fn resolve(&self, profile: &[f64]) -> Option<Vec<f64>> {
        match self {
            Gains::Profile => Some(profile.to_vec()),
            Gains::All(g) => Some(vec![*g; profile.len()]),
            Gains::PerJoint(v) => (v.len() == profile.len()).then(|| v.clone()),
        }
    }
}

/// As written in TOML: `"profile"`, a number, or an array of numbers.
impl fmt::Display for Gains {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Gains::Profile => f.write_str("\"profile\""),
            Gains::All(g) => write!(f, "{g:?}"),
            Gains::PerJoint(v) => write!(f, "{v:?}"),
        }
    }
}

impl Serialize for Gains {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        match self {
            Gains::Profile => s.serialize_str("profile"),
            Gains::All(g) => s.serialize_f64(*g),
            Gains::PerJoint(v) => v.serialize(s),
        }
    }
}

impl<'de> Deserialize<'de> for Gains {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        struct V;
        impl<'de> de::Visitor<'de> for V {
            type Value = Gains;
            fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
                f.write_str("\"profile\", a number, or an array of one number per joint")
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Gains, E> {
                if v == "profile" {
                    Ok(Gains::Profile)
                } else {
                    Err(E::invalid_value(de::Unexpected::Str(v), &self))
                }
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Gains, E> {
                Ok(Gains::All(v))
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Gains, E> {
                Ok(Gains::All(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Gains, E> {
                Ok(Gains::All(v as f64))
            }
            fn visit_seq<A: de::SeqAccess<'de>>(self, mut seq: A) -> Result<Gains, A::Error> {
                let mut out = Vec::new();
                while let Some(g) = seq.next_element::<f64>()? {
                    out.push(g);
                }
                Ok(Gains::PerJoint(out))
            }
        }
        d.deserialize_any(V)
    }
}

/// `[control]`: the sub-step count and the gains.
impl Table for ControlConfig {
    fn validate(&self, _: &EnvConfig) -> Result<(), ConfigError> {
        if !(1..=1000).contains(&self.sim_steps_per_env_step) {
            return Err(invalid(
                "control.sim_steps_per_env_step",
                self.sim_steps_per_env_step,
                "must be in 1..=1000",
            ));
        }
        gains_ok("control.kp", &self.kp)?;
        gains_ok("control.kd", &self.kd)
    }
}

/// Gains as written are finite and ≥ 0 (their count is checked against the robot when an
/// environment is built).
fn gains_ok(key: &str, g: &Gains) -> Result<(), ConfigError> {
    let ok = |v: &f64| v.is_finite() && *v >= 0.0;
    match g {
        Gains::Profile => Ok(()),
        Gains::All(v) if ok(v) => Ok(()),
        Gains::PerJoint(v) if v.iter().all(ok) => Ok(()),
        other => Err(ConfigError::Invalid {
            key: key.to_owned(),
            value: other.to_string(),
            expected: "gains must be finite and >= 0".to_owned(),
        }),
    }
}
