//! `[task]`: hyq-spec's [`TaskConfig`], the spec's §2 user variables, whose fields, defaults and
//! ranges hyq-spec states once; this table only names its keys `task.<field>`.

use hyq_spec::TaskConfig;

use super::validate::invalid;
use super::{ConfigError, EnvConfig, Table};

impl Table for TaskConfig {
    fn validate(&self, _: &EnvConfig) -> Result<(), ConfigError> {
        TaskConfig::validate(self).map_err(|e| match e {
            hyq_spec::ConfigError::Real {
                field,
                value,
                expected,
            } => invalid(
                &format!("task.{field}"),
                value,
                &format!("must be {expected}"),
            ),
            hyq_spec::ConfigError::Integer {
                field,
                value,
                expected,
            } => invalid(
                &format!("task.{field}"),
                value,
                &format!("must be {expected}"),
            ),
        })
    }
}
