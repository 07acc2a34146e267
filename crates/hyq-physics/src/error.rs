//! Errors of the robot model ([`ModelError`]) and of the physics seam ([`PhysicsError`]).
//!
//! Every variant names what was wrong (file, link, joint, field) and the offending value, so a
//! message alone is enough to fix the input.

use std::path::PathBuf;

/// Why a robot model could not be built from a URDF and a robot profile.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ModelError {
    /// A file could not be read.
    #[error("cannot read {what} file {}: {source}", path.display())]
    Io {
        /// Which file this was ("URDF", "robot profile").
        what: &'static str,
        /// The path that was tried.
        path: PathBuf,
        /// The operating system's error.
        #[source]
        source: std::io::Error,
    },
    /// The URDF is not well-formed XML or does not follow the URDF schema.
    #[error("malformed URDF {origin}: {message}")]
    Urdf {
        /// Where the URDF came from (a path or "bundled").
        origin: String,
        /// The parser's message.
        message: String,
    },
    /// The robot profile is not valid TOML or does not have the expected fields.
    #[error("malformed robot profile {origin}: {message}")]
    Profile {
        /// Where the profile came from (a path or "bundled").
        origin: String,
        /// The parser's message (it names the line and the field).
        message: String,
    },
    /// A profile field has a value the model cannot use.
    #[error("robot profile field {field}: {reason}")]
    InvalidProfile {
        /// The field, e.g. `joints[3].standing` or `spawn.height`.
        field: String,
        /// What is wrong with its value, with the value.
        reason: String,
    },
    /// The profile names a link the URDF does not have.
    #[error("the URDF has no link named {link:?} (named by {referenced_by})")]
    MissingLink {
        /// The link name that was looked up.
        link: String,
        /// Which profile field named it.
        referenced_by: String,
    },
    /// The profile names a joint the URDF does not have.
    #[error(
        "the URDF has no joint named {joint:?} (named by {referenced_by}); its movable joints \
         are: {available}"
    )]
    MissingJoint {
        /// The joint name that was looked up.
        joint: String,
        /// Which profile field named it.
        referenced_by: String,
        /// The URDF's movable joints, comma-separated: the names the field can take.
        available: String,
    },
    /// The profile names a collision element the URDF link does not have.
    #[error(
        "URDF link {link:?} has no <collision name={collision:?}> (named by {referenced_by}); \
         its collisions are: {available} (leave `collision` out to track them all)"
    )]
    MissingCollision {
        /// The URDF link.
        link: String,
        /// The collision name that was looked up.
        collision: String,
        /// Which profile field named it.
        referenced_by: String,
        /// The link's collision names (unnamed ones as `#i`), comma-separated.
        available: String,
    },
    /// A link's mass or inertia tensor is not physically valid.
    #[error("link {link:?}: invalid inertia: {reason}")]
    InvalidInertia {
        /// The URDF link (or, after lumping fixed joints, the body named after its first link).
        link: String,
        /// What is wrong, with the numbers.
        reason: String,
    },
    /// A joint cannot be simulated as written.
    #[error("joint {joint:?}: {reason}")]
    InvalidJoint {
        /// The URDF joint name.
        joint: String,
        /// What is wrong, with the value.
        reason: String,
    },
    /// A collision element cannot be simulated as written.
    #[error("link {link:?}, collision {collision}: {reason}")]
    InvalidGeometry {
        /// The URDF link.
        link: String,
        /// The collision element's name, or its index if it has none.
        collision: String,
        /// What is wrong, with the value.
        reason: String,
    },
    /// The URDF's links and joints do not form one tree rooted at the profile's trunk.
    #[error("URDF structure: {reason}")]
    Structure {
        /// What is wrong, naming the links or joints involved.
        reason: String,
    },
    /// A robot choice that is neither a bundled robot nor a profile path.
    #[error(
        "unknown robot {choice:?}: not a bundled robot ({bundled}) nor a path to a robot \
         profile (a .toml file next to its URDF)"
    )]
    UnknownRobot {
        /// What was asked for.
        choice: String,
        /// The bundled robots' names, comma-separated.
        bundled: String,
    },
    /// A robot profile file whose robot could not be built: the profile's path, then why.
    #[error("robot profile {}: {source}", path.display())]
    InProfile {
        /// The profile file.
        path: PathBuf,
        /// What was wrong with it or its URDF.
        #[source]
        source: Box<ModelError>,
    },
}

