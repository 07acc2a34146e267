//! The configuration's errors, and the parser's messages on one line.

use thiserror::Error;

/// Why [`EnvConfig::load`] failed: the file's error, or an override's; either reads as the
/// [`ConfigError`] it holds.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum LoadError {
    /// The file could not be read, or its configuration is invalid.
    #[error(transparent)]
    File(ConfigError),
    /// An override names an unknown key or a bad value, or leaves the configuration invalid.
    #[error(transparent)]
    Overrides(ConfigError),
}

impl From<LoadError> for ConfigError {
    fn from(e: LoadError) -> Self {
        match e {
            LoadError::File(e) | LoadError::Overrides(e) => e,
        }
    }
}

/// An invalid configuration; every variant names the key and, where there is one, the value.
#[derive(Clone, Debug, PartialEq, Error)]
pub enum ConfigError {
    /// The configuration file could not be read.
    #[error("cannot read configuration file {path}: {message}")]
    Io {
        /// The path that was tried.
        path: String,
        /// The operating system's message.
        message: String,
    },
    /// The text is not valid TOML, has an unknown key, or a value of the wrong type or range
    /// (the message names the key and shows the line).
    #[error("configuration {origin}: {message}")]
    Parse {
        /// Where the text came from (a path, or "text").
        origin: String,
        /// The parser's message.
        message: String,
    },
    /// A value out of its valid range.
    #[error("invalid {key} = {value}: {expected}")]
    Invalid {
        /// The dotted key, e.g. `goal.distance_m`.
        key: String,
        /// The rejected value as written.
        value: String,
        /// What the key accepts.
        expected: String,
    },
    /// A key given to [`EnvConfig::set`] that names no setting, or a change it refused.
    #[error("setting {key} = {value}: {message}")]
    Set {
        /// The dotted key as given.
        key: String,
        /// The value as given.
        value: String,
        /// What was wrong.
        message: String,
    },
}

/// `message` with every number of more than 24 digits (a float the parser or serde printed in
/// full, e.g. `1000000000000000000000000000000.0` for 1e30) in its shortest form (`1e30`). Up to
/// 24 digits stay as written, so integers such as 2^64 − 1 read as given.
fn compact_numbers(message: &str) -> String {
    let mut out = String::with_capacity(message.len());
    let mut rest = message;
    while let Some(start) = rest.find(|c: char| c.is_ascii_digit()) {
        out.push_str(&rest[..start]);
        let tail = &rest[start..];
        let end = tail
            .find(|c: char| !(c.is_ascii_digit() || c == '.'))
            .unwrap_or(tail.len());
        let number = &tail[..end];
        let digits = number.chars().filter(char::is_ascii_digit).count();
        match number.parse::<f64>() {
            Ok(v) if digits > 24 => out.push_str(&format!("{v:?}")),
            _ => out.push_str(number),
        }
        rest = &tail[end..];
    }
    out.push_str(rest);
    out
}

/// The TOML parser's words for a value that is not a string where a key takes one of a list of
/// names (`terrain.kind = 1`), and what they are said as.
const NOT_A_NAME: (&str, &str) = (
    "invalid type: unit variant, expected string only",
    "expected one of this key's names, in quotes",
);

/// A parser's message on one line (the fronts print errors on one line), as hyq-physics'
/// [`hyq_physics::one_line`] writes it, with numbers in their short form ([`compact_numbers`]),
/// control characters escaped ([`hyq_physics::printable`]: it quotes the user's keys) and the
/// parser's words for a name given as a number said plainly ([`NOT_A_NAME`]).
pub(super) fn parser_message(message: &str) -> String {
    let message = message.replace(NOT_A_NAME.0, NOT_A_NAME.1);
    hyq_physics::printable(&compact_numbers(&hyq_physics::one_line(&message)))
}
