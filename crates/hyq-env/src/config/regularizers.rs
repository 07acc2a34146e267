//! `[regularizers]`: the gait regularisers added to the spec's goal task's reward, each term's
//! scale a key over a preset, every one off by default (docs/regularizers.md). The keys,
//! meanings, defaults and ranges are hyq-tasks' ([`RegularizerConfig`]); this table only names
//! them `regularizers.<key>`. Read only under `task.kind = "goal"` (the velocity task has its
//! own regularisers in `[velocity]`; set under `"velocity"`, the table is an error) and not
//! written when it holds its defaults.

use hyq_tasks::RegularizerConfig;

use super::{ConfigError, EnvConfig, Table, TaskKind};

impl Table for RegularizerConfig {
    fn validate(&self, config: &EnvConfig) -> Result<(), ConfigError> {
        RegularizerConfig::validate(self).map_err(|e| ConfigError::Invalid {
            key: e.key,
            value: e.value,
            expected: e.expected,
        })?;
        if config.task.kind == TaskKind::Velocity && !self.is_default() {
            return Err(ConfigError::Invalid {
                key: "task.kind".into(),
                value: format!("{:?}", config.task.kind.as_str()),
                expected: "must be \"goal\" when [regularizers] is set (the velocity task's \
                           regularisers are [velocity]'s keys)"
                    .into(),
            });
        }
        Ok(())
    }
}