impl ModelError {
    /// The error itself, without the [`ModelError::InProfile`] wrapping that names the file.
    pub fn innermost(&self) -> &ModelError {
        match self {
            ModelError::InProfile { source, .. } => source.innermost(),
            other => other,
        }
    }
}

/// Why the physics seam refused an input or could not go on.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum PhysicsError {
    /// A physics parameter is out of its valid range.
    #[error("physics parameter {field} = {value}: {reason}")]
    InvalidParam {
        /// The parameter's name as in the configuration file, e.g. `dt`.
        field: &'static str,
        /// The rejected value, formatted.
        value: String,
        /// The valid range.
        reason: &'static str,
    },
    /// A slice has the wrong number of values (one per actuated joint is expected).
    #[error("{what}: expected {expected} values (one per actuated joint), got {got}")]
    WrongLength {
        /// What the slice holds, e.g. "joint torques".
        what: &'static str,
        /// How many values the robot model needs.
        expected: usize,
        /// How many were given.
        got: usize,
    },
    /// An input value is NaN or infinite.
    #[error("{what} is not finite ({value})")]
    NonFinite {
        /// Which value, e.g. "joint torque for lf_kfe" or "trunk pose translation z".
        what: String,
        /// The value.
        value: f64,
    },
    /// An input state is finite but not valid.
    #[error("{what}: {reason}")]
    InvalidState {
        /// Which part of the state.
        what: String,
        /// What is wrong, with the value.
        reason: String,
    },
    /// The simulated state became non-finite during a step: the episode cannot go on.
    #[error("simulation diverged: {what} is not finite after the step")]
    Diverged {
        /// The first non-finite quantity found.
        what: String,
    },
    /// An engine-specific failure.
    #[error("{backend} backend: {message}")]
    Backend {
        /// The backend's [`crate::Backend::NAME`].
        backend: &'static str,
        /// What went wrong.
        message: String,
    },
    /// The robot model could not be built.
    #[error(transparent)]
    Model(#[from] ModelError),
    /// A terrain could not be made or used.
    #[error(transparent)]
    Terrain(#[from] crate::terrain::TerrainError),
}

/// `message` on one line, as every front prints errors: a parser's source excerpt (the lines it
/// draws with `|`, and the numbered source lines) left out, the other lines trimmed and joined
/// by ": " (TOML's "TOML parse error at line 3, column 1" header, then its explanation).
pub fn one_line(message: &str) -> String {
    message
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !is_source_excerpt(l))
        .collect::<Vec<_>>()
        .join(": ")
}

/// `text` with every control character escaped (`\n`, `\u{1b}`), the rest as it is: what a
/// file or an argument holds (a name, a key, a parser's quote of it), safe to print in a
/// one-line message, where a raw escape sequence could recolour the terminal or a line break
/// forge another line.
pub fn printable(text: &str) -> String {
    let mut out = String::with_capacity(text.len());
    for c in text.chars() {
        if c.is_control() {
            out.extend(c.escape_debug());
        } else {
            out.push(c);
        }
    }
    out
}

/// Whether a trimmed line is part of a parser's source excerpt: `|` rules, or a source line
/// after its number (`3 | key = 1`).
fn is_source_excerpt(line: &str) -> bool {
    line.starts_with('|')
        || line
            .split_once(" |")
            .is_some_and(|(n, _)| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()))
}

#[cfg(test)]
mod tests {
    use super::{one_line, printable};

    #[test]
    fn control_characters_are_escaped_and_the_rest_kept() {
        assert_eq!(printable("a\u{1b}[31m\"b\"\nc"), "a\\u{1b}[31m\"b\"\\nc");
    }

    #[test]
    fn a_parser_message_keeps_its_header_and_explanation() {
        let message = "TOML parse error at line 3, column 1\n  |\n3 | spawn = 1\n  | ^^^^^\nunknown field `spawn`, expected `trunk`\n";
        assert_eq!(
            one_line(message),
            "TOML parse error at line 3, column 1: unknown field `spawn`, expected `trunk`"
        );
        assert_eq!(one_line("12 joints\n  expected"), "12 joints: expected");
    }
}
