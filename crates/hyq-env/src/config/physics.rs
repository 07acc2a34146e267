//! `[physics]`: the engine-independent physics parameters and one optional table per engine.

use std::collections::BTreeMap;

use hyq_physics::PhysicsParams;
use serde::de::{self, DeserializeOwned, Deserializer};
use serde::ser::Serializer;
use serde::{Deserialize, Serialize};

use super::{ConfigError, EnvConfig, Table};

/// The names of the engine tables `[physics.<name>]` a configuration may hold: one per engine of
/// hyq-engines' table. A table is read only by the backend of that name; the list exists so that
/// a misspelt engine table is an error rather than silently ignored.
pub const ENGINE_TABLES: [&str; hyq_engines::NAMES.len()] = hyq_engines::NAMES;

/// `[physics]`: hyq-physics' engine-independent [`PhysicsParams`] as plain keys, plus one
/// optional sub-table per engine (`[physics.rapier]`, `[physics.dart]`, `[physics.mujoco]`, see
/// [`ENGINE_TABLES`]) that is deserialised into that backend's `Options` when an environment
/// on it is built, so one file serves every engine.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct PhysicsConfig {
    /// dt, gravity, friction, contact distance (see [`PhysicsParams`] for each default).
    pub params: PhysicsParams,
    /// The engine tables, by engine name, as written.
    pub engines: BTreeMap<String, toml::Table>,
}

impl PhysicsConfig {
    /// The options of engine `name` (`[physics.<name>]`), or `O::default()` when the table is
    /// absent. Errors name the table and the key.
    pub fn engine_options<O: DeserializeOwned + Default>(
        &self,
        name: &str,
    ) -> Result<O, ConfigError> {
        match self.engines.get(name) {
            None => Ok(O::default()),
            Some(table) => O::deserialize(toml::Value::Table(table.clone())).map_err(|e| {
                ConfigError::Invalid {
                    key: format!("physics.{name}"),
                    value: table.to_string().trim().replace('\n', ", "),
                    expected: e.to_string(),
                }
            }),
        }
    }
}

impl Serialize for PhysicsConfig {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut table = toml::Table::try_from(&self.params).map_err(serde::ser::Error::custom)?;
        for (name, engine) in &self.engines {
            table.insert(name.clone(), toml::Value::Table(engine.clone()));
        }
        table.serialize(s)
    }
}

impl<'de> Deserialize<'de> for PhysicsConfig {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let mut table = toml::Table::deserialize(d)?;
        let mut engines = BTreeMap::new();
        for name in ENGINE_TABLES {
            match table.remove(name) {
                None => {}
                Some(toml::Value::Table(t)) => {
                    engines.insert(name.to_owned(), t);
                }
                Some(other) => {
                    return Err(de::Error::custom(format!(
                        "physics.{name} must be a table of {name} options, not `{other}`"
                    )));
                }
            }
        }
        if let Some((key, _)) = table.iter().find(|(_, v)| v.is_table()) {
            return Err(de::Error::custom(format!(
                "unknown engine table `physics.{key}` (engine tables: {})",
                ENGINE_TABLES.join(", ")
            )));
        }
        let params =
            PhysicsParams::deserialize(toml::Value::Table(table)).map_err(de::Error::custom)?;
        Ok(PhysicsConfig { params, engines })
    }
}

/// `[physics]`: the engine-independent parameters (hyq-physics' ranges); each engine table is
/// checked by its backend when an environment on that engine is built.
impl Table for PhysicsConfig {
    fn validate(&self, _: &EnvConfig) -> Result<(), ConfigError> {
        self.params.validate().map_err(|e| match e {
            hyq_physics::PhysicsError::InvalidParam {
                field,
                value,
                reason,
            } => ConfigError::Invalid {
                key: format!("physics.{field}"),
                value,
                expected: reason.to_owned(),
            },
            other => ConfigError::Invalid {
                key: "physics".into(),
                value: String::new(),
                expected: other.to_string(),
            },
        })
    }
}

/// hyq-engines reads an engine's options from the engine's table, by name (its `AnyOptions`
/// for a mixed-engine env).
impl hyq_engines::OptionsSource for PhysicsConfig {
    type Error = ConfigError;
    fn engine_options<O: DeserializeOwned + Default>(
        &self,
        engine: &str,
    ) -> Result<O, ConfigError> {
        PhysicsConfig::engine_options(self, engine)
    }
}
