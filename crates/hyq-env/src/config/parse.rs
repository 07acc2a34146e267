//! Reading a configuration, the same way for every front: TOML text, a file, and dotted-key
//! overrides (`hyq --config FILE --set table.key=value`, Python's keyword arguments and
//! `env_config`), each validated as a whole.

use std::path::Path;

use serde::Deserialize;

use super::messages::parser_message;
use super::{ConfigError, EnvConfig, LoadError};

/// The largest configuration file read (bytes): 1 MiB, hundreds of times any real
/// configuration, so that a wrong path (`/dev/zero`, a log file) is refused at once rather than
/// read until memory runs out.
pub const CONFIG_FILE_MAX_BYTES: usize = 1 << 20;

impl EnvConfig {
    /// Parses and validates a configuration from TOML text; `origin` (a path, or "text")
    /// appears in errors.
    ///
    /// Errors give the line of the offending key where the text has it: the parser's position for
    /// syntax, unknown keys and wrong types; for a value out of its range, the line of that key,
    /// found in the text (values are checked once the whole text is read).
    pub fn from_toml_str(text: &str, origin: &str) -> Result<Self, ConfigError> {
        let at = |key: &str, message: String| ConfigError::Parse {
            origin: origin.to_owned(),
            message: match line_of(text, key) {
                Some(line) => format!("line {line}: {message}"),
                None => message,
            },
        };
        let config: EnvConfig = toml::from_str(text).map_err(|e| ConfigError::Parse {
            origin: origin.to_owned(),
            message: parser_message(&e.to_string()),
        })?;
        config.validate().map_err(|e| match &e {
            ConfigError::Invalid { key, .. } => at(key, e.to_string()),
            _ => e,
        })?;
        Ok(config)
    }

    /// The configuration the fronts build (`hyq --config FILE --set KEY=VALUE`, and Python's
    /// `config_file=` with keyword arguments): the defaults, or `file`'s, with `overrides`
    /// (dotted key, TOML value) set on top by [`EnvConfig::set_all`], validated. The error says
    /// which of the two was wrong.
    pub fn load<K: AsRef<str>, V: AsRef<str>>(
        file: Option<&Path>,
        overrides: &[(K, V)],
    ) -> Result<Self, LoadError> {
        let mut config = match file {
            Some(path) => Self::from_file(path).map_err(LoadError::File)?,
            None => Self::default(),
        };
        if !overrides.is_empty() {
            let pairs: Vec<(&str, &str)> = overrides
                .iter()
                .map(|(k, v)| (k.as_ref(), v.as_ref()))
                .collect();
            config.set_all(&pairs).map_err(LoadError::Overrides)?;
        }
        Ok(config)
    }

    /// Reads, parses and validates a configuration file of at most
    /// [`CONFIG_FILE_MAX_BYTES`].
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, ConfigError> {
        use std::io::Read;
        let path = path.as_ref();
        let io = |message: String| ConfigError::Io {
            path: path.display().to_string(),
            message,
        };
        let mut bytes = Vec::new();
        std::fs::File::open(path)
            .and_then(|f| {
                f.take(CONFIG_FILE_MAX_BYTES as u64 + 1)
                    .read_to_end(&mut bytes)
            })
            .map_err(|e| io(e.to_string()))?;
        if bytes.len() > CONFIG_FILE_MAX_BYTES {
            return Err(io(format!(
                "larger than {} MiB, which no configuration is (is it the right file?)",
                CONFIG_FILE_MAX_BYTES >> 20
            )));
        }
        let text = String::from_utf8(bytes).map_err(|e| io(format!("not UTF-8 text: {e}")))?;
        Self::from_toml_str(&text, &path.display().to_string())
    }

    /// The configuration as TOML text, every key written (defaults included), so that it reads
    /// back to an equal configuration.
    pub fn to_toml_string(&self) -> String {
        // Invariant: every field serialises to TOML (numbers, strings, arrays, tables; the
        // optional fields are skipped when unset), which the round-trip test checks.
        toml::to_string(self).unwrap_or_else(|e| unreachable!("EnvConfig serialises: {e}"))
    }

