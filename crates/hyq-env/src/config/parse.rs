//! Reading a configuration, the same way for every front: TOML text, a file, and dotted-key
//! overrides (`hyq --config FILE --set table.key=value`, Python's keyword arguments and
//! `env_config`), each validated as a whole.

use std::path::Path;

use hyq_physics::input;
use serde::Deserialize;

use super::messages::parser_message;
use super::{ConfigError, EnvConfig, LoadError};

/// The largest configuration file read (bytes): 1 MiB, hundreds of times any real
/// configuration, so that a wrong path (`/dev/zero`, a log file) is refused at once rather than
/// read until memory runs out (hyq-physics' [`input::CONFIG`]).
pub const CONFIG_FILE_MAX_BYTES: usize = input::CONFIG.max_bytes as usize;

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
    /// [`CONFIG_FILE_MAX_BYTES`], through hyq-physics' capped reader (the one every user file
    /// goes through).
    pub fn from_file(path: impl AsRef<Path>) -> Result<Self, ConfigError> {
        let path = path.as_ref();
        let text = input::read_text(path, &input::CONFIG).map_err(|e| ConfigError::Io {
            path: path.display().to_string(),
            message: e.to_string(),
        })?;
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
    /// (`goal.mode=fixed` with `goal.position=[5, 1, 0.6]`, or a table key by key:
    /// `task.height_penalty.nominal_height_m`, `.tolerance_m`, `.rate_per_m`). This is what
    /// the CLI's `--set` options and the Python keyword arguments use.
    ///
    /// Each value is read as one TOML value (number, boolean, array, quoted string); anything
    /// that is not one is taken as a bare string, so `mode=random` works unquoted, and text
    /// holding more than one value (a second line) is refused rather than cut. An unknown key,
    /// or a value of the wrong type or outside its range, is an error naming that key and value;
    /// a combination that is invalid as a whole is an error naming the offending key. On error
    /// the configuration is unchanged.
    pub fn set_all(&mut self, pairs: &[(&str, &str)]) -> Result<(), ConfigError> {
        let base = toml::Table::try_from(&*self).map_err(|e| ConfigError::Parse {
            origin: "configuration".into(),
            message: e.to_string(),
        })?;
        let mut doc = base.clone();
        for (key, value) in pairs {
            insert(&mut doc, key, value).map_err(|m| set_error(key, value, &m))?;
        }
        let config =
            EnvConfig::deserialize(toml::Value::Table(doc)).map_err(|_| blame(base, pairs))?;
        config.validate()?;
        *self = config;
        Ok(())
    }
}

/// The error of the override `key = value`: the parser's `message` on one line, every part
/// printable (they are the user's text).
fn set_error(key: &str, value: &str, message: &str) -> ConfigError {
    ConfigError::Set {
        key: hyq_physics::printable(key),
        value: hyq_physics::printable(value),
        message: parser_message(message),
    }
}

/// Sets the dotted `key` of `doc` to `value`, read as one TOML value (see
/// [`EnvConfig::set_all`]); the reason when the key or the value cannot be used.
fn insert(doc: &mut toml::Table, key: &str, value: &str) -> Result<(), String> {
    let path: Vec<&str> = key.split('.').collect();
    if path.len() < 2 || path.iter().any(|p| p.is_empty()) {
        return Err("a key is `table.name`, e.g. `task.fall_penalty` or \
                    `physics.rapier.solver_iterations`"
            .into());
    }
    let parsed = match toml::from_str::<toml::Table>(&format!("v = {value}")) {
        // More than `v`: the text held a line break and more after it, which would be dropped.
        Ok(t) if t.len() > 1 => {
            return Err(
                "the value holds more than one TOML value (text after a line break): \
                        give one value per override"
                    .into(),
            );
        }
        Ok(mut t) => t.remove("v"),
        // An integer TOML cannot hold: say so, rather than read it as a bare string.
        Err(_) if is_integer_literal(value) => {
            return Err(
                "not an integer a configuration can hold: TOML's integers are 64-bit \
                        signed, from -9223372036854775808 to 9223372036854775807"
                    .into(),
            );
        }
        // A number past a float's range (`1e400`): say so, rather than read it as a string.
        Err(_) if is_out_of_range_float(value) => {
            return Err(
                "not a number a configuration can hold: beyond a float's range (±1.8e308)".into(),
            );
        }
        Err(_) => None,
    }
    .unwrap_or_else(|| toml::Value::String(value.to_owned()));
    let mut table = doc;
    for part in &path[..path.len() - 1] {
        let entry = table
            .entry(part.to_string())
            .or_insert_with(|| toml::Value::Table(toml::Table::new()));
        table = match entry {
            toml::Value::Table(t) => t,
            _ => return Err(format!("`{part}` is a value, not a table")),
        };
    }
    table.insert(path[path.len() - 1].to_owned(), parsed);
    Ok(())
}

/// The override a set that cannot be read is blamed on: replayed one at a time onto `doc`, the
/// first after which the configuration cannot be read for a reason other than a table still
/// missing keys (a later override may give them); failing that, the first that left a table
/// incomplete.
fn blame(mut doc: toml::Table, pairs: &[(&str, &str)]) -> ConfigError {
    let mut incomplete = None;
    for (key, value) in pairs {
        // Every pair was inserted once already: it inserts again.
        let _ = insert(&mut doc, key, value);
        if let Err(e) = EnvConfig::deserialize(toml::Value::Table(doc.clone())) {
            if !e.message().starts_with("missing field") {
                return set_error(key, value, &e.to_string());
            }
            incomplete.get_or_insert_with(|| {
                let message = format!(
                    "{} (a table given key by key needs every key: set the others too, or the \
                     table whole)",
                    e.message()
                );
                set_error(key, value, &message)
            });
        }
    }
    incomplete.unwrap_or_else(|| {
        let (key, value) = pairs.last().copied().unwrap_or(("", ""));
        set_error(key, value, "the overrides together cannot be read")
    })
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
/// Whether `value` is written as a decimal number that overflows f64 (`1e400`, `-2e308`), which
/// TOML refuses as a float.
fn is_out_of_range_float(value: &str) -> bool {
    let v = value.trim();
    v.chars()
        .all(|c| c.is_ascii_digit() || matches!(c, '+' | '-' | '.' | 'e' | 'E' | '_'))
        && v.chars().any(|c| c.is_ascii_digit())
        && v.replace('_', "")
            .parse::<f64>()
            .is_ok_and(f64::is_infinite)
}

fn is_integer_literal(value: &str) -> bool {
    let digits = value.trim().trim_start_matches(['+', '-']);
    !digits.is_empty() && digits.chars().all(|c| c.is_ascii_digit() || c == '_')
}
