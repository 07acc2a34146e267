//! What a comparison reports of `[randomize]` when it is on (nothing when it is off, so the
//! reports of the spec's environment are unchanged): whether every side drew the same values,
//! and, for a policy, how often each engine's episodes fell and how many pushes they had.
//!
//! The draws depend on the seed alone (hyq-env draws them, never an engine), so sides that share
//! a configuration and a seed draw alike; a line says so, and says it loudly when they did not
//! (a `--set-b randomize.*` varies one side only, so there they differ by design).

use hyq_env::{EpisodeDraw, EpisodeRandomization};
use serde::Serialize;

/// Whether every side drew the same values in each of its episodes, `sides[s]` being side s's
/// per-episode randomisation; `None` when no side randomised.
pub(crate) fn drew_alike<'a, I>(sides: impl IntoIterator<Item = I>) -> Option<bool>
where
    I: IntoIterator<Item = Option<&'a EpisodeRandomization>>,
{
    let draws: Vec<Vec<Option<&EpisodeDraw>>> = sides
        .into_iter()
        .map(|s| s.into_iter().map(|r| r.map(|r| &r.draw)).collect())
        .collect();
    if draws.iter().flatten().all(Option::is_none) {
        return None;
    }
    Some(draws.windows(2).all(|w| w[0] == w[1]))
}

/// The report's line for [`drew_alike`]'s answer, `sides` naming what was compared ("every
/// engine", "both sides").
pub(crate) fn line(alike: bool, sides: &str) -> String {
    if alike {
        format!(
            "Randomised (`[randomize]`): {sides} drew the same values in each episode (report.json lists them)."
        )
    } else {
        format!(
            "Randomised (`[randomize]`): **{sides} did not draw the same values** (report.json lists them; `--set-b randomize.*` varies one side only)."
        )
    }
}

/// One engine's randomised episodes: falls and pushes.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RandomizedSide {
    /// Episodes that ended with `fell` among their reasons.
    pub fell: u32,
    /// `fell` over the episodes (%).
    pub fall_rate_pct: f64,
    /// Mean pushes per episode.
    pub pushes_mean: f64,
    /// Fewest pushes in an episode.
    pub pushes_min: u64,
    /// Most pushes in an episode.
    pub pushes_max: u64,
}

impl RandomizedSide {
    /// The summary of episodes each given as (whether it fell, its randomisation); `None` when
    /// none randomised.
    pub(crate) fn of<'a>(
        episodes: impl IntoIterator<Item = (bool, Option<&'a EpisodeRandomization>)>,
    ) -> Option<Self> {
        let mut fell = 0u32;
        let mut pushes = Vec::new();
        for (f, r) in episodes {
            fell += u32::from(f);
            pushes.push(r?.pushes);
        }
        let n = pushes.len();
        (n > 0).then(|| Self {
            fell,
            fall_rate_pct: 100.0 * f64::from(fell) / n as f64,
            pushes_mean: pushes.iter().sum::<u64>() as f64 / n as f64,
            pushes_min: pushes.iter().copied().min().unwrap_or(0),
            pushes_max: pushes.iter().copied().max().unwrap_or(0),
        })
    }

    /// "1 of 20 (5 %)".
    pub fn fell_text(&self, episodes: usize) -> String {
        format!("{} of {episodes} ({:.0} %)", self.fell, self.fall_rate_pct)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use hyq_physics::{PhysicsParams, bundled};

    fn drawn(friction: f64, pushes: u64) -> EpisodeRandomization {
        let mut draw = EpisodeDraw::nominal(&bundled::hyq(), &PhysicsParams::default());
        draw.dynamics.ground_friction = friction;
        EpisodeRandomization { draw, pushes }
    }

    #[test]
    fn sides_drew_alike_when_every_episode_drew_the_same_whatever_the_pushes() {
        let (a, b, c) = (drawn(0.5, 2), drawn(0.7, 3), drawn(0.5, 1));
        assert_eq!(
            drew_alike([[Some(&a), Some(&b)], [Some(&c), Some(&b)]]),
            Some(true)
        );
        assert_eq!(
            drew_alike([[Some(&a), Some(&b)], [Some(&b), Some(&a)]]),
            Some(false)
        );
        assert_eq!(drew_alike([[None::<&EpisodeRandomization>], [None]]), None);
        assert!(line(false, "every engine").contains("did not draw the same"));
    }

    #[test]
    fn the_fall_rate_counts_episodes_that_fell() {
        let (a, b) = (drawn(0.5, 2), drawn(0.7, 4));
        let side = RandomizedSide::of([(true, Some(&a)), (false, Some(&b))]);
        let side = side.unwrap_or_else(|| panic!("randomised"));
        assert_eq!(
            (side.fell, side.fall_rate_pct, side.pushes_mean),
            (1, 50.0, 3.0)
        );
        assert_eq!((side.pushes_min, side.pushes_max), (2, 4));
        assert_eq!(side.fell_text(2), "1 of 2 (50 %)");
        assert_eq!(RandomizedSide::of([(true, None)]), None);
    }
}
