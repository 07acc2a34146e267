//! Errors raised by the DART bridge.

/// What went wrong inside the DART bridge.
#[derive(Debug, thiserror::Error)]
pub enum DartError {
    /// DART or the bridge refused a call; the message names the body, shape, joint or field.
    #[error("DART: {0}")]
    Cxx(String),
    /// DART handed back no world where one was expected.
    #[error("DART: the bridge returned no world")]
    NullWorld,
}

impl From<cxx::Exception> for DartError {
    fn from(e: cxx::Exception) -> Self {
        Self::Cxx(e.what().to_owned())
    }
}
