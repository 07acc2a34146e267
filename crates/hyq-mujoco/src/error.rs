//! Errors raised by the MuJoCo world.

/// What went wrong between this crate and MuJoCo.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum MujocoError {
    /// The library could not be opened, or is not the version the shim was built against.
    #[error("{0}")]
    Library(String),
    /// MuJoCo refused the model, or the model lacks an element the backend needs; MuJoCo's own
    /// message where it gave one.
    #[error("{0}")]
    Model(String),
    /// MuJoCo raised an error while running (its message).
    #[error("{0}")]
    Engine(String),
}
