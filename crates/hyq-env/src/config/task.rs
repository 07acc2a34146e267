//! `[task]`: hyq-spec's [`TaskConfig`], the spec's §2 user variables, whose fields, defaults and
//! ranges hyq-spec states once; this table only names its keys `task.<field>`.

use hyq_spec::TaskConfig;

use super::validate::invalid;
use super::{ConfigError, EnvConfig, Table};

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
