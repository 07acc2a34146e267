//! `[task]`: which task the environment poses (`kind`: the spec's `"goal"`, the default, or
//! `"velocity"`, hyq-tasks' velocity-command task, docs/velocity.md), and hyq-spec's
//! [`TaskConfig`], the spec's §2 user variables, whose fields, defaults and ranges hyq-spec
//! states once; this table only names its keys `task.<field>`.
//!
//! `kind` is the environment's key, not the spec's: [`TaskTable`] reads it beside the spec's
//! keys and hands the rest to hyq-spec's own reader, so hyq-spec keeps the spec alone. A table
//! of the default kind is written without it, so a written default configuration is what it was
//! before the key existed. The table derefs to the spec's [`TaskConfig`]
//! (`config.task.max_time_steps`).

use std::ops::{Deref, DerefMut};

use hyq_spec::TaskConfig;
use serde::de::Error as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use super::validate::invalid;
use super::{ConfigError, EnvConfig, Table};

/// Which task an environment poses.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum TaskKind {
    /// The spec's: walk the trunk to a goal (hyq-spec).
    #[default]
    Goal,
    /// Follow a commanded forward, sideways and turning speed (hyq-tasks, `[command]`,
    /// `[velocity]`).
    Velocity,
}

impl TaskKind {
    /// Every kind, the spec's first.
    pub const ALL: [TaskKind; 2] = [TaskKind::Goal, TaskKind::Velocity];

    /// The name a configuration writes.
    pub fn as_str(self) -> &'static str {
        match self {
            TaskKind::Goal => "goal",
            TaskKind::Velocity => "velocity",
        }
    }
}

/// `[task]`: the task's kind and the spec's user variables.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct TaskTable {
    /// Which task: `"goal"` (the spec's, default) or `"velocity"`.
    pub kind: TaskKind,
    /// The spec's §2 user variables (t_max, `max_time_steps`, is both tasks' time limit).
    pub spec: TaskConfig,
}

impl From<TaskConfig> for TaskTable {
    fn from(spec: TaskConfig) -> Self {
        Self {
            kind: TaskKind::Goal,
            spec,
        }
    }
}

impl Deref for TaskTable {
    type Target = TaskConfig;
    fn deref(&self) -> &TaskConfig {
        &self.spec
    }
}

impl DerefMut for TaskTable {
    fn deref_mut(&mut self) -> &mut TaskConfig {
        &mut self.spec
    }
}

impl<'de> Deserialize<'de> for TaskTable {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let mut table = toml::Table::deserialize(deserializer)?;
        let kind = match table.remove("kind") {
            Some(v) => TaskKind::deserialize(v)
                .map_err(|e| D::Error::custom(format!("task.kind: {}", e.message())))?,
            None => TaskKind::Goal,
        };
        let spec = TaskConfig::deserialize(toml::Value::Table(table))
            .map_err(|e| D::Error::custom(e.message()))?;
        Ok(Self { kind, spec })
    }
}

impl Serialize for TaskTable {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        /// The spec's keys after `kind`, in their own order.
        #[derive(Serialize)]
        struct WithKind<'a> {
            kind: TaskKind,
            #[serde(flatten)]
            spec: &'a TaskConfig,
        }
        match self.kind {
            // Exactly the spec's table, as before the key existed.
            TaskKind::Goal => self.spec.serialize(serializer),
            kind => WithKind {
                kind,
                spec: &self.spec,
            }
            .serialize(serializer),
        }
    }
}

impl Table for TaskTable {
    fn validate(&self, config: &EnvConfig) -> Result<(), ConfigError> {
        if self.kind == TaskKind::Goal {
            for (table, default) in [
                ("command", config.command == Default::default()),
                ("velocity", config.velocity == Default::default()),
            ] {
                if !default {
                    return Err(invalid(
                        "task.kind",
                        self.kind.as_str(),
                        &format!("must be \"velocity\" when [{table}] is set"),
                    ));
                }
            }
        }
        Table::validate(&self.spec, config)
    }
}

impl Table for TaskConfig {
    fn validate(&self, _: &EnvConfig) -> Result<(), ConfigError> {
        use hyq_spec::ConfigError as E;
        TaskConfig::validate(self).map_err(|e| match e {
            E::Real {
                field,
                value,
                expected,
            } => task_invalid(field, value, expected),
            E::Integer {
                field,
                value,
                expected,
            } => task_invalid(field, value, expected),
        })
    }
}

/// hyq-spec's refusal of `field`'s `value` as the error of key `task.<field>`.
fn task_invalid(field: &str, value: impl std::fmt::Debug, expected: &str) -> ConfigError {
    invalid(
        &format!("task.{field}"),
        value,
        &format!("must be {expected}"),
    )
}
