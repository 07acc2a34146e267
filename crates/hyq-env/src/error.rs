//! Why the environment refused a call ([`EnvError`]), apart from the environment so that every
//! part of it (the goal sampler, the vector env) can name it without importing the env itself.

use hyq_physics::PhysicsError;
use hyq_spec::EpisodeError;
use thiserror::Error;

use crate::action::ActionError;
use crate::config::ConfigError;
use crate::info::Reasons;

/// Why the environment refused a call. Every variant names what was wrong.
#[derive(Debug, Error)]
pub enum EnvError {
    /// `step` was called before the first `reset`.
    #[error("step called before reset: call reset first")]
    NotReset,
    /// `step` was called after the episode ended, without a reset.
    #[error(
        "step called after episode {episode} ended at t = {t} ({reasons:?}) without reset: call reset"
    )]
    EpisodeOver {
        /// The episode that ended.
        episode: u64,
        /// The step at which it ended.
        t: u64,
        /// Why it ended.
        reasons: Reasons,
    },
    /// The action was refused; the environment did not change.
    #[error(transparent)]
    Action(#[from] ActionError),
    /// The configuration is invalid for this robot or backend.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// The episode's goal or start cannot be used by the rules (e.g. a goal at the start).
    #[error(transparent)]
    Episode(#[from] EpisodeError),
    /// The backend could not be built, or refused a reset state.
    #[error(transparent)]
    Physics(#[from] PhysicsError),
}
