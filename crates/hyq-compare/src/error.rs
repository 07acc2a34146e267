//! What can go wrong in a comparison; every variant names the value that was wrong.

use std::path::PathBuf;

use thiserror::Error;

/// Why a comparison could not be made or written.
#[derive(Debug, Error)]
pub enum CompareError {
    /// A scenario name that is not one of the scenarios' names (`Scenario::NAMES`).
    #[error("unknown scenario {name:?}: expected one of stand, fall, limit, trot, random, reach")]
    UnknownScenario {
        /// The name given.
        name: String,
    },
    /// A run length that is not a positive number of seconds (or is too long).
    #[error("seconds {value}: {reason}")]
    Seconds {
        /// The value given.
        value: f64,
        /// What it must be.
        reason: &'static str,
    },
    /// The number of shared states for the one-step comparison is out of range.
    #[error("one-step states {value}: must be in 1..=1000")]
    OneStepStates {
        /// The value given.
        value: usize,
    },
    /// The number of episodes of a policy comparison is out of range.
    #[error("episodes {value}: must be in 1..=1000")]
    Episodes {
        /// The value given.
        value: u32,
    },
    /// The scenario cannot run on this robot.
    #[error("scenario {scenario}: {reason}")]
    Scenario {
        /// The scenario.
        scenario: &'static str,
        /// Why.
        reason: String,
    },
    /// The action mode makes actions depend on the state, so both backends could not be fed
    /// the same action sequence.
    #[error(
        "action.mode = {mode:?}: its actions depend on the simulated joint angles, so two backends \
         cannot receive the same action sequence; use \"normalized\" or \"absolute\""
    )]
    StateDependentActions {
        /// The mode.
        mode: String,
    },
    /// The environment configuration is invalid (scenario changes plus overrides).
    #[error("configuration: {0}")]
    Config(#[from] hyq_env::ConfigError),
    /// An override `KEY=VALUE` is malformed or refused.
    #[error("override {item:?}: {reason}")]
    Override {
        /// The override as given.
        item: String,
        /// What was wrong.
        reason: String,
    },
    /// An environment could not be built (its configuration refused, or the engine's library
    /// missing): the same words as `hyq run`'s.
    #[error("cannot build the {backend} environment: {message}")]
    Build {
        /// The side's label.
        backend: String,
        /// The environment's message.
        message: String,
    },
    /// An environment could not be reset, or refused an action.
    #[error("{backend}: {message}")]
    Env {
        /// The side's label.
        backend: String,
        /// The environment's message.
        message: String,
    },
    /// A shared state could not be set or stepped in the one-step comparison.
    #[error("{backend}: one-step comparison from the state after step {step}: {message}")]
    OneStep {
        /// The side's label.
        backend: String,
        /// The reference run's step whose state was used.
        step: u64,
        /// The backend's message.
        message: String,
    },
    /// The ledger file could not be read.
    #[error("ledger {path}: cannot read: {message}")]
    LedgerRead {
        /// The path tried.
        path: PathBuf,
        /// The operating system's message.
        message: String,
    },
    /// The ledger is not valid TOML or breaks a rule of its format.
    #[error("ledger {origin}: {message}")]
    Ledger {
        /// Where the ledger came from (a path, or "built-in").
        origin: String,
        /// What is wrong, naming the entry or key.
        message: String,
    },
    /// The output directory cannot be created or written.
    #[error("output directory {path}: {message}")]
    Output {
        /// The directory or file.
        path: PathBuf,
        /// The operating system's message.
        message: String,
    },
    /// The plot could not be drawn or written.
    #[error("plot {path}: {message}")]
    Plot {
        /// The PNG file.
        path: PathBuf,
        /// What failed.
        message: String,
    },
}