    /// Sets one value by its dotted key, e.g. `set("task.fall_penalty", "1.5")`,
    /// `set("task.exp_rew_scaling", "off")` or `set("physics.rapier.solver_iterations", "4")`,
    /// then validates the whole configuration. Same as [`EnvConfig::set_all`] with one pair.
    pub fn set(&mut self, key: &str, value: &str) -> Result<(), ConfigError> {
        self.set_all(&[(key, value)])
    }

    /// Sets several values by their dotted keys, then validates the whole configuration once,
    /// so that values that only make sense together can be given together
    /// (`goal.mode=fixed` with `goal.position=[5, 1, 0.6]`). This is what the CLI's `--set`
    /// options and the Python keyword arguments use.
    ///
    /// Each value is read as a TOML value (number, boolean, array, quoted string); anything
    /// that is not one is taken as a bare string, so `mode=random` works unquoted. An unknown
    /// key, or a value of the wrong type or outside its range, is an error naming that key and
    /// value; a combination that is invalid as a whole is an error naming the offending key. On
    /// error the configuration is unchanged.
    pub fn set_all(&mut self, pairs: &[(&str, &str)]) -> Result<(), ConfigError> {
        let mut doc = toml::Table::try_from(&*self).map_err(|e| ConfigError::Parse {
            origin: "configuration".into(),
            message: e.to_string(),
        })?;
        let mut config = self.clone();
        for (key, value) in pairs {
            // One line: the CLI prints errors on one line.
            let fail = |message: String| ConfigError::Set {
                key: (*key).to_owned(),
                value: (*value).to_owned(),
                message: parser_message(&message),
            };
            let path: Vec<&str> = key.split('.').collect();
            if path.len() < 2 || path.iter().any(|p| p.is_empty()) {
                return Err(fail(
                    "a key is `table.name`, e.g. `task.fall_penalty` or \
                     `physics.rapier.solver_iterations`"
                        .into(),
                ));
            }
            let parsed = match toml::from_str::<toml::Table>(&format!("v = {value}")) {
                Ok(mut t) => t.remove("v"),
                // An integer TOML cannot hold: say so, rather than read it as a bare string.
                Err(_) if is_integer_literal(value) => {
                    return Err(fail(
                        "not an integer a configuration can hold: TOML's integers are 64-bit \
                         signed, from -9223372036854775808 to 9223372036854775807"
                            .into(),
                    ));
                }
                Err(_) => None,
            }
            .unwrap_or_else(|| toml::Value::String((*value).to_owned()));
            let mut table = &mut doc;
            for part in &path[..path.len() - 1] {
                let entry = table
                    .entry(part.to_string())
                    .or_insert_with(|| toml::Value::Table(toml::Table::new()));
                table = match entry {
                    toml::Value::Table(t) => t,
                    _ => return Err(fail(format!("`{part}` is a value, not a table"))),
                };
            }
            table.insert(path[path.len() - 1].to_owned(), parsed);
            // Deserialised after every pair, so an unknown key or a wrong type is blamed on the
            // pair that brought it.
            config = EnvConfig::deserialize(toml::Value::Table(doc.clone()))
                .map_err(|e| fail(e.to_string()))?;
        }
        config.validate()?;
        *self = config;
        Ok(())
    }
}

/// The line (1 first) of the dotted `key` in the TOML `text`, if the text holds it.
fn line_of(text: &str, key: &str) -> Option<usize> {
    let doc = toml::de::DeTable::parse(text).ok()?;
    let mut table = doc.get_ref();
    let mut span = None;
    let mut parts = key.split('.').peekable();
    while let Some(part) = parts.next() {
        let (k, v) = table.get_key_value(part)?;
        span = Some(k.span());
        if parts.peek().is_some() {
            match v.get_ref() {
                toml::de::DeValue::Table(t) => table = t,
                _ => return None,
            }
        }
    }
    span.map(|s| text.get(..s.start).map_or(0, |t| t.matches('\n').count()) + 1)
}

/// Whether `value` is written as a TOML integer (sign, digits, underscores).
fn is_integer_literal(value: &str) -> bool {
    let digits = value.trim().trim_start_matches(['+', '-']);
    !digits.is_empty() && digits.chars().all(|c| c.is_ascii_digit() || c == '_')
}
