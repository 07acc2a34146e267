//! What `[randomize]` did in an episode, as the fronts report it: the step's info (flat keys
//! `randomize.<name>` in Python's), the `--record` lines and `hyq run --json` (an object under
//! `randomize`). Its one schema is [`RANDOMIZE_INFO_KEYS`](crate::RANDOMIZE_INFO_KEYS), declared
//! beside the info's [`INFO_KEYS`](crate::INFO_KEYS) in `info.rs` (so that this file needs
//! nothing of the info): the Python info dicts, `hyq.randomize_info_schema` and the documents'
//! table are made from it, and a test there holds the serialised names to it.

use serde::{Deserialize, Serialize};

use super::EpisodeDraw;

/// The episode's draws and the pushes so far, present on every step and reset of an
/// environment whose `[randomize]` is on (absent otherwise, so the spec's environment reports
/// what it always did).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct RandomizeInfo {
    /// The episode's drawn values (nominal for the options that are off).
    #[serde(flatten)]
    pub draw: EpisodeDraw,
    /// The velocity the step's push added to the trunk (m/s, world; zeros when none, and
    /// after reset).
    pub push_velocity_mps: [f64; 3],
    /// Pushes so far this episode.
    pub pushes: u64,
}

impl RandomizeInfo {
    /// The info of an episode that drew `draw`, before its first step.
    pub fn at_reset(draw: &EpisodeDraw) -> Self {
        Self {
            draw: draw.clone(),
            push_velocity_mps: [0.0; 3],
            pushes: 0,
        }
    }
}

/// What `[randomize]` did in a whole episode, as `hyq run --json` and `hyq compare` report it:
/// the drawn values (under the record's names) and how many pushes the episode had.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct EpisodeRandomization {
    /// The drawn values.
    #[serde(flatten)]
    pub draw: EpisodeDraw,
    /// Pushes in the episode.
    pub pushes: u64,
}

impl EpisodeRandomization {
    /// The randomisation of an episode that drew `draw`, before its first push.
    pub fn starting(draw: &EpisodeDraw) -> Self {
        Self {
            draw: draw.clone(),
            pushes: 0,
        }
    }
}

/// The prefix of every key of [`RANDOMIZE_INFO_KEYS`](crate::RANDOMIZE_INFO_KEYS); without it, a key is the name the
/// record, `hyq run --json` and `hyq compare` write under `randomize`.
pub const RANDOMIZE_PREFIX: &str = "randomize.";
