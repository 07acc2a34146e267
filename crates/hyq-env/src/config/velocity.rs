//! `[command]` and `[velocity]`: the velocity task's command ranges and resampling, and its
//! reward scales (a preset and any key on top) with its optional trunk-contact termination.
//! Their keys, meanings, defaults and ranges are hyq-tasks' ([`CommandConfig`],
//! [`VelocityConfig`]); these tables only name them `command.<key>` and `velocity.<key>`.
//! Both are read only under `task.kind = "velocity"` (set under `"goal"`, they are an error)
//! and are not written when they hold their defaults.

use hyq_tasks::{CommandConfig, VelocityConfig};

use super::{ConfigError, EnvConfig, Table};

/// hyq-tasks' refusal as the configuration's error.
fn keyed(e: hyq_tasks::ConfigError) -> ConfigError {
    ConfigError::Invalid {
        key: e.key,
        value: e.value,
        expected: e.expected,
    }
}

impl Table for CommandConfig {
    fn validate(&self, _: &EnvConfig) -> Result<(), ConfigError> {
        CommandConfig::validate(self).map_err(keyed)
    }
}

impl Table for VelocityConfig {
    fn validate(&self, _: &EnvConfig) -> Result<(), ConfigError> {
        VelocityConfig::validate(self).map_err(keyed)
    }
}

/// Whether `c` holds its defaults (the table is then not written).
pub(crate) fn is_default_command(c: &CommandConfig) -> bool {
    *c == CommandConfig::default()
}

/// Whether `c` holds its defaults (the table is then not written).
pub(crate) fn is_default_velocity(c: &VelocityConfig) -> bool {
    *c == VelocityConfig::default()
}
